"""One spec's plan unrolled over the horizon ``ethimon verify`` needs (imports z3): the plan, each
obligation's look-back, the horizon ``k``, the shared z3 encoding and decision trace (built once,
on first use), the further traces some checks need, and the way back from a z3 model to frames
replayed in a real :class:`Monitor`. Every check (``_properties.py``, ``_lints.py``,
``_tiers.py``) runs over it; none builds an encoding of its own."""

from __future__ import annotations

import math
from typing import Any

import z3

from ..compiler import Plan, plan_of
from ..language import Spec
from ..runtime import Monitor
from ._checks import Budget
from ._encode import DecisionTrace, FloatUnrolled, Unrolled, decision_trace, lookback, release_below, z3_value
from ._report import Counterexample
from ._tiers import base_spec

__all__ = ["Unrolling"]


class Unrolling:
    """The z3 encoding of one spec's plan over its horizon, built once per spec.

    The tiers (confirm band, judge) are proved on their own (``_tiers.py``); every other check
    runs on the spec without them (``spec``/``plan``), which they only add overrides to
    (``tier.adds_only``); ``full_spec``/``full_plan`` keep them.

    Args:
        spec: the loaded spec.
        max_unroll: most cycles of symbolic state to unroll.
        budget: the run's :class:`~._checks.Budget` (its solvers are the checks' solvers).

    Attributes:
        need: per obligation id, the cycles its verdict reads (look-back + response window + 1).
        k: the horizon, ``max(need)`` (at least 2) cut to ``max_unroll``; ``truncated`` if cut.
        tau, below, below_cut, below_float, below_z3: τ and the release bound τ − δ (exact, as
            the decimal the messages print, as the float cut the monitor tests, the largest float
            below it, as a z3 real).
        risk_sev, fault_sev: the severities of the risk and fault rules' responses.
    """

    # no __slots__: they are released in name order, and the order z3's terms are released in
    # decides the ids later terms get, which z3's search depends on: attributes are set (and
    # released) in the order of the mixin classes this replaced, so every result stays as it was
    def __init__(self, spec: Spec, *, max_unroll: int, budget: Budget) -> None:
        self.full_spec = spec
        self.full_plan = plan_of(spec)
        spec = base_spec(spec)
        self.spec = spec
        self.budget = budget
        self.plan: Plan = plan_of(spec)
        self.max_unroll = max(2, int(max_unroll))
        self.need: dict[str, int] = {}
        for ob in self.plan.obligations:
            lb = max(lookback(self.plan, ob.require), lookback(self.plan, ob.when) if ob.when is not None else 0)
            self.need[ob.id] = lb + (ob.within_cycles or 0) + 1
        want = max([2, *self.need.values()])
        self.k = min(want, self.max_unroll)
        self.truncated = want > self.max_unroll
        plan = self.plan  # τ, the release bound and the rules' releases: resolved once, in the plan
        self.tau = plan.threshold
        # the release bound tau - delta, exactly (0.27 - 0.05 is 0.22, not 0.22000000000000003)
        cut = plan.release_cut
        self.below = float(plan.release_exact)  # for messages
        self.below_z3 = release_below(plan)
        self.below_cut = cut  # a float R_e is below the bound exactly when R_e < cut
        self.below_float = math.nextafter(cut, -math.inf)  # the largest float below the bound
        self.risk_sev = plan.risk_rule.severity
        self.fault_sev = plan.fault_rule.severity
        self._enc: Unrolled | None = None
        self._dt: DecisionTrace | None = None
        self._ds: z3.Solver | None = None
        self._ds_n = 0

    # -- the horizon -------------------------------------------------------------------------
    def window_cycles(self, ids) -> int:
        """P: cycles of history that can still change a verdict of these obligations (look-back + response window)."""
        return max([self.need[i] for i in ids] + [1]) - 1

    def bound_note(self) -> str:
        """What a proof over the horizon says when the horizon was cut (else '')."""
        if self.truncated:
            return f" (bounded: windows need more than --max-unroll {self.max_unroll} cycles)"
        return ""

    def risk_range(self) -> tuple[float, float]:
        """Reachable R_e over every probability vector: exact, for any number of classes."""
        return self.plan.risk_plan.reachable

    # -- the shared encoding (built on first use) -------------------------------------------------
    @property
    def enc(self) -> Unrolled:
        """Every signal and R_e at each of the ``k`` cycles from a reset, and every term over them."""
        if self._enc is None:
            self._enc = Unrolled(self.plan, self.k)
        return self._enc

    @property
    def dt(self) -> DecisionTrace:
        """``Monitor.step``'s decision logic over :attr:`enc` (every obligation, from any latch state)."""
        if self._dt is None:
            self._dt = decision_trace(self.enc)
        return self._dt

    def only_trace(self, i: int) -> DecisionTrace:
        """The decision logic over :attr:`enc` with obligation ``i`` alone encoded (the others' verdicts
        and latches free: an over-approximation, see :func:`~._encode.decision_trace`)."""
        return decision_trace(self.enc, prefix=f"only{i}.", only=i)

    # -- further traces of the same plan (another horizon, their own variable names) -------------
    def trace(self, k: int, *, prefix: str, free_history: bool = False) -> Unrolled:
        """A trace of ``k`` cycles of the plan in the reals, its variables named ``prefix...``
        (``free_history``: the first cycle is any point of a longer run)."""
        return Unrolled(self.plan, k, prefix=prefix, free_history=free_history)

    def float_trace(self, k: int, *, prefix: str) -> FloatUnrolled:
        """A trace of ``k`` cycles of the plan in the monitor's IEEE-754 doubles."""
        return FloatUnrolled(self.plan, k, prefix=prefix)

    def solve_dt(self, *goals) -> tuple[str, z3.ModelRef | None, str]:
        """:meth:`Budget.solve` over the shared decision trace, with one incremental solver for every decision check.

        The trace (every obligation at every cycle, the latch) is asserted once; each check adds its
        goal in a scope of its own. Much faster than re-asserting it for each of hundreds of checks.
        """
        enc, dt = self.enc, self.dt
        if self._ds is None:
            self._ds = z3.Solver()
            self._ds.push()  # incremental mode: see Budget.solve()
            self._ds.add(*dt.init)
            self._ds_n = 0
        s = self._ds
        cons = enc.constraints
        if len(cons) > self._ds_n:  # domain and auxiliary definitions added since (e.g. sqrt)
            s.add(*cons[self._ds_n:])
            self._ds_n = len(cons)
        ms = self.budget.check_ms()
        if ms <= 0:
            return "unknown", None, "the run's budget is spent"
        s.set("timeout", ms)
        s.push()
        try:
            s.add(*goals)
            return self.budget.outcome(s)
        finally:
            s.pop()

    @staticmethod
    def state_prefs(dt: DecisionTrace) -> list[list[z3.BoolRef]]:
        """Initial latch states to try, most replayable first: fresh, just after a fault, any."""
        return [dt.start_with([]), dt.start_with(["fault"]), []]

    # -- back from a model: frames replayed in a Monitor --------------------------------------------
    def frames(self, model: z3.ModelRef, enc: Unrolled, upto: int) -> list[dict[str, Any]]:
        """The ``step`` inputs of cycles ``0 .. upto`` of ``enc`` under ``model``."""
        out = []
        for t in range(upto + 1):
            f: dict[str, Any] = {}
            for s in self.plan.signals:
                v = z3_value(model, enc.sig[t][s.name])
                f[s.name] = bool(v) if s.kind == "bool" else v
            f["risk"] = z3_value(model, enc.R[t])
            if self.plan.risk_plan.max_age_s is not None:
                f["risk_age_s"] = 0.0
            out.append(f)
        return out

    def fault_frame(self, like: dict[str, Any]) -> dict[str, Any]:
        """A frame that fails closed (a missing input) and keeps R_e below τ."""
        f = dict(like)
        if self.plan.signals:
            f.pop(self.plan.signals[0].name, None)
        else:
            f.pop("risk", None)
        return f

    def counterexample(self, prop: str, model: z3.ModelRef, enc: Unrolled, upto: int,
                       expect: dict[str, Any], broken, dt: DecisionTrace | None = None) -> Counterexample:
        """Build the frames, replay them in a fresh :class:`Monitor`, and check ``broken(decision)``."""
        frames = self.frames(model, enc, upto)
        cycle = upto
        if dt is not None:
            L0 = z3_value(model, dt.L0)
            if L0:  # reach the latched start state with one fault cycle first
                frames = [self.fault_frame(frames[0])] + frames
                cycle += 1
        monitor = Monitor(self.spec)
        decisions = [monitor.step(f) for f in frames]
        d = decisions[cycle]
        ok = bool(broken(d))
        note = (f"Monitor at cycle {cycle}: override={d.override}, response={d.response.value}, "
                f"violations={list(d.violations)}, faults={[f.message for f in d.faults]}")
        return Counterexample(prop, frames, cycle, expect, [x.as_dict() for x in decisions], ok, note)
