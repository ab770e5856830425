"""The properties and lints of ``ethimon verify`` (imports z3)."""

from __future__ import annotations

import itertools
import math
import time
from typing import Any

import z3

from ..compiler import Plan
from ..compiler import plan_of
from ..compiler._risk_formula import risk_bounds, risk_from_p_unsafe, risk_range, two_class_risk
from ..runtime import Monitor
from ..spec._expr import Name, walk
from ..spec import Response, Spec
from .._robot import out_of_range, safe_pose_problem
from ._policy import manual_rules, release_policy_warnings
from ._encode import (DecisionTrace, FloatUnrolled, Unrolled, decision_trace, lookback, real, release_below,
                      rules_of, z3_value)
from ._report import OK, PROVED, PROVED_REAL, REFUTED, SKIPPED, UNKNOWN, WARNING, Counterexample, Finding
from ._tiers import base_spec, has_tiers, lint_confirm_band, tier_properties

__all__ = ["Verifier", "BUDGET_NOTE"]

_SEV_NAME = {r.severity: r.value for r in Response}
#: how a check that the run's total budget did not let finish is reported
BUDGET_NOTE = "unknown (budget)"


def _fmt(x: float) -> str:
    return f"{x:.6g}"


class Verifier:
    """Runs every check of one compiled spec (see :func:`ethimon.verify.verify_spec`)."""

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
        r = spec.risk
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

    # -- properties -------------------------------------------------------------------------
    def property_tasks(self) -> list[tuple[str, Any]]:
        """``(name, check)`` of every property, in report order."""
        out: list[tuple[str, Any]] = [("risk.bounds", self.prop_risk_bounds),
                                      ("risk.override", self.prop_risk_override), ("fault.override", self.prop_fault)]
        for ob in self.plan.obligations:
            out.append((f"{ob.id}.defined", lambda ob=ob: self.prop_defined(ob)))
            out.append((f"{ob.id}.response", lambda ob=ob: self.prop_response(ob)))
        out += [("resume.explained", self.prop_resume_explained), ("release.rule", self.prop_release_rule),
                ("model.agrees", lambda: self._timed(self.check_model))]
        if has_tiers(self.full_spec):
            out += tier_properties(self)
        return out

    def properties(self) -> list[Finding]:
        return [fn() for _, fn in self.property_tasks()]

    def check_model(self, traces: int = 24) -> Finding:
        """The z3 model of this spec agrees with the real :class:`Monitor` on sampled traces.

        The proofs above are about the translation; this replays seeded random traces of
        ``k`` cycles (values at the range ends, the middle, random; inputs often held so
        windows fill) through both and compares violations, override and response.
        """
        import random
        name = "model.agrees"
        enc, dt = self.enc, self.dt
        rng = random.Random(f"ethimon-verify:{self.spec.name}")
        from ._encode import risk_input_range
        rlo, rhi = risk_input_range(self.plan)
        # the release bound's neighbours: the cut, the largest float below it, the float tau - delta
        r_pick = [rlo, rhi, self.tau, self.below_cut, self.below_float,
                  float(self.tau - self.spec.risk.release.hysteresis), min(max(self.below - 1e-3, rlo), rhi)]
        r_pick = [x for x in r_pick if rlo <= x <= rhi]
        s = z3.Solver()
        s.set("timeout", max(1, self.check_ms()))
        goals = [dt.L0 == 0, dt.C0 == 0, *dt.init]
        terms = [(dt.violated[t], dt.risk_fires[t], dt.override[t], dt.response[t]) for t in range(self.k)]
        s.add(*goals)
        s.add(*enc.constraints)
        compared = 0
        for i in range(traces):
            if self.out_of_budget():
                return Finding("property", name, UNKNOWN, f"{BUDGET_NOTE}: the z3 model agreed with the Monitor on "
                                                          f"{compared} sampled cycles ({i} of {traces} traces) when "
                                                          f"the run's budget was spent")
            frames: list[dict[str, Any]] = []
            prev: dict[str, Any] | None = None
            for _t in range(self.k):
                f: dict[str, Any] = {}
                for sig in self.plan.signals:
                    if prev is not None and rng.random() < 0.5:
                        f[sig.name] = prev[sig.name]
                    elif sig.kind == "bool":
                        f[sig.name] = rng.random() < 0.5
                    else:
                        lo, hi = max(sig.lo, -1e6), min(sig.hi, 1e6)
                        f[sig.name] = rng.choice([lo, hi, (lo + hi) / 2, rng.uniform(lo, hi), rng.uniform(lo, hi)])
                f["risk"] = (prev["risk"] if prev is not None and rng.random() < 0.5
                             else rng.choice(r_pick + [rng.uniform(rlo, rhi)] * 3))
                if self.spec.risk.max_age_s is not None:
                    f["risk_age_s"] = 0.0
                frames.append(f)
                prev = f
            monitor = Monitor(self.spec)
            decisions = []
            for f in frames:
                d = monitor.step(f)
                if d.faults:  # an evaluation error: the unrolled model has no faults, stop here
                    break
                decisions.append(d)
            s.push()
            for t, f in enumerate(frames):
                for sig in self.plan.signals:
                    v = enc.sig[t][sig.name]
                    s.add(v == (z3.BoolVal(bool(f[sig.name])) if sig.kind == "bool" else real(f[sig.name])))
                s.add(enc.R[t] == real(f["risk"]))
            st = s.check()
            if st != z3.sat:
                s.pop()
                return Finding("property", name, UNKNOWN, f"z3 could not evaluate a sampled trace ({st})")
            model = s.model()
            s.pop()
            for t, d in enumerate(decisions):
                viol, fires, override, response = terms[t]
                got = [ob.id for ob, v in zip(self.plan.obligations, viol)
                       if z3.is_true(model.eval(v, model_completion=True))]
                if z3.is_true(model.eval(fires, model_completion=True)):
                    got.append("risk")
                ov = z3.is_true(model.eval(override, model_completion=True))
                resp = model.eval(response, model_completion=True).as_long()
                if got != list(d.violations) or ov != d.override or resp != d.response.severity:
                    cex = Counterexample(name, frames[:t + 1], t, {}, [x.as_dict() for x in decisions[:t + 1]],
                                         True, f"model: violations={got}, override={ov}, response severity "
                                               f"{resp}; Monitor: {d!r}")
                    return Finding("property", name, REFUTED,
                                   f"the z3 model disagrees with the Monitor at cycle {t} of a sampled trace",
                                   counterexample=cex)
                compared += 1
        return Finding("property", name, OK,
                       f"the z3 model agrees with the Monitor on {compared} sampled cycles "
                       f"({traces} traces of {self.k} cycles)")

    def _timed(self, fn) -> Finding:
        t0 = time.perf_counter()
        f = fn()
        f.seconds = time.perf_counter() - t0
        return f

    def prop_risk_bounds(self) -> Finding:
        def run() -> Finding:
            name = "risk.bounds"
            r = self.spec.risk
            if r.classes != 2:
                lo, hi = self.risk_range()
                return Finding("property", name, SKIPPED,
                               f"not re-proved by z3 for K={r.classes} classes; R_e in [{_fmt(lo)}, {_fmt(hi)}] "
                               f"by the exact candidate search of risk_range")
            lo, hi = risk_bounds(r.alpha, r.beta, r.gamma, r.variance)
            q = z3.Real("q")
            R = two_class_risk(q, real(r.alpha), real(r.beta), real(r.gamma), r.variance, where=z3.If,
                               half=z3.RealVal("1/2"))
            eps = 1e-9 * max(1.0, abs(lo), abs(hi))
            st, model, why = self.solve(q >= 0, q <= 1, z3.Or(R < real(lo - eps), R > real(hi + eps)))
            if st == "unsat":
                return Finding("property", name, PROVED,
                               f"R_e in [{_fmt(lo)}, {_fmt(hi)}] for every p_unsafe in [0, 1] ({r.variance} variance)")
            if st == "sat":
                qv = z3_value(model, q)
                rv = risk_from_p_unsafe(qv, r.alpha, r.beta, r.gamma, r.variance)
                return Finding("property", name, REFUTED,
                               f"p_unsafe={qv!r} gives R_e={rv!r} outside [{_fmt(lo)}, {_fmt(hi)}]")
            return Finding("property", name, UNKNOWN, f"z3: {why}")
        return self._timed(run)

    def _decision_check(self, name: str, bad_at, expect_for, broken, proved_msg: str,
                        assume_defined: bool = True, only: int | None = None) -> Finding:
        """Search for a cycle ``t`` where ``bad_at(dt, t)`` holds; refute with a replayed trace.

        ``only=i``: first try to prove it with just obligation ``i`` encoded (the others'
        verdicts free, their definedness not assumed): an over-approximation, so "no such
        cycle" there is a proof. Otherwise, or if that finds one, the whole trace decides.
        """
        if only is not None:
            enc = self.enc
            dt_i = decision_trace(enc, prefix=f"only{only}.", only=only)
            ob = self.plan.obligations[only]
            terms = [z3.And(z3.And([enc.obligation_defined(ob, j) for j in range(t + 1)]), b)
                     if assume_defined else b for t in range(self.k) if (b := bad_at(dt_i, t)) is not None]
            if not terms:
                return Finding("property", name, PROVED, proved_msg + self._bound_note())
            st, _, _ = self.solve(*dt_i.init, z3.Or(terms), enc=enc)
            if st == "unsat":
                return Finding("property", name, PROVED, proved_msg + self._bound_note())
        enc, dt = self.enc, self.dt
        terms = {}
        for t in range(self.k):
            bad = bad_at(dt, t)
            if bad is not None:
                terms[t] = z3.And(self.all_defined(enc, t), bad) if assume_defined else bad
        if not terms:
            return Finding("property", name, PROVED, proved_msg + self._bound_note())
        st, model, why = self.solve_dt(z3.Or(list(terms.values())))
        if st == "unknown":
            return Finding("property", name, UNKNOWN, f"z3: {why}")
        if st == "unsat":
            return Finding("property", name, PROVED, proved_msg + self._bound_note())
        t = next(t for t, term in terms.items() if z3.is_true(model.eval(term, model_completion=True)))
        for pref in self._state_prefs(dt):  # most replayable start state first
            st2, m2, _ = self.solve_dt(terms[t], *pref)
            if st2 == "sat":
                model = m2
                break
        cex = self.counterexample(name, model, enc, t, expect_for(t), lambda d: broken(d, t), dt)
        return Finding("property", name, REFUTED, f"fails at cycle {t}", counterexample=cex)

    def _bound_note(self) -> str:
        if self.truncated:
            return f" (bounded: windows need more than --max-unroll {self.max_unroll} cycles)"
        return ""

    def prop_risk_override(self) -> Finding:
        sev = self.risk_sev

        def bad(dt, t):
            return z3.And(dt.risk_fires[t], z3.Not(z3.And(dt.override[t], dt.response[t] >= sev)))
        return self._timed(lambda: self._decision_check(
            "risk.override", bad, lambda t: {"final_override": True, "fired": ["risk"]},
            lambda d, t: not (d.override and d.response.severity >= sev),
            f"R_e >= tau={_fmt(self.tau)} => override ({_SEV_NAME[sev]} or more) in the same cycle"))

    def prop_fault(self) -> Finding:
        """On a fault cycle the decision is override with at least ``on_fault`` (and the risk response if R_e ≥ τ)."""
        def run() -> Finding:
            L = z3.Int("latched")
            r = z3.Real("risk")
            has_r = z3.Bool("risk_known")
            tau = real(self.tau)
            sev = z3.If(L >= self.fault_sev, L, z3.IntVal(self.fault_sev))
            rs = z3.IntVal(self.risk_sev)
            sev = z3.If(z3.And(has_r, r >= tau, rs > sev), rs, sev)
            ok = z3.And(sev >= self.fault_sev, z3.Implies(z3.And(has_r, r >= tau), sev >= self.risk_sev), sev > 0)
            st, _, why = self.solve(L >= 0, L <= 4, z3.Not(ok))
            if st == "unsat":
                # and the monitor itself, on each kind of bad input
                bad = self._fault_replay()
                if bad:
                    return Finding("property", "fault.override", REFUTED, bad)
                return Finding("property", "fault.override", PROVED,
                               f"missing/NaN/out-of-range/wrong-type/stale input => override "
                               f"({self.spec.on_fault} or more), replayed for each input kind")
            return Finding("property", "fault.override", UNKNOWN if st == "unknown" else REFUTED, why or "")
        return self._timed(run)

    def _fault_replay(self) -> str:
        """Drive the real monitor with each kind of bad input for each signal; '' if all fail closed."""
        good: dict[str, Any] = {}
        for s in self.plan.signals:
            good[s.name] = False if s.kind == "bool" else (s.lo if math.isfinite(s.lo) and abs(s.lo) < 1e300
                                                          else 0.0)
        good["risk"] = 0.0 if 0.0 < self.tau else None
        if good["risk"] is None:
            good.pop("risk")
            good["p_unsafe"] = 0.0
        if self.spec.risk.max_age_s is not None:
            good["risk_age_s"] = 0.0
        cases: list[tuple[str, dict]] = []
        for s in self.plan.signals:
            miss = dict(good)
            miss.pop(s.name)
            cases.append((f"{s.name} missing", miss))
            cases.append((f"{s.name} wrong type", {**good, s.name: "x"}))
            if s.kind == "number":
                cases.append((f"{s.name} NaN", {**good, s.name: math.nan}))
                if s.hi < 1.7e308:
                    cases.append((f"{s.name} above range", {**good, s.name: s.hi + max(1.0, abs(s.hi))}))
                if s.lo > -1.7e308:
                    cases.append((f"{s.name} below range", {**good, s.name: s.lo - max(1.0, abs(s.lo))}))
        no_risk = {k: v for k, v in good.items() if k not in ("risk", "p_unsafe", "p")}
        cases.append(("risk missing", no_risk))
        cases.append(("risk NaN", {**no_risk, "risk": math.nan}))
        cases.append(("p_unsafe NaN", {**no_risk, "p_unsafe": math.nan}))
        if self.spec.risk.max_age_s is not None:
            cases.append(("risk stale", {**good, "risk_age_s": self.spec.risk.max_age_s * 2}))
            cases.append(("risk age missing", {k: v for k, v in good.items() if k != "risk_age_s"}))
        for label, frame in cases:
            m = Monitor(self.spec)
            d = m.step(frame)
            if not (d.override and d.faults and d.response.severity >= self.fault_sev):
                return f"{label}: the monitor did not fail closed ({d!r})"
        return ""

    def prop_defined(self, ob) -> Finding:
        name = f"{ob.id}.defined"

        def run() -> Finding:
            k = min(self.need[ob.id], self.max_unroll)
            enc = Unrolled(self.plan, k, prefix=f"{ob.id}.")
            for t in range(k):
                st, model, why = self.solve(z3.Not(enc.obligation_defined(ob, t)),
                                            *[enc.obligation_defined(ob, j) for j in range(t)], enc=enc)
                if st == "sat":
                    cex = self.counterexample(
                        name, model, enc, t, {"fault": False},
                        lambda d: any(f.kind == "internal" for f in d.faults))
                    return Finding("property", name, REFUTED,
                                   f"evaluation fails (division by zero, sqrt of a negative or a negative "
                                   f"separation_distance() argument) on in-range "
                                   f"input at cycle {t}: the monitor stops the arm with a fault", counterexample=cex)
                if st == "unknown":
                    return Finding("property", name, UNKNOWN, f"z3: {why}")
            return self._defined_in_floats(ob, k)
        return self._timed(run)

    def _arith(self, ob) -> bool:
        """Whether ``ob`` computes anything (arithmetic or a function): else floats are the reals."""
        from ..spec._expr import Binary, Call, Unary
        return any((isinstance(n, Binary) and n.op in ("+", "-", "*", "/")) or
                   (isinstance(n, Unary) and n.op == "-") or
                   (isinstance(n, Call) and n.func in ("sqrt", "abs", "min", "max", "separation_distance"))
                   for root in (ob.when, ob.require) if root is not None for n in walk(root))

    def _defined_in_floats(self, ob, k: int) -> Finding:
        """The real arithmetic found no raise: check again in the monitor's doubles (IEEE-754), where
        ``a * b`` of in-range non-zero inputs can be 0 and ``x / (a * b)`` raise."""
        name = f"{ob.id}.defined"
        what = "no division by zero, sqrt of a negative or negative separation_distance() argument for any in-range input"
        from ..spec._expr import Binary, Call
        if not any((isinstance(n, Binary) and n.op == "/") or (isinstance(n, Call) and n.func in (
                "sqrt", "separation_distance")) for root in (ob.when, ob.require) if root is not None
                for n in walk(root)):
            return Finding("property", name, PROVED, what + " (nothing that can raise: no /, sqrt or "
                           "separation_distance)")
        from ._floats import defined_in_doubles
        if defined_in_doubles(self.plan, ob):
            return Finding("property", name, PROVED, what + " (in doubles too: every divisor's real value stays "
                           "farther from 0 than rounding can move it, every sqrt/separation_distance argument "
                           "is >= 0 without subtraction, nothing overflows)")
        fenc = FloatUnrolled(self.plan, k, prefix=f"{ob.id}.f.")
        for t in range(k):
            st, model, why = self.solve_fp(z3.Not(fenc.obligation_defined(ob, t)),
                                           *[fenc.obligation_defined(ob, j) for j in range(t)], enc=fenc)
            if st == "sat":
                cex = self.counterexample(name, model, fenc, t, {"fault": False},
                                          lambda d: any(f.kind == "internal" for f in d.faults))
                if cex.confirmed:
                    return Finding("property", name, REFUTED,
                                   f"evaluation fails in floating point on in-range input at cycle {t} (a "
                                   f"float division by zero, e.g. a product that underflows to 0; in real "
                                   f"arithmetic it would not): the monitor stops the arm with a fault",
                                   counterexample=cex)
                return Finding("property", name, PROVED_REAL,
                               what + " in real arithmetic; the IEEE-754 model finds a raise that the replay "
                               "did not confirm", counterexample=cex)
            if st == "unknown":
                return Finding("property", name, PROVED_REAL,
                               what + f" in real arithmetic; the IEEE-754 check was not decided (z3: {why})")
        return Finding("property", name, PROVED, what + " (in IEEE-754 doubles, as the monitor computes)")

    def float_hazard(self, ob) -> str:
        """Where the monitor's doubles can leave the reals on ``ob`` ('' if nowhere): an overflow to
        ±inf, or an underflow that a comparison or product can see (:func:`._floats.float_hazards`),
        for inputs in their declared ranges."""
        got = self._hazard.get(ob.id)
        if got is None:
            from ._floats import float_hazards
            hz = float_hazards(self.plan, ob)
            ranges = ", ".join(f"{s.name} in [{s.lo:g}, {s.hi:g}]" for s in self.plan.signals if s.kind == "number")
            got = self._hazard[ob.id] = (f"floats can differ from the reals: {'; '.join(hz)} (inputs {ranges})"
                                         if hz else "")
        return got

    def prop_response(self, ob) -> Finding:
        n = ob.within_cycles or 0
        sev = ob.response.severity
        name = f"{ob.id}.response"
        if n >= self.k:
            return Finding("property", name, UNKNOWN,
                           f"within_cycles={n} needs more than --max-unroll {self.max_unroll} cycles")
        i = self.plan.obligations.index(ob)

        def bad(dt, t):
            j = t - n
            if j < 0:
                return None
            enc = dt.enc
            when = z3.BoolVal(True) if ob.when is None else enc.ev(ob.when, j)
            cond = z3.And([when] + [z3.Not(enc.ev(ob.require, m)) for m in range(j, t + 1)])
            return z3.And(cond, z3.Not(z3.And(dt.override[t], dt.response[t] >= sev, dt.violated[t][i])))
        what = "when & not require" if ob.when is not None else "not require"
        bound = f" for {n + 1} cycles" if n else ""

        def in_floats(f: Finding) -> Finding:
            # the premise is the condition as written (real numbers); the monitor judges it in doubles
            if f.status == PROVED:
                hazard = self.float_hazard(ob)
                if hazard:
                    f.status, f.message = PROVED_REAL, f"{f.message}; {hazard}"
            return f
        return self._timed(lambda: in_floats(self._decision_check(
            name, bad, lambda t: {"final_override": True, "fired": [ob.id]},
            lambda d, t: not (d.override and d.response.severity >= sev and ob.id in d.violations),
            f"{what}{bound} => violation and override ({ob.response.value} or more)"
            + (f" by {n} cycles after the trigger" if n else " in the same cycle"), only=i)))

    def prop_resume_explained(self) -> Finding:
        def bad(dt, t):
            return z3.And(z3.Not(dt.override[t]), z3.Or([dt.risk_fires[t], *dt.violated[t]]))
        return self._timed(lambda: self._decision_check(
            "resume.explained", bad, lambda t: {"final_override": True},
            lambda d, t: not d.override,
            "no override => every obligation holds and R_e < tau"))

    def prop_release_rule(self) -> Finding:
        """A latched override ends by itself only when every rule latched the cycle before is
        automatic and its release condition held its ``hold_cycles`` consecutive cycles; a rule
        with a manual release never ends it (only ``acknowledge()``/``release()``/``reset()``)."""
        def bad(dt, t):
            was = dt.lat0 if t == 0 else dt.lat[t - 1]
            oks = []
            for k, r in enumerate(dt.rules):
                if r.manual:
                    oks.append(z3.Not(was[k]))
                    continue
                span = range(max(0, t - r.hold + 1), t + 1)
                streak = z3.And([dt.cond[m][k] for m in span])
                if t - r.hold + 1 < 0:  # the rest of the streak lies before the trace: the count covers it
                    streak = z3.And(streak, dt.cnt0[k] >= r.hold - (t + 1))
                oks.append(z3.Implies(was[k], streak))
            return z3.And(z3.Or(was), z3.Not(dt.override[t]), z3.Not(z3.And(oks)))
        rules = rules_of(self.plan)
        auto = [r for r in rules if not r.manual]
        manual = [r.name for r in rules if r.manual]
        conds = {"risk": f"R_e < tau - delta = {_fmt(self.below)}", "fault": "no fault"}
        parts = [f"{r.name} after {r.hold} cycle{'s' if r.hold != 1 else ''} of {conds.get(r.name, 'holding')}"
                 for r in auto]
        msg = "a latched override resumes by itself only once each rule latched is released: " + (
            "; ".join(parts) if parts else "no rule releases automatically")
        if manual:
            msg += f"; manual (Monitor.acknowledge() only): {', '.join(manual)}"
        return self._timed(lambda: self._decision_check(
            "release.rule", bad, lambda t: {"final_override": True},
            lambda d, t: not d.override, msg))

    # -- lints ---------------------------------------------------------------------------
    def lint_tasks(self) -> list[tuple[str, Any]]:
        """``(name, check)`` of every lint, in report order (each check returns a list of findings)."""
        return [("lint.tau_range", lambda: [self._timed(self.lint_tau)]),
                ("lint.risk_monotone", lambda: [self._timed(self.lint_monotone)]),
                ("lint.release", lambda: [self._timed(self.lint_release)]),
                ("lint.release_policy", self.lint_release_policy),
                ("lint.vacuous", self.lint_vacuous), ("lint.contradiction", self.lint_contradictions),
                ("lint.unbounded", self.lint_unbounded), ("lint.fault_gap", self.lint_fault_gap),
                ("lint.safe_pose_range", self.lint_safe_pose_range)] + (
                    [("lint.confirm_band", lambda: [self._timed(lambda: lint_confirm_band(self))])]
                    if has_tiers(self.full_spec) else [])

    def lints(self) -> list[Finding]:
        return [f for _, fn in self.lint_tasks() for f in fn()]

    def risk_range(self) -> tuple[float, float] | None:
        """Reachable R_e over every probability vector: exact, for any number of classes."""
        r = self.spec.risk
        return risk_range(r.alpha, r.beta, r.gamma, r.variance, r.classes)

    def lint_tau(self) -> Finding:
        lo, hi = self.risk_range()
        tau = self.tau
        if tau > hi:
            return Finding("lint", "lint.tau_range", WARNING,
                           f"tau={_fmt(tau)} is above the largest reachable R_e={_fmt(hi)}: "
                           f"the risk rule can never fire")
        if tau <= lo:
            return Finding("lint", "lint.tau_range", WARNING,
                           f"tau={_fmt(tau)} is at or below the smallest reachable R_e={_fmt(lo)}: "
                           f"the risk rule fires every cycle")
        return Finding("lint", "lint.tau_range", OK, f"tau={_fmt(tau)} inside reachable R_e [{_fmt(lo)}, {_fmt(hi)}]")

    def lint_monotone(self) -> Finding:
        """R_e should not fall when the classifier grows more sure the task is unsafe."""
        name = "lint.risk_monotone"
        r = self.spec.risk
        if r.classes != 2:
            return Finding("lint", name, SKIPPED, f"checked for two classes only (K={r.classes})")
        q1, q2 = z3.Real("q1"), z3.Real("q2")

        def R(q):
            return two_class_risk(q, real(r.alpha), real(r.beta), real(r.gamma), r.variance, where=z3.If,
                                  half=z3.RealVal("1/2"))
        st, model, why = self.solve(q1 >= 0, q2 <= 1, q1 < q2, R(q1) > R(q2))
        if st == "sat":
            a, b = z3_value(model, q1), z3_value(model, q2)
            ra = risk_from_p_unsafe(a, r.alpha, r.beta, r.gamma, r.variance)
            rb = risk_from_p_unsafe(b, r.alpha, r.beta, r.gamma, r.variance)
            return Finding("lint", name, WARNING,
                           f"R_e falls as p_unsafe grows: p_unsafe {a:.4g} -> R_e {ra:.4g}, p_unsafe {b:.4g} -> "
                           f"R_e {rb:.4g} (monotone needs alpha >= beta and alpha + beta >= "
                           f"{2 if r.variance == 'sample' else 1}*gamma)")
        if st == "unknown":
            return Finding("lint", name, SKIPPED, f"z3: {why}")
        return Finding("lint", name, OK, "R_e never falls as p_unsafe grows")

    # -- windows of consecutive cycles ---------------------------------------------------
    def _window_cycles(self, ids) -> int:
        """P: cycles of history that can still change a verdict of these obligations (look-back + response window)."""
        return max([self.need[i] for i in ids] + [1]) - 1

    def window_search(self, goal, ids, s: int) -> tuple[str, Any]:
        """Is there a run with ``s`` consecutive fault-free cycles at each of which ``goal(enc, t)`` holds?

        ``ids`` are the obligations ``goal`` talks about; ``P`` (:meth:`_window_cycles`) cycles
        before the window are enough for their verdicts inside it. A run either starts (at a reset,
        or after a fault, which clears the history) fewer than ``P`` cycles before the window --
        the exact encodings with ``p < P`` prefix cycles -- or at least ``P`` cycles before it --
        covered by the free-history encoding of ``P + s`` cycles, which admits every history.

        Returns:
            ``("sat", (enc, model, p))``: an exact run from a reset whose cycles ``p .. p+s-1``
            are the window; ``("unsat", None)``: no run of any length has such a window;
            ``("unknown", reason)``: neither was shown (solver limit, or the free-history
            window is possible but no run was found).
        """
        P = self._window_cycles(ids)
        if P + s > self.max_unroll:
            return "unknown", (f"needs {P + s} cycles of unrolling ({s} in the window, {P} of history), more than "
                               f"--max-unroll {self.max_unroll}")
        why_unknown = ""

        def attempt(p: int, free: bool = False):
            enc = Unrolled(self.plan, p + s, prefix=f"w{'f' if free else p}.", free_history=free)
            goals = [self.all_defined(enc, p + s - 1)] + [goal(enc, t) for t in range(p, p + s)]
            st, model, why = self.solve(*goals, enc=enc)
            if st == "sat" and not free:  # prefer a run whose comparisons are clear of their boundaries
                st2, model2, _ = self.solve(*goals, *enc.decisive(), enc=enc)
                if st2 == "sat":
                    model = model2
            return enc, (st, model, why)

        for p in range(P):
            enc, (st, model, why) = attempt(p)
            if st == "sat":
                return "sat", (enc, model, p)
            if st == "unknown":
                why_unknown = why_unknown or why
        _, (st, _, why) = attempt(P, free=True)
        if st == "unsat":
            return ("unknown", why_unknown) if why_unknown else ("unsat", None)
        if st == "unknown":
            return "unknown", why_unknown or why
        enc, (st, model, why) = attempt(P)
        if st == "sat":
            return "sat", (enc, model, P)
        return "unknown", why_unknown or why or (
            f"no run from a reset has such a window within {2 * P + s} cycles, and the solver could not rule "
            f"out one after a longer history")

    def _replay_release(self, frames: list[dict[str, Any]]) -> tuple[bool, int]:
        """Replay a cycle where the risk rule fires (R_e at its largest reachable value) and
        then ``frames`` in a fresh Monitor: is the risk rule's latch released at the end?"""
        first = dict(frames[0])
        first["risk"] = max(self.tau, self.risk_range()[0])
        seq = [first] + frames
        m = Monitor(self.spec)
        ds = [m.step(f) for f in seq]
        return ("risk" in ds[0].violations and "risk" not in m.latched_rules), len(seq) - 1

    def lint_release(self) -> Finding:
        """Can the risk rule's latch auto-release (``hold_cycles`` cycles in a row with R_e < τ − δ,
        and, so that the override can end, every obligation held)?

        Only a run replayed in the real Monitor makes it "reachable"; "never" is a proof over runs
        of any length (:meth:`window_search`); anything else is ``unknown``.
        """
        rel = self.plan.risk_rule
        name = "lint.release"
        if rel.manual:
            return Finding("lint", name, WARNING, "risk.release.mode is manual: the risk rule's latch never "
                                                  "releases by itself (only Monitor.acknowledge(), release() "
                                                  "or reset())")
        lo, hi = self.risk_range()
        bound = f"R_e < tau - delta = {_fmt(self.below)}"
        if self.below_float < lo:
            return Finding("lint", name, WARNING,
                           f"release needs {bound}, but the smallest reachable R_e is {_fmt(lo)}: a latched "
                           f"override never auto-releases")
        hold = rel.hold
        ids = [ob.id for ob in self.plan.obligations]
        below = real(self.below_float)  # R_e arrives as a float: below the exact bound <=> at most this float

        def goal(enc: Unrolled, t: int):
            return z3.And([enc.R[t] <= below, enc.R[t] >= real(lo), enc.R[t] <= real(hi)]
                          + [z3.Not(enc.violated(ob, t)) for ob in self.plan.obligations])
        never = (f"no run has {hold} consecutive cycles with {bound} and every obligation held "
                 f"(checked over runs of any length): a latched override never auto-releases")
        P = self._window_cycles(ids)
        if P + hold <= self.max_unroll:
            st, info = self.window_search(goal, ids, hold)
            if st == "unsat":
                return Finding("lint", name, WARNING, never)
            if st == "unknown":
                return Finding("lint", name, UNKNOWN, f"release not decided: {info}")
            enc, model, p = info
            frames = self.frames(model, enc, p + hold - 1)
        else:
            # too long to unroll: a shorter window that no run has is still a proof ...
            short = self.max_unroll - P
            if short >= 1:
                st, _ = self.window_search(goal, ids, short)
                if st == "unsat":
                    return Finding("lint", name, WARNING,
                                   never.replace(f"{hold} consecutive", f"even {short} consecutive"))
            # ... and a run that repeats one input is a witness once its windows are full
            enc = Unrolled(self.plan, P + 1, prefix="wc.")
            same = [enc.sig[t][sg] == enc.sig[0][sg] for t in range(1, P + 1) for sg in enc.sig[0]]
            same += [enc.R[t] == enc.R[0] for t in range(1, P + 1)]
            st, model, why = self.solve(*same, self.all_defined(enc, P), goal(enc, P), *enc.decisive(), enc=enc)
            if st == "unsat":
                st, model, why = self.solve(*same, self.all_defined(enc, P), goal(enc, P), enc=enc)
            if st != "sat":
                return Finding("lint", name, UNKNOWN,
                               f"release not decided: hold_cycles={hold} needs {P + hold} cycles of unrolling "
                               f"(> --max-unroll {self.max_unroll}) and no constant input releases"
                               + (f" (z3: {why})" if why else ""))
            frames = self.frames(model, enc, 0) * (P + hold)
        ok, at = self._replay_release(frames)
        if not ok:
            return Finding("lint", name, UNKNOWN, "release not decided: the solver's run did not release when "
                                                  "replayed in the Monitor")
        return Finding("lint", name, OK, f"release reachable: {hold} cycles with {bound} and every obligation "
                                         f"held (a run replayed in the Monitor releases at cycle {at}: the risk "
                                         f"rule's latch)")

    def lint_release_policy(self) -> list[Finding]:
        """Release policies an engineer would question (:func:`release_policy_warnings`: an
        automatic release after a stop of category 0 or 1, an automatic fault release); else,
        as information, which rules wait for an operator (the integration must offer
        ``Monitor.acknowledge()``)."""
        name = "lint.release_policy"
        out = [Finding("lint", name, WARNING, w) for w in release_policy_warnings(self.plan)]
        manual = manual_rules(self.plan)
        if not out:
            out.append(Finding("lint", name, OK, (
                f"manual release for {', '.join(manual)}: the integration must offer an operator "
                f"acknowledgement (Monitor.acknowledge(); refused while a rule still fails)") if manual else
                "every rule releases automatically; none is a stop of category 0 or 1"))
        return out

    def lint_vacuous(self) -> list[Finding]:
        """Each obligation can be violated by some fault-free run from a reset (one incremental solver)."""
        t0 = time.perf_counter()
        out: list[Finding] = []
        obs = self.plan.obligations
        if obs:
            k = min(max(self.need[ob.id] for ob in obs), self.max_unroll)
            enc = Unrolled(self.plan, k, prefix="v.")
            upto = []  # every obligation defined at cycles 0 .. t
            acc = z3.BoolVal(True)
            for t in range(k):
                acc = z3.And(acc, *[enc.obligation_defined(o, t) for o in obs])
                upto.append(acc)
            goals = {ob.id: z3.Or([z3.And(upto[t], enc.violated(ob, t)) for t in range(k)]) for ob in obs}
            s = z3.Solver()
            s.push()
            s.add(*enc.constraints)
            for i, ob in enumerate(obs):
                ms = self.check_ms()
                if ms <= 0:
                    out.append(self.unreached("lint", "lint.vacuous",
                                              f"{len(obs) - i} of {len(obs)} obligations not checked for vacuity"))
                    break
                s.set("timeout", ms)
                s.push()
                s.add(goals[ob.id])
                st = s.check()
                if st == z3.unsat:
                    out.append(Finding("lint", f"lint.vacuous.{ob.id}", WARNING,
                                       f"obligation {ob.id!r} can never be violated inside the declared ranges"))
                elif st == z3.unknown:
                    out.append(Finding("lint", f"lint.vacuous.{ob.id}", UNKNOWN, f"z3: {s.reason_unknown()}"))
                s.pop()
        if not out:
            out.append(Finding("lint", "lint.vacuous", OK, "every obligation can be violated inside the ranges"))
        dt = time.perf_counter() - t0
        for f in out:
            f.seconds = dt / len(out)
        return out

    def _components(self) -> dict[str, int]:
        """Obligations that share no signal (nor R_e) through any chain get different numbers."""
        parent: dict[str, str] = {}

        def find(x: str) -> str:
            while parent.setdefault(x, x) != x:
                parent[x] = parent[parent[x]]
                x = parent[x]
            return x
        for ob in self.plan.obligations:
            names = [f"ob:{ob.id}"] + [f"sig:{n.id}" for root in (ob.when, ob.require) if root is not None
                                       for n in walk(root) if isinstance(n, Name)]
            for n in names[1:]:
                parent[find(n)] = find(names[0])
        return {ob.id: hash(find(f"ob:{ob.id}")) for ob in self.plan.obligations}

    def lint_contradictions(self) -> list[Finding]:
        """Obligations that cannot hold together (for a few cycles in a row: response windows take time to close)."""
        t0 = time.perf_counter()
        obs = self.plan.obligations
        out: list[Finding] = []

        def holds(subset):
            return lambda enc, t: z3.And([z3.Not(enc.violated(ob, t)) for ob in subset])

        def cycles(subset) -> int:
            return self._window_cycles([ob.id for ob in subset]) + 1

        def in_a_row(n: int) -> str:
            return "" if n == 1 else f" for {n} cycles in a row"

        def overrides(n: int) -> str:
            return "the monitor overrides every cycle" if n == 1 else f"the monitor overrides at least every {n} cycles"

        def done(found: list[Finding]) -> list[Finding]:
            dt = time.perf_counter() - t0
            for f in found:
                f.seconds = dt / len(found)
            return found
        if not obs:
            return done([Finding("lint", "lint.contradiction", OK, "no obligations")])
        n_all = cycles(obs)
        st_all, why_all = self.window_search(holds(obs), [ob.id for ob in obs], n_all)
        if st_all == "sat":
            return done([Finding("lint", "lint.contradiction", OK,
                                 f"the obligations can all hold together{in_a_row(n_all)}")])
        # find the culprits: each obligation alone, then pairs that share a signal
        alone_ok, undecided = [], 0
        for i, ob in enumerate(obs):
            if self.out_of_budget():
                out.append(self.unreached("lint", "lint.unsatisfiable", f"{len(obs) - i} obligations not checked"))
                return done(out)
            n = cycles([ob])
            st, _ = self.window_search(holds([ob]), [ob.id], n)
            if st == "unsat":
                out.append(Finding("lint", f"lint.unsatisfiable.{ob.id}", WARNING,
                                   f"obligation {ob.id!r} cannot hold{in_a_row(n) or ' for any input'} inside the "
                                   f"ranges ({overrides(n)})"))
            elif st == "sat":
                alone_ok.append(ob)
            else:
                undecided += 1
        comp = self._components()
        pairs = [(a, b) for a, b in itertools.combinations(alone_ok, 2) if comp[a.id] == comp[b.id]]
        for i, (a, b) in enumerate(pairs):
            if self.out_of_budget():
                out.append(self.unreached("lint", "lint.contradiction", f"{len(pairs) - i} of {len(pairs)} pairs of "
                                                                        f"obligations not checked"))
                return done(out)
            n = cycles([a, b])
            st, _ = self.window_search(holds([a, b]), [a.id, b.id], n)
            if st == "unsat":
                out.append(Finding("lint", f"lint.contradiction.{a.id}.{b.id}", WARNING,
                                   f"obligations {a.id!r} and {b.id!r} contradict: no input inside the ranges "
                                   f"satisfies both{in_a_row(n)} ({overrides(n)})"))
            elif st == "unknown":
                undecided += 1
        if not out:
            if st_all == "unsat":
                out.append(Finding("lint", "lint.contradiction.all", WARNING,
                                   f"no input satisfies all obligations together{in_a_row(n_all)}"))
            else:
                out.append(Finding("lint", "lint.contradiction", UNKNOWN,
                                   f"not decided whether the obligations can all hold together{in_a_row(n_all)}: "
                                   f"{why_all}"))
        return done(out)

    def lint_unbounded(self) -> list[Finding]:
        out = [Finding("lint", f"lint.unbounded.{s.name}", WARNING,
                       f"signal {s.name!r} has no range: only NaN/infinity fail closed, any other value is trusted")
               for s in self.plan.signals if s.kind == "number" and s.name in self.spec.signals
               and self.spec.signals[s.name].range is None]
        return out or [Finding("lint", "lint.unbounded", OK, "every numeric signal has a declared range")]

    def lint_safe_pose_range(self) -> list[Finding]:
        """The safe pose inside the Franka Panda's rated joint range (``ethimon._robot``, FCI
        'Limits for Panda'): outside it the real arm aborts the motion and the simulation refuses
        the spec; ``ethimon lint`` reports it as an error. One warning naming each joint, its
        value and the rated limits, at the spec's file:line:column when known."""
        name = "lint.safe_pose_range"
        joints = tuple(self.spec.safe_pose.joints_rad)
        if len(joints) != 7:
            return [Finding("lint", name, WARNING, f"safe_pose.joints_rad has {len(joints)} values; the "
                            "Franka Panda (the simulated arm, the rated-limit table) has 7 joints")]
        problem = safe_pose_problem(joints)
        if problem is None:
            return [Finding("lint", name, OK, "the safe pose lies inside the Franka Panda's rated joint range")]
        where = ""
        src = getattr(self.spec, "source", None)
        if src is not None:  # the first joint outside its range, in the spec file
            err = src.error(problem, ("safe_pose", "joints_rad", out_of_range(joints)[0][0] - 1))
            if err.line is not None:
                where = f"{err.location}: "
        return [Finding("lint", name, WARNING, f"{where}{problem} (an error for 'ethimon lint' and "
                        "'check --sim'; FCI 'Limits for Panda')")]

    def lint_fault_gap(self) -> list[Finding]:
        """The fault latch's hold must cover every obligation's window: a fault clears the
        history, so a shorter hold lets the arm resume (by itself, or on an acknowledgement
        that is accepted) before a windowed obligation can see its violation again."""
        mode, hold = self.plan.fault_rule.mode, self.plan.fault_rule.hold
        how = "resume by itself" if mode == "auto" else "be acknowledged and resume"
        out = []
        for ob in self.plan.obligations:
            need = self.need[ob.id]
            if need > 1 and hold < need:
                out.append(Finding(
                    "lint", f"lint.fault_gap.{ob.id}", WARNING,
                    f"after a fault clears the history, {ob.id!r} needs {need} cycles to fire again but the "
                    f"fault latch's hold_cycles={hold}: the arm can {how} while it is still violated"))
        return out or [Finding("lint", "lint.fault_gap", OK,
                               "the fault latch's hold_cycles covers every obligation's window after a fault")]
