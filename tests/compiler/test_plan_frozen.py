"""The plan is frozen and holds the whole risk rule and the tiers (issue 33, item 2): consumers
read ``plan.risk_plan`` and ``plan.tiers``, never ``spec.risk`` again; the accepted risk range is
written once (``RiskPlan.accepted``)."""

from __future__ import annotations

import dataclasses
from fractions import Fraction

import pytest

import ethimon
from ethimon.compiler import plan_of
from ethimon.compiler._plan import EstimatorPlan, JudgePlan, LatchRule, RestartPlan, RiskPlan, Tiers
from ethimon.compiler._plans import spec_without_tiers
from ethimon.compiler._risk_formula import risk_range

SPEC = """ethimon: 1
name: plan-risk
signals:
  x: {range: [0, 4]}
risk:
  threshold: 0.27
  classes: 3
  unsafe_index: 1
  alpha: 0.5
  beta: 0.3
  gamma: 0.2
  variance: population
  max_age_s: 0.5
  response: stop_2
  release: {mode: manual, hysteresis: 0.05, hold_cycles: 4}
obligations:
  - {id: slow, require: "x < 2"}
"""


def test_the_plan_is_frozen():
    plan = plan_of(ethimon.load_spec_text(SPEC))
    with pytest.raises(dataclasses.FrozenInstanceError):
        plan.threshold = 0.9  # type: ignore[misc]
    with pytest.raises(dataclasses.FrozenInstanceError):
        plan.risk_plan.threshold = 0.9  # type: ignore[misc]


def test_the_plan_holds_the_whole_risk_rule():
    spec = ethimon.load_spec_text(SPEC)
    rp = plan_of(spec).risk_plan
    assert isinstance(rp, RiskPlan)
    assert (rp.threshold, rp.alpha, rp.beta, rp.gamma, rp.classes, rp.unsafe_index, rp.variance, rp.max_age_s) == (
        0.27, 0.5, 0.3, 0.2, 3, 1, "population", 0.5)
    assert rp.release_exact == Fraction(22, 100) and rp.release_cut == plan_of(spec).release_cut
    assert rp.latch == LatchRule("risk", ethimon.Response.STOP_2, True, 4) == plan_of(spec).risk_rule
    assert rp.hysteresis == 0.05
    lo, hi = risk_range(0.5, 0.3, 0.2, "population", 3)
    assert rp.reachable == (lo, hi) and rp.accepted == (min(0.0, lo), max(1.0, hi))


def test_the_monitor_and_the_reference_accept_the_plans_range():
    spec = ethimon.load_spec_text(SPEC.replace("alpha: 0.5", "alpha: 1.5"))  # R_e can exceed 1
    lo, hi = plan_of(spec).risk_plan.accepted
    assert hi > 1.0
    from ethimon.testing import ReferenceMonitor
    for v, ok in ((hi, True), (hi * 1.0001, False), (lo, True), (-0.01, False)):
        for mon in (ethimon.Monitor(spec), ReferenceMonitor(spec)):
            d = mon.step({"x": 1.0, "risk": v, "risk_age_s": 0.0})
            assert (not d.faults) is ok, (type(mon).__name__, v, d.faults)


def test_the_tiers_are_resolved_once():
    plan = plan_of(ethimon.load_spec_text(SPEC))
    assert plan.tiers == Tiers() and not plan.tiers.on
    text = SPEC.replace("  max_age_s: 0.5\n", "  max_age_s: 0.5\n  confirm_threshold: 0.1\n"
                        "  judge: {url: 'http://127.0.0.1:9/v1', model: m, safe_below: 0.2, unsafe_from: 0.8}\n"
                        "  judge_may_hold_above_tau: {ceiling: 0.5}\n")
    tiers = plan_of(ethimon.load_spec_text(text)).tiers
    judge = JudgePlan("risk.judge", "http://127.0.0.1:9/v1", "m", 5.0, None, None, 0.2, 0.8, None, 600.0, 500)
    assert tiers == Tiers(0.1, (0.2, 0.8), 0.5, (judge,), False) and tiers.on


def test_the_tiers_hold_every_judge_and_where_it_is_written():
    text = SPEC.replace("  max_age_s: 0.5\n", "  max_age_s: 0.5\n  judges:\n"
                        "    - {url: 'http://127.0.0.1:9/v1', model: a, safe_below: 0.1, api_key_env: K,\n"
                        "       canaries: {path: c.csv, every_s: 60, every_texts: 7}}\n"
                        "    - {url: 'http://127.0.0.1:8/v1', model: b, unsafe_from: 0.9, prompt: rubric}\n")
    t = plan_of(ethimon.load_spec_text(text)).tiers
    assert t.consensus and t.judge_cuts == (0.1, 0.9) and t.on
    assert [j.where for j in t.judges] == ["risk.judges[0]", "risk.judges[1]"]
    assert t.judges[0] == JudgePlan("risk.judges[0]", "http://127.0.0.1:9/v1", "a", 5.0, "K", None, 0.1, 0.8, "c.csv",
                                    60.0, 7)
    assert (t.judges[1].model, t.judges[1].prompt, t.judges[1].unsafe_from) == ("b", "rubric", 0.9)
    one = plan_of(ethimon.load_spec_text(text.replace(
        "    - {url: 'http://127.0.0.1:8/v1', model: b, unsafe_from: 0.9, prompt: rubric}\n", ""))).tiers
    assert one.consensus and [j.where for j in one.judges] == ["risk.judges[0]"]  # a panel of one is a panel


def test_the_plan_holds_the_estimator_settings_and_the_restart_block():
    plan = plan_of(ethimon.load_spec_text(SPEC))
    assert plan.estimator == EstimatorPlan(None, None, None, None, "auto") and plan.restart is None
    text = SPEC.replace("  max_age_s: 0.5\n", "  max_age_s: 0.5\n  estimator: {model: m, quantize: int8, "
                        "temperature: 2, max_length: 64, backend: onnx}\n") + "restart: {standstill: x_ok}\n"
    text = text.replace("  x: {range: [0, 4]}\n", "  x: {range: [0, 4]}\n  x_ok: {type: bool}\n")
    plan = plan_of(ethimon.load_spec_text(text))
    assert plan.estimator == EstimatorPlan("m", "int8", 2.0, 64, "onnx")
    assert plan.restart == RestartPlan("command", "x_ok")


def test_the_compiler_builds_the_spec_without_its_tiers():
    spec = ethimon.load_spec_text(SPEC)
    assert spec_without_tiers(spec) is spec
    text = SPEC.replace("  max_age_s: 0.5\n", "  max_age_s: 0.5\n  confirm_threshold: 0.1\n"
                        "  judge: {url: 'http://127.0.0.1:9/v1', model: m}\n  judge_may_hold_above_tau: {ceiling: 0.5}\n")
    full = ethimon.load_spec_text(text)
    base = spec_without_tiers(full)
    assert plan_of(base).tiers == Tiers() and plan_of(full).tiers.on
    assert plan_of(base).risk_plan == plan_of(full).risk_plan  # the same rule, without the tiers
