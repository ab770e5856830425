"""Fault injection: every fault ends in an override with a reason, and the audit log says so."""

from __future__ import annotations

import math

import pytest

import ethimon
from ethimon import Response
from ethimon.audit import AuditLog, read_log, verify_log
from ethimon.loop import AsyncRiskSource, GovernedLoop, LoopConfig

from tests._estimators import FakeClock, ScriptedEstimator, wait_for

SPEC = """
ethimon: 1
name: faults
signals:
  human_distance: {unit: m, range: [0, 10]}
  gripper_closed: {type: bool}
risk: {threshold: 0.5, max_age_s: 0.2, release: {mode: auto, hysteresis: 0.05, hold_cycles: 3}}
on_fault: stop_1
obligations:
  - {id: keep_away, require: "human_distance >= 0.5", response: stop_2}
"""

GOOD = {"human_distance": 2.0, "gripper_closed": False}


def _run(tmp_path, *, estimator=None, signals=GOOD, cycles=3, clock=None, poll=True, **kw):
    """Build a loop with an audit log, run a few cycles, return (decisions, records)."""
    clock = clock or FakeClock()
    src = None
    if estimator is not None:
        src = AsyncRiskSource(estimator, text="hand the knife over", clock=clock, start=False)
        if poll:
            src.poll_once()
    log = AuditLog(tmp_path / "audit.jsonl")
    loop = GovernedLoop(ethimon.Monitor(ethimon.load_spec_text(SPEC)), risk=src, audit=log, clock=clock,
                        config=LoopConfig(period_s=0.001), **kw)
    out = []
    for _ in range(cycles):
        clock.advance(0.001)
        out.append(loop.cycle(signals))
    log.close()
    rep = verify_log(tmp_path / "audit.jsonl", require_closed=True)
    assert rep.ok, rep.summary()
    return out, read_log(tmp_path / "audit.jsonl")


def _assert_logged(records, needle):
    on = [r for r in records if r["kind"] == "decision" and r["override"]]
    assert on, "no override record in the audit log"
    assert any(needle in f for r in on for f in r["faults"]), [r["faults"] for r in on]


# ---------------------------------------------------------------- the estimator misbehaves
# the source reads the output once into floats (a non-sequence or a raise is its fault); whether the
# probabilities are usable is judged once, by the monitor, with the rule it applies to every p
@pytest.mark.parametrize("mode, kind, needle", [
    ("raise", "estimator", "risk estimator raised RuntimeError: CUDA error"),
    ("nan", "invalid", "p contains nan (NaN, not a number or outside [0, 1])"),
    ("inf", "invalid", "p contains inf (NaN, not a number or outside [0, 1])"),
    ("badsum", "invalid", "sums to 1.4, not 1"),
    ("wronglen", "invalid", "p has 1 classes, the spec expects 2"),
    ("notseq", "estimator", "returned float, not a sequence"),
])
def test_estimator_bad_output_overrides(tmp_path, mode, kind, needle):
    decisions, records = _run(tmp_path, estimator=ScriptedEstimator(mode=mode))
    for d in decisions:
        assert d.override and d.response is Response.STOP_1
        assert any(f.kind == kind and needle in f.message for f in d.faults), d.faults
    _assert_logged(records, needle)


def test_estimator_failure_replaces_an_older_good_estimate(tmp_path):
    """A fault is never papered over by the last good (low) risk."""
    clock = FakeClock()
    est = ScriptedEstimator()
    src = AsyncRiskSource(est, text="t", clock=clock, start=False)
    src.poll_once()
    assert src.latest()[0] == (0.95, 0.05)
    est.mode = "raise"
    src.poll_once()
    assert src.latest() == (None, math.inf) and "raised" in src.fault
    assert src.errors == 1


def test_estimator_hang_past_deadline_overrides(tmp_path):
    est = ScriptedEstimator(mode="hang")
    src = AsyncRiskSource(est, text="t", rate_hz=50.0, hang_timeout_s=0.05)
    log = AuditLog(tmp_path / "audit.jsonl")
    loop = GovernedLoop(ethimon.Monitor(ethimon.load_spec_text(SPEC)), risk=src, audit=log,
                        config=LoopConfig(period_s=0.001, deadline_s=1.0))
    try:
        assert wait_for(lambda: (src.fault or "").startswith("risk estimator hung"))
        d = loop.cycle(GOOD)
        assert d.override and any(f.kind == "estimator" and f.message.startswith("risk estimator hung")
                                  for f in d.faults)
        # restart without stopping the loop: the loop keeps stepping, then recovers
        src.restart(ScriptedEstimator())
        assert wait_for(lambda: src.fault is None)
        decisions = [loop.cycle(GOOD) for _ in range(5)]
        # the fault latch is manual (the default): held, then ready after hold_cycles clean cycles
        assert decisions[-1].override and decisions[-1].awaiting_release
        assert loop.monitor.acknowledge()
        assert not loop.cycle(GOOD).override
    finally:
        est.release()
        src.stop()
        log.close()
    _assert_logged(read_log(tmp_path / "audit.jsonl"), "risk estimator hung")


