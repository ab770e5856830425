"""The O(1) state machines of the compiled closures: one per temporal operator, and the margin of a
bounded response.

Each factory returns ``(update, reset)``: ``update`` is called once per valid cycle (inner
operators first, by :func:`~ethimon.compiler._closures.build_machine`'s order) and writes the
operator's value into ``tv[k]``; ``reset`` forgets the history. Counters only, no buffers (the
bounded margin keeps a ring of ``n + 1`` floats); no allocation per cycle.
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Callable

__all__ = ["held_machine", "once_machine", "since_machine", "prev_machine", "bounded_margin", "safe"]

INF = math.inf
NAN = math.nan


def held_machine(e: Callable[[], object], tv: list, k: int, n: int):
    """``held(e, n)``: ``e`` at each of the last ``n`` cycles (a run counter)."""
    run = 0

    def upd() -> None:
        nonlocal run
        if e():
            if run < n:
                run += 1
        else:
            run = 0
        tv[k] = run >= n

    def rst() -> None:
        nonlocal run
        run = 0
        tv[k] = False
    return upd, rst


def once_machine(e: Callable[[], object], tv: list, k: int, n: int):
    """``once(e, n)``: ``e`` at some cycle of the last ``n`` (the age of the last one)."""
    age = n  # n means "not seen within the window"

    def upd() -> None:
        nonlocal age
        if e():
            age = 0
        elif age < n:
            age += 1
        tv[k] = age < n

    def rst() -> None:
        nonlocal age
        age = n
        tv[k] = False
    return upd, rst


def since_machine(a: Callable[[], object], b: Callable[[], object], tv: list, k: int, n: int | None):
    """``since(a, b[, n])``: ``b`` at some cycle (within ``n``) and ``a`` at every cycle after it."""
    cap = n if n is not None else 1
    bounded = n is not None
    age = cap

    def upd() -> None:
        nonlocal age
        va = a()
        if b():
            age = 0
        elif va and age < cap:
            if bounded:
                age += 1
        else:
            age = cap
        tv[k] = age < cap

    def rst() -> None:
        nonlocal age
        age = cap
        tv[k] = False
    return upd, rst


def prev_machine(e: Callable[[], object], init: Callable[[], object] | None, is_bool: bool, tv: list, k: int):
    """``prev(e[, init])``: ``e`` one cycle back; at the first cycle ``init`` (without it ``false`` for a
    condition, ``e`` itself for a number)."""
    first = True
    last: object = None

    def upd() -> None:
        nonlocal first, last
        cur = e()
        iv = init() if init is not None else None
        if first:
            first = False
            tv[k] = iv if init is not None else (False if is_bool else cur)
        else:
            tv[k] = last
        last = cur

    def rst() -> None:
        nonlocal first, last
        first = True
        last = None
        tv[k] = False
    return upd, rst


def safe(f: Callable[[], float]) -> float:
    try:
        return f()
    except Exception:  # a margin that cannot be computed is NaN (e.g. a division by zero that
        return math.nan  # the verdict short-circuits past); it is a diagnostic, never a fault


def bounded_margin(rw: Callable[[], float] | None, rr: Callable[[], float], n: int,
                    raise_w: bool = True, raise_r: bool = True):
    """Robustness of a bounded response ``when ⇒ require within n cycles``, O(1) amortised.

    The obligation is violated at ``t`` iff some trigger ``s ≤ t − n`` saw ``require``
    false at every cycle of ``s .. t``. Its robustness is therefore

        M(t) = min over s ≤ t − n of  max(−rob(when)(s), max over u in s..t of rob(require)(u))

    (+inf while no trigger is old enough), whose sign agrees with the verdict; NaN from the
    first due window that holds a term that could not be computed (until reset). Since
    ``max(·, x)`` is monotone, ``M(t) = min(max(M(t−1), rr(t)), max(−rw(t−n), W(t)))``
    with ``W(t)`` the maximum of ``rr`` over the last ``n + 1`` cycles, kept by a
    monotone deque over a ring buffer (no per-cycle allocation beyond the deque's ints).

    Must be called exactly once per valid cycle (the monitor computes every margin
    once per cycle, and each call here never raises); the returned reset clears it.
    ``raise_w``/``raise_r``: whether ``rw``/``rr`` can raise (else they are called unguarded).
    """
    if raise_w and rw is not None:
        rw = (lambda f: lambda: safe(f))(rw)
    if raise_r:
        rr = (lambda f: lambda: safe(f))(rr)
    has_w = rw is not None
    size = n + 1
    ring_w = [0.0] * size  # −rob(when) of the last n + 1 cycles
    ring_r = [0.0] * size  # rob(require) of the last n + 1 cycles
    win: deque[int] = deque()  # cycle numbers whose ring_r is decreasing: the window max at win[0]
    t = -1
    m = INF
    unknown = False  # a NaN term entered some due window: NaN until reset, as in the reference

    def margin() -> float:
        nonlocal t, m, unknown
        t += 1
        a = -rw() if has_w else -INF
        b = rr()
        if b != b:
            unknown = True  # every window from now on contains it (the oldest trigger's does)
        if unknown:
            return NAN if t >= n else INF
        i = t % size
        ring_w[i] = a
        ring_r[i] = b
        while win and not ring_r[win[-1] % size] > b:
            win.pop()
        win.append(t)
        if win[0] < t - n:
            win.popleft()
        if b > m:
            m = b
        if t >= n:
            cand = ring_w[(t - n) % size]
            if cand == INF:  # no trigger at t - n (a false boolean `when`): max(inf, W) < m never holds
                return m
            if cand != cand:
                unknown = True
                return NAN
            top = ring_r[win[0] % size]
            if top > cand:
                cand = top
            if cand < m:
                m = cand
        return m

    def reset() -> None:
        nonlocal t, m, unknown
        t = -1
        m = INF
        unknown = False
        win.clear()
    return margin, reset

