"""The live Foxglove view, watched by a real client speaking the Foxglove WebSocket protocol (loopback,
a free port, every wait bounded): ``GovernedLoop(foxglove=...)`` publishes each cycle's decision (the
latched rules by name), margins by rule id, R_e against τ and τ_confirm, and every input."""

from __future__ import annotations

import threading

import pytest

pytest.importorskip("foxglove")
pytest.importorskip("websockets")

import ethimon  # noqa: E402
from ethimon.loop import GovernedLoop, LoopConfig  # noqa: E402
from ethimon.view import DECISION, FAULTS, INPUTS, MARGINS, RISK, FoxgloveView, VerdictChannels, parse_address  # noqa: E402

from ._client import FoxgloveClient  # noqa: E402

SPEC = """
ethimon: 1
name: fox
signals:
  human_distance: {unit: m}
  speed: {unit: m/s}
obligations:
  - id: separation
    require: human_distance >= 0.5
    response: safe_pose
  - id: slow
    require: speed <= 1.0
    response: stop_2
risk: {threshold: 0.6, confirm_threshold: 0.3}
"""

OK = {"risk": 0.1, "human_distance": 0.8, "speed": 0.25}
TOPICS = [DECISION, MARGINS, RISK, FAULTS, INPUTS + "human_distance", INPUTS + "speed"]


def _watch(loop: GovernedLoop, client: FoxgloveClient) -> None:
    """Subscribe to every topic and wait (bounded) until the server has taken the subscriptions."""
    client.handshake(set(TOPICS))
    client.subscribe(TOPICS)
    assert loop.foxglove.wait_subscribed(len(TOPICS), timeout=5.0)
    loop.cycle(OK)  # one clean cycle first: every channel delivers
    loop.foxglove.flush()
    m = _cycle(client)
    assert not m[DECISION]["override"] and m[DECISION]["latched_rules"] == []


def _cycle(client: FoxgloveClient) -> dict[str, dict]:
    """The messages of one cycle, by topic (decision, margins, risk, faults and both inputs)."""
    return {topic: obj for topic, _, obj in client.messages(len(TOPICS))}


def test_a_protocol_client_sees_named_margins_risk_and_the_latch() -> None:
    loop = GovernedLoop(ethimon.load_spec_text(SPEC), foxglove=0, config=LoopConfig(period_s=1.0))
    client = FoxgloveClient(loop.foxglove.url)
    try:
        assert client.ws.subprotocol in ("foxglove.sdk.v1", "foxglove.websocket.v1")
        _watch(loop, client)
        assert client.channels[MARGINS]["schemaEncoding"] == "jsonschema"
        assert client.channels[DECISION]["encoding"] == "json"
        loop.cycle({"risk": 0.45, "human_distance": 0.2, "speed": 0.25})  # separation fails, R_e in the band
        loop.foxglove.flush()
        m = _cycle(client)
        assert m[DECISION]["override"] and m[DECISION]["response"] == "stop_2"  # the confirm hold (stop 2) outranks safe_pose
        assert m[DECISION]["violations"] == ["separation", "confirm"]
        assert set(m[DECISION]["latched_rules"]) == {"separation", "confirm"}
        assert m[MARGINS]["separation"] == pytest.approx(-0.3) and m[MARGINS]["slow"] == pytest.approx(0.75)
        assert m[RISK] == {"R_e": 0.45, "tau": 0.6, "tau_confirm": 0.3, "checked": True, "band": "confirm",
                           "judge": None, "confirm_hold": True, "judge_hold": False}
        assert m[INPUTS + "human_distance"] == {"value": 0.2}
        assert m[FAULTS] == {"faults": []}
        loop.cycle({"risk": 0.1, "human_distance": 0.8})  # speed missing: a fault, published by kind
        loop.foxglove.flush()
        m = {topic: obj for topic, _, obj in client.messages(len(TOPICS))}
        assert m[DECISION]["fault"] and "fault" in m[DECISION]["latched_rules"]
        assert [f["kind"] for f in m[FAULTS]["faults"]] == ["missing"]
        assert m[INPUTS + "speed"] == {"value": None}
    finally:
        client.close()
        loop.stop()
    assert loop.foxglove.dropped == 0 and loop.foxglove.error is None


