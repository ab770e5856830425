"""The runtime monitor: ``Monitor.step(signals) -> Decision`` every control cycle.

The monitor never imports YAML, the loader, torch or pybullet. Everything is
resolved at construction (signal slots, closures, thresholds); ``step`` reads
the inputs, updates O(1) temporal state, evaluates each obligation once and
applies the latch/release rule. One guard turns any internal fault into a
fail-closed override: no exception escapes ``step``.
"""

from __future__ import annotations

import math
from math import isfinite as _isfinite
from collections.abc import Mapping
from typing import Any

from ..compiler import Plan, plan_of, stateless_slots
from ..compiler._closures import build_machine  # the compiler's closures: runtime is their one caller
from ..spec import SEVERITY_ORDER, Response, Spec
from ..compiler._risk_formula import risk_from_probs, risk_range, two_class_risk
from ._decision import Acknowledgement, Decision
from ._fault import Fault
from ._inputs import as_bool, as_number, as_probs

__all__ = ["Monitor"]

_RESPONSES = SEVERITY_ORDER  # severity -> Response
_EMPTY: tuple = ()
_NONE = Response.NONE  # read once: an Enum member's attribute access is slow on CPython 3.11
_EXTERNAL = Fault("external", "external fault")
_INTERNAL = Fault("internal", "internal error")
_NO_TASK = object()  # acknowledge() without a task_id: confirm the last cycle's text
_NO_RISK = Fault("missing", "no risk input this cycle (give risk, p_unsafe or p)", "risk")


def _all_margins(fns: tuple) -> tuple[float, ...]:
    """Every margin, each computed exactly once (bounded-response margins keep state); NaN
    where one raises (robustness ignores short-circuits, so ``y <= 0 or x / y < 2`` can divide
    by zero in its margin but not in its verdict)."""
    out = []
    i, n = 0, len(fns)
    while i < n:
        try:
            while i < n:
                out.append(fns[i]())
                i += 1
        except Exception:
            out.append(math.nan)
            i += 1
    return tuple(out)


