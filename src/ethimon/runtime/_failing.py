"""Failing closed: the fault rule's latch, a cycle that cannot be judged, and a fault found
outside the monitor (watchdog, estimator, audit)."""

from __future__ import annotations

from ..language import SEVERITY_ORDER
from ._calls import _EMPTY
from ._decision import Decision
from ._fault import Fault
from ._inputs import as_number

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
                        decision.cycle, decision.latched, decision.faults + reasons, False, self.obligation_ids,
                        _EMPTY, self._names, self._lat[:])

    def _latch_fault(self, k: int | None = None) -> int:
        """Latch the fault rule (or rule ``k``: the pending hold); every release count restarts (the cycle
        is not a clean one). Returns the most severe latched response."""
        lat, run = self._lat, self._run
        fi = self._fi if k is None else k
        if not lat[fi]:
            lat[fi] = self._fault_sev if k is None else self._sevs[k]
            self._since[fi] = self._cycle - 1
            self._nlat += 1
        sev = 0
        for k in range(self._nsrc):
            run[k] = 0
            if lat[k] > sev:
                sev = lat[k]
        return sev

    def _pending(self, cycle: int, faults: list, bad: list | None, pend, r: float | None) -> Decision:
        """A cycle whose inputs are awaited (``pending_s``): the pending hold, or the fault it becomes.

        It is a pending hold (stop 2, no fault, released by itself on the first cycle with every input
        usable) only while every fault is a ``missing`` input (a signal, the risk input or its age) and the
        wait ``pending_s`` is a number of seconds within the age limit of the risk estimate; past the
        limit, without a limit, or with any other fault the cycle fails closed as before.
        """
        w = as_number(pend)
        limit = self._max_age
        if w is None or w < 0.0 or limit is None or any(f.kind != "missing" for f in faults):
            if w is None or w < 0.0:
                faults.append(Fault("invalid", f"pending_s={pend!r} is not a number of seconds >= 0", "pending_s"))
            return self._fault(cycle, tuple(faults), r, bad)
        if w > limit:
            faults.append(Fault("estimator", f"inputs still missing {w:.3f} s after the start or the new task "
                                f"text, more than max_age_s {limit:g}: " + "; ".join(f.message for f in faults),
                                "pending_s"))
            return self._fault(cycle, tuple(faults), r, bad)
        self._confirmed = False  # a confirmation is for a text whose R_e was seen in the band
        rs = self._rslot
        if not self._risk_free or any(s != rs for s in bad):
            return self._fault(cycle, _EMPTY, None, bad, latch=self._pi)
        # every signal usable and no condition reads R_e: judge them all, the temporal history goes on
        lat, run, sevs = self._lat, self._run, self._sevs
        try:
            self._ucall()
            vs = self._vcall()
            margins = self._mcall() if self._margins_on else _EMPTY
        except Exception as exc:  # fail closed, as step does
            return self._fault(cycle, (Fault("internal", f"internal error: {type(exc).__name__}: {exc}"),), None)
        found = [oid for (fn, oid, sv, i), v in zip(self._obs, vs) if v]
        found.append("pending")
        for (fn, oid, sv, i), v in zip(self._obs, vs):
            if v:
                if not lat[i]:
                    lat[i] = sevs[i]
                    self._since[i] = cycle
                    self._nlat += 1
                run[i] = -1
        pi = self._pi
        if not lat[pi]:
            lat[pi] = sevs[pi]
            self._since[pi] = cycle
            self._nlat += 1
        run[pi] = -1
        sev, awaiting = self._release_pass(False)  # no R_e: the risk rule's count restarts
        return Decision(True, _RESPONSES[sev], tuple(found), margins, None, cycle, False, _EMPTY, awaiting,
                        self.obligation_ids, _EMPTY, self._names, self._lat[:])

    def _fault(self, cycle: int, reasons: tuple[Fault, ...], r: float | None,
               bad: list[int] | None = None, latch: int | None = None) -> Decision:
        """Fail closed: override with the spec's fault response; history is invalid.

        With ``bad`` (the slots of the unusable inputs), the stateless obligations
        whose inputs are all valid are still evaluated, so a more severe response
        they demand (e.g. a stop 0 on a contact force) is not hidden by the fault.
        ``latch``: the rule latched instead of the fault rule (the pending hold; no fault then).
        """
        try:
            self._m.reset()
        except Exception:  # pragma: no cover
            pass
        self._hist0 = cycle + 1  # the temporal history restarts after this cycle
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
                            self._since[i] = cycle
                            self._nlat += 1
        if r is not None and r >= self._tau:
            found.append("risk")
            if not lat[self._ri]:
                lat[self._ri] = self._risk_sev
                self._since[self._ri] = cycle
                self._nlat += 1
        if latch is not None:
            found.append(self._names[latch])
        violations = tuple(found) if found else _EMPTY
        sev = self._latch_fault(latch)
        margins = self._nan_margins if self._margins_on else _EMPTY
        return Decision(True, _RESPONSES[sev], violations, margins, r, cycle, False, reasons, False,
                        self.obligation_ids, _EMPTY, self._names, self._lat[:])
