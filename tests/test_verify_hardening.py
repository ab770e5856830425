"""Issue 11, "proofs and lints that are wrong or flaky": regression tests for ``ethimon verify``.

* the release bound τ − δ is exact (0.27 − 0.05 is 0.22, not 0.22000000000000003);
* the release and contradiction lints look at whole traces, not one cycle;
* the K-class R_e range is exact and cheap (no z3 optimisation at its timeout);
* a run has a total budget and reports what it did not reach.
"""

from __future__ import annotations

import itertools
import random
from fractions import Fraction

import pytest

from ethimon.risk._formula import _risk_range_exact, risk_bounds, risk_from_probs, risk_range

WEIGHTS = [(0.6, 0.2, 0.2), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (0.0, 0.0, 0.0),
           (0.2, 0.7, 0.9), (0.1, 0.1, 3.0), (0.05, 0.9, 4.0), (0.5, 0.5, -0.8), (-0.3, 0.4, 0.5),
           (0.3, -0.6, -2.0)]


def _grid(k: int, n: int):
    """Every p with K entries that are multiples of 1/n (the unsafe class last)."""
    for cut in itertools.combinations(range(n + k - 1), k - 1):
        parts, prev = [], -1
        for c in cut + (n + k - 1,):
            parts.append((c - prev - 1) / n)
            prev = c
        yield parts


def _random_simplex(rng: random.Random, k: int):
    e = [rng.expovariate(1.0) ** rng.choice((1, 3)) for _ in range(k)]
    s = sum(e)
    return [x / s for x in e]


@pytest.mark.parametrize("k, n", [(3, 60), (4, 24), (5, 12)])
@pytest.mark.parametrize("variance", ["sample", "population"])
def test_risk_range_matches_brute_force(k, n, variance):
    rng = random.Random(f"risk-range-{k}-{variance}")
    points = list(_grid(k, n)) + [_random_simplex(rng, k) for _ in range(1500)]
    for a, b, g in WEIGHTS:
        lo, p_lo, hi, p_hi = _risk_range_exact(a, b, g, variance, k)
        # both ends are attained, by a probability vector
        for p, end in ((p_lo, lo), (p_hi, hi)):
            assert len(p) == k and min(p) >= 0 and sum(p) == 1
            assert risk_from_probs([float(x) for x in p], a, b, g, variance) == pytest.approx(float(end), abs=1e-12)
        # and nothing on a dense grid or at random points goes outside them
        vals = [risk_from_probs(p, a, b, g, variance) for p in points]
        assert min(vals) >= float(lo) - 1e-12 and max(vals) <= float(hi) + 1e-12, (a, b, g)
        # a hill climb from the best grid points cannot beat them either
        for sign, end in ((1, hi), (-1, lo)):
            best = max(points, key=lambda p: sign * risk_from_probs(p, a, b, g, variance))
            fb = sign * risk_from_probs(best, a, b, g, variance)
            step = 0.05
            for _ in range(300):
                i, j = rng.sample(range(k), 2)
                d = rng.uniform(0, step) * best[i]
                cand = list(best)
                cand[i] -= d
                cand[j] += d
                fc = sign * risk_from_probs(cand, a, b, g, variance)
                if fc > fb:
                    best, fb = cand, fc
                else:
                    step = max(step * 0.97, 1e-6)
            assert fb <= sign * float(end) + 1e-12, (a, b, g, sign)


def test_risk_range_interior_optimum_is_found():
    # large γ: the minimum is not at a corner or the uniform point but inside an edge/face
    for k in (3, 4, 5):
        _, p, _, _ = _risk_range_exact(0.05, 0.9, 4.0, "sample", k)
        assert 0 not in p and len(set(p)) > 1  # no zero class, not uniform: not a corner of any region
        _, _, _, p = _risk_range_exact(0.3, -0.6, -2.0, "sample", k)
        assert 0 not in p and len(set(p)) > 1  # γ < 0: the maximum is the inner one


def test_risk_range_two_classes_agrees_with_risk_bounds():
    for a, b, g in WEIGHTS:
        for variance in ("sample", "population"):
            lo, hi = risk_range(a, b, g, variance, 2)
            blo, bhi = risk_bounds(a, b, g, variance)
            assert lo == pytest.approx(blo, abs=1e-12) and hi == pytest.approx(bhi, abs=1e-12)


def test_risk_range_paper_weights_and_errors():
    assert risk_range(classes=3) == pytest.approx((0.2 / 3, 0.6 + 0.2 / 3))
    assert risk_range(classes=4, variance="population") == pytest.approx((0.2 * 3 / 16, 0.6 + 0.2 * 3 / 16))
    for bad in (dict(classes=1), dict(variance="median"), dict(alpha=float("nan")), dict(classes=2.5)):
        with pytest.raises(ValueError):
            risk_range(**bad)


def test_risk_range_is_cheap_for_many_classes():
    import time
    t0 = time.perf_counter()
    for k in range(2, 65):
        lo, hi = risk_range(0.6, 0.2, 0.2, "sample", k)
        assert lo <= hi
    assert time.perf_counter() - t0 < 2.0
