"""Stage 3 of 3: the runtime monitor (and its reference interpreter)."""

from ._decision import Decision
from ._monitor import Monitor, plan_of
from ._reference import ReferenceMonitor

__all__ = ["Decision", "Monitor", "ReferenceMonitor", "plan_of"]
