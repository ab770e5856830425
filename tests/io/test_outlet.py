"""What goes out is a port of its own (``channel.out``, an :class:`ethimon.io.Outlet`): the live monitor
writes its decisions and its answers there; acknowledgement requests come in with the cycle's samples and
are applied after its decision; a flood of requests in one cycle is answered, never queued without end."""

from __future__ import annotations

import json
import threading

import ethimon
from ethimon.io import AckRequest, LiveMonitor, MemoryChannel, Outlet, load_mapping_text
from ethimon.loop import GovernedLoop, LoopConfig
from tests._estimators import FakeClock

SPEC = """
ethimon: 1
name: outlet
signals:
  d: {unit: m, range: [0, 100]}
obligations:
  - {id: near, require: "d >= 0.5", response: stop_1, release: {mode: manual, hold_cycles: 1}}
"""

MAPPING = """
ethimon: 1
rate_hz: 100
max_age_s: 1.0
ros2: {allow_unauthenticated_acknowledge: "a test bench"}
signals:
  d: {topic: /range, field: range}
  p_unsafe: {topic: /p, field: data}
"""


class Split:
    """A channel whose outlet is another object: what the monitor writes never goes to the read side."""

    def __init__(self, clock):
        self.inbox, self.out = MemoryChannel(clock=clock), _Out()
        self.now, self.take, self.faults, self.acks = (self.inbox.now, self.inbox.take, self.inbox.faults,
                                                      self.inbox.acks)


class _Out:
    def __init__(self):
        self.written = []

    def write_override(self, value):
        self.written.append(("override", value))

    def write_decision(self, text):
        self.written.append(("decision", json.loads(text)["cycle"]))

    def write_ack_result(self, text):
        self.written.append(("ack", json.loads(text)["released"]))


def _live(ch, clock):
    loop = GovernedLoop(ethimon.Monitor(ethimon.load_spec_text(SPEC)), clock=clock,
                        config=LoopConfig(period_s=0.01, deadline_s=1e6, stall_s=1e6))
    return loop, LiveMonitor(loop, load_mapping_text(MAPPING), ch)


def _cycle(loop, ch, clock, d):
    ch.publish("d", d)
    ch.publish("p_unsafe", 0.0)
    out = loop.cycle()
    clock.t += 0.01
    return out


def test_the_monitor_writes_to_the_channels_outlet_in_order_override_decision_then_answers():
    clock = FakeClock(10.0)
    ch = Split(clock)
    loop, _ = _live(ch, clock)
    assert isinstance(ch.out, Outlet) and isinstance(MemoryChannel().out, Outlet)
    _cycle(loop, ch.inbox, clock, 0.2)                    # too near: stop_1, latched (manual)
    ch.inbox.request_ack(AckRequest("ops-1", reason="cleared"))
    _cycle(loop, ch.inbox, clock, 2.0)                    # the request is taken with this cycle's samples
    assert ch.out.written == [("override", True), ("decision", 0), ("override", True), ("decision", 1),
                              ("ack", True)]
    assert not _cycle(loop, ch.inbox, clock, 2.0).override  # the next cycle is the first to see the release


def test_a_request_that_arrives_during_a_cycle_is_applied_after_the_next_decision():
    clock = FakeClock(10.0)
    ch = MemoryChannel(clock=clock)
    loop, live = _live(ch, clock)
    _cycle(loop, ch, clock, 0.2)
    live.frame()  # the cycle's inputs are read (as the loop does), then a request comes in
    ch.request_ack(AckRequest("ops-1"))
    assert ch.ack_results == []
    _cycle(loop, ch, clock, 2.0)
    assert [json.loads(r)["released"] for r in ch.ack_results] == [True]


def test_a_flood_of_requests_in_one_cycle_is_answered_beyond_the_queue_not_kept():
    clock = FakeClock(10.0)
    ch = MemoryChannel(clock=clock)
    loop, live = _live(ch, clock)
    _cycle(loop, ch, clock, 0.2)
    for k in range(100):
        ch.request_ack(AckRequest(f"ops-{k}", reason="flood"))
    _cycle(loop, ch, clock, 2.0)
    answers = [json.loads(r) for r in ch.ack_results]
    assert len(answers) == 100 and answers[0]["released"]
    refused = [a for a in answers if "too many acknowledgement requests" in a["message"]]
    assert len(refused) == 100 - 64 and all(not a["released"] for a in refused)
    assert live.acks_refused == 36 and live._acks == []


def test_the_memory_outlet_takes_the_override_from_two_threads():
    ch = MemoryChannel()
    threads = [threading.Thread(target=lambda: [ch.out.write_override(True) for _ in range(2000)])
               for _ in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert ch.overrides == [True] * 4000


def test_a_channel_without_an_outlet_is_refused_when_the_monitor_is_built():
    import pytest

    class Old:  # writes by itself, as channels did before the outlet: refused with what to give
        def now(self, clock):
            return 0.0

        def take(self):
            return []

        def faults(self):
            return ()

        def acks(self):
            return []

        def write_override(self, value):
            pass

    with pytest.raises(TypeError, match="Old has no outlet: a Channel's 'out' is an ethimon.io.Outlet"):
        _live(Old(), FakeClock(0.0))


def test_a_raising_decision_callback_leaves_no_request_unanswered_and_the_queue_bounded():
    """Review finding: the user's on_decision ran before the requests were applied; when it raised they
    stayed queued (and grew by the refusals of every later cycle), never answered."""
    clock = FakeClock(10.0)
    ch = MemoryChannel(clock=clock)

    def boom(d):
        raise RuntimeError("a callback that fails")

    loop = GovernedLoop(ethimon.Monitor(ethimon.load_spec_text(SPEC)), clock=clock, on_decision=boom,
                        config=LoopConfig(period_s=0.01, deadline_s=1e6, stall_s=1e6))
    live = LiveMonitor(loop, load_mapping_text(MAPPING), ch)
    for _ in range(3):
        for k in range(300):
            ch.request_ack(AckRequest(f"ops-{k}", reason="flood"))
        _cycle(loop, ch, clock, 2.0)
        assert live._acks == []
    assert len(ch.ack_results) == 3 * 128 and live.acks_dropped == 3 * (300 - 128)
    assert _cycle(loop, ch, clock, 2.0).override  # the callback's fault overrides, as before
