"""The rounding bound behind "proved (real arithmetic)" (issue 31 item 6) is sound: on random
arithmetic over in-range doubles, the double a term computes (as the Monitor computes it) is never
farther from its exact real value than the bound ``verify`` uses; and a comparison whose doubles
decide otherwise than the reals on sampled inputs, by more than the inputs' own precision, is labelled."""

from __future__ import annotations

from fractions import Fraction

import pytest
from hypothesis import given, note
from hypothesis import strategies as st

import ethimon
from ethimon.compiler import plan_of
from ethimon.language._expr import Binary, Name, Num
from ethimon.verify._floats import _Err, exact_value, rounding_hazards

SPEC = """
ethimon: 1
name: floats
signals:
  x: {range: [0, 10]}
  y: {range: [-1000, 1000000]}
obligations:
  - {id: o, require: "%s >= 1.5"}
"""

_CONST = st.sampled_from(["0.1", "3", "2.5", "0.5", "1e16", "1e6", "1e-7", "7.25"])
_LEAF = st.one_of(st.just("x"), st.just("y"), _CONST)


def _tree(depth: int):
    if depth == 0:
        return _LEAF
    sub = _tree(depth - 1)
    return st.one_of(_LEAF, st.tuples(sub, st.sampled_from(["+", "-", "*"]), sub).map(
        lambda t: f"({t[0]} {t[1]} {t[2]})"))


def _double(plan, node, env):
    """The term in Python floats, as the Monitor computes it."""
    if isinstance(node, Num):
        return float(node.value)
    if isinstance(node, Name):
        return float(env[node.id])
    a, b = _double(plan, node.left, env), _double(plan, node.right, env)
    return {"+": a + b, "-": a - b, "*": a * b}[node.op]


_X = st.floats(0, 10, allow_nan=False)
_Y = st.floats(-1000, 1e6, allow_nan=False)


@pytest.mark.slow
@given(_tree(3), st.lists(st.tuples(_X, _Y), min_size=1, max_size=8))
def test_the_rounding_bound_holds_on_random_arithmetic(expr, points):
    plan = plan_of(ethimon.load_spec_text(SPEC % expr))
    ob = plan.obligations[0]
    side = ob.require.left
    note(expr)
    got = _Err(plan).of(side)
    assert got is not None
    bound = got[0]
    for x, y in points:
        env = {"x": x, "y": y}
        real = exact_value(plan, side, {k: Fraction(v) for k, v in env.items()})
        dbl = _double(plan, side, env)
        if abs(dbl) == float("inf"):
            continue  # an overflow: float_hazards' other check
        assert abs(Fraction(dbl) - real) <= Fraction(bound) * (1 + Fraction(1, 1 << 40)), (x, y, dbl, bound)


@pytest.mark.slow
@given(st.floats(0, 10, allow_nan=False), st.sampled_from(["1e16", "1e12", "1e9"]))
def test_absorption_that_flips_a_verdict_is_labelled(x, big):
    """Wherever ``(x + big) - big >= 1.5`` decides otherwise in doubles than in the reals, verify labels it."""
    spec = ethimon.load_spec_text(SPEC % f"((x + {big}) - {big})")
    plan = plan_of(spec)
    real = Fraction(x) >= Fraction(3, 2)
    dbl = (x + float(big)) - float(big) >= 1.5
    if real != dbl:
        assert rounding_hazards(plan, plan.obligations[0]), (x, big)
