"""Resampling bag samples onto the monitor's cycle grid: zero-order hold plus staleness.

Cycle ``k`` is at ``t0 + rint(k * 1e9 / rate_hz)`` ns (float64 arithmetic, as
written); the grid runs until a cycle at or after the bag's last sample, so the
tail is judged too. At cycle time ``t`` a signal takes the last sample with time ``<= t``
(a sample at exactly ``t`` counts). It is *missing* when it has no such
sample yet, and *stale* when that sample is older than its limit:
``t - t_sample > max_age_s * 1e9``. A missing or stale input is unusable
(NaN in its column): the monitor fails closed on that cycle, as it does
online for a missing input.
"""

from __future__ import annotations

import numpy as np

__all__ = ["OK", "MISSING", "STALE", "MAX_CYCLES", "cycle_grid", "hold", "judged"]

OK, MISSING, STALE = 0, 1, 2
#: most cycles one bag may replay to (e.g. 13.9 hours at 1 kHz)
MAX_CYCLES = 50_000_000


def cycle_grid(t0: int, t_end: int, rate_hz: float) -> np.ndarray:
    """Cycle times (int64 ns) ``t0 + rint(k * 1e9 / rate_hz)`` from ``t0`` up to and including the first
    cycle at or after ``t_end`` (a sample in the bag's tail is judged by that last cycle)."""
    if t_end < t0:
        return np.zeros(0, dtype=np.int64)
    if not (rate_hz > 0 and np.isfinite(rate_hz)):
        raise ValueError(f"rate_hz must be a positive number, got {rate_hz!r}")
    span = (int(t_end) - int(t0)) * float(rate_hz) / 1e9
    if span > MAX_CYCLES:
        raise ValueError(f"{int(span):,} cycles at {rate_hz:g} Hz: more than the limit of {MAX_CYCLES:,}")
    n = int(span) + 3
    k = np.arange(n, dtype=np.float64)
    grid = int(t0) + np.rint(k * (1e9 / float(rate_hz))).astype(np.int64)
    last = int(np.searchsorted(grid, t_end, side="left"))  # the first cycle at or after t_end
    return grid[: last + 1]


def hold(times: np.ndarray, values: np.ndarray, grid: np.ndarray,
         max_age_s: float | None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Zero-order hold of one signal on ``grid``.

    Returns:
        ``(values, code, index)``: the held value (NaN when missing or stale), the code per
        cycle (:data:`OK`, :data:`MISSING`, :data:`STALE`) and the index of the held sample (-1: none).
    """
    idx = np.searchsorted(times, grid, side="right") - 1
    seen = idx >= 0
    safe = np.where(seen, idx, 0)
    if times.size:
        vals = np.where(seen, values[safe], np.nan)
        age = grid - times[safe]
    else:
        vals = np.full(grid.shape, np.nan)
        age = np.zeros(grid.shape, dtype=np.int64)
    code = np.where(seen, OK, MISSING).astype(np.int8)
    if max_age_s is not None:
        stale = seen & (age > max_age_s * 1e9)
        code[stale] = STALE
        vals = np.where(stale, np.nan, vals)
    return vals, code, np.where(seen, idx, -1)


def judged(times: np.ndarray, values: np.ndarray, idx: np.ndarray) -> np.ndarray:
    """Which samples some cycle judges: those held by a cycle (``idx`` from :func:`hold`), and those
    sharing a time and a value with one that is (the one cycle judges both)."""
    out = np.zeros(times.size, dtype=bool)
    held = idx[idx >= 0]
    out[held] = True
    if times.size > 1:
        same = np.flatnonzero(times[:-1] == times[1:])
        for i in same[::-1]:  # a run of equal times: the last one is held
            a, b = values[i], values[i + 1]
            if a == b or (a != a and b != b):
                out[i] = out[i] or out[i + 1]
    return out
