"""The ethical-risk formula R_e = α·p_unsafe + β·(1 − max p) + γ·Var(p).

Spec semantics, so it lives on the compiler floor (the monitor, the reference
interpreter and the z3 encoder use it); ``ethimon.risk`` re-exports the names.

Pure Python on purpose: the monitor calls it inside ``Monitor.step`` and it
must not import numpy arrays, torch or allocate more than a float.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from decimal import Decimal
from fractions import Fraction

from ..language import DEFAULT_ALPHA, DEFAULT_BETA, DEFAULT_GAMMA, VARIANCE_MODES

__all__ = ["DEFAULT_ALPHA", "DEFAULT_BETA", "DEFAULT_GAMMA", "two_class_risk", "risk_from_p_unsafe", "risk_from_probs", "risk_bounds",
           "release_bound", "decimal_reading", "risk_range", "VARIANCE_MODES", "OUTCOMES", "judge_verdict",
           "tier_outcome"]

def two_class_risk(q, alpha, beta, gamma, variance: str = "sample", *, where=None, half=0.5):
    """The two-class R_e, written once for every back-end's arithmetic.

    ``R_e = α·q + β·(1 − max(q, 1 − q)) + γ·c·(q − ½)²`` with ``c = 2`` for the sample
    variance (n − 1 = 1) and ``c = 1`` for the population variance. The back-end supplies its
    numbers and its ``if``: plain floats (``where=None``: a Python conditional), numpy arrays
    (``where=np.where``), z3 terms (``where=z3.If``, ``half=z3.RealVal("1/2")``, weights as z3
    reals). The float form is the one the monitor's hot path inlines (a test checks it equals
    this on a grid); the operations and their order are the same for every back-end, so the
    floats, the arrays and the exact reals agree.

    Example:
        >>> two_class_risk(1.0, 0.6, 0.2, 0.2), two_class_risk(0.0, 0.6, 0.2, 0.2, "population")
        (0.7, 0.05)
    """
    d = q - half
    var = 2.0 * d * d if variance == "sample" else d * d
    if where is None:
        top = q if q >= half else 1.0 - q
    else:
        top = where(q >= half, q, 1.0 - q)
    return alpha * q + beta * (1.0 - top) + gamma * var


def risk_from_p_unsafe(p_unsafe: float, alpha: float = DEFAULT_ALPHA, beta: float = DEFAULT_BETA,
                       gamma: float = DEFAULT_GAMMA, variance: str = "sample") -> float:
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
    return two_class_risk(p_unsafe, alpha, beta, gamma, variance)


def risk_from_probs(p: Sequence[float], alpha: float = DEFAULT_ALPHA, beta: float = DEFAULT_BETA,
                    gamma: float = DEFAULT_GAMMA, variance: str = "sample",
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


def risk_bounds(alpha: float = DEFAULT_ALPHA, beta: float = DEFAULT_BETA, gamma: float = DEFAULT_GAMMA,
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


def decimal_reading(x: float) -> Fraction:
    """The number a float *reads as*: the exact value of the decimal its shortest ``repr`` prints
    (``0.42`` for the float nearest 0.42, not its binary value 0.41999999999999998446...).

    This is the one reading of numbers in the release rule: the spec's τ and δ are decimals, and
    R_e is compared with τ − δ as the decimal it prints as. For ``R_e ≥ τ`` the reading changes
    nothing (``repr`` is strictly increasing on floats, so ``r ≥ τ`` exactly when
    ``decimal_reading(r) ≥ decimal_reading(τ)``).

    Example:
        >>> decimal_reading(0.42), decimal_reading(0.1 + 0.2)
        (Fraction(21, 50), Fraction(7500000000000001, 25000000000000000))
    """
    return Fraction(Decimal(repr(float(x))))


def release_bound(threshold: float, hysteresis: float) -> tuple[Fraction, float]:
    """The release bound ``τ − δ`` as the spec writes it, and the float test that reads R_e the same way.

    One reading of numbers (see :func:`decimal_reading`): τ, δ *and* R_e are the decimals their
    shortest repr prints, and the release condition is ``R_e < τ − δ`` on those decimals, exactly.
    So with τ 0.27, δ 0.05 an R_e of ``0.22`` does not release (0.22 < 0.22 is false), and with
    τ 0.47, δ 0.05 an R_e of ``0.42`` does not either, whichever side of the decimal the float
    nearest it lies (float subtraction would give ``0.27 - 0.05 == 0.22000000000000003``, and the
    binary value of ``0.42`` is below 0.42: each alone releases one of the two).

    Returns:
        ``(exact, cut)``: the exact rational bound and the smallest float whose decimal reading is
        at least the bound, so that for every float ``r``: ``r < cut`` holds exactly when
        ``decimal_reading(r) < exact`` (what the monitor, the reference interpreter, the offline
        checker and the z3 encoding test).

    Example:
        >>> exact, cut = release_bound(0.27, 0.05)
        >>> exact, 0.22 < cut, 0.21999999999999997 < cut
        (Fraction(11, 50), False, True)
        >>> 0.42 < release_bound(0.47, 0.05)[1]
        False
    """
    exact = decimal_reading(threshold) - decimal_reading(hysteresis)
    cut = float(exact)
    # decimal_reading is strictly increasing, so the floats reading below the bound are those below cut
    while decimal_reading(cut) < exact:
        cut = math.nextafter(cut, math.inf)
    while decimal_reading(math.nextafter(cut, -math.inf)) >= exact:
        cut = math.nextafter(cut, -math.inf)
    return exact, cut


def _segment_extremes(g, lo: Fraction, hi: Fraction) -> list[tuple[Fraction, Fraction]]:
    """``(value, s)`` at the ends of ``[lo, hi]`` and at the stationary point of the quadratic ``g`` inside it."""
    out = [(g(lo), lo), (g(hi), hi)]
    if hi == lo:
        return out
    h0, hm, h1 = out[0][0], g((lo + hi) / 2), out[1][0]
    a = 2 * h1 - 4 * hm + 2 * h0  # g(lo + u·(hi − lo)) = h0 + b·u + a·u²
    b = h1 - h0 - a
    if a != 0:
        u = -b / (2 * a)
        if 0 < u < 1:
            s = lo + u * (hi - lo)
            out.append((g(s), s))
    return out


def _risk_range_exact(alpha: float, beta: float, gamma: float, variance: str,
                      classes: int) -> tuple[Fraction, tuple[Fraction, ...], Fraction, tuple[Fraction, ...]]:
    """Exact ``(min, p_min, max, p_max)`` of R_e over the probability simplex (unsafe class last).

    Derivation. With ``S = Σ p_i²`` the variance is ``c·(S − 1/K)``, ``c = 1/(K−1)``
    (sample) or ``1/K`` (population), so on the region where class ``m`` holds the
    largest probability, ``R = α·p_u + β·(1 − p_m) + γ·c·(S − 1/K)`` is linear plus
    ``γ·c·S``: convex if ``γ ≥ 0``, concave if ``γ < 0``. Every point lies in such a
    region (``m = u``, or ``m`` another class: all those are alike by symmetry).

    * The extreme that convexity pushes to a corner (the maximum for ``γ ≥ 0``, the
      minimum for ``γ < 0``, both for ``γ = 0``) is at a vertex of a region. The
      vertices of ``{p ∈ simplex : p_m ≥ p_j ∀j}`` are the uniform distributions over
      a set containing ``m``; R there depends only on the set's size ``s`` and on
      whether it contains ``u``: at most ``2K − 1`` values.
    * The other extreme: R is symmetric and convex (resp. concave) in the classes other
      than ``u`` and ``m``, and the region is symmetric in them, so averaging over
      their permutations does not make it worse: an optimum has them all equal. That
      leaves ``p_u = x`` (region ``m = u``, one variable on ``[1/K, 1]``) or
      ``p_m = x, p_u = y`` (two variables on a quadrilateral); a quadratic's
      extremes on a segment or polygon lie at its vertices, at the stationary point
      of an edge, or at its interior stationary point.

    Every candidate is a point of the simplex, so both ends are attained exactly.
    """
    K = int(classes)
    if K < 2 or K != classes:
        raise ValueError(f"need an integer number of classes >= 2, got {classes!r}")
    if variance not in VARIANCE_MODES:
        raise ValueError(f"variance must be one of {VARIANCE_MODES}, got {variance!r}")
    al, be, ga = Fraction(alpha), Fraction(beta), Fraction(gamma)  # ValueError on NaN / infinity
    w = ga / (K - 1 if variance == "sample" else K)
    one, inv_k = Fraction(1), Fraction(1, K)

    def R(p: tuple[Fraction, ...], m: int) -> Fraction:  # p[-1] is the unsafe class, p[m] the largest
        return al * p[-1] + be * (1 - p[m]) + w * (sum(v * v for v in p) - inv_k)

    cands: list[tuple[Fraction, tuple[Fraction, ...]]] = []
    # corners: uniform over s classes, with (last) or without (first) the unsafe class
    for s in range(1, K + 1):
        v = Fraction(1, s)
        p = (Fraction(0),) * (K - s) + (v,) * s
        cands.append((R(p, K - 1), p))
        if s < K:
            p = (v,) * s + (Fraction(0),) * (K - s)
            cands.append((R(p, 0), p))

    # region m = u: p_u = x, every other class (1 − x)/(K − 1)
    def pa(x: Fraction) -> tuple[Fraction, ...]:
        return ((1 - x) / (K - 1),) * (K - 1) + (x,)
    cands += [(val, pa(x)) for val, x in _segment_extremes(lambda x: R(pa(x), K - 1), inv_k, one)]

    # region m = 0 (not u): p_0 = x, p_u = y, the K − 2 others (1 − x − y)/(K − 2)
    if K == 2:
        def pb2(x: Fraction) -> tuple[Fraction, ...]:
            return (x, 1 - x)
        cands += [(val, pb2(x)) for val, x in _segment_extremes(lambda x: R(pb2(x), 0), Fraction(1, 2), one)]
    else:
        def pb(x: Fraction, y: Fraction) -> tuple[Fraction, ...]:
            return (x,) + ((1 - x - y) / (K - 2),) * (K - 2) + (y,)

        def f(x: Fraction, y: Fraction) -> Fraction:
            return R(pb(x, y), 0)
        # feasible set: cx·x + cy·y + c0 >= 0 for each row
        rows = [(Fraction(0), one, Fraction(0)),         # y >= 0
                (one, -one, Fraction(0)),                # y <= x
                (-one, -one, one),                       # others >= 0
                (Fraction(K - 1), one, -one)]            # others <= x

        def feasible(x: Fraction, y: Fraction) -> bool:
            return all(cx * x + cy * y + c0 >= 0 for cx, cy, c0 in rows)
        verts = set()
        for (a1, b1, c1), (a2, b2, c2) in itertools.combinations(rows, 2):
            det = a1 * b2 - a2 * b1
            if det != 0:
                x, y = (b1 * c2 - b2 * c1) / det, (a2 * c1 - a1 * c2) / det
                if feasible(x, y):
                    verts.add((x, y))
        for x, y in verts:
            cands.append((f(x, y), pb(x, y)))
        for cx, cy, c0 in rows:  # the stationary point of each edge
            on = sorted(v for v in verts if cx * v[0] + cy * v[1] + c0 == 0)
            if len(on) >= 2:
                (x0, y0), (x1, y1) = on[0], on[-1]
                for val, u in _segment_extremes(lambda u: f(x0 + u * (x1 - x0), y0 + u * (y1 - y0)),
                                                Fraction(0), one):
                    cands.append((val, pb(x0 + u * (x1 - x0), y0 + u * (y1 - y0))))
        # the interior stationary point of f = A x² + B x y + C y² + D x + E y + F
        F0 = f(Fraction(0), Fraction(0))
        fx1, fxm, fy1, fym = f(one, Fraction(0)), f(-one, Fraction(0)), f(Fraction(0), one), f(Fraction(0), -one)
        A, D = (fx1 + fxm) / 2 - F0, (fx1 - fxm) / 2
        C, E = (fy1 + fym) / 2 - F0, (fy1 - fym) / 2
        B = f(one, one) - A - C - D - E - F0
        det = 4 * A * C - B * B
        if det != 0:
            x, y = (B * E - 2 * C * D) / det, (B * D - 2 * A * E) / det
            if feasible(x, y):
                cands.append((f(x, y), pb(x, y)))
    lo = min(cands, key=lambda c: c[0])
    hi = max(cands, key=lambda c: c[0])
    return lo[0], lo[1], hi[0], hi[1]


def risk_range(alpha: float = DEFAULT_ALPHA, beta: float = DEFAULT_BETA, gamma: float = DEFAULT_GAMMA,
               variance: str = "sample", classes: int = 2) -> tuple[float, float]:
    """Exact range of R_e over every probability vector of ``classes`` classes (any weights' signs).

    No optimiser and no grid: the extremes of R_e on the simplex lie among a few
    dozen candidate points (see :func:`_risk_range_exact` for the derivation), which
    are evaluated in exact rational arithmetic; the ends are then rounded to the
    nearest float. Which class is the unsafe one does not matter (symmetry).

    Raises:
        ValueError: fewer than two classes, an unknown variance mode, or a weight that is not finite.

    Example:
        >>> tuple(round(x, 6) for x in risk_range())
        (0.1, 0.7)
        >>> tuple(round(x, 6) for x in risk_range(classes=3))  # a safe corner; the unsafe one
        (0.066667, 0.666667)
    """
    lo, _, hi, _ = _risk_range_exact(alpha, beta, gamma, variance, classes)
    return float(lo), float(hi)


#: the three outcomes of the tiers, least to most restrictive
OUTCOMES = ("execute", "confirm", "stop")


def judge_verdict(p_judge: float | None, safe_below: float, unsafe_from: float) -> str | None:
    """``"safe"`` (p < safe_below), ``"unsafe"`` (p ≥ unsafe_from), ``"unsure"`` between, ``None``: no judgement.

    Example:
        >>> [judge_verdict(p, 0.2, 0.8) for p in (0.1, 0.5, 0.8, None)]
        ['safe', 'unsure', 'unsafe', None]
    """
    if p_judge is None or not (0.0 <= p_judge <= 1.0):  # NaN / out of range: no usable judgement
        return None
    if p_judge >= unsafe_from:
        return "unsafe"
    return "safe" if p_judge < safe_below else "unsure"


def tier_outcome(r_e: float, p_judge: float | None, *, threshold: float, confirm_threshold: float | None = None,
                 safe_below: float = 0.2, unsafe_from: float = 0.8, judge: bool = True,
                 hold_ceiling: float | None = None) -> str:
    """The tiered outcome of one task text, as the monitor decides it on its first cycle.

    * R_e ≥ τ: ``"stop"`` whatever the judge says;
    * an unsafe verdict: ``"stop"`` at any R_e (below τ the judge can only raise the risk);
    * τ_confirm ≤ R_e < τ: ``"execute"`` on a safe verdict, else (unsure, no judgement) ``"confirm"``;
    * below τ_confirm (or with no band): ``"execute"``.

    ``hold_ceiling`` (``risk.judge_may_hold_above_tau.ceiling``): τ ≤ R_e < ceiling with a safe verdict is
    ``"confirm"`` (a person releases it), never ``"execute"``.

    ``judge=False``: the spec has no judge; its p is ignored. A NaN/out-of-range p counts as no judgement
    here (the monitor fails closed on it as a bad input, which is at least as restrictive).

    Example:
        >>> [tier_outcome(r, None, threshold=0.5, confirm_threshold=0.3) for r in (0.2, 0.4, 0.5)]
        ['execute', 'confirm', 'stop']
        >>> tier_outcome(0.4, 0.05, threshold=0.5, confirm_threshold=0.3), tier_outcome(0.1, 0.9, threshold=0.5)
        ('execute', 'stop')
    """
    v = judge_verdict(p_judge, safe_below, unsafe_from) if judge else None
    if r_e >= threshold:
        return "confirm" if (hold_ceiling is not None and r_e < hold_ceiling and v == "safe") else "stop"
    if v == "unsafe":
        return "stop"
    if confirm_threshold is not None and r_e >= confirm_threshold and v != "safe":
        return "confirm"
    return "execute"
