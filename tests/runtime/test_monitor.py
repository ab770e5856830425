"""Behaviour of Monitor.step: risk rule, inputs, fail-closed, latch/release, temporal operators."""

import math

import numpy as np
import pytest

import ethimon
from ethimon.testing import ReferenceMonitor
from ethimon import Response


def spec_text(obligations: str = "", signals: str = "", extra: str = "") -> str:
    return ("ethimon: 1\nname: t\n"
            + (f"signals:\n{signals}" if signals else "")
            + (f"obligations:\n{obligations}" if obligations else "") + extra)


SIG = "  d: {unit: m, range: [0, 10]}\n  v: {unit: m/s, range: [0, 3]}\n  ok: {type: bool}\n"


def mon(obligations="", signals=SIG, extra=""):
    return ethimon.Monitor(ethimon.load_spec_text(spec_text(obligations, signals, extra)))


def inp(**kw):
    base = {"p_unsafe": 0.05, "d": 5.0, "v": 0.1, "ok": True}
    base.update(kw)
    return base


def test_risk_rule_inclusive_threshold_and_inputs():
    m = mon()
    assert not m.step(inp(risk=0.4999)).override
    m.reset()
    d = m.step(inp(risk=0.5))
    assert d.override and d.violations == ("risk",) and d.response is Response.SAFE_POSE and d.risk == 0.5
    m.reset()
    d = m.step(inp(p_unsafe=0.9))
    assert d.override and d.risk == pytest.approx(ethimon.risk_from_p_unsafe(0.9))
    m.reset()
    d = m.step({**inp(), "p_unsafe": None, "p": np.array([0.2, 0.8])})
    assert d.risk == pytest.approx(ethimon.risk_from_probs([0.2, 0.8]))


def test_risk_input_priority_risk_then_p_unsafe_then_p():
    m = mon()
    d = m.step(inp(risk=0.2, p_unsafe=0.99, p=[0.0, 1.0]))
    assert d.risk == 0.2 and not d.override


@pytest.mark.parametrize("bad,reason", [
    ({"d": None}, "missing"),
    ({"d": math.nan}, "NaN"),
    ({"d": 11.0}, "outside"),
    ({"d": -0.1}, "outside"),
    ({"d": math.inf}, "outside"),
    ({"d": "3"}, "must be a number"),
    ({"d": True}, "must be a number"),
    ({"d": [1.0]}, "must be a number"),
    ({"d": np.float32(11.0)}, "outside"),
    ({"ok": 2}, "true/false"),
    ({"ok": "yes"}, "true/false"),
    ({"p_unsafe": None}, "no risk input"),
    ({"p_unsafe": math.nan}, "p_unsafe"),
    ({"p_unsafe": 1.2}, "p_unsafe"),
    ({"p_unsafe": None, "p": [0.5, 0.6]}, "sums to"),
    ({"p_unsafe": None, "p": [1.0]}, "classes"),
    ({"p_unsafe": None, "p": 0.3}, "sequence"),
    ({"p_unsafe": None, "risk": math.nan}, "risk input"),
])
def test_bad_inputs_fail_closed_with_reason(bad, reason):
    m = mon("  - {id: near, require: 'd > 0.5 and ok'}\n")
    kw = inp()
    for k, v in bad.items():
        if v is None:
            kw.pop(k, None)
        else:
            kw[k] = v
    d = m.step(kw)
    assert d.override and d.faults and any(reason in f.message for f in d.faults), d.faults
    assert d.response is Response.SAFE_POSE


def test_non_mapping_and_internal_errors_fail_closed():
    m = mon("  - {id: div, require: '1 / (d - 2) > 0'}\n")
    d = m.step(None)
    assert d.override and d.faults[0].kind == "internal" and d.faults[0].message.startswith("internal error")
    d = m.step(inp(d=2.0))  # division by zero inside an obligation
    assert d.override and d.faults[0].kind == "internal" and "ZeroDivisionError" in d.faults[0].message


