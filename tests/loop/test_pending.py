"""Issue 31, item 2: the start and a new task text are a pending hold (stop 2, released by itself when the
estimate arrives within its age limit), never a manual fault latch; and the loop says which latch holds."""

from __future__ import annotations

from pathlib import Path

import pytest

import ethimon
from ethimon.loop import AsyncRiskSource, GovernedLoop, LoopConfig

ROOT = Path(__file__).resolve().parents[2]
SPEC = ROOT / "examples" / "replay" / "spec.yaml"
HEALTHY = {"human_distance": 3.0, "ee_speed": 0.1, "contact_force": 1.0, "joint_speed_max": 0.5}
TEXT = "Place the red box on the second shelf."


class Fixed:
    def probs(self, text):
        return (0.9, 0.1)  # R_e 0.144 under the example spec


class Clock:
    def __init__(self):
        self.t = 0.0

    def __call__(self):
        return self.t


def _loop(clock=None):
    src = AsyncRiskSource(Fixed(), text=TEXT, start=False, **({"clock": clock} if clock else {}))
    return src, GovernedLoop(ethimon.load_spec(SPEC), risk=src, signals=lambda: HEALTHY,
                             config=LoopConfig(period_s=0.001, deadline_s=60.0, stall_s=60.0))


def test_start_is_a_pending_hold_released_by_the_estimate():
    src, loop = _loop()
    d = loop.cycle(HEALTHY)
    assert d.override and d.response == ethimon.Response.STOP_2 and d.faults == ()
    assert "pending" in d.violations
    src.poll_once()
    assert not loop.cycle(HEALTHY).override  # the estimate arrived: the arm may move, no acknowledgement
    assert loop.stats.pending_cycles == 1 and loop.stats.fault_cycles == 0


def test_a_new_text_is_a_pending_hold_too():
    src, loop = _loop()
    src.poll_once()
    assert not loop.cycle(HEALTHY).override
    src.set_text("Put the cup in the dishwasher.")
    d = loop.cycle(HEALTHY)
    assert d.override and d.response == ethimon.Response.STOP_2 and not d.faults
    src.poll_once()
    assert not loop.cycle(HEALTHY).override


def test_an_estimate_that_never_arrives_is_a_fault():
    clock = Clock()
    src, loop = _loop(clock)
    assert loop.cycle(HEALTHY).faults == ()
    clock.t = 0.6  # past max_risk_age_s 0.5: the text's estimate never came
    d = loop.cycle(HEALTHY)
    assert d.override and d.response == ethimon.Response.STOP_1
    assert any(f.kind == "estimator" for f in d.faults)
    src.poll_once()
    d = loop.cycle(HEALTHY)
    assert d.override and d.latched  # the fault latch is manual: a person acknowledges it


def test_a_crashed_estimator_stays_a_fault():
    class Broken:
        def probs(self, text):
            raise RuntimeError("boom")
    src = AsyncRiskSource(Broken(), text=TEXT, start=False)
    loop = GovernedLoop(ethimon.load_spec(SPEC), risk=src, config=LoopConfig(period_s=1.0, deadline_s=60.0))
    src.poll_once()
    d = loop.cycle(HEALTHY)
    assert d.override and any(f.kind == "estimator" for f in d.faults)


def test_a_signal_seen_before_and_missing_now_is_a_fault_even_while_a_text_is_pending():
    src, loop = _loop()
    src.poll_once()
    loop.cycle(HEALTHY)
    src.set_text("another text")
    d = loop.cycle({k: v for k, v in HEALTHY.items() if k != "ee_speed"})
    assert d.override and any(f.kind == "missing" and f.subject == "ee_speed" for f in d.faults)


def test_a_signal_not_seen_since_the_start_is_awaited():
    src, loop = _loop()
    src.poll_once()
    d = loop.cycle({})
    assert d.override and d.faults == () and "pending" in d.violations
    assert not loop.cycle(HEALTHY).override


def test_monitor_pending_input():
    m = ethimon.Monitor(ethimon.load_spec(SPEC), max_age_s=0.5)
    d = m.step({**HEALTHY, "pending_s": 0.2})
    assert d.override and d.response == ethimon.Response.STOP_2 and not d.faults
    assert not m.step({**HEALTHY, "p": (0.9, 0.1), "risk_age_s": 0.01}).override
    d = m.step({**HEALTHY, "pending_s": 0.7})  # past the limit
    assert d.override and d.faults and d.response == ethimon.Response.STOP_1
    bad = m.step({**HEALTHY, "pending_s": float("nan")})
    assert any(f.subject == "pending_s" and f.kind == "invalid" for f in bad.faults)
    # without an age limit nothing bounds the wait: a fault as before
    m2 = ethimon.Monitor(ethimon.load_spec(SPEC))
    assert m2.step({**HEALTHY, "pending_s": 0.0}).faults


def test_pending_keeps_temporal_history_and_other_rules_fire():
    spec = ethimon.load_spec_text("""
ethimon: 1
name: t
signals: {x: {range: [0, 10]}, y: {range: [0, 10]}}
risk: {max_age_s: 0.5}
obligations:
  - {id: o, require: "once(y > 4, 3) implies x < 6", response: stop_1}
""")
    m = ethimon.Monitor(spec)
    assert not m.step({"x": 1.0, "y": 5.0, "p_unsafe": 0.0, "risk_age_s": 0.0}).override
    d = m.step({"x": 1.0, "y": 0.0, "pending_s": 0.1})
    assert d.response == ethimon.Response.STOP_2 and d.violations == ("pending",)
    d = m.step({"x": 7.0, "y": 0.0, "p_unsafe": 0.0, "risk_age_s": 0.0})
    assert d.override and "o" in d.violations  # the event two cycles ago is remembered


def test_holding_says_which_latch_holds_since_when_and_how():
    clock = Clock()
    src, loop = _loop(clock)
    assert loop.holding() == [] or loop.holding()[0]["rule"] == "pending"
    loop.cycle(HEALTHY)
    (h,) = loop.holding()
    assert h["rule"] == "pending" and h["release"] == "estimate" and h["since_cycle"] == 0
    assert h["since_t_unix"] is not None and h["acknowledge"] is False and h["response"] == "stop_2"
    clock.t = 1.0
    loop.cycle(HEALTHY)
    rules = {h["rule"]: h for h in loop.holding()}
    f = rules["fault"]
    assert f["release"] == "acknowledge" and f["acknowledge_allowed"] and f["since_cycle"] == 1
    refused = {h["rule"]: h for h in loop.holding(acknowledge_refused="unauthenticated")}["fault"]
    assert refused["release"] == "person" and not refused["acknowledge_allowed"] and "unauthenticated" in refused["how"]
    assert "fault (stop_1) since cycle 1" in loop.hold_text


def test_run_summary_names_the_hold():
    clock = Clock()
    src, loop = _loop(clock)
    loop.run(cycles=1)
    assert loop.stats.held_by.startswith("pending (stop_2) since cycle 0")
    assert "held by pending" in loop.stats.summary()
    src.poll_once()
    loop.run(cycles=2)
    assert loop.stats.held_by == "" and "free" in loop.stats.summary()


@pytest.mark.parametrize("n", [1])
def test_documented_live_example_moves(n):
    """The docs' example spec, a healthy robot and a safe text: only the cycles before the estimate hold."""
    src, loop = _loop()
    overrides = sum(loop.cycle(HEALTHY).override for _ in range(3))
    src.poll_once()
    overrides += sum(loop.cycle(HEALTHY).override for _ in range(597))
    assert overrides == 3