def test_stale_estimate_overrides(tmp_path):
    clock = FakeClock()
    src = AsyncRiskSource(ScriptedEstimator(), text="t", clock=clock, start=False)
    src.poll_once()
    log = AuditLog(tmp_path / "audit.jsonl")
    loop = GovernedLoop(ethimon.Monitor(ethimon.load_spec_text(SPEC)), risk=src, audit=log, clock=clock,
                        config=LoopConfig(period_s=1.0))
    assert not loop.cycle(GOOD).override
    clock.advance(0.5)
    d = loop.cycle(GOOD)
    assert d.override and any(f.kind == "stale" for f in d.faults)
    log.close()
    _assert_logged(read_log(tmp_path / "audit.jsonl"), "stale")


def test_no_estimate_yet_overrides(tmp_path):
    decisions, records = _run(tmp_path, estimator=ScriptedEstimator(), poll=False)
    assert all(d.override for d in decisions)
    # awaited, not a fault (issue 31): the pending hold (stop 2), named in the audit record
    on = [r for r in records if r["kind"] == "decision" and r["override"]]
    assert on and all("pending" in r["violations"] and r["response"] == "stop_2" for r in on)


def test_loop_enforces_max_age_when_spec_has_none(tmp_path):
    clock = FakeClock()
    src = AsyncRiskSource(ScriptedEstimator(), text="t", clock=clock, start=False)
    src.poll_once()
    spec = ethimon.load_spec_text(SPEC.replace(", max_age_s: 0.2", ""))
    loop = GovernedLoop(ethimon.Monitor(spec), risk=src, clock=clock,
                        config=LoopConfig(period_s=10.0, max_risk_age_s=0.3))
    assert not loop.cycle(GOOD).override
    clock.advance(1.0)
    d = loop.cycle(GOOD)
    assert d.override and any(f.kind == "stale" and "risk estimate is stale" in f.message for f in d.faults)


# ---------------------------------------------------------------- the signals are bad
@pytest.mark.parametrize("signals, needle", [
    ({"gripper_closed": False}, "signal 'human_distance' is missing"),
    ({"human_distance": float("nan"), "gripper_closed": False}, "is NaN or outside its range"),
    ({"human_distance": 11.0, "gripper_closed": False}, "is NaN or outside its range [0, 10]"),
    ({"human_distance": -0.1, "gripper_closed": False}, "outside its range"),
    ({"human_distance": float("inf"), "gripper_closed": False}, "outside its range"),
    ({"human_distance": "2.0", "gripper_closed": False}, "must be a number, got '2.0'"),
    ({"human_distance": True, "gripper_closed": False}, "must be a number, got True"),
    ({"human_distance": [2.0], "gripper_closed": False}, "must be a number, got [2.0]"),
    ({"human_distance": None, "gripper_closed": False}, "is missing"),
    ({"human_distance": 2.0, "gripper_closed": "yes"}, "must be true/false"),
])
def test_bad_signals_override(tmp_path, signals, needle):
    decisions, records = _run(tmp_path, estimator=ScriptedEstimator(), signals=signals)
    if needle.endswith("is missing"):  # not seen since the start: awaited (issue 31), a pending hold (stop 2)
        assert all(d.override and d.response == Response.STOP_2 and "pending" in d.violations and not d.faults
                   for d in decisions)
        return  # seen, then missing: a fault (tests/loop/test_pending.py)
    for d in decisions:
        assert d.override and any(needle in f.message for f in d.faults), d.faults
    _assert_logged(records, needle)


def test_signals_not_a_mapping_overrides(tmp_path):
    decisions, records = _run(tmp_path, estimator=ScriptedEstimator(), signals=42)
    assert all(d.override for d in decisions)
    _assert_logged(records, "signal source raised TypeError")


def test_simulator_raising_mid_run_overrides(tmp_path):
    """The signal source (a simulator, a driver) raising mid-run is a fault, not a crash."""
    calls = {"n": 0}

    def sim_step():
        calls["n"] += 1
        if calls["n"] >= 3:
            raise RuntimeError("pybullet: not connected to physics server")
        return GOOD

    clock = FakeClock()
    src = AsyncRiskSource(ScriptedEstimator(), text="t", clock=clock, start=False)
    src.poll_once()
    log = AuditLog(tmp_path / "audit.jsonl")
    loop = GovernedLoop(ethimon.Monitor(ethimon.load_spec_text(SPEC)), risk=src, signals=sim_step, audit=log,
                        clock=clock, sleep=clock.advance, config=LoopConfig(period_s=0.001))
    loop.run(cycles=5)
    log.close()
    assert loop.last_decision.override
    assert any(f.kind == "signals" and "signal source raised RuntimeError: pybullet" in f.message
               for f in loop.last_decision.faults)
    _assert_logged(read_log(tmp_path / "audit.jsonl"), "pybullet: not connected")


