"""The tier rules of ``ethimon verify``: the confirm band (``risk.confirm_threshold``) and the judge
(``risk.judge``), proved with z3 over one valid cycle and replayed on the real :class:`Monitor`.

The encoding is the monitor's rule for one cycle, written as formulas over free inputs: R_e (any value
the monitor accepts), a judgement (known or not; any p in [0, 1]), whether an operator's confirmation
holds for this task, and the severity already latched by earlier cycles (any). Each property is
proved by showing that its negation is unsatisfiable; ``tier.agrees`` then steps fresh monitors on
every boundary of the thresholds and checks that they fire exactly what the encoding says, so the
proofs are about the monitor and not only about the formulas.

The other properties of ``verify`` are checked on the spec without its tiers: the tier rules only add
overrides (``tier.adds_only``), so whatever the base spec guarantees still holds with them.
"""

from __future__ import annotations

import itertools
import math
from typing import Any

import z3

from ..compiler import Plan, plan_of, spec_without_tiers
from ..compiler._risk_formula import tier_outcome
from ..runtime import Monitor
from ..language import SEVERITY_ORDER, Response, Spec
from ._encode import real, risk_input_range
from ._checks import Check
from ._report import OK, PROVED, REFUTED, UNKNOWN, WARNING, Finding

__all__ = ["has_tiers", "base_spec", "tier_checks", "lint_confirm_band"]


_STOP_2 = Response.STOP_2.severity


def has_tiers(spec: Spec | Plan) -> bool:
    """Whether the spec sets a confirm band or a judge (its plan's ``tiers.on``)."""
    return plan_of(spec).tiers.on


def base_spec(spec: Spec) -> Spec:
    """The spec without its tiers (what the decision-trace properties are checked on): built by the
    compiler, which knows which keys are the tiers (:func:`~ethimon.compiler.spec_without_tiers`)."""
    return spec_without_tiers(spec)


class _Cycle:
    """The free inputs of one valid cycle and the rules' fire conditions (the monitor's, as formulas)."""

    def __init__(self, plan: Plan, tag: str = "") -> None:
        rp, t = plan.risk_plan, plan.tiers
        self.R = z3.Real(f"R{tag}")
        self.jk = z3.Bool(f"judged{tag}")
        self.j = z3.Real(f"p_judge{tag}")
        self.conf = z3.Bool(f"confirmed{tag}")
        self.L = z3.Int(f"latched{tag}")
        lo, hi = risk_input_range(plan)
        self.domain = [self.R >= real(lo), self.R <= real(hi), self.j >= 0, self.j <= 1, self.L >= 0, self.L <= 4]
        tau = real(rp.threshold)
        self.tau = tau
        self.risk_sev = rp.latch.response.severity
        cuts = t.judge_cuts  # one judge's cuts, or the consensus input's (risk.judges)
        judge_on = z3.BoolVal(cuts is not None)
        self.unsafe = z3.And(judge_on, self.jk, self.j >= real(cuts[1] if cuts else 1.0))
        self.safe = z3.And(judge_on, self.jk, self.j < real(cuts[0] if cuts else 0.0))
        self.ceiling = real(t.hold_ceiling) if t.hold_ceiling is not None else None  # only with a judge
        # risk.judge_may_hold_above_tau: a safe verdict at tau <= R_e < ceiling is a confirm hold, not a stop
        self.held = (z3.And(self.R >= tau, self.R < self.ceiling, self.safe) if self.ceiling is not None
                     else z3.BoolVal(False))
        self.risk_fires = z3.And(self.R >= tau, z3.Not(self.held))
        self.judge_fires = self.unsafe
        if t.confirm_threshold is None:
            self.in_band = z3.BoolVal(False)
        else:
            self.in_band = z3.And(self.R >= real(t.confirm_threshold), self.R < tau)
        self.confirm_fires = z3.Or(
            z3.And(z3.Not(self.judge_fires), self.in_band, z3.Not(self.conf), z3.Not(self.safe)),
            z3.And(z3.Not(self.judge_fires), self.held, z3.Not(self.conf)))
        sev = self.L
        for fires, s in ((self.risk_fires, self.risk_sev), (self.judge_fires, self.risk_sev),
                         (self.confirm_fires, _STOP_2)):
            sev = z3.If(z3.And(fires, sev < s), z3.IntVal(s), sev)
        self.sev = sev
        self.override = sev > 0
        base_fires = self.R >= tau
        self.base_override = z3.Or(self.L > 0, base_fires)
        self.base_sev = z3.If(z3.And(base_fires, self.L < self.risk_sev), z3.IntVal(self.risk_sev), self.L)


