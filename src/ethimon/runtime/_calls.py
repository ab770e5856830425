"""The one-call tuples the monitor builds at construction: every update, verdict or margin of a cycle
in one call (no generator, no list), and the guarded form for margins that can raise."""

from __future__ import annotations

import math

_EMPTY: tuple = ()


def _all_margins(fns: tuple) -> tuple[float, ...]:
    """Every margin, each computed exactly once (bounded-response margins keep state); NaN
    where one raises (robustness ignores short-circuits, so ``y <= 0 or x / y < 2`` can divide
    by zero in its margin but not in its verdict)."""
    out = []
    i, n = 0, len(fns)
    while i < n:
        try:
            while i < n:
                out.append(fns[i]())
                i += 1
        except Exception:
            out.append(math.nan)
            i += 1
    return tuple(out)


def _tuple_of_calls(fns: tuple):
    """A closure returning ``tuple(f() for f in fns)``, written out for up to 8 (no generator, no list)."""
    n = len(fns)
    if n == 0:
        return lambda: _EMPTY
    if n == 1:
        f0, = fns
        return lambda: (f0(),)
    if n == 2:
        f0, f1 = fns
        return lambda: (f0(), f1())
    if n == 3:
        f0, f1, f2 = fns
        return lambda: (f0(), f1(), f2())
    if n == 4:
        f0, f1, f2, f3 = fns
        return lambda: (f0(), f1(), f2(), f3())
    if n == 5:
        f0, f1, f2, f3, f4 = fns
        return lambda: (f0(), f1(), f2(), f3(), f4())
    if n == 6:
        f0, f1, f2, f3, f4, f5 = fns
        return lambda: (f0(), f1(), f2(), f3(), f4(), f5())
    if n == 7:
        f0, f1, f2, f3, f4, f5, f6 = fns
        return lambda: (f0(), f1(), f2(), f3(), f4(), f5(), f6())
    if n == 8:
        f0, f1, f2, f3, f4, f5, f6, f7 = fns
        return lambda: (f0(), f1(), f2(), f3(), f4(), f5(), f6(), f7())
    return lambda: tuple([f() for f in fns])
