"""Issue 31 item 6: proofs labelled by floats. ``verify`` said "proved", unlabelled, for
``(x + 1e16) - 1e16 >= 1.5`` while the monitor does not override at x = 1.1 (absorption). Rounding
that can flip a comparison by more than the inputs' own precision (absorption, cancellation, a
division that amplifies an error) now labels the proof "proved (real arithmetic)", names the term,
and carries a counterexample the Monitor replays when one is found in doubles."""

from __future__ import annotations

import pytest

import ethimon
from ethimon.verify import verify_spec

SPEC = """
ethimon: 1
name: floats
signals:
  a: {range: [0, 1]}
  x: {range: [0, 10]}
  y: {range: [0, 1000000]}
obligations:
%s
"""


def _spec(obligations: str):
    return ethimon.load_spec_text(SPEC % obligations)


def _frame(**kw):
    return {"a": 0.5, "x": 5.0, "y": 5.0, "risk": 0.0, **kw}


@pytest.mark.slow
def test_absorption_is_labelled_real_arithmetic_with_a_replayed_counterexample():
    spec = _spec('  - {id: absorb, require: "(x + 1e16) - 1e16 >= 1.5"}')
    assert not ethimon.Monitor(spec).step(_frame(x=1.1)).override   # 1.1 < 1.5, yet no override
    f = verify_spec(spec).finding("absorb.response")
    assert f.status == "proved (real arithmetic)", (f.status, f.message)
    assert "x + 1e+16" in f.message and "absorption" in f.message, f.message
    cex = f.counterexample
    assert cex is not None and cex.confirmed, f.message
    x = cex.frames[-1]["x"]
    assert 0 <= x < 1.5 and not ethimon.Monitor(spec).step(cex.frames[-1]).override


@pytest.mark.slow
def test_cancellation_of_an_identity_is_labelled():
    """``(y + 0.1) - y <= 0.1`` holds for every real y; in doubles it fails for many: the monitor
    overrides where the proof says nothing can fire."""
    spec = _spec('  - {id: cancel, require: "(y + 0.1) - y <= 0.1"}')
    f = verify_spec(spec).finding("cancel.response")
    assert f.status == "proved (real arithmetic)" and "cancellation" in f.message, (f.status, f.message)


@pytest.mark.slow
def test_division_that_amplifies_rounding_is_labelled():
    spec = _spec('  - {id: div, require: "((y + 0.3) - y) / 0.0000001 >= 3000000"}')
    f = verify_spec(spec).finding("div.response")
    assert f.status == "proved (real arithmetic)", (f.status, f.message)


def test_ordinary_arithmetic_stays_proved():
    """Rounding no larger than what the inputs' own precision moves is no reason to weaken a proof."""
    from ethimon.verify._floats import rounding_hazards
    spec = _spec('  - {id: lin, require: "x * 1.1 - y * 0.5 <= 20 + a * x"}\n'
                 '  - {id: sq, require: "x * x - a * a >= 0.001"}\n'
                 '  - {id: quot, require: "x / (1 + a) <= 10"}\n'
                 '  - {id: diff, require: "y - x >= 0.001"}')
    from ethimon.compiler import plan_of
    plan = plan_of(spec)
    for ob in plan.obligations:
        assert rounding_hazards(plan, ob) == [], ob.id
    absorb = plan_of(_spec('  - {id: absorb, require: "(x + 1e16) - 1e16 >= 1.5"}'))
    assert rounding_hazards(absorb, absorb.obligations[0])