def _prove(u, name: str, cyc: _Cycle, claim, what: str, *extra) -> Finding:
    st, model, why = u.budget.solve(*cyc.domain, *extra, z3.Not(claim))
    if st == "unsat":
        return Finding("property", name, PROVED, what)
    if st == "sat":
        vals = {k: ck_val(model, v) for k, v in (("R_e", cyc.R), ("judged", cyc.jk), ("p_judge", cyc.j),
                                                  ("confirmed", cyc.conf), ("latched", cyc.L))}
        return Finding("property", name, REFUTED, f"fails for {vals}")
    return Finding("property", name, UNKNOWN, f"z3: {why}")


def ck_val(model, v) -> Any:
    x = model.eval(v, model_completion=True)
    if z3.is_true(x) or z3.is_false(x):
        return z3.is_true(x)
    if z3.is_int_value(x):
        return x.as_long()
    return float(x.as_fraction()) if z3.is_rational_value(x) else str(x)


def tier_checks(u) -> list[Check]:
    """Every tier property over the unrolling ``u`` (its ``full_spec`` has tiers), in report order."""
    plan: Plan = u.full_plan
    t = plan.tiers
    response = plan.risk_plan.latch.response.value
    band = t.confirm_threshold is not None
    judge = t.judge_cuts is not None
    hold_on = t.hold_ceiling is not None  # only with a judge
    cuts = t.judge_cuts
    out: list[Check] = []

    def cyc(tag=""):
        return _Cycle(plan, tag)

    def stop(u) -> Finding:
        c = cyc()
        if not hold_on:
            return _prove(u, "tier.stop", c, z3.Implies(c.R >= c.tau, z3.And(c.override, c.sev >= c.risk_sev)),
                          f"R_e >= tau => override ({response} or more) whatever the judge says")
        ceil = t.hold_ceiling
        claim = z3.And(z3.Implies(z3.And(c.R >= c.tau, z3.Not(c.safe)), z3.And(c.override, c.sev >= c.risk_sev)),
                       z3.Implies(c.R >= c.ceiling, z3.And(c.override, c.sev >= c.risk_sev)))
        return _prove(u, "tier.stop", c, claim,
                      f"R_e >= tau without a safe verdict, or R_e >= ceiling {ceil:g} whatever the judge says => "
                      f"override ({response} or more)")
    out.append(Check("property", "tier.stop", stop))
    if hold_on:
        def hold_above(u) -> Finding:
            c = cyc()
            # the least an unconfirmed text at R_e >= tau gets: a hold (stop_2) or the risk rule's own response,
            # whichever is lower (a spec may answer R_e >= tau with safe_pose, below a hold)
            least = min(_STOP_2, c.risk_sev)
            claim = z3.Implies(z3.And(c.R >= c.tau, z3.Not(c.conf)), z3.And(c.override, c.sev >= least))
            return _prove(u, "tier.hold_above_tau", c, claim,
                          f"judge_may_hold_above_tau (ceiling {t.hold_ceiling:g}): at R_e >= tau a safe verdict "
                          "gives at most a confirm hold (stop_2): never execute without a person's confirmation "
                          f"of that text (override, {SEVERITY_ORDER[least].value} or more)")
        out.append(Check("property", "tier.hold_above_tau", hold_above))
    if band:
        def hold(u) -> Finding:
            c = cyc()
            no_safe = z3.And(z3.Not(c.safe), z3.Not(c.conf), c.in_band)
            claim = z3.And(z3.Implies(no_safe, c.override),
                           z3.Implies(z3.And(no_safe, z3.Not(c.unsafe)), c.sev >= _STOP_2),
                           z3.Implies(z3.And(c.in_band, z3.Not(c.jk), z3.Not(c.conf)), c.sev >= _STOP_2))
            return _prove(u, "tier.band", c, claim,
                          "tau_confirm <= R_e < tau without a safe verdict or a confirmation => override; unsure or "
                          "no judgement (timeout, error, malformed, none) => hold (stop_2 or more): never execute "
                          "on a missing judgement")
        out.append(Check("property", "tier.band", hold))
    if judge:
        def unsafe(u) -> Finding:
            c = cyc()
            return _prove(u, "tier.judge_unsafe", c, z3.Implies(c.unsafe, z3.And(c.override, c.sev >= c.risk_sev)),
                          f"an unsafe verdict (p_judge >= {cuts[1]:g}) => override ({response} or more) "
                          f"at any R_e")
        out.append(Check("property", "tier.judge_unsafe", unsafe))

        def raise_only(u) -> Finding:
            c = cyc()
            below = c.R < (real(t.confirm_threshold) if band else c.tau)
            # the same cycle with no judgement: the judgement can only add overrides below the band
            nj = z3.substitute(z3.And(c.override, c.sev >= 0), (c.jk, z3.BoolVal(False)))
            nj_sev = z3.substitute(c.sev, (c.jk, z3.BoolVal(False)))
            claim = z3.Implies(below, z3.And(z3.Implies(nj, c.override), c.sev >= nj_sev))
            return _prove(u, "tier.raise_only", c, claim,
                          "below tau_confirm a judgement never lowers the decision: with any verdict the override "
                          "and its severity are at least those with no judgement")
        out.append(Check("property", "tier.raise_only", raise_only))

    def adds_only(u) -> Finding:
        c = cyc()
        if hold_on:  # the hold lowers a stop's severity to stop_2 (held for a person), never to execute
            claim = z3.And(z3.Implies(z3.And(c.base_override, z3.Not(c.conf)), c.override),
                           z3.Or(c.sev >= c.base_sev, c.held))
            return _prove(u, "tier.adds_only", c, claim,
                          "the tier rules only add overrides to the spec without them, except that a held text "
                          "(judge_may_hold_above_tau) is stop_2 until a person confirms it")
        claim = z3.And(z3.Implies(c.base_override, c.override), c.sev >= c.base_sev)
        return _prove(u, "tier.adds_only", c, claim,
                      "the tier rules only add overrides to the spec without them (its properties above hold "
                      "with the tiers too)")
    out.append(Check("property", "tier.adds_only", adds_only))
    out.append(Check("property", "tier.agrees", agrees))
    return out


