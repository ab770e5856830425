"""Stage 3 of 3: the runtime monitor (and its reference interpreter).

The governed loop around it (async risk, watchdog, audit, reload) is one floor
up, in :mod:`ethimon.loop`.
"""

from ._decision import Acknowledgement, Decision
from ._fault import FAULT_KINDS, Fault
from ._monitor import Monitor
from ._reference import ReferenceMonitor

__all__ = ["Acknowledgement", "Decision", "FAULT_KINDS", "Fault", "Monitor", "ReferenceMonitor"]
