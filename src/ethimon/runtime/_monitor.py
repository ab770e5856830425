"""The runtime monitor: ``Monitor.step(signals) -> Decision`` every control cycle.

The monitor never imports YAML, the loader, torch or pybullet. Everything is
resolved at construction (signal slots, closures, thresholds); ``step`` reads
the inputs, updates O(1) temporal state, evaluates each obligation once and
applies the latch/release rule. One guard turns any internal fault into a
fail-closed override: no exception escapes ``step``.
"""

from __future__ import annotations

import math
import re
from math import isfinite as _isfinite
from collections.abc import Mapping
from typing import Any

from ..compiler import Plan, plan_of, stateless_slots
from ..compiler._closures import build_machine  # the compiler's closures: runtime is their one caller
from ..language import SEVERITY_ORDER, Response, Spec
from ._calls import _EMPTY, _all_margins, _tuple_of_calls
from ._decision import Acknowledgement, Decision
from ._fault import Fault
from ._inputs import as_bool, as_number
from ._latches import Latches
from ._risk_input import RiskInput
from ._tiers import Tiers

__all__ = ["Monitor"]

_RESPONSES = SEVERITY_ORDER  # severity -> Response
_NONE = Response.NONE  # read once: an Enum member's attribute access is slow on CPython 3.11
_INTERNAL = Fault("internal", "internal error")
_EXTERNAL = Fault("external", "external fault")
_NO_TASK = object()  # acknowledge() without a task_id: confirm the last cycle's text
_READS_RISK = re.compile(r"\brisk\b")


