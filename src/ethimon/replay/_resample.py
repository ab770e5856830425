"""Resampling bag samples onto the monitor's cycle grid: zero-order hold plus staleness.

Cycle ``k`` is at ``t0 + rint(k * 1e9 / rate_hz)`` ns (float64 arithmetic, as
written). At cycle time ``t`` a signal takes the last sample with time ``<= t``
(a sample at exactly ``t`` counts). It is *missing* when it has no such
sample yet, and *stale* when that sample is older than its limit:
``t - t_sample > max_age_s * 1e9``. A missing or stale input is unusable
(NaN in its column): the monitor fails closed on that cycle, as it does
online for a missing input.
"""

from __future__ import annotations

import numpy as np

__all__ = ["OK", "MISSING", "STALE", "MAX_CYCLES", "cycle_grid", "hold"]

OK, MISSING, STALE = 0, 1, 2
#: most cycles one bag may replay to (e.g. 13.9 hours at 1 kHz)
MAX_CYCLES = 50_000_000


def cycle_grid(t0: int, t_end: int, rate_hz: float) -> np.ndarray:
    """Cycle times (int64 ns) from ``t0`` while ``<= t_end``: ``t0 + rint(k * 1e9 / rate_hz)``."""
    if t_end < t0:
        return np.zeros(0, dtype=np.int64)
    n = int((t_end - t0) * float(rate_hz) / 1e9) + 2
    if n > MAX_CYCLES + 2:
        raise ValueError(f"{n - 2:,} cycles at {rate_hz:g} Hz: more than the limit of {MAX_CYCLES:,}")
    k = np.arange(n, dtype=np.float64)
    grid = t0 + np.rint(k * 1e9 / float(rate_hz)).astype(np.int64)
    return grid[grid <= t_end]


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
