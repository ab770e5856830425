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

from ..compiler._risk_formula import tier_outcome
from ..runtime import Monitor
from ..language import Response, Spec
from ._encode import real, risk_input_range
from ._checks import Check
from ._report import OK, PROVED, REFUTED, UNKNOWN, WARNING, Finding

__all__ = ["has_tiers", "base_spec", "tier_checks", "lint_confirm_band"]


_STOP_2 = Response.STOP_2.severity


def has_tiers(spec: Spec) -> bool:
    """Whether the spec sets a confirm band or a judge."""
    return spec.risk.confirm_threshold is not None or bool(spec.risk.judge_list)


def base_spec(spec: Spec) -> Spec:
    """The spec without its tiers (what the decision-trace properties are checked on)."""
    if not has_tiers(spec):
        return spec
    risk = spec.risk.model_copy(update={"confirm_threshold": None, "judge": None, "judges": None,
                                        "judge_may_hold_above_tau": None})
    return spec.model_copy(update={"risk": risk})


class _Cycle:
    """The free inputs of one valid cycle and the rules' fire conditions (the monitor's, as formulas)."""

    def __init__(self, spec: Spec, plan, tag: str = "") -> None:
        r = spec.risk
        self.R = z3.Real(f"R{tag}")
        self.jk = z3.Bool(f"judged{tag}")
        self.j = z3.Real(f"p_judge{tag}")
        self.conf = z3.Bool(f"confirmed{tag}")
        self.L = z3.Int(f"latched{tag}")
        lo, hi = risk_input_range(plan)
        self.domain = [self.R >= real(lo), self.R <= real(hi), self.j >= 0, self.j <= 1, self.L >= 0, self.L <= 4]
        tau = real(r.threshold)
        self.tau = tau
        self.risk_sev = Response(r.response).severity
        cuts = r.judge_cuts()  # one judge's cuts, or the consensus input's (risk.judges)
        judge_on = z3.BoolVal(cuts is not None)
        self.unsafe = z3.And(judge_on, self.jk, self.j >= real(cuts[1] if cuts else 1.0))
        self.safe = z3.And(judge_on, self.jk, self.j < real(cuts[0] if cuts else 0.0))
        hold = r.judge_may_hold_above_tau
        self.ceiling = real(hold.ceiling) if (hold is not None and cuts is not None) else None
        # risk.judge_may_hold_above_tau: a safe verdict at tau <= R_e < ceiling is a confirm hold, not a stop
        self.held = (z3.And(self.R >= tau, self.R < self.ceiling, self.safe) if self.ceiling is not None
                     else z3.BoolVal(False))
        self.risk_fires = z3.And(self.R >= tau, z3.Not(self.held))
        self.judge_fires = self.unsafe
        if r.confirm_threshold is None:
            self.in_band = z3.BoolVal(False)
        else:
            self.in_band = z3.And(self.R >= real(r.confirm_threshold), self.R < tau)
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
    spec: Spec = u.full_spec
    r = spec.risk
    band = r.confirm_threshold is not None
    judge = bool(r.judge_list)
    hold_on = judge and r.judge_may_hold_above_tau is not None
    cuts = r.judge_cuts()
    out: list[Check] = []

    def cyc(tag=""):
        return _Cycle(spec, u.full_plan, tag)

    def stop(u) -> Finding:
        c = cyc()
        if not hold_on:
            return _prove(u, "tier.stop", c, z3.Implies(c.R >= c.tau, z3.And(c.override, c.sev >= c.risk_sev)),
                          f"R_e >= tau => override ({r.response} or more) whatever the judge says")
        ceil = r.judge_may_hold_above_tau.ceiling
        claim = z3.And(z3.Implies(z3.And(c.R >= c.tau, z3.Not(c.safe)), z3.And(c.override, c.sev >= c.risk_sev)),
                       z3.Implies(c.R >= c.ceiling, z3.And(c.override, c.sev >= c.risk_sev)))
        return _prove(u, "tier.stop", c, claim,
                      f"R_e >= tau without a safe verdict, or R_e >= ceiling {ceil:g} whatever the judge says => "
                      f"override ({r.response} or more)")
    out.append(Check("property", "tier.stop", stop))
    if hold_on:
        def hold_above(u) -> Finding:
            c = cyc()
            claim = z3.Implies(z3.And(c.R >= c.tau, z3.Not(c.conf)), z3.And(c.override, c.sev >= _STOP_2))
            return _prove(u, "tier.hold_above_tau", c, claim,
                          f"judge_may_hold_above_tau (ceiling {r.judge_may_hold_above_tau.ceiling:g}): at R_e >= tau "
                          "a safe verdict gives at most a confirm hold (stop_2 or more): never execute without a "
                          "person's confirmation of that text")
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
                          f"an unsafe verdict (p_judge >= {cuts[1]:g}) => override ({r.response} or more) "
                          f"at any R_e")
        out.append(Check("property", "tier.judge_unsafe", unsafe))

        def raise_only(u) -> Finding:
            c = cyc()
            below = c.R < (real(r.confirm_threshold) if band else c.tau)
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