def _points(plan: Plan) -> tuple[list[float], list[float | None]]:
    t, tau = plan.tiers, plan.risk_plan.threshold
    lo, hi = risk_input_range(plan)
    rs = {lo, hi, tau, math.nextafter(tau, -math.inf), (lo + hi) / 2}
    if t.confirm_threshold is not None:
        tc = t.confirm_threshold
        rs |= {tc, math.nextafter(tc, -math.inf), math.nextafter(tc, math.inf), (tc + tau) / 2}
    if t.hold_ceiling is not None:
        cl = t.hold_ceiling
        rs |= {cl, math.nextafter(cl, -math.inf), (tau + cl) / 2}
    js: set[float] = {0.0, 0.5, 1.0}
    cuts = t.judge_cuts
    if cuts is not None:
        for x in cuts:
            js |= {x, max(0.0, math.nextafter(x, -math.inf)), min(1.0, math.nextafter(x, math.inf))}
    return sorted(x for x in rs if lo <= x <= hi), [None, *sorted(js)]


def agrees(u) -> Finding:
    """Fresh monitors on every threshold boundary fire what the encoding says (confirmed or not)."""
    plan: Plan = u.full_plan
    rs, js = _points(plan)
    c = _Cycle(plan)
    rp, t = plan.risk_plan, plan.tiers
    cuts = t.judge_cuts
    n = 0
    for R, jp, confirmed in itertools.product(rs, js, (False, True)):
        m = Monitor(plan, margins=False)
        frame: dict[str, Any] = {sig.name: (True if sig.kind == "bool" else min(max(0.0, sig.lo), sig.hi))
                                 for sig in plan.signals}
        if rp.max_age_s is not None:
            frame["risk_age_s"] = 0.0
        if confirmed:  # a confirmation needs the band (or a held text): confirm one first, same task
            if t.confirm_threshold is not None:
                m.step({**frame, "risk": t.confirm_threshold, "task_id": "t"})
            elif t.hold_ceiling is not None and cuts[0] > 0:  # a hold ceiling only with a judge
                m.step({**frame, "risk": rp.threshold, "judge": 0.0, "task_id": "t"})
            else:
                continue
            if not m.acknowledge().released:
                continue  # an obligation of the spec holds the arm here; nothing to compare
        d = m.step({**frame, "risk": R, "judge": jp, "task_id": "t"})
        if d.faults:
            continue
        sub = [(c.R, real(R)), (c.jk, z3.BoolVal(jp is not None)), (c.j, real(jp if jp is not None else 0.0)),
               (c.conf, z3.BoolVal(confirmed)), (c.L, z3.IntVal(0))]
        want = [name for name, f in (("risk", c.risk_fires), ("judge", c.judge_fires), ("confirm", c.confirm_fires))
                if z3.is_true(z3.simplify(z3.substitute(f, *sub)))]
        got = [v for v in d.violations if v in ("risk", "judge", "confirm")]
        if got != want:
            return Finding("property", "tier.agrees", REFUTED,
                           f"R_e={R!r}, p_judge={jp!r}, confirmed={confirmed}: the Monitor fired {got}, the "
                           f"encoding {want}")
        outcome = tier_outcome(R, jp, threshold=rp.threshold, confirm_threshold=t.confirm_threshold,
                               safe_below=cuts[0] if cuts else 0.2, unsafe_from=cuts[1] if cuts else 0.8,
                               judge=cuts is not None, hold_ceiling=t.hold_ceiling)
        if not confirmed and not [v for v in d.violations if v not in ("risk", "judge", "confirm")]:
            seen = "stop" if ("risk" in got or "judge" in got) else ("confirm" if got else "execute")
            if seen != outcome:
                return Finding("property", "tier.agrees", REFUTED,
                               f"R_e={R!r}, p_judge={jp!r}: tier_outcome says {outcome}, the Monitor {seen}")
        n += 1
    return Finding("property", "tier.agrees", OK,
                   f"the Monitor fires what the encoding says (and tier_outcome agrees) at {n} boundary points")


