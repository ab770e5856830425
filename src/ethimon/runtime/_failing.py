"""Failing closed: the fault rule's latch, a cycle that cannot be judged, and a fault found
outside the monitor (watchdog, estimator, audit)."""

from __future__ import annotations

from ..language import SEVERITY_ORDER
from ._calls import _EMPTY
from ._decision import Decision
from ._fault import Fault

_RESPONSES = SEVERITY_ORDER  # severity -> Response
_EXTERNAL = Fault("external", "external fault")


class _FailClosed:
    """The fault path (a base of :class:`~ethimon.runtime.Monitor`)."""

    __slots__ = ()

    def fault(self, *reasons: Fault | str, decision: Decision | None = None) -> Decision:
        """Fail closed on a fault found outside the monitor (watchdog, estimator, audit).

        Args:
            reasons: why: each a :class:`~ethimon.runtime.Fault`, or a line of text
                (it becomes ``Fault("external", text)``).
            decision: the :class:`Decision` that :meth:`step` just returned for this
                cycle. If given, that cycle is escalated in place: same cycle number,
                violations and margins kept, ``override`` forced, the response raised to
                at least the spec's ``on_fault``, and the reasons appended to ``faults``;
                temporal history is kept (the inputs were valid). Without it, the fault
                counts as a cycle of its own in which no input was evaluated (history
                is cleared, as for a bad input).

        Returns:
            The fail-closed :class:`Decision`; the override latches like any other.

        Example:
            >>> import ethimon
            >>> m = ethimon.Monitor(ethimon.load_spec_text("{ethimon: 1, name: demo}"))
            >>> d = m.fault("risk estimator hung")
            >>> d.override, d.faults
            (True, (Fault('external', 'risk estimator hung'),))
        """
        reasons = tuple(r if type(r) is Fault else Fault("external", str(r)) for r in reasons) or (_EXTERNAL,)
        if decision is None:
            cycle = self._cycle
            self._cycle = cycle + 1
            return self._fault(cycle, reasons, None)
        self._confirmed = False  # a fault found outside the monitor ends a confirmation too (issue 31)
        sev = max(decision.response.severity, self._latch_fault())
        return Decision(True, _RESPONSES[sev], decision.violations, decision.margins, decision.risk,
                        decision.cycle, decision.latched, decision.faults + reasons)

    def _latch_fault(self) -> int:
        """Latch the fault rule; every release count restarts (the cycle is not a clean one).
        Returns the most severe latched response."""
        lat, run = self._lat, self._run
        fi = self._fi
        if not lat[fi]:
            lat[fi] = self._fault_sev
            self._nlat += 1
        sev = 0
        for k in range(self._nsrc):
            run[k] = 0
            if lat[k] > sev:
                sev = lat[k]
        return sev

    def _fault(self, cycle: int, reasons: tuple[Fault, ...], r: float | None,
               bad: list[int] | None = None) -> Decision:
        """Fail closed: override with the spec's fault response; history is invalid.

        With ``bad`` (the slots of the unusable inputs), the stateless obligations
        whose inputs are all valid are still evaluated, so a more severe response
        they demand (e.g. a stop 0 on a contact force) is not hidden by the fault.
        """
        try:
            self._m.reset()
        except Exception:  # pragma: no cover
            pass
        self._confirmed = False  # a fault cycle ends a confirmation: the next band cycle asks again
        found: list[str] = []
        lat = self._lat
        if bad is not None and self._stateless:
            badset = set(bad)
            if r is not None and self._rslot not in badset:
                self._vals[self._rslot] = r
            for fn, oid, s, slots, i in self._stateless:
                if badset.isdisjoint(slots):
                    try:
                        hit = fn()
                    except Exception:
                        continue  # this cycle fails closed anyway
                    if hit:
                        found.append(oid)
                        if not lat[i]:
                            lat[i] = s
                            self._nlat += 1
        if r is not None and r >= self._tau:
            found.append("risk")
            if not lat[self._ri]:
                lat[self._ri] = self._risk_sev
                self._nlat += 1
        violations = tuple(found) if found else _EMPTY
        sev = self._latch_fault()
        margins = self._nan_margins if self._margins_on else _EMPTY
        return Decision(True, _RESPONSES[sev], violations, margins, r, cycle, False, reasons)
