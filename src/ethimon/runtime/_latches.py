"""The monitor's latches: one per rule, what holds them (public state), their release count after a
valid cycle, the operator's acknowledgement, a forced release, and carrying latches over a reload."""

from __future__ import annotations

from typing import Any

from ..language import SEVERITY_ORDER
from ._decision import Acknowledgement

_NO_TASK = object()  # acknowledge() without a task_id: confirm the last cycle's text


class _Latches:
    """Latch state and release (a base of :class:`~ethimon.runtime.Monitor`)."""

    __slots__ = ()

    @property
    def latched(self) -> bool:
        """Whether an override is latched right now."""
        return self._nlat > 0

    @property
    def latched_rules(self) -> tuple[str, ...]:
        """The rules whose latch holds the override now: obligation ids, ``"risk"``, ``"fault"``."""
        return tuple(name for name, s in zip(self._names, self._lat) if s)

    def holding(self) -> tuple[dict, ...]:
        """What holds the override now: one JSON-ready dict per latched rule, the most severe first
        (empty when nothing is latched). O(rules); nothing is computed while nothing is latched.

        Each dict: ``rule`` (an obligation id, ``"risk"``, ``"fault"``, ``"judge"``, ``"confirm"`` or
        ``"pending"``), ``response``, ``since_cycle`` (the cycle it latched), ``release`` (how it is
        released: ``"auto"`` after ``hold_cycles`` clean cycles in a row, ``"estimate"``: by itself once
        the awaited inputs arrive, ``"acknowledge"``: an operator's :meth:`acknowledge` once its
        condition has held ``hold_cycles`` cycles, ``"confirm"``: an acknowledgement confirms the text, or
        it releases by itself once the band no longer holds it), ``hold_cycles``, ``held_cycles`` (its
        count so far), ``acknowledge`` (whether :meth:`acknowledge` releases it) and ``how`` (one line
        for a person).

        Example:
            >>> import ethimon
            >>> m = ethimon.Monitor(ethimon.load_spec_text("{ethimon: 1, name: demo}"))
            >>> _ = m.step({})  # no risk input: a fault
            >>> [(h["rule"], h["release"], h["acknowledge"]) for h in m.holding()]
            [('fault', 'acknowledge', True)]
        """
        if not self._nlat:
            return ()
        lat, run, holds, manual, names, since = self._lat, self._run, self._holds, self._manual, self._names, self._since
        out = []
        for k in range(self._nsrc):
            s = lat[k]
            if not s:
                continue
            n, c = holds[k], max(run[k], 0)
            if k == self._pi:
                how, text = "estimate", ("by itself on the first cycle with every awaited input usable (the task "
                                         "text's risk estimate, a signal not seen since the start)")
            elif k == self._ci:
                how, text = "confirm", ("an acknowledgement confirms the text in the band; or by itself once the "
                                        "band no longer holds it (the judge said safe, R_e left the band)")
            elif manual[k]:
                how, text = "acknowledge", (f"an acknowledgement once its condition has held {n} cycles in a row "
                                            f"({c} of {n} now)")
            else:
                how, text = "auto", f"by itself after {n} clean cycles in a row ({c} of {n} now)"
            out.append({"rule": names[k], "response": SEVERITY_ORDER[s].value, "since_cycle": since[k],
                        "release": how, "hold_cycles": n, "held_cycles": c,
                        "acknowledge": bool(manual[k]) or k == self._ci, "how": text, "_sev": s})
        out.sort(key=lambda h: -h["_sev"])
        for h in out:
            del h["_sev"]
        return tuple(out)

    @property
    def history_cycles(self) -> int:
        """How many of the last cycles the temporal history spans (since the start, a :meth:`reset` or a
        fault cycle, which restarts it)."""
        return self._cycle - self._hist0

    @property
    def pending_responses(self) -> tuple[str, ...]:
        """The obligations whose bounded response is due: ``when`` fired, ``require`` not met yet,
        ``within_cycles`` not yet passed (a fresh monitor would forget the deadline)."""
        return tuple(oid for oid, due in self._m.pending if due())

    def carry_latches(self, rules) -> None:
        """Latch ``rules`` (names as in :attr:`latched_rules` of the monitor this one replaces) here,
        each with this monitor's response and release for it, its release count at 0: the release
        condition must hold its ``hold_cycles`` again, and a manual rule still needs :meth:`acknowledge`.

        Raises:
            ValueError: a name that is no rule of this monitor (nothing is latched then).
        """
        idx = {n: k for k, n in enumerate(self._names)}
        missing = [n for n in rules if n not in idx]
        if missing:
            raise ValueError(f"no rule {', '.join(map(repr, missing))} in spec {self.spec.name!r}")
        for n in rules:
            k = idx[n]
            if not self._lat[k]:
                self._lat[k] = self._sevs[k]
                self._since[k] = self._cycle
                self._nlat += 1
            self._run[k] = 0

    def _clear(self) -> None:
        for k in range(self._nsrc):
            self._lat[k] = 0
            self._run[k] = 0
        self._nlat = 0
        self._confirmed = False

    def reset(self) -> None:
        """Start a fresh trace: cycle 0, no latch, empty temporal history."""
        self._m.reset()
        self._cycle = 0
        self._hist0 = 0
        self._clear()

    def release(self) -> None:
        """Force the release of every latch, automatic and manual, with no check (commissioning,
        tests); an operator acknowledges with :meth:`acknowledge`, which checks.

        Temporal history is kept; the next :meth:`step` still overrides if a
        rule is violated or an input is bad.
        """
        self._clear()

    def acknowledge(self, task_id: Any = _NO_TASK) -> Acknowledgement:
        """An operator's acknowledgement: release the rules latched with ``release: manual``.

        Refused (nothing is released) while any of them has not met its release
        condition on the last ``hold_cycles`` consecutive cycles: the obligation held,
        R_e < τ − δ for the risk rule, no fault for the fault latch. Automatic latches
        keep their own rule. A latched ``"confirm"`` (the confirm band) needs no count: the
        acknowledgement is the confirmation, and it holds for the last cycle's ``task_id`` until
        that changes, R_e leaves the band, or a cycle faults (refused while that cycle gave no
        ``task_id``: a confirmation bound to no text would hold for every text in the band). Takes effect from the next :meth:`step`, which overrides
        again if a rule is violated or an input is bad.

        Args:
            task_id: the ``task_id`` of the text the operator was shown. While ``"confirm"`` is
                latched and this names another text than the last cycle's (the planner replaced
                it meanwhile), nothing is released: a person confirms only what they saw. Omitted:
                the last cycle's text is confirmed.

        Returns:
            An :class:`~ethimon.runtime.Acknowledgement`: ``released`` (also its truth
            value), the rules released or refused, and a message for the operator.

        Example:
            >>> import ethimon
            >>> m = ethimon.Monitor(ethimon.load_spec_text('''
            ... ethimon: 1
            ... name: demo
            ... signals: {contact_force: {unit: N, range: [0, 1000]}}
            ... obligations:
            ...   - {id: contact, require: contact_force <= 140, response: stop_0}
            ... risk: {release: {hold_cycles: 2}}
            ... '''))
            >>> m.step({"p_unsafe": 0.0, "contact_force": 300.0}).response
            <Response.STOP_0: 'stop_0'>
            >>> m.acknowledge().message
            'refused: contact still fails'
            >>> for _ in range(2):
            ...     d = m.step({"p_unsafe": 0.0, "contact_force": 0.0})
            >>> d.override, d.awaiting_release, bool(m.acknowledge())
            (True, True, True)
            >>> m.step({"p_unsafe": 0.0, "contact_force": 0.0}).override
            False
        """
        lat, run, holds, manual, names = self._lat, self._run, self._holds, self._manual, self._names
        ready = [k for k in range(self._nsrc) if lat[k] and manual[k] and run[k] >= holds[k]]
        ci = self._ci
        waiting = [k for k in range(self._nsrc) if lat[k] and manual[k] and run[k] < holds[k]]
        if waiting:
            return Acknowledgement(False, tuple(names[k] for k in waiting), "refused: " + "; ".join(
                f"{names[k]} still fails" if run[k] <= 0 else
                f"{names[k]} has held {run[k]} of {holds[k]} cycles" for k in waiting))
        if lat[ci]:  # the confirm band: the acknowledgement is its release condition
            if task_id is not _NO_TASK and task_id != self._last_task:
                return Acknowledgement(False, (names[ci],), "refused: confirm is for the task in the band now, "
                                       "not the one acknowledged (the task text changed since it was shown)")
            if self._last_task is None:  # bound to nothing, it would hold for every text in the band
                return Acknowledgement(False, (names[ci],), "refused: confirm needs the task_id of the text "
                                       "in the band (none was given this cycle) to bind the confirmation to")
            ready.append(ci)
        if not ready:
            return Acknowledgement(False, (), "nothing awaits an acknowledgement" + (
                " (the override is held by automatic releases)" if self._nlat else ""))
        for k in ready:
            lat[k] = 0
            run[k] = 0
        self._nlat -= len(ready)
        if ci in ready:  # the text in the band is confirmed until it changes
            self._confirmed = True
            self._ctask = self._last_task
        return Acknowledgement(True, tuple(names[k] for k in ready),
                               "released: " + ", ".join(names[k] for k in ready))

    def _release_pass(self, below: bool) -> tuple[int, bool]:
        """After a valid cycle: count each latched rule's release condition, release the
        automatic ones whose count reached their hold. O(rules), only while latched.

        Returns:
            ``(severity still latched, awaiting_release)``.
        """
        lat, run, holds, manual = self._lat, self._run, self._holds, self._manual
        ri, ci = self._ri, self._ci
        sev = 0
        n_manual = ready = 0
        for k in range(self._nsrc):
            s = lat[k]
            if not s:
                continue
            c = run[k]
            if c < 0 or (k == ri and not below):  # fired this cycle, or R_e not below τ − δ
                c = 0
            else:
                c += 1
                if c >= holds[k]:
                    if not manual[k]:
                        lat[k] = 0
                        run[k] = 0
                        self._nlat -= 1
                        continue
                    c = holds[k]  # a manual count stops at its hold: ready for acknowledge()
            run[k] = c
            if s > sev:
                sev = s
            if manual[k]:
                n_manual += 1
                if c >= holds[k]:
                    ready += 1
            elif k == ci:  # auto-released once the band stops holding; acknowledge() releases it at once
                n_manual += 1
                ready += 1
        return sev, n_manual > 0 and ready == n_manual
