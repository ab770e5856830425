"""The ethical-risk formula R_e = α·p_unsafe + β·(1 − max p) + γ·Var(p).

Pure Python on purpose: the monitor calls it inside ``Monitor.step`` and it
must not import numpy arrays, torch or allocate more than a float.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from decimal import Decimal
from fractions import Fraction

__all__ = ["risk_from_p_unsafe", "risk_from_probs", "risk_bounds", "release_bound", "VARIANCE_MODES"]

VARIANCE_MODES = ("sample", "population")


def risk_from_p_unsafe(p_unsafe: float, alpha: float = 0.6, beta: float = 0.2,
                       gamma: float = 0.2, variance: str = "sample") -> float:
    """R_e for a two-class classifier, from its unsafe-class probability.

    With ``p = (1 − q, q)``: ``max p = max(q, 1 − q)``; the sample variance
    (``torch.var`` default, n − 1 = 1) is ``2·(q − ½)²`` and the population
    variance ``(q − ½)²``.

    Args:
        p_unsafe: q, the probability of the unsafe class, in [0, 1].
        alpha, beta, gamma: the weights α, β, γ.
        variance: ``"sample"`` or ``"population"``.

    Returns:
        R_e as a float. NaN in gives NaN out (the monitor fails closed on it).

    Example:
        >>> round(risk_from_p_unsafe(0.0), 6), round(risk_from_p_unsafe(1.0), 6)
        (0.1, 0.7)
        >>> round(risk_from_p_unsafe(0.5), 6)
        0.4
    """
    q = p_unsafe
    d = q - 0.5
    var = 2.0 * d * d if variance == "sample" else d * d
    return alpha * q + beta * (1.0 - (q if q >= 0.5 else 1.0 - q)) + gamma * var


def risk_from_probs(p: Sequence[float], alpha: float = 0.6, beta: float = 0.2,
                    gamma: float = 0.2, variance: str = "sample",
                    unsafe_index: int = -1) -> float:
    """R_e from a full class-probability vector ``p`` (K ≥ 2 classes).

    Args:
        p: the softmax output; the unsafe class is ``p[unsafe_index]``.
        alpha, beta, gamma: the weights α, β, γ.
        variance: ``"sample"`` (divide by K − 1) or ``"population"`` (by K).
        unsafe_index: which entry is the unsafe class (default: the last).

    Returns:
        R_e as a float.

    Raises:
        ValueError: fewer than two classes.

    Example:
        >>> round(risk_from_probs([0.3, 0.7]), 6) == round(risk_from_p_unsafe(0.7), 6)
        True
    """
    k = len(p)
    if k < 2:
        raise ValueError(f"need at least two class probabilities, got {k}")
    total = 0.0
    top = -math.inf
    for v in p:
        total += v
        if v > top:
            top = v
    mean = total / k
    ss = 0.0
    for v in p:
        ss += (v - mean) * (v - mean)
    var = ss / (k - 1) if variance == "sample" else ss / k
    return alpha * p[unsafe_index] + beta * (1.0 - top) + gamma * var


def risk_bounds(alpha: float = 0.6, beta: float = 0.2, gamma: float = 0.2,
                variance: str = "sample", steps: int = 2001) -> tuple[float, float]:
    """Reachable range of R_e for two classes (grid over q plus the critical points).

    The formula is piecewise quadratic in q on [0, ½] and [½, 1], so the extrema
    lie at 0, ½, 1 or at a vertex; we evaluate those exactly.

    Example:
        >>> tuple(round(x, 6) for x in risk_bounds())
        (0.1, 0.7)
    """
    cands = {0.0, 0.5, 1.0}
    c = 2.0 if variance == "sample" else 1.0
    # derivative on [0, ½): alpha + beta + 2·gamma·c·(q − ½) = 0
    # derivative on (½, 1]: alpha − beta + 2·gamma·c·(q − ½) = 0
    if gamma != 0.0:
        for slope in (alpha + beta, alpha - beta):
            q = 0.5 - slope / (2.0 * gamma * c)
            if 0.0 <= q <= 1.0:
                cands.add(q)
    vals = [risk_from_p_unsafe(q, alpha, beta, gamma, variance) for q in cands]
    return (min(vals), max(vals))


def release_bound(threshold: float, hysteresis: float) -> tuple[Fraction, float]:
    """The release bound ``τ − δ``, computed exactly as the spec writes it.

    Float subtraction is not exact: ``0.27 - 0.05 == 0.22000000000000003``, so an
    R_e of ``0.22`` would count as *below* the bound and release a latch that the
    spec says must hold. Both numbers are taken as the decimals they print as
    (the shortest repr, which is what a YAML spec says) and subtracted exactly.

    Returns:
        ``(exact, cut)``: the exact rational bound (for the z3 encoding) and a
        float such that, for every float ``r``, ``r < cut`` holds exactly when
        ``Fraction(r) < exact`` (what the monitor and the reference interpreter test).

    Example:
        >>> exact, cut = release_bound(0.27, 0.05)
        >>> exact, 0.22 < cut, 0.21999999999999997 < cut
        (Fraction(11, 50), False, True)
    """
    exact = Fraction(Decimal(repr(float(threshold)))) - Fraction(Decimal(repr(float(hysteresis))))
    cut = float(exact)
    if Fraction(cut) < exact:  # cut itself is below the bound: let r == cut pass too
        cut = math.nextafter(cut, math.inf)
    return exact, cut
