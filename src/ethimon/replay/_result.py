"""What one bag's replay found: a :class:`CheckResult` per rule and the inputs, in a :class:`BagReplay`."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ._verdicts import CycleResults

__all__ = ["BagReplay", "CheckResult"]


@dataclass
class CheckResult:
    """One obligation (or the risk rule, or the input faults) over a whole bag.

    ``first_t_ns`` is the bag timestamp of the first violating cycle, ``first_t_s`` the
    seconds since the replay's first cycle; ``worst_margin`` is the smallest robustness
    margin over the cycles where it was evaluated (for ``risk``: τ − the largest R_e).
    """

    id: str
    kind: str  # "obligation" | "risk" | "faults"
    response: str
    cycles: int
    first_cycle: int | None
    first_t_ns: int | None
    first_t_s: float | None
    worst_margin: float | None
    detail: str = ""
    status: str = ""  # PASS | FAIL | NOT EVALUATED (no cycle could judge it) | NOT CHECKED (risk: none)

    def __post_init__(self) -> None:
        if not self.status:
            self.status = "FAIL" if self.cycles else "PASS"

    @property
    def passed(self) -> bool:
        """True only for PASS: a rule NOT EVALUATED or NOT CHECKED did not pass."""
        return self.status == "PASS"

    def as_dict(self) -> dict[str, Any]:
        wm = self.worst_margin
        shown = wm if wm is None or math.isfinite(wm) else ("inf" if wm > 0 else "-inf")
        return {"id": self.id, "kind": self.kind, "response": self.response, "status": self.status,
                "passed": self.passed,
                "cycles_violated": self.cycles, "first_violation": None if self.first_cycle is None else {
                    "cycle": self.first_cycle, "bag_time_ns": self.first_t_ns, "t_s": self.first_t_s},
                "worst_margin": shown, "detail": self.detail}


@dataclass
class BagReplay:
    """The verdicts of one bag."""

    path: str
    storage: str
    rate_hz: float
    cycles: int
    start_ns: int
    end_ns: int
    checks: list[CheckResult]
    override_cycles: int
    first_override: int | None
    signals: dict[str, dict[str, Any]] = field(default_factory=dict)
    tasks: list[dict[str, Any]] = field(default_factory=list)
    engine: str = "Monitor.step"
    #: the override runs (at most ``replay.MAX_RUNS`` of them, the one to the end of the bag always):
    #: start, length, cause, ``until_end`` and the latch that held each at its last cycle (``held_by``)
    latches: list[dict[str, Any]] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    started: dict[str, Any] = field(default_factory=dict)
    topics: dict[str, dict[str, Any]] = field(default_factory=dict)  # topic -> messages read, samples judged
    trace: CycleResults | None = field(default=None, repr=False)
    grid: np.ndarray | None = field(default=None, repr=False)
    columns: dict[str, np.ndarray] | None = field(default=None, repr=False)
    override_runs: int = 0  # how many override runs there are in all (``latches`` may list fewer)

    @property
    def passed(self) -> bool:
        """No check failed and every check was evaluated (a rule NOT CHECKED by the mapping's
        ``risk: none`` does not fail the bag)."""
        return all(c.status in ("PASS", "NOT CHECKED") for c in self.checks)

    def check(self, cid: str) -> CheckResult:
        for c in self.checks:
            if c.id == cid:
                return c
        raise KeyError(cid)

    def as_dict(self) -> dict[str, Any]:
        return {"name": self.path, "path": self.path, "passed": self.passed, "storage": self.storage,
                "rate_hz": self.rate_hz, "cycles": self.cycles, "start_ns": self.start_ns,
                "end_ns": self.end_ns, "duration_s": (self.end_ns - self.start_ns) / 1e9,
                "override_cycles": self.override_cycles, "first_override_cycle": self.first_override,
                "override_runs": self.override_runs,
                "checks": [c.as_dict() for c in self.checks], "signals": self.signals, "tasks": self.tasks,
                "topics": self.topics, "latches": self.latches, "warnings": self.warnings, "started": self.started,
                "engine": self.engine}