def _points(spec: Spec, plan) -> tuple[list[float], list[float | None]]:
    r = spec.risk
    lo, hi = risk_input_range(plan)
    rs = {lo, hi, float(r.threshold), math.nextafter(float(r.threshold), -math.inf), (lo + hi) / 2}
    if r.confirm_threshold is not None:
        tc = float(r.confirm_threshold)
        rs |= {tc, math.nextafter(tc, -math.inf), math.nextafter(tc, math.inf), (tc + float(r.threshold)) / 2}
    hold = r.judge_may_hold_above_tau
    if hold is not None:
        cl = float(hold.ceiling)
        rs |= {cl, math.nextafter(cl, -math.inf), (float(r.threshold) + cl) / 2}
    js: set[float] = {0.0, 0.5, 1.0}
    cuts = r.judge_cuts()
    if cuts is not None:
        for x in cuts:
            js |= {x, max(0.0, math.nextafter(x, -math.inf)), min(1.0, math.nextafter(x, math.inf))}
    return sorted(x for x in rs if lo <= x <= hi), [None, *sorted(js)]


def agrees(u) -> Finding:
    """Fresh monitors on every threshold boundary fire what the encoding says (confirmed or not)."""
    spec: Spec = u.full_spec
    rs, js = _points(spec, u.full_plan)
    c = _Cycle(spec, u.full_plan)
    r = spec.risk
    cuts = r.judge_cuts()
    hold = r.judge_may_hold_above_tau if cuts is not None else None
    n = 0
    for R, jp, confirmed in itertools.product(rs, js, (False, True)):
        m = Monitor(u.full_plan, margins=False)
        frame: dict[str, Any] = {sig.name: (True if sig.kind == "bool" else min(max(0.0, sig.lo), sig.hi))
                                 for sig in u.full_plan.signals}
        if r.max_age_s is not None:
            frame["risk_age_s"] = 0.0
        if confirmed:  # a confirmation needs the band (or a held text): confirm one first, same task
            if r.confirm_threshold is not None:
                m.step({**frame, "risk": float(r.confirm_threshold), "task_id": "t"})
            elif r.judge_may_hold_above_tau is not None and cuts is not None and cuts[0] > 0:
                m.step({**frame, "risk": float(r.threshold), "judge": 0.0, "task_id": "t"})
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
        outcome = tier_outcome(R, jp, threshold=r.threshold, confirm_threshold=r.confirm_threshold,
                               safe_below=cuts[0] if cuts else 0.2, unsafe_from=cuts[1] if cuts else 0.8,
                               judge=cuts is not None, hold_ceiling=hold.ceiling if hold is not None else None)
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
    spec: Spec = u.full_spec
    r = spec.risk
    name = "lint.confirm_band"
    if r.confirm_threshold is None:
        return Finding("lint", name, OK, "no confirm band" + (" (the judge can only stop)" if r.judge_list else "")
                       + _hold_note(r))
    lo, hi = u.risk_range()  # reachable R_e (the tiers do not change the formula)
    tc, tau = float(r.confirm_threshold), float(r.threshold)
    if tc >= tau:  # pragma: no cover - the spec model rejects it
        return Finding("lint", name, WARNING, f"tau_confirm={tc:g} is not below tau={tau:g}")
    if tc <= lo:
        return Finding("lint", name, WARNING,
                       f"tau_confirm={tc:g} is at or below the smallest reachable R_e={lo:g}: every text without a "
                       f"safe verdict is held for a person")
    if tc >= hi:
        return Finding("lint", name, WARNING, f"tau_confirm={tc:g} is above every reachable R_e: the band is empty")
    who = ("the judges in consensus or a person" if r.judges else "the judge or a person") if r.judge_list \
        else "a person (no judge)"
    return Finding("lint", name, OK, f"tau_confirm={tc:g} < tau={tau:g}; R_e in [{tc:g}, {tau:g}) goes to {who}"
                   + _hold_note(r))


def _hold_note(r) -> str:
    """What lint says about risk.judge_may_hold_above_tau (named whenever it is on)."""
    h = r.judge_may_hold_above_tau
    if h is None:
        return ""
    return (f"; judge_may_hold_above_tau: a canary-passed judge's safe verdict holds R_e in [{float(r.threshold):g}, "
            f"{float(h.ceiling):g}) for a person (stop_2) instead of stopping it")