def _tuple_of_calls(fns: tuple):
    """A closure returning ``tuple(f() for f in fns)``, written out for up to 8 (no generator, no list)."""
    n = len(fns)
    if n == 0:
        return lambda: _EMPTY
    if n == 1:
        f0, = fns
        return lambda: (f0(),)
    if n == 2:
        f0, f1 = fns
        return lambda: (f0(), f1())
    if n == 3:
        f0, f1, f2 = fns
        return lambda: (f0(), f1(), f2())
    if n == 4:
        f0, f1, f2, f3 = fns
        return lambda: (f0(), f1(), f2(), f3())
    if n == 5:
        f0, f1, f2, f3, f4 = fns
        return lambda: (f0(), f1(), f2(), f3(), f4())
    if n == 6:
        f0, f1, f2, f3, f4, f5 = fns
        return lambda: (f0(), f1(), f2(), f3(), f4(), f5())
    if n == 7:
        f0, f1, f2, f3, f4, f5, f6 = fns
        return lambda: (f0(), f1(), f2(), f3(), f4(), f5(), f6())
    if n == 8:
        f0, f1, f2, f3, f4, f5, f6, f7 = fns
        return lambda: (f0(), f1(), f2(), f3(), f4(), f5(), f6(), f7())
    return lambda: tuple([f() for f in fns])


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

    __slots__ = ("spec", "plan", "obligation_ids", "_m", "_sig", "_vals", "_rslot", "_obs",
                 "_margin_fns", "_nan_margins", "_tau", "_risk_sev", "_fault_sev", "_release_cut",
                 "_alpha", "_beta", "_gamma", "_sample", "_k", "_uidx", "_rlo", "_rhi",
                 "_max_age", "_age_missing", "_cycle", "_margins_on", "_stateless",
                 "_lat", "_run", "_sevs", "_holds", "_manual", "_names", "_nlat", "_ri", "_fi", "_nsrc",
                 "_ji", "_ci", "_tiers", "_judge_on", "_tc", "_jsafe", "_junsafe", "_confirmed", "_ctask",
                 "_last_task", "_fsig", "_mcall", "_p2", "_ucall", "_vcall")

    def __init__(self, plan: Plan | Spec, *, margins: bool = True, max_age_s: float | None = None) -> None:
        plan = plan_of(plan)
        self.plan = plan
        self.spec = plan.spec
        m = build_machine(plan)
        self._m = m
        self._vals = m.vals
        self._sig = tuple((s.name, s.slot, s.kind == "bool", s.lo, s.hi,
                           Fault("missing", f"signal {s.name!r} is missing", s.name))  # built once, not per cycle
                          for s in plan.signals)
        # the fast reading: (index, name, slot, is_bool, lo, hi); the first input that is not a
        # built-in float in range (or a bool) hands over to _read_rest, which judges it as before
        self._fsig = tuple((k, s.name, s.slot, s.kind == "bool", s.lo, s.hi) for k, s in enumerate(plan.signals))
        self._rslot = plan.risk_slot
        # one call each per cycle: every temporal update (inner operators first), then every
        # obligation's verdict (all of them, in order: bounded responses keep state), as one tuple
        self._ucall = m.updates[0] if len(m.updates) == 1 else _tuple_of_calls(m.updates)
        self._vcall = _tuple_of_calls(m.violated)
        self._obs = tuple((fn, ob.id, ob.response.severity, i)
                          for i, (fn, ob) in enumerate(zip(m.violated, plan.obligations)))
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
        r = plan.risk
        # τ, the release cut and every rule's release: resolved once in the plan
        self._tau = plan.threshold
        self._risk_sev = plan.risk_rule.severity
        self._fault_sev = plan.fault_rule.severity
        self._release_cut = plan.release_cut  # exact: 0.27 - 0.05 is 0.22
        # one latch per rule, in preallocated slots: the obligations in order, then the risk
        # rule, the fault latch, the judge's unsafe verdict and the confirm band (the last two
        # never latch unless the spec sets risk.judge / risk.confirm_threshold).
        # _lat[k]: the rule's severity while latched, else 0;
        # _run[k]: consecutive cycles its release condition has held (-1: it fired this cycle)
        n = len(plan.obligations)
        self._ri, self._fi, self._ji, self._ci, self._nsrc = n, n + 1, n + 2, n + 3, n + 4
        self._names = tuple(ob.id for ob in plan.obligations) + ("risk", "fault", "judge", "confirm")
        # the confirm latch is released automatically once the band no longer holds the text (the
        # judge said safe, R_e left the band) or at once by acknowledge(): the confirmation itself
        rules = plan.rules()  # obligations, risk, fault, judge, confirm: the order above
        self._holds = tuple(rule.hold for rule in rules)
        self._manual = tuple(rule.manual for rule in rules)
        self._sevs = tuple(rule.severity for rule in rules)
        self._lat = [0] * (n + 4)
        self._run = [0] * (n + 4)
        # the tiers (risk.confirm_threshold, risk.judge): off for specs without them
        self._tc = None if r.confirm_threshold is None else float(r.confirm_threshold)
        j = r.judge
        self._judge_on = j is not None
        self._jsafe = float(j.safe_below) if j is not None else -1.0
        self._junsafe = float(j.unsafe_from) if j is not None else 2.0
        self._tiers = self._judge_on or self._tc is not None
        self._confirmed = False  # acknowledge() confirmed the text in the band (bound to _ctask)
        self._ctask = None
        self._last_task = None
        self._nlat = 0
        self._alpha, self._beta, self._gamma = float(r.alpha), float(r.beta), float(r.gamma)
        self._sample = r.variance == "sample"
        self._k = int(r.classes)
        self._p2 = self._k == 2
        self._uidx = int(r.unsafe_index)
        lo, hi = risk_range(r.alpha, r.beta, r.gamma, r.variance, r.classes)  # exact, any K
        self._rlo, self._rhi = min(0.0, lo), max(1.0, hi)
        self._max_age = None
        self._age_missing = None
        self.set_max_age(max_age_s)
        self._cycle = 0

    def set_max_age(self, fallback: float | None) -> None:
        """Set the one age limit of the risk input: the spec's ``risk.max_age_s`` if it sets one, else
        ``fallback`` seconds (``None``: no limit, ``risk_age_s`` is not required).

        The constructor's ``max_age_s`` goes through here; :class:`~ethimon.loop.GovernedLoop` calls it with
        its ``max_risk_age_s`` when it feeds the monitor from a risk source and neither the spec nor the
        monitor set a limit. With a limit, a cycle without ``risk_age_s`` or with an older estimate is a fault.

        Raises:
            ValueError: ``fallback`` is not a positive, finite number of seconds or ``None``.
        """
        spec_age = self.plan.risk.max_age_s
        if spec_age is not None:
            self._max_age, why = float(spec_age), "the spec sets risk.max_age_s"
        elif fallback is not None:
            if not (isinstance(fallback, (int, float)) and not isinstance(fallback, bool) and fallback > 0
                    and math.isfinite(fallback)):
                raise ValueError(f"max_age_s={fallback!r}; expected a positive number of seconds or None")
            self._max_age, why = float(fallback), "an estimate age limit is set"
        else:
            self._max_age, why = None, ""
        self._age_missing = Fault("missing", f"risk_age_s is missing ({why})", "risk_age_s") if why else None

    @property
    def max_age_s(self) -> float | None:
        """The age limit in force for risk estimates (the spec's ``risk.max_age_s`` first), or ``None``."""
        return self._max_age

    # -- public state ------------------------------------------------------------
    @property
    def cycle(self) -> int:
        """Number of cycles stepped since construction or the last :meth:`reset`."""
        return self._cycle

    @property
    def latched(self) -> bool:
        """Whether an override is latched right now."""
        return self._nlat > 0

    @property
    def latched_rules(self) -> tuple[str, ...]:
        """The rules whose latch holds the override now: obligation ids, ``"risk"``, ``"fault"``."""
        return tuple(name for name, s in zip(self._names, self._lat) if s)

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

    # -- the hot path --------------------------------------------------------------
    def _risk(self, get) -> tuple[float | None, Fault | None]:
        """R_e from this cycle's risk input, converted once at the boundary (see ``_inputs``)."""
        r = get("risk")
        if r is not None:
            return self._risk_direct(r)
        return self._risk_p(get, get("p_unsafe"))

    def _risk_direct(self, r) -> tuple[float | None, Fault | None]:
        """R_e given directly (``risk``), read once by the caller."""
        f = r if type(r) is float else as_number(r)
        if f is None or not self._rlo <= f <= self._rhi:
            return None, Fault("invalid" if f is None else "range",
                               f"risk input R_e={r!r} is NaN, not a number or outside "
                               f"[{self._rlo:g}, {self._rhi:g}]", "risk")
        return f, None

    def _risk_p(self, get, q) -> tuple[float | None, Fault | None]:
        """R_e from ``p_unsafe`` (``q``, read once by the caller; ``None``: absent) or else ``p``."""
        if q is not None:
            if self._k != 2:
                return None, Fault("invalid",
                                   f"p_unsafe alone needs a 2-class spec (risk.classes is {self._k}); pass p", "p_unsafe")
            f = q if type(q) is float else as_number(q)
            if f is None or not 0.0 <= f <= 1.0:
                return None, Fault("invalid" if f is None or not _isfinite(f) else "range",
                                   f"p_unsafe={q!r} is NaN, not a number or outside [0, 1]", "p_unsafe")
            return two_class_risk(f, self._alpha, self._beta, self._gamma,
                                  "sample" if self._sample else "population"), None
        p = get("p")
        if p is None:
            return None, _NO_RISK
        probs, why = as_probs(p, self._k)
        if why is not None:
            return None, Fault("invalid", why, "p")
        return risk_from_probs(probs, self._alpha, self._beta, self._gamma,
                               "sample" if self._sample else "population", self._uidx), None

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
            vals = self._vals
            faults = None
            bad = None  # slots whose input is unusable this cycle (fault path only)
            for k, name, slot, is_bool, lo, hi in self._fsig:
                v = get(name)
                if is_bool:
                    if v is True or v is False:
                        vals[slot] = v
                        continue
                elif type(v) is float and lo <= v <= hi:  # the common case: a built-in float in range
                    vals[slot] = v
                    continue
                faults, bad = self._read_rest(get, k, v)  # anything else: judged there, once
                break
            rin = get("risk")
            if rin is not None:
                r, why = self._risk_direct(rin)
            else:
                q = get("p_unsafe")
                if type(q) is float and self._p2 and 0.0 <= q <= 1.0:  # the common case, as _risk_p
                    # compiler._risk_formula.two_class_risk inlined (hot path; tests/test_plan_of.py
                    # checks this copy equals the one definition on a grid of inputs and weights)
                    d = q - 0.5
                    var = 2.0 * d * d if self._sample else d * d
                    top = q if q >= 0.5 else 1.0 - q
                    r, why = self._alpha * q + self._beta * (1.0 - top) + self._gamma * var, None
                else:
                    r, why = self._risk_p(get, q)
            if why is None and not _isfinite(r):  # weights and inputs are finite; never trust it blindly
                r, why = None, Fault("internal", f"R_e={r!r} is not finite")
            if why is not None:
                (faults := faults or []).append(why)
                (bad := bad or []).append(self._rslot)
            if self._max_age is not None:
                age = get("risk_age_s")
                a = None if age is None else as_number(age)
                if age is None:
                    (faults := faults or []).append(self._age_missing)
                    (bad := bad or []).append(self._rslot)
                elif a is None or not 0.0 <= a <= self._max_age:
                    (faults := faults or []).append(Fault(
                        "stale",
                        f"risk estimate is stale or its age is invalid: {age!r} s > max_age_s {self._max_age:g}", "risk_age_s"))
                    (bad := bad or []).append(self._rslot)
            jp = None
            if self._judge_on:  # the judge's p_unsafe, or None: no judgement (a normal state)
                jin = get("judge")
                if jin is not None:
                    jp = jin if type(jin) is float else as_number(jin)
                    if jp is None or not 0.0 <= jp <= 1.0:
                        (faults := faults or []).append(Fault(
                            "invalid", f"judge input {jin!r} is not a p_unsafe in [0, 1] (null: no judgement)",
                            "judge"))
                        bad = bad or []
                        jp = None
            if faults is not None:
                return self._fault(cycle, tuple(faults), r, bad)
            vals[self._rslot] = r
            self._ucall()
            violations = None
            hits = None  # latched only once every obligation was judged (a later one may raise)
            vs = self._vcall()  # each verdict is a bool
            if True in vs:
                violations = []
                hits = []
                for (fn, oid, s, i), v in zip(self._obs, vs):
                    if v:
                        violations.append(oid)
                        hits.append(i)
            if r >= self._tau:
                if violations is None:
                    violations = ["risk"]
                    hits = [self._ri]
                else:
                    violations.append("risk")
                    hits.append(self._ri)
            if self._tiers:
                tier = self._tier(r, jp, get)
                if tier is not None:
                    if violations is None:
                        violations = [tier[0]]
                        hits = [tier[1]]
                    else:
                        violations.append(tier[0])
                        hits.append(tier[1])
            if hits is not None:
                lat, run, sevs = self._lat, self._run, self._sevs
                for i in hits:
                    if not lat[i]:
                        lat[i] = sevs[i]
                        self._nlat += 1
                    run[i] = -1
            margins = _EMPTY
            if self._margins_on:
                margins = self._mcall()  # a margin that cannot be computed is NaN
            if not self._nlat:
                return Decision(False, _NONE, _EMPTY, margins, r, cycle, False, _EMPTY)
            sev, awaiting = self._release_pass(r < self._release_cut)
            if violations is not None:
                return Decision(True, _RESPONSES[sev], tuple(violations), margins, r, cycle, False, _EMPTY,
                                awaiting)
            if not self._nlat:  # the last latch released this cycle
                return Decision(False, _NONE, _EMPTY, margins, r, cycle, False, _EMPTY)
            return Decision(True, _RESPONSES[sev], _EMPTY, margins, r, cycle, True, _EMPTY, awaiting)
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

    def _tier(self, r: float, jp: float | None, get) -> tuple[str, int] | None:
        """The judge tier and the confirm band on a valid cycle (R_e = ``r``, judge p_unsafe ``jp``).

        An unsafe verdict (``jp >= unsafe_from``) fires ``"judge"`` at any R_e: below τ the judge can
        only raise the risk. In the band [τ_confirm, τ) only a safe verdict (``jp < safe_below``)
        or an operator's confirmation of this task (``acknowledge()``, bound to ``task_id``) lets the arm
        execute; anything else (unsure, no judgement) fires ``"confirm"`` (stop 2). R_e ≥ τ is the
        risk rule's, whatever the judge says.
        """
        tc = self._tc
        if tc is not None:  # first, on every cycle (the judge's too): the text this cycle is about
            task = get("task_id")
            if self._confirmed and (task != self._ctask or not tc <= r < self._tau):
                self._confirmed = False  # a confirmation is for one text while it stays in the band
            self._last_task = task
        if jp is not None and jp >= self._junsafe:
            return "judge", self._ji
        if tc is None:
            return None
        if tc <= r < self._tau and not self._confirmed and not (jp is not None and jp < self._jsafe):
            return "confirm", self._ci
        return None

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

    def __repr__(self) -> str:
        return f"Monitor(spec={self.spec.name!r}, obligations={len(self.obligation_ids)}, cycle={self._cycle})"
