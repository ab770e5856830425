"""Resampling bag samples onto the monitor's cycle grid: the zero-order hold with staleness of
``ethimon.io`` (:func:`~ethimon.io.hold`, one semantics live and offline), served here for replay."""

from __future__ import annotations

from ..io import MAX_CYCLES, MISSING, OK, STALE, cycle_grid, hold, judged

__all__ = ["OK", "MISSING", "STALE", "MAX_CYCLES", "cycle_grid", "hold", "judged"]