def lint_confirm_band(u) -> Finding:
    """Where the confirm band lies in the reachable R_e (and what ``judge_may_hold_above_tau`` does)."""
    plan: Plan = u.full_plan
    t = plan.tiers
    name = "lint.confirm_band"
    if t.confirm_threshold is None:
        return Finding("lint", name, OK, "no confirm band" + (" (the judge can only stop)" if t.judges else "")
                       + _hold_note(plan))
    lo, hi = u.risk_range()  # reachable R_e (the tiers do not change the formula)
    tc, tau = t.confirm_threshold, plan.risk_plan.threshold
    if tc >= tau:  # pragma: no cover - the spec model rejects it
        return Finding("lint", name, WARNING, f"tau_confirm={tc:g} is not below tau={tau:g}")
    if tc <= lo:
        return Finding("lint", name, WARNING,
                       f"tau_confirm={tc:g} is at or below the smallest reachable R_e={lo:g}: every text without a "
                       f"safe verdict is held for a person")
    if tc >= hi:
        return Finding("lint", name, WARNING, f"tau_confirm={tc:g} is above every reachable R_e: the band is empty")
    who = ("the judges in consensus or a person" if t.consensus else "the judge or a person") if t.judges \
        else "a person (no judge)"
    return Finding("lint", name, OK, f"tau_confirm={tc:g} < tau={tau:g}; R_e in [{tc:g}, {tau:g}) goes to {who}"
                   + _hold_note(plan))


def _hold_note(plan: Plan) -> str:
    """What lint says about risk.judge_may_hold_above_tau (named whenever it is on)."""
    h = plan.tiers.hold_ceiling
    if h is None:
        return ""
    return (f"; judge_may_hold_above_tau: a canary-passed judge's safe verdict holds R_e in "
            f"[{plan.risk_plan.threshold:g}, {h:g}) for a person (stop_2) instead of stopping it")
