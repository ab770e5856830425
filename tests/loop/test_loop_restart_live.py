"""Issue 32 item 4 through ``ethimon ros2``'s path (LiveMonitor on a MemoryChannel, a fake clock): the
acknowledgement it forwards is refused until the robot reports standstill, and the decision it publishes
holds (``restart`` in ``latched_rules``, the reason in ``hold``) until the start input rises."""

from __future__ import annotations

import json

import ethimon
from ethimon.io import AckRequest, LiveMonitor, MemoryChannel, load_mapping_text
from ethimon.loop import GovernedLoop, LoopConfig
from tests._estimators import FakeClock

SPEC = """
ethimon: 1
name: live_restart
signals:
  dist: {unit: m, range: [0, 100]}
  at_rest: {type: bool}
  go: {type: bool}
obligations:
  - {id: near, require: "dist >= 0.5", response: stop_1, release: {mode: manual, hold_cycles: 1}}
restart: {start: go, standstill: at_rest}
"""

MAPPING = """
ethimon: 1
rate_hz: 100
max_age_s: 1.0
signals:
  dist: {topic: /range, field: range}
  at_rest: {topic: /at_rest, field: data}
  go: {topic: /go, field: data}
  p_unsafe: {topic: /p, field: data}
"""


def test_ros2_path_gates_the_acknowledgement_on_standstill_and_holds_until_the_start_input_rises():
    clock = FakeClock(100.0)
    ch = MemoryChannel(clock=clock)
    loop = GovernedLoop(ethimon.Monitor(ethimon.load_spec_text(SPEC)),
                        clock=clock, config=LoopConfig(period_s=0.01, deadline_s=1e6, stall_s=1e6))
    LiveMonitor(loop, load_mapping_text(MAPPING), ch)

    def cycle(**values):
        for k, v in values.items():
            ch.publish(k, v)
        d = loop.cycle()
        clock.t += 0.01
        return d, json.loads(ch.decisions[-1])

    cycle(dist=0.2, at_rest=False, go=False, p_unsafe=0.0)
    cycle(dist=2.0, at_rest=False, go=False, p_unsafe=0.0)
    ch.request_ack(AckRequest("ops-1", authenticated=True))
    cycle(dist=2.0, at_rest=False, go=False, p_unsafe=0.0)  # applied after this cycle's decision: braking
    refused = json.loads(ch.ack_results[-1])
    assert not refused["released"] and "the stop has not completed: at_rest" in refused["message"]
    ch.request_ack(AckRequest("ops-1", authenticated=True))
    cycle(dist=2.0, at_rest=True, go=False, p_unsafe=0.0)  # the robot reports the stop completed
    assert json.loads(ch.ack_results[-1])["released"]
    d, pub = cycle(dist=2.0, at_rest=True, go=False, p_unsafe=0.0)
    assert d.override and pub["override"] and pub["response"] == "stop_2" and "restart" in pub["latched_rules"]
    assert "waiting for the start (the rising edge of input go)" in pub["hold"][0]["how"]
    d, _ = cycle(dist=2.0, at_rest=True, go=True, p_unsafe=0.0)  # the button: taken at the next cycle
    assert d.override
    d, pub = cycle(dist=2.0, at_rest=True, go=True, p_unsafe=0.0)
    assert not d.override and not pub["override"] and pub["hold"] == []
