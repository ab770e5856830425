"""Faults are values: ``Fault(kind, message)``, a kind from a closed set, never parsed from text."""

from __future__ import annotations

import json
import math

import pytest

import ethimon
from ethimon.audit import AuditLog, read_log, verify_log
from ethimon.loop import AsyncRiskSource, GovernedLoop, LoopConfig
from ethimon.runtime import FAULT_KINDS, Fault

from tests._estimators import FakeClock, ScriptedEstimator

SPEC = """
ethimon: 1
name: kinds
signals:
  d: {unit: m, range: [0, 10]}
  ok: {type: bool}
risk: {threshold: 0.5, max_age_s: 0.2}
obligations:
  - {id: near, require: "d >= 0.5 and ok"}
  - {id: div, require: "1 / (d - 2) > -100"}
"""
GOOD = {"d": 3.0, "ok": True, "p_unsafe": 0.05, "risk_age_s": 0.0}


def _spec(text=SPEC):
    return ethimon.load_spec_text(text)


@pytest.mark.parametrize("change, kind", [
    ({"d": None}, "missing"),
    ({"p_unsafe": None}, "missing"),
    ({"risk_age_s": None}, "missing"),
    ({"d": "3"}, "invalid"),
    ({"d": math.nan}, "invalid"),
    ({"d": math.inf}, "invalid"),
    ({"ok": "yes"}, "invalid"),
    ({"p_unsafe": math.nan}, "invalid"),
    ({"p_unsafe": None, "p": [0.5, 0.6]}, "invalid"),
    ({"d": 11.0}, "range"),
    ({"p_unsafe": 1.5}, "range"),
    ({"p_unsafe": None, "risk": 5.0}, "range"),
    ({"risk_age_s": 0.5}, "stale"),
    ({"risk_age_s": -1.0}, "stale"),
    ({"d": 2.0}, "internal"),  # 1 / 0 inside an obligation
])
def test_each_monitor_fault_has_its_kind(change, kind):
    frame = dict(GOOD)
    for k, v in change.items():
        if v is None:
            frame.pop(k)
        else:
            frame[k] = v
    d = ethimon.Monitor(_spec()).step(frame)
    assert d.override and [f.kind for f in d.faults] == [kind], d.faults
    assert all(type(f) is Fault and f.kind in FAULT_KINDS and f.message for f in d.faults)


def test_a_fault_is_an_immutable_value_not_a_string():
    f = Fault("stale", "risk estimate is stale: 0.6 s > 0.5 s")
    assert (f.kind, f.message, str(f)) == ("stale", "risk estimate is stale: 0.6 s > 0.5 s", f.message)
    assert f == Fault("stale", f.message) and hash(f) == hash(Fault("stale", f.message))
    assert f != Fault("range", f.message) and f != f.message
    with pytest.raises(AttributeError):
        f.kind = "range"
    with pytest.raises(TypeError):
        "stale" in f  # noqa: B015 - text matching is exactly what must not work silently
    with pytest.raises(ValueError, match="not one of"):
        Fault("nan-ish", "x")
    assert f.as_dict() == {"kind": "stale", "message": f.message, "subject": ""}
    g = Fault("missing", "signal 'a' is missing", "a")
    assert g.subject == "a" and g != Fault("missing", g.message) and "subject='a'" in repr(g)
    assert repr(f) == "Fault('stale', 'risk estimate is stale: 0.6 s > 0.5 s')"


def test_decision_as_dict_keeps_messages_and_adds_kinds():
    d = ethimon.Monitor(_spec()).step({**GOOD, "d": 11.0, "ok": "no"})
    doc = json.loads(json.dumps(d.as_dict()))
    assert doc["fault_kinds"] == ["range", "invalid"] and doc["faults"] == [f.message for f in d.faults]
    assert d.reasons[-1] == "fault: " + d.faults[-1].message


def test_monitor_fault_wraps_text_as_external_and_keeps_fault_values():
    m = ethimon.Monitor(_spec())
    d = m.fault("estimator died", Fault("deadline", "late"))
    assert d.faults == (Fault("external", "estimator died"), Fault("deadline", "late"))


