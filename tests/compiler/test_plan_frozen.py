"""The plan is frozen and holds the whole risk rule and the tiers (issue 33, item 2): consumers
read ``plan.risk_plan`` and ``plan.tiers``, never ``spec.risk`` again; the accepted risk range is
written once (``RiskPlan.accepted``)."""

from __future__ import annotations

import dataclasses
from fractions import Fraction

import pytest

import ethimon
from ethimon.compiler import plan_of
from ethimon.compiler._plan import LatchRule, RiskPlan, Tiers
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
    assert tiers == Tiers(0.1, (0.2, 0.8), 0.5) and tiers.on
