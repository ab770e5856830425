"""The governed loop: the monitor stepped at a fixed rate with an async risk estimator.

An integration floor above ``runtime``, ``verify``, ``audit`` and ``risk``
(below ``cli``): :class:`GovernedLoop` paces the monitor, configured by one
:class:`LoopConfig`; it feeds the monitor the latest estimate of an
:class:`AsyncRiskSource` (in a thread, or in a child process with
:class:`ProcessEstimator`), watches for stalls (:class:`Watchdog`), writes the
audit trail, applies acknowledgements through an :class:`AckGate` and reloads
specs through a :class:`Reloader` (refusing one that :func:`weakenings` finds
weaker unless asked, optionally gated by the SMT proofs).
"""

from ._acknowledge import AckGate
from ._config import LoopConfig
from ._governed import GovernedLoop
from ._process import ProcessEstimator
from ._reload import ReloadResult, Reloader
from ._source import AsyncJudgeSource, AsyncRiskSource, RiskReading
from ._stats import LoopStats
from ._watchdog import Watchdog
from ._weakenings import CANNOT_TELL, weakenings

__all__ = ["AckGate", "AsyncJudgeSource", "AsyncRiskSource", "GovernedLoop", "LoopConfig", "LoopStats",
           "ProcessEstimator", "Reloader", "ReloadResult"]
