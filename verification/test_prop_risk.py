"""The R_e formula: bounds, monotonicity, agreement with numpy and with the monitor."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import assume, given
from hypothesis import strategies as st

import ethimon
from ethimon.risk._formula import risk_bounds, risk_from_p_unsafe, risk_from_probs

unit = st.floats(0.0, 1.0, allow_nan=False)
weight = st.floats(0.0, 2.0, allow_nan=False)
variance = st.sampled_from(("sample", "population"))


def weights_monotone(a: float, b: float, g: float, var: str) -> bool:
    """R_e(q) is non-decreasing on [0, 1] iff both pieces have a non-negative slope at their left end.

    On [0, ½]: dR/dq = α + β + 2cγ(q − ½) ≥ α + β − cγ; on [½, 1]: α − β + 2cγ(q − ½) ≥ α − β
    (c = 2 for the sample variance of two classes, 1 for the population variance).
    """
    c = 2.0 if var == "sample" else 1.0
    return a >= b and a + b >= c * g


@given(unit)
def test_paper_weights_two_classes_sample_variance_stay_in_0_1_to_0_7(q):
    r = risk_from_p_unsafe(q, 0.6, 0.2, 0.2, "sample")
    assert 0.1 - 1e-12 <= r <= 0.7 + 1e-12


def test_paper_bounds_are_attained():
    lo, hi = risk_bounds(0.6, 0.2, 0.2, "sample")
    assert math.isclose(lo, 0.1) and math.isclose(hi, 0.7)
    assert math.isclose(risk_from_p_unsafe(0.0), 0.1) and math.isclose(risk_from_p_unsafe(1.0), 0.7)


@given(weight, weight, weight, variance, unit)
def test_risk_bounds_bracket_every_p_unsafe(a, b, g, var, q):
    lo, hi = risk_bounds(a, b, g, var)
    r = risk_from_p_unsafe(q, a, b, g, var)
    eps = 1e-12 * max(1.0, abs(lo), abs(hi))
    assert lo - eps <= r <= hi + eps


@given(weight, weight, weight, variance)
def test_risk_bounds_are_tight(a, b, g, var):
    lo, hi = risk_bounds(a, b, g, var)
    grid = [risk_from_p_unsafe(i / 4000, a, b, g, var) for i in range(4001)]
    # the bounds are reached (up to the grid spacing's effect on a smooth function)
    slack = 1e-3 * (1 + a + b + g)
    assert min(grid) - slack <= lo <= min(grid) + 1e-12
    assert max(grid) - 1e-12 <= hi <= max(grid) + slack


@given(weight, weight, weight, variance, unit, unit)
def test_monotone_in_p_unsafe_for_monotone_weights(a, b, g, var, q1, q2):
    assume(weights_monotone(a, b, g, var))
    lo, hi = min(q1, q2), max(q1, q2)
    r1, r2 = risk_from_p_unsafe(lo, a, b, g, var), risk_from_p_unsafe(hi, a, b, g, var)
    assert r1 <= r2 + 1e-12 * (1 + a + b + g)


@given(unit, unit)
def test_paper_weights_are_monotone(q1, q2):
    assert weights_monotone(0.6, 0.2, 0.2, "sample")
    lo, hi = min(q1, q2), max(q1, q2)
    assert risk_from_p_unsafe(lo) <= risk_from_p_unsafe(hi) + 1e-15


def test_non_negative_weights_alone_do_not_make_r_e_monotone():
    # α, β, γ ≥ 0 is not enough: with β > α a more unsafe score lowers R_e above ½
    assert not weights_monotone(0.1, 0.5, 0.0, "sample")
    assert risk_from_p_unsafe(0.9, 0.1, 0.5, 0.0) < risk_from_p_unsafe(0.6, 0.1, 0.5, 0.0)
    # and with a large γ the variance term dominates below ½
    assert not weights_monotone(0.1, 0.1, 1.0, "sample")
    assert risk_from_p_unsafe(0.0, 0.1, 0.1, 1.0) > risk_from_p_unsafe(0.2, 0.1, 0.1, 1.0)


@st.composite
def prob_vectors(draw, k_max: int = 7):
    k = draw(st.integers(2, k_max))
    raw = draw(st.lists(st.floats(0.0, 1.0), min_size=k, max_size=k))
    s = sum(raw)
    assume(s > 1e-6)
    return [v / s for v in raw]


@given(prob_vectors(), weight, weight, weight, variance, st.data())
def test_exact_agreement_with_numpy(p, a, b, g, var, data):
    u = data.draw(st.integers(-len(p), len(p) - 1))
    arr = np.asarray(p, dtype=np.float64)
    expect = a * arr[u] + b * (1.0 - arr.max()) + g * np.var(arr, ddof=1 if var == "sample" else 0)
    got = risk_from_probs(p, a, b, g, var, u)
    assert got == float(expect) or math.isclose(got, float(expect), rel_tol=0, abs_tol=4 * np.finfo(float).eps)


@given(unit, weight, weight, weight, variance)
def test_two_class_closed_form_matches_the_vector_form(q, a, b, g, var):
    r1 = risk_from_p_unsafe(q, a, b, g, var)
    r2 = risk_from_probs([1.0 - q, q], a, b, g, var)
    assert math.isclose(r1, r2, rel_tol=1e-12, abs_tol=1e-12)


SPEC = """
ethimon: 1
name: r
risk: {{alpha: {a}, beta: {b}, gamma: {g}, variance: {var}, threshold: 10.0,
        allow: {{threshold: "R_e formation only: the rule must never fire", weights: "zero weights are an edge case"}}}}
"""


@given(unit, st.sampled_from((0.0, 0.2, 0.6, 1.0)), st.sampled_from((0.0, 0.2, 0.5)),
       st.sampled_from((0.0, 0.2, 0.8)), variance)
def test_monitor_forms_r_e_exactly_as_the_formula(q, a, b, g, var):
    spec = ethimon.load_spec_text(SPEC.format(a=a, b=b, g=g, var=var))
    m = ethimon.Monitor(spec)
    assert m.step({"p_unsafe": q}).risk == risk_from_p_unsafe(q, a, b, g, var)
    assert m.step({"p": (1.0 - q, q)}).risk == risk_from_probs([1.0 - q, q], a, b, g, var)
    assert m.step({"risk": 0.25}).risk == 0.25