def test_extra_keys_ignored_and_stale_risk():
    m = mon(extra="risk: {max_age_s: 0.1}\n")
    assert not m.step(inp(risk_age_s=0.05, unknown_key=object())).override
    d = m.step(inp(risk_age_s=0.2))
    assert d.override and d.faults[0].kind == "stale" and "stale" in d.faults[0].message
    d = m.step(inp())
    assert d.override and d.faults[0].kind == "missing" and "risk_age_s is missing" in d.faults[0].message


def test_fault_response_and_most_severe_wins():
    m = mon("  - {id: a, require: 'd > 1', response: stop_2}\n  - {id: b, require: 'v < 1', response: stop_0}\n",
            extra="on_fault: stop_1\n")
    d = m.step(inp(d=0.5))
    assert d.response is Response.STOP_2
    d = m.step(inp(d=0.5, v=2.0))
    assert d.response is Response.STOP_0 and d.violations == ("a", "b")
    m.reset()
    d = m.step(inp(d=math.nan))
    assert d.response is Response.STOP_1
    m.reset()
    d = m.step(inp(d=math.nan, p_unsafe=None, risk=0.9))
    assert d.violations == ("risk",) and d.response is Response.STOP_1  # fault (stop_1) beats risk (safe_pose)


def test_latch_and_release_with_hysteresis():
    m = mon(extra="risk: {threshold: 0.5, release: {hysteresis: 0.1, hold_cycles: 3}}\n")
    assert m.step(inp(risk=0.6)).override
    # below tau but not below tau - delta: stays latched, never counts
    for _ in range(5):
        d = m.step(inp(risk=0.45))
        assert d.override and d.latched and not d.violations
    # below tau - delta: releases at the third consecutive cycle
    assert m.step(inp(risk=0.3)).override
    assert m.step(inp(risk=0.3)).override
    d = m.step(inp(risk=0.3))
    assert not d.override and not d.latched
    # an interruption restarts the count
    m.step(inp(risk=0.7))
    m.step(inp(risk=0.3))
    m.step(inp(risk=0.45))
    m.step(inp(risk=0.3))
    assert m.step(inp(risk=0.3)).override
    assert not m.step(inp(risk=0.3)).override


def test_latched_response_keeps_most_severe_until_release():
    m = mon("  - {id: a, require: 'v < 1', response: stop_0}\n", extra="risk: {release: {hold_cycles: 2}}\n")
    m.step(inp(v=2.0))
    d = m.step(inp(risk=0.6))  # risk response is safe_pose, latch keeps stop_0
    assert d.response is Response.STOP_0


def test_manual_release_only_by_reset_or_release():
    m = mon(extra="risk: {release: {mode: manual}}\n")
    m.step(inp(risk=0.9))
    for _ in range(50):
        assert m.step(inp(risk=0.1)).override
    m.release()
    assert not m.step(inp(risk=0.1)).override
    m.step(inp(risk=0.9))
    m.reset()
    d = m.step(inp(risk=0.1))
    assert not d.override and d.cycle == 0


def test_bounded_response_within_cycles():
    m = mon("  - {id: slow, when: 'd < 1', require: 'v <= 0.25', within_cycles: 3}\n")
    assert not m.step(inp(d=0.8, v=1.0)).override  # trigger at 0
    assert not m.step(inp(d=0.8, v=1.0)).override
    assert not m.step(inp(d=0.8, v=1.0)).override
    d = m.step(inp(d=0.8, v=1.0))  # 3 cycles after the trigger with no response
    assert d.override and d.violations == ("slow",)
    m.reset()
    for v in (1.0, 1.0, 0.2, 0.2, 1.0):  # answered at cycle 2; re-triggered at 4
        assert not m.step(inp(d=0.8, v=v)).override


def test_temporal_operators_semantics():
    m = mon("  - {id: h, require: 'not held(d < 1, 3)'}\n")
    assert [m.step(inp(d=0.5)).violations != () for _ in range(4)] == [False, False, True, True]
    m = mon("  - {id: o, require: 'not once(d < 1, 3)'}\n")
    seq = [0.5, 5, 5, 5, 5]
    assert [m.step(inp(d=x)).violations != () for x in seq] == [True, True, True, False, False]
    m = mon("  - {id: p, require: 'prev(d, 9) >= 1'}\n")
    assert [m.step(inp(d=x)).violations != () for x in (0.5, 2, 0.5, 3)] == [False, True, False, True]
    m = mon("  - {id: s, require: 'not since(v > 1, d < 1, 3)'}\n")
    # since: d<1 at j, v>1 at every cycle after j, and t - j < 3
    seq = [(0.5, 0), (5, 2), (5, 2), (5, 2), (0.5, 0), (5, 0)]
    assert [m.step(inp(d=a, v=b)).violations != () for a, b in seq] == [True, True, True, False, True, False]


