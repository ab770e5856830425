"""The verdict of one monitor cycle."""

from __future__ import annotations

from itertools import compress

from ..language import Response
from ._fault import Fault

__all__ = ["Decision", "Acknowledgement", "Fault", "Response"]


class Decision:
    """What the monitor decided in one control cycle.

    Attributes:
        override: ``True`` means: leave the task now and execute ``response``.
        response: the :class:`Response` to execute (``Response.NONE`` when not overriding).
        violations: ids of the obligations violated this cycle (``"risk"`` for the
            built-in rule R_e ≥ τ).
        margins: robustness of each obligation this cycle, in ``Monitor.obligation_ids``
            order (> 0 satisfied, < 0 violated, ±inf for purely boolean conditions,
            NaN on a fault cycle when nothing was evaluated).
        risk: R_e used this cycle, or ``None`` if no usable risk input arrived.
        cycle: the cycle number (0 after construction or ``reset()``).
        latched: the override is held by the release rule, not by a current violation.
        faults: fail-closed reasons, each a :class:`Fault` (``kind`` such as ``"missing"``,
            ``"range"``, ``"stale"``, ``"internal"``, and a ``message``); empty when none.
        awaiting_release: a manual latch is ready for the operator: every rule latched with
            ``release: manual`` has met its release condition for its ``hold_cycles``, so
            :meth:`Monitor.acknowledge` would release it now (``False`` when none is latched).
        ids: the obligation ids that name ``margins`` (the monitor's ``obligation_ids`` tuple, shared by
            reference: nothing is copied per cycle); read a margin by name with :meth:`margin`.
        latched_rules: the rules whose latch holds the override after this cycle, by name (obligation
            ids, ``"risk"``, ``"fault"``, ``"judge"``, ``"confirm"``, ``"pending"``; as
            :attr:`Monitor.latched_rules`); empty when the cycle did not override (filled on override
            cycles only, so a clean cycle allocates nothing for it).

    Example:
        >>> d = Decision(True, Response.SAFE_POSE, ("risk",), (), 0.62, 3, False, ())
        >>> d.override, str(d.response), d.violations
        (True, 'safe_pose', ('risk',))
    """

    __slots__ = ("override", "response", "violations", "margins", "risk", "cycle", "latched", "faults",
                 "awaiting_release", "ids", "_rules", "_names", "_lat")

    def __init__(self, override: bool, response: Response, violations: tuple[str, ...],
                 margins: tuple[float, ...], risk: float | None, cycle: int, latched: bool,
                 faults: tuple[Fault, ...], awaiting_release: bool = False, ids: tuple[str, ...] = (),
                 latched_rules: tuple[str, ...] = (), _names: tuple[str, ...] | None = None,
                 _lat: list | None = None) -> None:
        self.override = override
        self.response = response
        self.violations = violations
        self.margins = margins
        self.risk = risk
        self.cycle = cycle
        self.latched = latched
        self.faults = faults
        self.awaiting_release = awaiting_release
        self.ids = ids
        self._rules = latched_rules
        # from Monitor.step on an override cycle: the rule names (by reference) and a copy of the latch
        # severities, resolved to names on first read (a list copy per override cycle, no name tuple)
        self._names = _names
        self._lat = _lat

    @property
    def latched_rules(self) -> tuple[str, ...]:
        """The rules whose latch holds the override after this cycle, by name (see the class doc)."""
        lat = self._lat  # read once: a viewer's thread may resolve it at the same time
        if lat is not None:
            self._rules = tuple(compress(self._names, lat))
            self._lat = None
        return self._rules

    def margin(self, rule: str) -> float:
        """The margin of obligation ``rule`` this cycle (NaN where it was not evaluated, e.g. a fault cycle).

        Raises:
            KeyError: ``rule`` is no obligation of the monitor that made this decision (the message
                lists its ids).

        Example:
            >>> import ethimon
            >>> m = ethimon.Monitor(ethimon.load_spec_text(
            ...     "{ethimon: 1, name: d, signals: {gap: {unit: m}}, "
            ...     "obligations: [{id: separation, require: gap >= 0.5}]}"))
            >>> m.step({"gap": 0.8, "risk": 0.1}).margin("separation")
            0.30000000000000004
        """
        try:
            j = self.ids.index(rule)
        except ValueError:
            raise KeyError(f"no rule {rule!r} has a margin in this decision; its obligations: "
                           f"{', '.join(self.ids) or '(none)'}") from None
        if not self.margins:
            return float("nan")  # the monitor was built with margins=False
        return self.margins[j]

    def margins_by_id(self) -> dict[str, float]:
        """Every margin by obligation id (a new dict: built on request, never by :meth:`Monitor.step`)."""
        return dict(zip(self.ids, self.margins)) if self.margins else {r: float("nan") for r in self.ids}

    @property
    def reasons(self) -> tuple[str, ...]:
        """Human-readable reasons for an override (violations, faults, latch)."""
        out = [f"violated: {v}" for v in self.violations]
        out += [f"fault: {f.message}" for f in self.faults]
        if self.awaiting_release:
            out.append("latched: waiting for an operator acknowledgement (Monitor.acknowledge())")
        elif self.latched:
            out.append("latched: waiting for the release rule")
        return tuple(out)

    def as_dict(self) -> dict:
        """A JSON-ready dict of this decision (``faults``: the messages, ``fault_kinds``: their kinds)."""
        return {
            "cycle": self.cycle, "override": self.override, "response": self.response.value,
            "violations": list(self.violations), "risk": self.risk, "latched": self.latched,
            "faults": [f.message for f in self.faults], "fault_kinds": [f.kind for f in self.faults],
            "awaiting_release": self.awaiting_release, "latched_rules": list(self.latched_rules),
            "margins": [m if m == m and abs(m) != float("inf") else (None if m != m else (
                "inf" if m > 0 else "-inf")) for m in self.margins],
        }

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Decision):
            return NotImplemented
        return (self.override, self.response, self.violations, self.risk, self.cycle, self.latched,
                self.faults, self.awaiting_release) == (other.override, other.response, other.violations,
                                                        other.risk, other.cycle, other.latched, other.faults,
                                                        other.awaiting_release)

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        return (f"Decision(cycle={self.cycle}, override={self.override}, response={self.response.value!r}, "
                f"violations={self.violations!r}, risk={self.risk!r}, latched={self.latched}, "
                f"faults={self.faults!r}" + (", awaiting_release=True)" if self.awaiting_release else ")"))


