"""Stage 3 of 3: the runtime monitor (and its reference interpreter)."""

from ._decision import Decision
from ._loop import (AsyncRiskSource, GovernedLoop, LoopStats, ProbEstimator, ProcessEstimator, ReloadResult,
                    RiskReading, Watchdog)
from ._monitor import Monitor, plan_of
from ._reference import ReferenceMonitor

__all__ = ["AsyncRiskSource", "Decision", "GovernedLoop", "LoopStats", "Monitor", "ProbEstimator",
           "ProcessEstimator", "ReferenceMonitor", "ReloadResult", "RiskReading", "Watchdog", "plan_of"]
