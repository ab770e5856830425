"""Counters of a governed loop."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["LoopStats"]


@dataclass
class LoopStats:
    """Counters of a :class:`GovernedLoop` (read them any time)."""

    cycles: int = 0
    overrides: int = 0
    fault_cycles: int = 0
    deadline_misses: int = 0
    skipped_slots: int = 0
    risk_faults: int = 0
    stale_overrides: int = 0
    audit_drops: int = 0
    audit_records: int = 0
    audit_faults: int = 0
    stalls: int = 0
    reloads_applied: int = 0
    reloads_rejected: int = 0
    max_cycle_s: float = 0.0
    max_late_s: float = 0.0
    max_gap_s: float = 0.0

    def as_dict(self) -> dict:
        return dict(self.__dict__)