class Acknowledgement:
    """The answer to :meth:`Monitor.acknowledge` (an operator's release of manual latches).

    Attributes:
        released: the manual latches were released (truthiness is this flag).
        rules: the rules released (obligation ids, ``"risk"``, ``"fault"``) when ``released``;
            otherwise the rules that refused, each still violated or not yet held for its
            ``hold_cycles`` (empty when nothing awaited an acknowledgement).
        message: one line for the operator.

    Example:
        >>> a = Acknowledgement(False, ("clamping",), "refused: clamping still fails")
        >>> bool(a), a.rules
        (False, ('clamping',))
    """

    __slots__ = ("released", "rules", "message")

    def __init__(self, released: bool, rules: tuple[str, ...], message: str) -> None:
        self.released = released
        self.rules = rules
        self.message = message

    def __bool__(self) -> bool:
        return self.released

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Acknowledgement):
            return NotImplemented
        return (self.released, self.rules, self.message) == (other.released, other.rules, other.message)

    __hash__ = None  # type: ignore[assignment]

    def as_dict(self) -> dict:
        """A JSON-ready dict."""
        return {"released": self.released, "rules": list(self.rules), "message": self.message}

    def __repr__(self) -> str:
        return f"Acknowledgement(released={self.released}, rules={self.rules!r}, message={self.message!r})"
