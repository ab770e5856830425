"""What the properties (``_properties.py``) and lints (``_lints.py``) of ``ethimon verify`` share
(imports z3): the spec and its plan, the unrolling, the z3 solvers, the run's budget and the
counterexamples replayed in a real :class:`Monitor`."""

from __future__ import annotations

import math
import time
from typing import Any

import z3

from ..compiler import Plan
from ..compiler import plan_of
from ..compiler._risk_formula import risk_range
from ..runtime import Monitor
from ..language import Response, Spec
from ._encode import DecisionTrace, Unrolled, decision_trace, lookback, release_below, z3_value
from ._report import SKIPPED, UNKNOWN, Counterexample, Finding
from ._tiers import base_spec

__all__ = ["CheckBase", "BUDGET_NOTE"]

_SEV_NAME = {r.severity: r.value for r in Response}
#: how a check that the run's total budget did not let finish is reported
BUDGET_NOTE = "unknown (budget)"


def _fmt(x: float) -> str:
    return f"{x:.6g}"


class CheckBase:
    """The state and tools of the checks of one compiled spec; :meth:`run` runs the
    ``property_tasks()`` and ``lint_tasks()`` of the subclasses (``_verifier.Verifier``)."""

    def __init__(self, spec: Spec, *, path: str, timeout_s: float, max_unroll: int,
                 budget_s: float | None = None, started: float | None = None) -> None:
        # the tiers (confirm band, judge) are proved on their own (verify/_tiers.py); every other
        # property is checked on the spec without them, which they only add overrides to (tier.adds_only)
        self.full_spec = spec
        self.full_plan = plan_of(spec)
        spec = base_spec(spec)
        self.spec = spec
        self.budget_s = budget_s
        t0 = time.perf_counter() if started is None else started
        self.deadline = None if budget_s is None else t0 + budget_s
        self.plan: Plan = plan_of(spec)
        self.path = path
        self.timeout_ms = max(1, int(timeout_s * 1000))
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
        self._hazard: dict[str, str] = {}

    # -- solver helpers ----------------------------------------------------------------
    def solve(self, *constraints, enc: Unrolled | None = None) -> tuple[str, z3.ModelRef | None, str]:
        """``sat`` (with a model), ``unsat`` or ``unknown`` (with the reason).

        ``enc``'s domain and auxiliary constraints are added last, after every goal term
        was built (building a term can define an auxiliary variable, e.g. for ``sqrt``).
        """
        ms = self.check_ms()
        if ms <= 0:
            return "unknown", None, "the run's budget is spent"
        s = z3.Solver()
        s.set("timeout", ms)
        # incremental mode (push first): z3's SMT core with its nonlinear arithmetic module, which is
        # ~20x faster here than the one-shot tactic the default solver picks for these problems
        s.push()
        for c in constraints:
            s.add(c)
        if enc is not None:
            s.add(*enc.constraints)
        return self._outcome(s)

    def solve_fp(self, *constraints, enc: Unrolled) -> tuple[str, z3.ModelRef | None, str]:
        """:meth:`solve` for IEEE-754 (``FloatUnrolled``) problems: z3's QF_FP solver (bit-blasting),
        which decides these in a second where the incremental core used for the reals gives up."""
        ms = self.check_ms()
        if ms <= 0:
            return "unknown", None, "the run's budget is spent"
        s = z3.SolverFor("QF_FP")
        s.set("timeout", ms)
        for c in constraints:
            s.add(c)
        s.add(*enc.constraints)
        return self._outcome(s)

    def _outcome(self, s: z3.Solver) -> tuple[str, z3.ModelRef | None, str]:
        """Check ``s`` as it stands: ``sat`` with its model, ``unsat``, or ``unknown`` with the reason."""
        r = s.check()
        if r == z3.sat:
            return "sat", s.model(), ""
        if r == z3.unsat:
            return "unsat", None, ""
        if self.out_of_budget():
            return "unknown", None, "the run's budget is spent"
        return "unknown", None, s.reason_unknown()

    # -- the run's budget ----------------------------------------------------------------
    def left_s(self) -> float:
        return math.inf if self.deadline is None else self.deadline - time.perf_counter()

    def out_of_budget(self) -> bool:
        return self.left_s() <= 0

    def check_ms(self) -> int:
        """The z3 time limit for the next check: ``--timeout-s``, or less if the budget has less left."""
        left = self.left_s()
        if left == math.inf:
            return self.timeout_ms
        return min(self.timeout_ms, int(left * 1000))

    def unreached(self, kind: str, name: str, what: str = "") -> Finding:
        return Finding(kind, name, UNKNOWN, f"{BUDGET_NOTE}: {what or 'not checked'}; the run's budget "
                                            f"(--budget-s {self.budget_s:g}) was spent")

    def run(self, lints: bool = True) -> tuple[list[Finding], int]:
        """Every property, then every lint, while the budget lasts.

        Returns:
            The findings and how many checks the budget did not let run or finish (each is
            reported as an ``unknown`` row whose message starts with :data:`BUDGET_NOTE`).
        """
        out: list[Finding] = []
        for name, fn in self.property_tasks():
            if self.out_of_budget():
                out.append(self.unreached("property", name))
                continue
            f = fn()
            if f.status == UNKNOWN and self.out_of_budget() and not f.message.startswith(BUDGET_NOTE):
                f.message = f"{BUDGET_NOTE}: {f.message}"
            out.append(f)
        if lints:
            for name, fn in self.lint_tasks():
                if self.out_of_budget():
                    out.append(self.unreached("lint", name))
                    continue
                for f in fn():
                    if (f.status in (UNKNOWN, SKIPPED) and self.out_of_budget()
                            and not f.message.startswith(BUDGET_NOTE)):
                        f.status, f.message = UNKNOWN, f"{BUDGET_NOTE}: {f.message}"
                    out.append(f)
        return out, sum(f.message.startswith(BUDGET_NOTE) for f in out)

    def solve_dt(self, *goals) -> tuple[str, z3.ModelRef | None, str]:
        """:meth:`solve` over the shared decision trace, with one incremental solver for every decision check.

        The trace (every obligation at every cycle, the latch) is asserted once; each check adds its
        goal in a scope of its own. Much faster than re-asserting it for each of hundreds of checks.
        """
        enc, dt = self.enc, self.dt
        if self._ds is None:
            self._ds = z3.Solver()
            self._ds.push()  # incremental mode: see solve()
            self._ds.add(*dt.init)
            self._ds_n = 0
        s = self._ds
        cons = enc.constraints
        if len(cons) > self._ds_n:  # domain and auxiliary definitions added since (e.g. sqrt)
            s.add(*cons[self._ds_n:])
            self._ds_n = len(cons)
        ms = self.check_ms()
        if ms <= 0:
            return "unknown", None, "the run's budget is spent"
        s.set("timeout", ms)
        s.push()
        try:
            s.add(*goals)
            return self._outcome(s)
        finally:
            s.pop()

    @property
    def enc(self) -> Unrolled:
        if self._enc is None:
            self._enc = Unrolled(self.plan, self.k)
        return self._enc

    @property
    def dt(self) -> DecisionTrace:
        if self._dt is None:
            self._dt = decision_trace(self.enc)
        return self._dt

    def all_defined(self, enc: Unrolled, upto: int) -> z3.BoolRef:
        return enc.all_defined(upto)

    def _state_prefs(self, dt: DecisionTrace) -> list[list[z3.BoolRef]]:
        """Initial latch states to try, most replayable first: fresh, just after a fault, any."""
        return [dt.start_with([]), dt.start_with(["fault"]), []]

    # -- counterexamples ------------------------------------------------------------------
    def frames(self, model: z3.ModelRef, enc: Unrolled, upto: int) -> list[dict[str, Any]]:
        out = []
        for t in range(upto + 1):
            f: dict[str, Any] = {}
            for s in self.plan.signals:
                v = z3_value(model, enc.sig[t][s.name])
                f[s.name] = bool(v) if s.kind == "bool" else v
            f["risk"] = z3_value(model, enc.R[t])
            if self.spec.risk.max_age_s is not None:
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

    def _timed(self, fn) -> Finding:
        t0 = time.perf_counter()
        f = fn()
        f.seconds = time.perf_counter() - t0
        return f

    def risk_range(self) -> tuple[float, float] | None:
        """Reachable R_e over every probability vector: exact, for any number of classes."""
        r = self.spec.risk
        return risk_range(r.alpha, r.beta, r.gamma, r.variance, r.classes)