def test_the_missing_signal_fault_is_built_once_not_per_cycle():
    m = ethimon.Monitor(_spec())
    a, b = m.step({**GOOD, "d": None}).faults[0], m.step({**GOOD, "d": None}).faults[0]
    assert a is b and a.kind == "missing"


# ---------------------------------------------------------------- one judge, one limit
def _loop(spec_text, config=LoopConfig(period_s=10.0), **kw):
    clock = FakeClock()
    src = AsyncRiskSource(ScriptedEstimator(), text="t", clock=clock, start=False)
    src.poll_once()
    return GovernedLoop(ethimon.Monitor(_spec(spec_text)), risk=src, clock=clock, config=config, **kw), clock


def test_staleness_is_judged_once_by_the_monitor_with_the_loop_limit_as_fallback():
    loop, clock = _loop(SPEC.replace(", max_age_s: 0.2", ""), config=LoopConfig(period_s=10.0, max_risk_age_s=0.3))
    assert loop.monitor.max_age_s == 0.3
    assert not loop.cycle({"d": 3.0, "ok": True}).override
    clock.advance(1.0)
    d = loop.cycle({"d": 3.0, "ok": True})
    assert [f.kind for f in d.faults] == ["stale"], d.faults  # once, not by the loop and the monitor
    assert loop.stats.stale_overrides == 1 and loop.stats.risk_faults == 1


def test_the_spec_age_limit_wins_over_the_loop_setting():
    loop, clock = _loop(SPEC, config=LoopConfig(period_s=10.0, max_risk_age_s=5.0))
    assert loop.monitor.max_age_s == 0.2
    clock.advance(0.3)
    d = loop.cycle({"d": 3.0, "ok": True})
    assert [f.kind for f in d.faults] == ["stale"]


def test_without_a_risk_source_the_loop_sets_no_age_limit():
    spec = _spec(SPEC.replace(", max_age_s: 0.2", ""))
    loop = GovernedLoop(ethimon.Monitor(spec), clock=FakeClock(), config=LoopConfig(period_s=10.0, max_risk_age_s=0.3))
    assert loop.monitor.max_age_s is None
    assert not loop.cycle({"d": 3.0, "ok": True, "p_unsafe": 0.05}).override


def test_probabilities_are_judged_once_by_the_monitor():
    clock = FakeClock()
    est = ScriptedEstimator(mode="nan")
    src = AsyncRiskSource(est, text="t", clock=clock, start=False)
    assert src.poll_once().fault is None  # the source only reads the output into floats
    loop = GovernedLoop(ethimon.Monitor(_spec()), risk=src, clock=clock, config=LoopConfig(period_s=10.0))
    d = loop.cycle({"d": 3.0, "ok": True})
    assert [f.kind for f in d.faults] == ["invalid"] and d.faults[0].message.startswith("p contains nan")
    assert loop.stats.risk_faults == 1


def test_audit_records_fault_messages_and_kinds(tmp_path):
    clock = FakeClock()
    src = AsyncRiskSource(ScriptedEstimator(), text="t", clock=clock, start=False)
    src.poll_once()
    log = AuditLog(tmp_path / "a.jsonl")
    loop = GovernedLoop(ethimon.Monitor(_spec()), risk=src, audit=log, clock=clock, config=LoopConfig(period_s=10.0))
    loop.cycle({"d": 3.0, "ok": True})
    loop.cycle({"d": 11.0, "ok": True})
    loop.cycle({"d": 12.0, "ok": True})  # same kinds, another number: no new state, no new record
    log.close()
    assert verify_log(tmp_path / "a.jsonl", require_closed=True).ok
    recs = [r for r in read_log(tmp_path / "a.jsonl") if r["kind"] == "decision"]
    assert len(recs) == 2
    assert recs[1]["fault_kinds"] == ["range"] and "outside its range" in recs[1]["faults"][0]
