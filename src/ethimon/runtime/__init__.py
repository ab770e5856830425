"""Stage 3 of 3: the runtime monitor (its reference interpreter, the test oracle, is :mod:`ethimon.testing`).

The governed loop around it (async risk, watchdog, audit, reload) is one floor
up, in :mod:`ethimon.loop`.
"""

from ._decision import Acknowledgement, Decision
from ._fault import FAULT_KINDS, Fault
from ._monitor import Monitor

__all__ = ["Acknowledgement", "Decision", "FAULT_KINDS", "Fault", "Monitor"]