# ---------------------------------------------------------------- timing and the audit log itself
def test_missed_deadline_overrides_and_is_logged(tmp_path):
    clock = FakeClock()

    def slow():
        clock.advance(0.005)
        return GOOD

    src = AsyncRiskSource(ScriptedEstimator(), text="t", clock=clock, start=False)
    src.poll_once()
    log = AuditLog(tmp_path / "audit.jsonl")
    loop = GovernedLoop(ethimon.Monitor(ethimon.load_spec_text(SPEC)), risk=src, signals=slow, audit=log,
                        clock=clock, config=LoopConfig(period_s=0.001))
    d = loop.cycle()
    assert d.override and d.response is Response.STOP_1
    log.close()
    _assert_logged(read_log(tmp_path / "audit.jsonl"), "missed its deadline")


def test_full_audit_queue_overrides_and_the_drop_is_recorded(tmp_path):
    import threading
    clock = FakeClock()
    src = AsyncRiskSource(ScriptedEstimator(), text="t", clock=clock, start=False)
    src.poll_once()
    log = AuditLog(tmp_path / "audit.jsonl", queue_size=2)
    gate = threading.Event()
    real = log._write
    log._write = lambda recs, force_sync=False: (gate.wait(5.0), real(recs, force_sync))
    loop = GovernedLoop(ethimon.Monitor(ethimon.load_spec_text(SPEC)), risk=src, audit=log, clock=clock,
                        config=LoopConfig(period_s=0.001, audit_every_cycle=True))
    decisions = []
    for _ in range(10):
        clock.advance(0.001)
        decisions.append(loop.cycle(GOOD))
    assert loop.stats.audit_drops > 0
    faulted = [d for d in decisions if any(f.kind == "audit" and "audit log failed or its queue is full" in f.message
                                          for f in d.faults)]
    assert faulted and all(d.override for d in faulted)
    gate.set()
    log.close()
    recs = read_log(tmp_path / "audit.jsonl")
    assert sum(r["count"] for r in recs if r["kind"] == "dropped") == log.dropped > 0


def test_on_decision_callback_raising_overrides_next_cycle(tmp_path):
    clock = FakeClock()
    src = AsyncRiskSource(ScriptedEstimator(), text="t", clock=clock, start=False)
    src.poll_once()

    def actuator(d):
        raise ConnectionError("franka: communication_constraints_violation")

    loop = GovernedLoop(ethimon.Monitor(ethimon.load_spec_text(SPEC)), risk=src, clock=clock,
                        on_decision=actuator, config=LoopConfig(period_s=0.001))
    loop.cycle(GOOD)
    clock.advance(0.001)
    d = loop.cycle(GOOD)
    assert d.override and any(f.kind == "callback" and "on_decision callback raised ConnectionError" in f.message
                                for f in d.faults)


# ---------------------------------------------------------------- Monitor.fault (core hook)
def test_monitor_fault_as_its_own_cycle():
    m = ethimon.Monitor(ethimon.load_spec_text(SPEC))
    d = m.fault("estimator died")
    assert d.override and d.response is Response.STOP_1 and d.cycle == 0
    assert d.faults == (ethimon.Fault("external", "estimator died"),)
    assert m.cycle == 1 and m.latched
    assert all(math.isnan(x) for x in d.margins)


def test_monitor_fault_escalates_a_stepped_cycle():
    m = ethimon.Monitor(ethimon.load_spec_text(SPEC))
    inputs = {**GOOD, "p_unsafe": 0.05, "risk_age_s": 0.0}
    d = m.step(inputs)
    e = m.fault("late", decision=d)
    assert e.cycle == d.cycle and m.cycle == 1 and e.faults == (ethimon.Fault("external", "late"),)
    assert e.override and e.response is Response.STOP_1 and e.margins == d.margins
    # a more severe violation is kept, not lowered to on_fault
    spec0 = ethimon.load_spec_text(SPEC.replace("response: stop_2", "response: stop_0"))
    m0 = ethimon.Monitor(spec0)
    d = m0.step({**inputs, "human_distance": 0.1})
    e = m0.fault("late", decision=d)
    assert e.response is Response.STOP_0 and e.violations == ("keep_away",)
    # and it latches: clean cycles are needed to release
    d = m.step(inputs)
    assert d.override and d.latched