def test_a_slow_viewer_drops_the_oldest_cycles_and_counts_them() -> None:
    mon = ethimon.Monitor(ethimon.load_spec_text(SPEC))
    view = FoxgloveView(VerdictChannels.of_spec(mon.spec, mon.obligation_ids), 0, queue=2)
    taken, release = threading.Event(), threading.Event()
    real = view.channels.of_decision

    def stuck(*a, **k):
        taken.set()
        release.wait(5)
        return real(*a, **k)

    view.channels.of_decision = stuck  # the worker hangs on its first cycle
    try:
        view.put(mon.step(OK), OK)
        assert taken.wait(5)
        for _ in range(5):  # the loop never waits: 5 more cycles into a queue of 2
            view.put(mon.step(OK), OK)
        assert view.dropped == 3 and view.pending == 2
    finally:
        release.set()
        view.close()
    assert view.cycles == 3


def test_a_loop_feeds_its_view_once_per_cycle_and_closes_it() -> None:
    seen = []

    class Sink:
        def put(self, d, inputs):
            seen.append((d.cycle, inputs.get("speed")))

    loop = GovernedLoop(ethimon.load_spec_text(SPEC), foxglove=Sink(), config=LoopConfig(period_s=1.0))
    loop.cycle(OK)
    loop.cycle({**OK, "speed": 2.0})
    assert seen == [(0, 0.25), (1, 2.0)]


def test_a_view_that_raises_fails_closed_on_the_next_cycle() -> None:
    class Broken:
        def put(self, d, inputs):
            raise RuntimeError("viewer gone")

    loop = GovernedLoop(ethimon.load_spec_text(SPEC), foxglove=Broken(), config=LoopConfig(period_s=1.0))
    loop.cycle(OK)
    d = loop.cycle(OK)
    assert d.override and [f.kind for f in d.faults] == ["callback"] and "viewer gone" in d.faults[0].message


@pytest.mark.parametrize("text, want", [("8765", ("127.0.0.1", 8765)), (9000, ("127.0.0.1", 9000)),
                                        ("0.0.0.0:1234", ("0.0.0.0", 1234)), ("[::1]:8765", ("::1", 8765)),
                                        (None, ("127.0.0.1", 8765))])
def test_address(text, want) -> None:
    assert parse_address(text) == want


@pytest.mark.parametrize("text", ["", "host:", "localhost:99999", "abc", True, 1.5])
def test_a_bad_address_is_refused_with_the_form(text) -> None:
    with pytest.raises(ValueError, match=r"\[HOST:\]PORT"):
        parse_address(text)


@pytest.mark.slow  # a fresh interpreter
def test_no_foxglove_import_until_a_view_starts() -> None:
    import subprocess
    import sys
    code = ("import sys, ethimon, ethimon.view, ethimon.loop, ethimon.replay, ethimon.cli\n"
            "print(sorted(m for m in ('foxglove', 'websockets') if m in sys.modules))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and r.stdout.strip() == "[]", r.stderr


def test_wait_subscribed_settles_until_a_clients_last_subscription() -> None:
    """Regression (CI, stop 35): ``ethimon replay --foxglove`` started after the FIRST channel of a client's
    subscription and published before the second was registered, so the client missed messages. With
    ``settle_s`` the wait lasts until subscriptions stop coming."""
    loop = GovernedLoop(ethimon.load_spec_text(SPEC), foxglove=0, config=LoopConfig(period_s=1.0))
    client = FoxgloveClient(loop.foxglove.url)
    try:
        client.handshake(set(TOPICS))
        client.subscribe(TOPICS[:1])
        later = threading.Timer(0.15, client.subscribe, args=(TOPICS[1:],))
        later.start()
        assert loop.foxglove.wait_subscribed(1, timeout=5.0, settle_s=0.5)
        assert loop.foxglove.subscriptions == len(TOPICS)  # the second request was waited for
        later.join()
        assert not loop.foxglove.wait_subscribed(len(TOPICS) + 1, timeout=0.05, settle_s=0.5)
    finally:
        client.close()
        loop.stop()