def test_fault_clears_temporal_history():
    # the fault latch releases by itself here (the default is manual): this test is about history
    m = mon("  - {id: h, require: 'not held(d < 1, 3)'}\n",
            extra="risk: {release: {hold_cycles: 1}}\non_fault: {response: safe_pose, release: auto}\n")
    m.step(inp(d=0.5))
    m.step(inp(d=0.5))
    assert m.step(inp(d=math.nan)).faults
    assert not m.step(inp(d=0.5)).override  # the window restarted after the fault
    assert not m.step(inp(d=0.5)).override
    assert m.step(inp(d=0.5)).override


def test_margins_are_robustness():
    m = mon("  - {id: a, require: 'd >= 1'}\n  - {id: b, when: 'd < 2', require: 'v <= 0.5'}\n  - {id: c, require: ok}\n")
    d = m.step(inp(d=1.5, v=0.2))
    assert d.margins[0] == pytest.approx(0.5) and d.margins[1] == pytest.approx(0.3) and d.margins[2] == math.inf
    d = m.step(inp(d=0.5, v=0.2, ok=False))
    assert d.margins[0] == pytest.approx(-0.5) and d.margins[2] == -math.inf
    assert all(math.isnan(x) for x in m.step(inp(d=math.nan)).margins)
    assert ethimon.Monitor(m.spec, margins=False).step(inp()).margins == ()


def test_cycle_counter_and_decision_dict():
    m = mon()
    for i in range(3):
        assert m.step(inp()).cycle == i
    d = m.step(inp(risk=0.9)).as_dict()
    assert d["override"] is True and d["response"] == "safe_pose" and d["violations"] == ["risk"]


def test_shipped_specs_load_and_step(root):
    for name in ("governor", "cobot_cell"):
        spec = ethimon.load_spec(root / "specs" / f"{name}.yaml")
        m = ethimon.Monitor(spec)
        d = m.step({"p_unsafe": 0.02, "human_distance": 5.0, "ee_speed": 0.1, "contact_force": 0.0,
                    "joint_speed_max": 0.2})
        assert not d.override, d


def test_fault_does_not_hide_a_more_severe_stateless_violation(root):
    spec = ethimon.load_spec(root / "specs" / "cobot_cell.yaml")  # on_fault: stop_1
    for monitor in (ethimon.Monitor(spec), ReferenceMonitor(spec)):
        d = monitor.step({"human_distance": 5.0, "ee_speed": 0.1, "contact_force": 300.0,
                          "joint_speed_max": 0.2})  # no risk input: a fault
        assert d.override and d.faults
        assert d.violations == ("transient_contact",) and d.response is Response.STOP_0
        # an obligation that reads the bad input is not judged on stale values
        d = monitor.step({"p_unsafe": 0.1, "human_distance": math.nan, "ee_speed": 0.1,
                          "contact_force": 0.0, "joint_speed_max": 0.2})
        assert "separation" not in d.violations


def test_fault_with_risk_over_threshold_reports_risk():
    m = mon("  - {id: a, require: 'v < 1', response: stop_2}\n")
    d = m.step(inp(d=math.nan, v=2.0, p_unsafe=0.99))
    assert d.violations == ("a", "risk") and d.response is Response.STOP_2


def test_wrong_type_signal_still_judges_other_stateless_rules():
    m = mon("  - {id: near, require: 'd > 0.5'}\n  - {id: fast, require: 'v < 1', response: stop_0}\n")
    d = m.step(inp(d=[1.0], v=2.0))  # a list is bad input (not an internal error)
    assert d.override and d.violations == ("fast",) and d.response is Response.STOP_0
    ref = ReferenceMonitor(m.spec)
    r = ref.step(inp(d=[1.0], v=2.0))
    assert r.violations == d.violations and r.response is d.response
