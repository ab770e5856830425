"""Offline checking: a whole recorded trace through a spec at once, vectorised with numpy.

:func:`check_trace` gives, for every cycle of a trace, what ``Monitor.step``
gives (verdict per obligation, override, response, latched flag, faults, R_e,
margins), computed column by column instead of cycle by cycle; per obligation
it also reports the first violation, the cycles violated and the worst margin.
The property suite checks it against ``Monitor.step`` on random specs and
traces (``verification/test_prop_offline.py``).

Not imported by ``import ethimon``; it needs only numpy (a core dependency).
"""

from ._trace import OfflineResult, check_trace, iter_rows

__all__ = ["OfflineResult", "check_trace", "iter_rows"]