class Monitor:
    """Runtime monitor compiled from a spec; call :meth:`step` once per control cycle.

    Args:
        plan: a compiled :class:`~ethimon.compiler.Plan`, or a :class:`~ethimon.Spec` from
            :func:`ethimon.load_spec` (which carries its plan: :func:`ethimon.compiler.plan_of` reads it).
        margins: compute per-obligation robustness margins each cycle (a little slower).

    Each cycle pass a mapping with the spec's signals and one risk input:
    ``risk`` (R_e itself), or ``p_unsafe`` (two classes), or ``p`` (the class
    probability vector); the monitor then forms R_e with the spec's formula.
    With an age limit (the spec's ``risk.max_age_s``, else ``max_age_s`` here),
    ``risk_age_s`` (seconds since the estimate) is required too, and an older
    estimate is a ``"stale"`` fault. Keys the spec does not declare are ignored.

    With a confirm band (``risk.confirm_threshold``) or a judge (``risk.judge``), two more inputs:
    ``judge``, the judge's p_unsafe (absent or ``None``: no judgement; anything else outside [0, 1]
    is an ``"invalid"`` fault), and ``task_id``, any value naming the task text (its hash), to which
    an operator's confirmation is bound. The rule ``"judge"`` fires on an unsafe verdict at any R_e;
    ``"confirm"`` (stop 2) fires in [τ_confirm, τ) unless the judge said safe or the task is confirmed.

    Every rule (each obligation, the risk rule, the fault rule) has its own latch:
    an override lasts while any is set, with the most severe latched response. An
    ``auto`` latch releases once its condition has held ``hold_cycles`` cycles in a
    row; a ``manual`` one (default: faults and stop_0/stop_1 rules) only through
    :meth:`acknowledge`, :meth:`release` or :meth:`reset`.

    Args:
        max_age_s: oldest usable risk estimate in seconds when the spec sets no
            ``risk.max_age_s`` (the spec's value wins when it has one); ``None``:
            no limit. :class:`~ethimon.loop.GovernedLoop` passes its ``max_risk_age_s``.

    Example:
        >>> import ethimon
        >>> spec = ethimon.load_spec_text('''
        ... ethimon: 1
        ... name: demo
        ... signals: {human_distance: {unit: m, range: [0, 10]}}
        ... obligations:
        ...   - {id: keep_away, require: "human_distance >= 0.5"}
        ... ''')
        >>> m = ethimon.Monitor(spec)
        >>> m.step({"p_unsafe": 0.05, "human_distance": 2.0}).override
        False
        >>> d = m.step({"p_unsafe": 0.05, "human_distance": 0.3})
        >>> d.override, d.violations
        (True, ('keep_away',))
    """

    __slots__ = ("spec", "plan", "obligation_ids", "_m", "_vals", "_sig", "_fsig", "_rslot", "_ucall", "_vcall",
                 "_obs", "_stateless", "_margins_on", "_margin_fns", "_mcall", "_nan_margins",
                 "_tau", "_release_cut", "_risk_free", "_cycle", "_hist0", "_risk", "_tiers", "_latches", "_hot",
                 "_sindex")

    def __init__(self, plan: Plan | Spec, *, margins: bool = True, max_age_s: float | None = None) -> None:
        plan = plan_of(plan)
        self.plan = plan
        self.spec = plan.spec
        # the compiled machine and the signal slots: everything step reads, resolved once
        m = build_machine(plan)
        self._m = m
        self._vals = m.vals
        self._sig = tuple((s.name, s.slot, s.kind == "bool", s.lo, s.hi,
                           Fault("missing", f"signal {s.name!r} is missing", s.name))  # built once, not per cycle
                          for s in plan.signals)
        # the fast reading: (name, slot, is_bool, lo, hi); the first input that is not a built-in float
        # in range (or a bool) hands over to _read_rest (from its index in _sindex), which judges it as before
        self._fsig = tuple((s.name, s.slot, s.kind == "bool", s.lo, s.hi) for s in plan.signals)
        self._sindex = {s.name: k for k, s in enumerate(plan.signals)}
        self._rslot = plan.risk_slot
        # one call each per cycle: every temporal update (inner operators first), then every
        # obligation's verdict (all of them, in order: bounded responses keep state), as one tuple
        self._ucall = m.updates[0] if len(m.updates) == 1 else _tuple_of_calls(m.updates)
        self._vcall = _tuple_of_calls(m.violated)
        self._obs = tuple((ob.id, i) for i, ob in enumerate(plan.obligations))  # (id, latch index) per verdict
        self._stateless = tuple((fn, ob.id, ob.response.severity, slots, i)
                                for i, (fn, ob) in enumerate(zip(m.violated, plan.obligations))
                                if (slots := stateless_slots(plan, ob)) is not None)
        self.obligation_ids: tuple[str, ...] = tuple(ob.id for ob in plan.obligations)
        self._margins_on = margins
        self._margin_fns = m.margins
        # every margin once per cycle: unguarded in one tuple when none can raise (chosen at compile
        # time: no division, sqrt or separation_distance), else each guarded (NaN where one raises)
        self._mcall = _tuple_of_calls(m.margins) if not m.margins_raise else (
            lambda fns=m.margins: _all_margins(fns))
        self._nan_margins = tuple(math.nan for _ in plan.obligations)
        # the risk rule: τ and the release cut, resolved once in the plan (exact: 0.27 - 0.05 is 0.22)
        self._tau = plan.threshold
        self._release_cut = plan.release_cut
        # a pending cycle with every signal usable keeps the temporal history when no obligation reads R_e
        # (the word ``risk`` in no condition; a false positive only takes the fault path's evaluation)
        self._risk_free = not any(_READS_RISK.search(t) for ob in plan.obligations
                                  for t in (ob.when_text or "", ob.require_text))
        # the parts that own their state: the risk input, the latches, the tiers
        self._risk = RiskInput(plan, max_age_s)
        self._latches = latches = Latches(plan)
        self._tiers = Tiers(plan, latches.ji, latches.ci)
        self._cycle = 0
        self._hist0 = 0  # the cycle from which the temporal history runs (set by a reset or a fault)
        # what a clean cycle reads, bound once: step unpacks it into locals in one go (none of it is ever
        # rebound; the lists and the parts change in place). ``clean``: the verdicts of a cycle on which
        # no obligation fires (a tuple compared by identity of its bools, no ``True in`` scan);
        # ``cut``: R_e below it and clean verdicts, nothing can fire (τ; -inf with a judge or a confirm
        # band, whose tier is judged on every valid cycle)
        clean = tuple(False for _ in plan.obligations)
        cut = self._tau if not self._tiers.on else -math.inf
        self._hot = (self._fsig, self._vals, self._risk, self._tiers, latches, self._rslot, self._ucall,
                     self._vcall, clean, cut, self._mcall if margins else None, self.obligation_ids)

    # -- public state ----------------------------------------------------------------
    @property
    def cycle(self) -> int:
        """Number of cycles stepped since construction or the last :meth:`reset`."""
        return self._cycle

    def set_max_age(self, fallback: float | None) -> None:
        """Set the one age limit of the risk input: the spec's ``risk.max_age_s`` if it sets one, else
        ``fallback`` seconds (``None``: no limit, ``risk_age_s`` is not required).

        The constructor's ``max_age_s`` goes through here; :class:`~ethimon.loop.GovernedLoop` calls it with
        its ``max_risk_age_s`` when it feeds the monitor from a risk source and neither the spec nor the
        monitor set a limit. With a limit, a cycle without ``risk_age_s`` or with an older estimate is a fault.

        Raises:
            ValueError: ``fallback`` is not a positive, finite number of seconds or ``None``.
        """
        self._risk.set_max_age(fallback)

    @property
    def max_age_s(self) -> float | None:
        """The age limit in force for risk estimates (the spec's ``risk.max_age_s`` first), or ``None``."""
        return self._risk.max_age

    def step(self, signals: Mapping[str, Any]) -> Decision:
        """Check one control cycle.

        Args:
            signals: the cycle's inputs by name (extra keys are ignored).

        Returns:
            The :class:`Decision`. Never raises: bad input or an internal error
            gives ``override=True`` with the reason in ``Decision.faults``.
        """
        cycle = self._cycle
        self._cycle = cycle + 1
        r = None
        try:
            get = signals.get
            fsig, vals, risk, tiers, latches, rslot, ucall, vcall, clean, cut, mcall, ids = self._hot
            faults = None
            bad = None  # slots whose input is unusable this cycle (fault path only)
            for name, slot, is_bool, lo, hi in fsig:
                v = get(name)
                if is_bool:
                    if v is True or v is False:
                        vals[slot] = v
                        continue
                elif type(v) is float and lo <= v <= hi:  # the common case: a built-in float in range
                    vals[slot] = v
                    continue
                faults, bad = self._read_rest(get, self._sindex[name], v)  # anything else: judged there, once
                break
            rin = get("risk")  # read first; p_unsafe only without it
            if rin is None and type(q := get("p_unsafe")) is float and risk.p2 and 0.0 <= q <= 1.0:
                # the common case, as RiskInput.from_p: compiler._risk_formula.two_class_risk inlined (hot
                # path; tests/compiler/test_plan_of.py checks this copy equals the one definition on a grid
                # of inputs and weights)
                d = q - 0.5
                var = 2.0 * d * d if risk.sample else d * d
                top = q if q >= 0.5 else 1.0 - q
                r = risk.alpha * q + risk.beta * (1.0 - top) + risk.gamma * var
                if not _isfinite(r):  # weights and inputs are finite; never trust it blindly
                    why = Fault("internal", f"R_e={r!r} is not finite")
                    r = None
                    (faults := faults or []).append(why)
                    (bad := bad or []).append(rslot)
            else:
                r, why = risk.direct(rin) if rin is not None else risk.from_p(get, q)
                if why is None and not _isfinite(r):  # as above
                    r, why = None, Fault("internal", f"R_e={r!r} is not finite")
                if why is not None:
                    (faults := faults or []).append(why)
                    (bad := bad or []).append(rslot)
            max_age = risk.max_age
            if max_age is not None:
                age = get("risk_age_s")
                a = None if age is None else as_number(age)
                if age is None:
                    (faults := faults or []).append(risk.age_missing)
                    (bad := bad or []).append(rslot)
                elif a is None or not 0.0 <= a <= max_age:
                    (faults := faults or []).append(Fault(
                        "stale",
                        f"risk estimate is stale or its age is invalid: {age!r} s > max_age_s {max_age:g}", "risk_age_s"))
                    (bad := bad or []).append(rslot)
            jp = None
            if tiers.judge_on:  # the judge's p_unsafe, or None: no judgement (a normal state)
                jin = get("judge")
                if jin is not None:
                    jp = jin if type(jin) is float else as_number(jin)
                    if jp is None or not 0.0 <= jp <= 1.0:
                        (faults := faults or []).append(tiers.judge_fault(jin))
                        bad = bad or []
                        jp = None
            if faults is not None:
                pend = get("pending_s")
                if pend is not None:  # inputs awaited after the start or a new task text
                    return self._pending(cycle, faults, bad, pend, r)
                return self._fault(cycle, tuple(faults), r, bad)
            vals[rslot] = r
            ucall()
            vs = vcall()  # each verdict is a bool
            violations = None
            held = False
            # the common case (verdicts all clean, R_e below the cut): nothing fires, nothing to latch
            if vs != clean or r >= cut:
                hits = None  # latched only once every obligation was judged (a later one may raise)
                if vs != clean:
                    violations = []
                    hits = []
                    for (oid, i), v in zip(self._obs, vs):
                        if v:
                            violations.append(oid)
                            hits.append(i)
                if r >= self._tau and not (held := (tiers.hold_hi is not None and r < tiers.hold_hi
                                                    and jp is not None and jp < tiers.jsafe)):
                    if violations is None:
                        violations = ["risk"]
                        hits = [latches.ri]
                    else:
                        violations.append("risk")
                        hits.append(latches.ri)
                if tiers.on:
                    tier = tiers.tier(r, jp, get)
                    if tier is not None:
                        if violations is None:
                            violations = [tier[0]]
                            hits = [tier[1]]
                        else:
                            violations.append(tier[0])
                            hits.append(tier[1])
                if hits is not None:
                    lat, sevs = latches.lat, latches.sevs
                    run = latches.run
                    for i in hits:
                        if not lat[i]:
                            lat[i] = sevs[i]
                            latches.since[i] = cycle
                            latches.n += 1
                        run[i] = -1
            margins = _EMPTY if mcall is None else mcall()  # a margin that cannot be computed is NaN
            if not latches.n:  # ids: the obligation-id tuple by reference (Decision.margin reads it)
                return Decision(False, _NONE, _EMPTY, margins, r, cycle, False, _EMPTY, False, ids)
            sev, awaiting = latches.release_pass(r < self._release_cut or held)  # held: the confirm latch holds
            if violations is not None:
                return Decision(True, _RESPONSES[sev], tuple(violations), margins, r, cycle, False, _EMPTY,
                                awaiting, ids, _EMPTY, latches.names, latches.lat[:])
            if not latches.n:  # the last latch released this cycle
                return Decision(False, _NONE, _EMPTY, margins, r, cycle, False, _EMPTY, False, ids)
            return Decision(True, _RESPONSES[sev], _EMPTY, margins, r, cycle, True, _EMPTY, awaiting,
                            ids, _EMPTY, latches.names, latches.lat[:])
        except BaseException as exc:  # fail closed: nothing escapes into the control loop, not even
            # a KeyboardInterrupt raised by a hostile input's __float__: the arm is told to stop instead
            try:
                reason = Fault("internal", f"internal error: {type(exc).__name__}: {exc}")
            except BaseException:  # pragma: no cover - a broken __str__
                reason = _INTERNAL
            return self._fault(cycle, (reason,), r if type(r) is float else None)

    def _read_rest(self, get, start: int, v0) -> tuple[list | None, list | None]:
        """The signals from index ``start`` on (``v0``: the value already read for it), each
        converted once at the boundary (see ``_inputs``): ``(faults, bad slots)``, ``None`` each if
        every one was usable."""
        vals = self._vals
        faults = None
        bad = None
        sig = self._sig
        for j in range(start, len(sig)):
            name, slot, is_bool, lo, hi, missing = sig[j]
            v = v0 if j == start else get(name)
            if v is None:
                (faults := faults or []).append(missing)
                (bad := bad or []).append(slot)
            elif is_bool:
                b = v if (v is True or v is False) else as_bool(v)
                if b is None:
                    (faults := faults or []).append(
                        Fault("invalid", f"signal {name!r} must be true/false, got {v!r}", name))
                    (bad := bad or []).append(slot)
                else:
                    vals[slot] = b
            else:
                # the common case (a built-in float) first; anything else is converted once
                f = v if type(v) is float else as_number(v)
                if f is None:
                    (faults := faults or []).append(Fault(
                        "invalid", f"signal {name!r} must be a number, got {v!r} (a finite int, float or "
                        f"numpy scalar; not a bool, string or NaN)", name))
                    (bad := bad or []).append(slot)
                elif lo <= f <= hi:
                    vals[slot] = f
                else:
                    (faults := faults or []).append(Fault(
                        "range" if _isfinite(f) else "invalid",
                        f"signal {name!r} = {v!r} is NaN or outside its range [{lo:g}, {hi:g}]", name))
                    (bad := bad or []).append(slot)
        return faults, bad

    # -- the latches (runtime/_latches.py owns their state) -----------------------------
    @property
    def latched(self) -> bool:
        """Whether an override is latched right now."""
        return self._latches.n > 0

    @property
    def latched_rules(self) -> tuple[str, ...]:
        """The rules whose latch holds the override now: obligation ids, ``"risk"``, ``"fault"``."""
        return self._latches.rules()

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
        return self._latches.holding()

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
        self._latches.carry(rules, self._cycle, self.spec.name)

    def reset(self) -> None:
        """Start a fresh trace: cycle 0, no latch, empty temporal history."""
        self._m.reset()
        self._cycle = 0
        self._hist0 = 0
        self._latches.clear()
        self._tiers.end()

    def release(self) -> None:
        """Force the release of every latch, automatic and manual, with no check (commissioning,
        tests); an operator acknowledges with :meth:`acknowledge`, which checks.

        Temporal history is kept; the next :meth:`step` still overrides if a
        rule is violated or an input is bad.
        """
        self._latches.clear()
        self._tiers.end()

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
        latches = self._latches
        refused = latches.refusal()
        if refused is not None:
            return refused
        ready = latches.ready()
        ci, names = latches.ci, latches.names
        if latches.lat[ci]:  # the confirm band: the acknowledgement is its release condition
            why = self._tiers.refusal(task_id, _NO_TASK)
            if why is not None:
                return Acknowledgement(False, (names[ci],), why)
            ready.append(ci)
        if not ready:
            return Acknowledgement(False, (), "nothing awaits an acknowledgement" + (
                " (the override is held by automatic releases)" if latches.n else ""))
        latches.unlatch(ready)
        if ci in ready:  # the text in the band is confirmed until it changes
            self._tiers.confirm()
        return Acknowledgement(True, tuple(names[k] for k in ready),
                               "released: " + ", ".join(names[k] for k in ready))

    # read by loop/ (the latch times of GovernedLoop.holding, a reload's carried latches): the latches' state
    @property
    def _nlat(self) -> int:
        return self._latches.n

    @property
    def _since(self) -> list[int]:
        return self._latches.since

    @property
    def _names(self) -> tuple[str, ...]:
        return self._latches.names

    # -- failing closed --------------------------------------------------------------
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
        self._tiers.end()  # a fault found outside the monitor ends a confirmation too (issue 31)
        latches = self._latches
        sev = max(decision.response.severity, latches.latch_fault(None, self._cycle - 1))
        return Decision(True, _RESPONSES[sev], decision.violations, decision.margins, decision.risk,
                        decision.cycle, decision.latched, decision.faults + reasons, False, self.obligation_ids,
                        _EMPTY, latches.names, latches.lat[:])

    def _pending(self, cycle: int, faults: list, bad: list | None, pend, r: float | None) -> Decision:
        """A cycle whose inputs are awaited (``pending_s``): the pending hold, or the fault it becomes.

        It is a pending hold (stop 2, no fault, released by itself on the first cycle with every input
        usable) only while every fault is a ``missing`` input (a signal, the risk input or its age) and the
        wait ``pending_s`` is a number of seconds within the age limit of the risk estimate; past the
        limit, without a limit, or with any other fault the cycle fails closed as before.
        """
        w = as_number(pend)
        limit = self._risk.max_age
        if w is None or w < 0.0 or limit is None or any(f.kind != "missing" for f in faults):
            if w is None or w < 0.0:
                faults.append(Fault("invalid", f"pending_s={pend!r} is not a number of seconds >= 0", "pending_s"))
            return self._fault(cycle, tuple(faults), r, bad)
        if w > limit:
            faults.append(Fault("estimator", f"inputs still missing {w:.3f} s after the start or the new task "
                                f"text, more than max_age_s {limit:g}: " + "; ".join(f.message for f in faults),
                                "pending_s"))
            return self._fault(cycle, tuple(faults), r, bad)
        self._tiers.end()  # a confirmation is for a text whose R_e was seen in the band
        latches = self._latches
        rs = self._rslot
        if not self._risk_free or any(s != rs for s in bad):
            return self._fault(cycle, _EMPTY, None, bad, latch=latches.pi)
        # every signal usable and no condition reads R_e: judge them all, the temporal history goes on
        run = latches.run
        try:
            self._ucall()
            vs = self._vcall()
            margins = self._mcall() if self._margins_on else _EMPTY
        except Exception as exc:  # fail closed, as step does
            return self._fault(cycle, (Fault("internal", f"internal error: {type(exc).__name__}: {exc}"),), None)
        found = [oid for (oid, i), v in zip(self._obs, vs) if v]
        found.append("pending")
        for (oid, i), v in zip(self._obs, vs):
            if v:
                latches.latch(i, cycle)
                run[i] = -1
        latches.latch(latches.pi, cycle)
        run[latches.pi] = -1
        sev, awaiting = latches.release_pass(False)  # no R_e: the risk rule's count restarts
        return Decision(True, _RESPONSES[sev], tuple(found), margins, None, cycle, False, _EMPTY, awaiting,
                        self.obligation_ids, _EMPTY, latches.names, latches.lat[:])

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
        self._tiers.end()  # a fault cycle ends a confirmation: the next band cycle asks again
        latches = self._latches
        found: list[str] = []
        lat = latches.lat
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
                            latches.since[i] = cycle
                            latches.n += 1
        if r is not None and r >= self._tau:
            found.append("risk")
            if not lat[latches.ri]:
                lat[latches.ri] = latches.risk_sev
                latches.since[latches.ri] = cycle
                latches.n += 1
        if latch is not None:
            found.append(latches.names[latch])
        violations = tuple(found) if found else _EMPTY
        sev = latches.latch_fault(latch, self._cycle - 1)
        margins = self._nan_margins if self._margins_on else _EMPTY
        return Decision(True, _RESPONSES[sev], violations, margins, r, cycle, False, reasons, False,
                        self.obligation_ids, _EMPTY, latches.names, latches.lat[:])

    def __repr__(self) -> str:
        return f"Monitor(spec={self.spec.name!r}, obligations={len(self.obligation_ids)}, cycle={self._cycle})"
