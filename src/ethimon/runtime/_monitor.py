"""The runtime monitor: ``Monitor.step(signals) -> Decision`` every control cycle.

The monitor never imports YAML, the loader, torch or pybullet. Everything is
resolved at construction (signal slots, closures, thresholds); ``step`` reads
the inputs, updates O(1) temporal state, evaluates each obligation once and
applies the latch/release rule. One guard turns any internal fault into a
fail-closed override: no exception escapes ``step``.
"""

from __future__ import annotations

from math import isfinite as _isfinite
from collections.abc import Mapping
from typing import Any

from ..compiler import Plan, plan_of
from ..language import SEVERITY_ORDER, Response, Spec
from ..compiler._risk_formula import risk_from_probs, two_class_risk
from ._calls import _EMPTY
from ._construction import _Construction
from ._decision import Decision
from ._failing import _FailClosed
from ._fault import Fault
from ._inputs import as_bool, as_number, as_probs
from ._latches import _Latches

__all__ = ["Monitor"]

_RESPONSES = SEVERITY_ORDER  # severity -> Response
_NONE = Response.NONE  # read once: an Enum member's attribute access is slow on CPython 3.11
_INTERNAL = Fault("internal", "internal error")
_NO_RISK = Fault("missing", "no risk input this cycle (give risk, p_unsafe or p)", "risk")


class Monitor(_Construction, _Latches, _FailClosed):
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
                 "_ji", "_ci", "_tiers", "_judge_on", "_tc", "_jsafe", "_junsafe", "_confirmed", "_ctask", "_hold_hi",
                 "_last_task", "_fsig", "_mcall", "_p2", "_ucall", "_vcall", "_pi", "_since", "_risk_free", "_hist0")

    def __init__(self, plan: Plan | Spec, *, margins: bool = True, max_age_s: float | None = None) -> None:
        self._build(plan_of(plan), margins, max_age_s)  # runtime/_construction.py

    # -- public state (the latches' is in runtime/_latches.py) -------------------
    @property
    def cycle(self) -> int:
        """Number of cycles stepped since construction or the last :meth:`reset`."""
        return self._cycle

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
                    # compiler._risk_formula.two_class_risk inlined (hot path; tests/compiler/test_plan_of.py
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
                pend = get("pending_s")
                if pend is not None:  # inputs awaited after the start or a new task text (runtime/_failing.py)
                    return self._pending(cycle, faults, bad, pend, r)
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
            held = False
            if r >= self._tau and not (held := (self._hold_hi is not None and r < self._hold_hi and jp is not None
                                                and jp < self._jsafe)):
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
                        self._since[i] = cycle
                        self._nlat += 1
                    run[i] = -1
            margins = _EMPTY
            if self._margins_on:
                margins = self._mcall()  # a margin that cannot be computed is NaN
            if not self._nlat:  # ids: the obligation-id tuple by reference (Decision.margin reads it)
                return Decision(False, _NONE, _EMPTY, margins, r, cycle, False, _EMPTY, False, self.obligation_ids)
            sev, awaiting = self._release_pass(r < self._release_cut or held)  # held: the confirm latch holds
            if violations is not None:
                return Decision(True, _RESPONSES[sev], tuple(violations), margins, r, cycle, False, _EMPTY,
                                awaiting, self.obligation_ids, _EMPTY, self._names, self._lat[:])
            if not self._nlat:  # the last latch released this cycle
                return Decision(False, _NONE, _EMPTY, margins, r, cycle, False, _EMPTY, False, self.obligation_ids)
            return Decision(True, _RESPONSES[sev], _EMPTY, margins, r, cycle, True, _EMPTY, awaiting,
                            self.obligation_ids, _EMPTY, self._names, self._lat[:])
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
        risk rule's, whatever the judge says, except with ``risk.judge_may_hold_above_tau``: there a safe
        verdict at τ ≤ R_e < ceiling fires ``"confirm"`` instead (a person releases it, never the judge).
        """
        tc = self._tc
        hi = self._hold_hi
        if tc is not None or hi is not None:  # first, on every cycle (the judge's too): the text this cycle is about
            task = get("task_id")
            lo = tc if tc is not None else self._tau
            if self._confirmed and (task != self._ctask or not lo <= r < (hi if hi is not None else self._tau)):
                self._confirmed = False  # a confirmation is for one text while it stays in the band
            self._last_task = task
        if jp is not None and jp >= self._junsafe:
            return "judge", self._ji
        if r >= self._tau:  # the risk rule's, unless held (risk.judge_may_hold_above_tau, a safe verdict)
            held = hi is not None and r < hi and jp is not None and jp < self._jsafe  # as in step()
            return ("confirm", self._ci) if held and not self._confirmed else None
        if tc is None:
            return None
        if tc <= r < self._tau and not self._confirmed and not (jp is not None and jp < self._jsafe):
            return "confirm", self._ci
        return None

    def __repr__(self) -> str:
        return f"Monitor(spec={self.spec.name!r}, obligations={len(self.obligation_ids)}, cycle={self._cycle})"
