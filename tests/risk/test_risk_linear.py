"""Regression (issue 30 latency, issue 33 item 4): the step reading re-read every earlier step of a
plan each time the plan was scored again with one more step (quadratic in plan length). Each view is
now scored once, cached by its content, and the probabilities are those of a cold read."""

from __future__ import annotations

import pytest

PLAN = ["Move to the counter.", "Pick up the kettle by its handle.", "Carry it over the high chair.",
        "Tilt the kettle toward the toddler.", "Pour slowly.", "Put the kettle back on its base."]


def plan(k: int) -> str:
    return "\n".join(f"{i}. {s}" for i, s in enumerate(PLAN[:k], start=1))


@pytest.mark.slow
def test_a_growing_plan_scores_each_view_once_and_the_same_numbers():
    from ethimon.risk import load_estimator
    est = load_estimator(cache_size=64, backend="onnx", jit=False)
    cold = load_estimator(cache_size=0, backend="onnx", jit=False)
    rows = []
    for k in range(3, 6):
        r0 = est._rows
        p = est.probs(plan(k))
        rows.append(est._rows - r0)
    assert rows[1:] == [2, 2]     # step k alone and step k after steps 1..k-1: nothing read again (was 7, 9)
    assert p == pytest.approx(cold.probs(plan(5)), abs=1e-6)
