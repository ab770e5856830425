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
    #: cycles held by the pending hold alone (an input awaited after the start or a new task text)
    pending_cycles: int = 0
    reloads_applied: int = 0
    reloads_rejected: int = 0
    max_cycle_s: float = 0.0
    max_late_s: float = 0.0
    max_gap_s: float = 0.0
    #: what held the arm when :meth:`GovernedLoop.run` returned (``GovernedLoop.hold_text``; "" if nothing)
    held_by: str = ""

    def as_dict(self) -> dict:
        return dict(self.__dict__)

    def summary(self) -> str:
        """One line for a person: cycles, overrides, faults, pending, misses, stalls and what holds the arm."""
        line = (f"{self.cycles} cycles, {self.overrides} with override ({self.pending_cycles} pending, "
                f"{self.fault_cycles} with faults), {self.deadline_misses} deadline misses, {self.stalls} stalls, "
                f"max late {self.max_late_s * 1e3:.2f} ms")
        return line + (f"; held by {self.held_by}" if self.held_by else "; the arm was free at the end")
