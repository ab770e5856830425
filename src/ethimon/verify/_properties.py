"""The properties of ``ethimon verify`` (imports z3): what the monitor does, proved over the
spec's :class:`~._unrolling.Unrolling` (risk bounds and override, faults, each obligation's
definedness and response, resume and release), and the z3 model checked against the real
:class:`Monitor`. Each is a function of the unrolling; :func:`property_checks` lists them."""

from __future__ import annotations

import math
from typing import Any

import z3

from ..compiler._risk_formula import risk_bounds, risk_from_p_unsafe, two_class_risk
from ..runtime import Monitor
from ..language._expr import walk
from ._checks import _SEV_NAME, BUDGET_NOTE, Check, _fmt
from ._encode import real, rules_of, z3_value
from ._report import OK, PROVED, PROVED_REAL, REFUTED, SKIPPED, UNKNOWN, Counterexample, Finding
from ._tiers import has_tiers, tier_checks
from ._unrolling import Unrolling

__all__ = ["property_checks"]


def property_checks(u: Unrolling) -> list[Check]:
    """Every property of ``u``'s spec, in report order (the tiers' last, when it has any)."""
    out = [Check("property", "risk.bounds", risk_bounds_check), Check("property", "risk.override", risk_override),
           Check("property", "fault.override", fault_override)]
    for ob in u.plan.obligations:
        out.append(Check("property", f"{ob.id}.defined", lambda u, ob=ob: defined(u, ob)))
        out.append(Check("property", f"{ob.id}.response", lambda u, ob=ob: response(u, ob)))
    out += [Check("property", "resume.explained", resume_explained), Check("property", "release.rule", release_rule),
            Check("property", "model.agrees", model_agrees)]
    if has_tiers(u.full_spec):
        out += tier_checks(u)
    return out


def model_agrees(u: Unrolling, traces: int = 24) -> Finding:
    """The z3 model of this spec agrees with the real :class:`Monitor` on sampled traces.

    The proofs above are about the translation; this replays seeded random traces of
    ``k`` cycles (values at the range ends, the middle, random; inputs often held so
    windows fill) through both and compares violations, override and response.
    """
    import random
    name = "model.agrees"
    enc, dt = u.enc, u.dt
    rng = random.Random(f"ethimon-verify:{u.spec.name}")
    from ._encode import risk_input_range
    rlo, rhi = risk_input_range(u.plan)
    # the release bound's neighbours: the cut, the largest float below it, the float tau - delta
    r_pick = [rlo, rhi, u.tau, u.below_cut, u.below_float,
              float(u.tau - u.plan.risk_plan.hysteresis), min(max(u.below - 1e-3, rlo), rhi)]
    r_pick = [x for x in r_pick if rlo <= x <= rhi]
    s = z3.Solver()
    s.set("timeout", max(1, u.budget.check_ms()))
    goals = [dt.L0 == 0, dt.C0 == 0, *dt.init]
    terms = [(dt.violated[t], dt.risk_fires[t], dt.override[t], dt.response[t]) for t in range(u.k)]
    s.add(*goals)
    s.add(*enc.constraints)
    compared = 0
    for i in range(traces):
        if u.budget.out_of_budget():
            return Finding("property", name, UNKNOWN, f"{BUDGET_NOTE}: the z3 model agreed with the Monitor on "
                                                      f"{compared} sampled cycles ({i} of {traces} traces) when "
                                                      f"the run's budget was spent")
        frames: list[dict[str, Any]] = []
        prev: dict[str, Any] | None = None
        for _t in range(u.k):
            f: dict[str, Any] = {}
            for sig in u.plan.signals:
                if prev is not None and rng.random() < 0.5:
                    f[sig.name] = prev[sig.name]
                elif sig.kind == "bool":
                    f[sig.name] = rng.random() < 0.5
                else:
                    lo, hi = max(sig.lo, -1e6), min(sig.hi, 1e6)
                    f[sig.name] = rng.choice([lo, hi, (lo + hi) / 2, rng.uniform(lo, hi), rng.uniform(lo, hi)])
            f["risk"] = (prev["risk"] if prev is not None and rng.random() < 0.5
                         else rng.choice(r_pick + [rng.uniform(rlo, rhi)] * 3))
            if u.plan.risk_plan.max_age_s is not None:
                f["risk_age_s"] = 0.0
            frames.append(f)
            prev = f
        monitor = Monitor(u.spec)
        decisions = []
        for f in frames:
            d = monitor.step(f)
            if d.faults:  # an evaluation error: the unrolled model has no faults, stop here
                break
            decisions.append(d)
        s.push()
        for t, f in enumerate(frames):
            for sig in u.plan.signals:
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
            got = [ob.id for ob, v in zip(u.plan.obligations, viol)
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
                   f"({traces} traces of {u.k} cycles)")


def risk_bounds_check(u: Unrolling) -> Finding:
    name = "risk.bounds"
    r = u.plan.risk_plan
    if r.classes != 2:
        lo, hi = u.risk_range()
        return Finding("property", name, SKIPPED,
                       f"not re-proved by z3 for K={r.classes} classes; R_e in [{_fmt(lo)}, {_fmt(hi)}] "
                       f"by the exact candidate search of risk_range")
    lo, hi = risk_bounds(r.alpha, r.beta, r.gamma, r.variance)
    q = z3.Real("q")
    R = two_class_risk(q, real(r.alpha), real(r.beta), real(r.gamma), r.variance, where=z3.If,
                       half=z3.RealVal("1/2"))
    eps = 1e-9 * max(1.0, abs(lo), abs(hi))
    st, model, why = u.budget.solve(q >= 0, q <= 1, z3.Or(R < real(lo - eps), R > real(hi + eps)))
    if st == "unsat":
        return Finding("property", name, PROVED,
                       f"R_e in [{_fmt(lo)}, {_fmt(hi)}] for every p_unsafe in [0, 1] ({r.variance} variance)")
    if st == "sat":
        qv = z3_value(model, q)
        rv = risk_from_p_unsafe(qv, r.alpha, r.beta, r.gamma, r.variance)
        return Finding("property", name, REFUTED,
                       f"p_unsafe={qv!r} gives R_e={rv!r} outside [{_fmt(lo)}, {_fmt(hi)}]")
    return Finding("property", name, UNKNOWN, f"z3: {why}")


def _decision_check(u: Unrolling, name: str, bad_at, expect_for, broken, proved_msg: str,
                    assume_defined: bool = True, only: int | None = None) -> Finding:
    """Search for a cycle ``t`` where ``bad_at(dt, t)`` holds; refute with a replayed trace.

    ``only=i``: first try to prove it with just obligation ``i`` encoded (the others'
    verdicts free, their definedness not assumed): an over-approximation, so "no such
    cycle" there is a proof. Otherwise, or if that finds one, the whole trace decides.
    """
    if only is not None:
        enc = u.enc
        dt_i = u.only_trace(only)
        ob = u.plan.obligations[only]
        terms = [z3.And(z3.And([enc.obligation_defined(ob, j) for j in range(t + 1)]), b)
                 if assume_defined else b for t in range(u.k) if (b := bad_at(dt_i, t)) is not None]
        if not terms:
            return Finding("property", name, PROVED, proved_msg + u.bound_note())
        st, _, _ = u.budget.solve(*dt_i.init, z3.Or(terms), enc=enc)
        if st == "unsat":
            return Finding("property", name, PROVED, proved_msg + u.bound_note())
    enc, dt = u.enc, u.dt
    terms = {}
    for t in range(u.k):
        bad = bad_at(dt, t)
        if bad is not None:
            terms[t] = z3.And(enc.all_defined(t), bad) if assume_defined else bad
    if not terms:
        return Finding("property", name, PROVED, proved_msg + u.bound_note())
    st, model, why = u.solve_dt(z3.Or(list(terms.values())))
    if st == "unknown":
        return Finding("property", name, UNKNOWN, f"z3: {why}")
    if st == "unsat":
        return Finding("property", name, PROVED, proved_msg + u.bound_note())
    t = next(t for t, term in terms.items() if z3.is_true(model.eval(term, model_completion=True)))
    for pref in u.state_prefs(dt):  # most replayable start state first
        st2, m2, _ = u.solve_dt(terms[t], *pref)
        if st2 == "sat":
            model = m2
            break
    cex = u.counterexample(name, model, enc, t, expect_for(t), lambda d: broken(d, t), dt)
    return Finding("property", name, REFUTED, f"fails at cycle {t}", counterexample=cex)


def risk_override(u: Unrolling) -> Finding:
    sev = u.risk_sev

    def bad(dt, t):
        return z3.And(dt.risk_fires[t], z3.Not(z3.And(dt.override[t], dt.response[t] >= sev)))
    return _decision_check(
        u, "risk.override", bad, lambda t: {"final_override": True, "fired": ["risk"]},
        lambda d, t: not (d.override and d.response.severity >= sev),
        f"R_e >= tau={_fmt(u.tau)} => override ({_SEV_NAME[sev]} or more) in the same cycle")


def fault_override(u: Unrolling) -> Finding:
    """On a fault cycle the decision is override with at least ``on_fault`` (and the risk response if R_e ≥ τ)."""
    L = z3.Int("latched")
    r = z3.Real("risk")
    has_r = z3.Bool("risk_known")
    tau = real(u.tau)
    sev = z3.If(L >= u.fault_sev, L, z3.IntVal(u.fault_sev))
    rs = z3.IntVal(u.risk_sev)
    sev = z3.If(z3.And(has_r, r >= tau, rs > sev), rs, sev)
    ok = z3.And(sev >= u.fault_sev, z3.Implies(z3.And(has_r, r >= tau), sev >= u.risk_sev), sev > 0)
    st, _, why = u.budget.solve(L >= 0, L <= 4, z3.Not(ok))
    if st == "unsat":
        # and the monitor itself, on each kind of bad input
        bad = _fault_replay(u)
        if bad:
            return Finding("property", "fault.override", REFUTED, bad)
        return Finding("property", "fault.override", PROVED,
                       f"missing/NaN/out-of-range/wrong-type/stale input => override "
                       f"({u.spec.on_fault} or more), replayed for each input kind")
    return Finding("property", "fault.override", UNKNOWN if st == "unknown" else REFUTED, why or "")


def _fault_replay(u: Unrolling) -> str:
    """Drive the real monitor with each kind of bad input for each signal; '' if all fail closed."""
    good: dict[str, Any] = {}
    for s in u.plan.signals:
        good[s.name] = False if s.kind == "bool" else (s.lo if math.isfinite(s.lo) and abs(s.lo) < 1e300
                                                      else 0.0)
    good["risk"] = 0.0 if 0.0 < u.tau else None
    if good["risk"] is None:
        good.pop("risk")
        good["p_unsafe"] = 0.0
    if u.plan.risk_plan.max_age_s is not None:
        good["risk_age_s"] = 0.0
    cases: list[tuple[str, dict]] = []
    for s in u.plan.signals:
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
    if u.plan.risk_plan.max_age_s is not None:
        cases.append(("risk stale", {**good, "risk_age_s": u.plan.risk_plan.max_age_s * 2}))
        cases.append(("risk age missing", {k: v for k, v in good.items() if k != "risk_age_s"}))
    for label, frame in cases:
        m = Monitor(u.spec)
        d = m.step(frame)
        if not (d.override and d.faults and d.response.severity >= u.fault_sev):
            return f"{label}: the monitor did not fail closed ({d!r})"
    return ""


def defined(u: Unrolling, ob) -> Finding:
    name = f"{ob.id}.defined"
    k = min(u.need[ob.id], u.max_unroll)
    enc = u.trace(k, prefix=f"{ob.id}.")
    for t in range(k):
        st, model, why = u.budget.solve(z3.Not(enc.obligation_defined(ob, t)),
                                        *[enc.obligation_defined(ob, j) for j in range(t)], enc=enc)
        if st == "sat":
            cex = u.counterexample(
                name, model, enc, t, {"fault": False},
                lambda d: any(f.kind == "internal" for f in d.faults))
            return Finding("property", name, REFUTED,
                           f"evaluation fails (division by zero, sqrt of a negative or a negative "
                           f"separation_distance() argument) on in-range "
                           f"input at cycle {t}: the monitor stops the arm with a fault", counterexample=cex)
        if st == "unknown":
            return Finding("property", name, UNKNOWN, f"z3: {why}")
    return _defined_in_floats(u, ob, k)


def _defined_in_floats(u: Unrolling, ob, k: int) -> Finding:
    """The real arithmetic found no raise: check again in the monitor's doubles (IEEE-754), where
    ``a * b`` of in-range non-zero inputs can be 0 and ``x / (a * b)`` raise."""
    name = f"{ob.id}.defined"
    what = "no division by zero, sqrt of a negative or negative separation_distance() argument for any in-range input"
    from ..language._expr import Binary, Call
    if not any((isinstance(n, Binary) and n.op == "/") or (isinstance(n, Call) and n.func in (
            "sqrt", "separation_distance")) for root in (ob.when, ob.require) if root is not None
            for n in walk(root)):
        return Finding("property", name, PROVED, what + " (nothing that can raise: no /, sqrt or "
                       "separation_distance)")
    from ._floats import defined_in_doubles
    if defined_in_doubles(u.plan, ob):
        return Finding("property", name, PROVED, what + " (in doubles too: every divisor's real value stays "
                       "farther from 0 than rounding can move it, every sqrt/separation_distance argument "
                       "is >= 0 without subtraction, nothing overflows)")
    fenc = u.float_trace(k, prefix=f"{ob.id}.f.")
    for t in range(k):
        st, model, why = u.budget.solve_fp(z3.Not(fenc.obligation_defined(ob, t)),
                                           *[fenc.obligation_defined(ob, j) for j in range(t)], enc=fenc)
        if st == "sat":
            cex = u.counterexample(name, model, fenc, t, {"fault": False},
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


def float_hazard(u: Unrolling, ob) -> str:
    """Where the monitor's doubles can leave the reals on ``ob`` ('' if nowhere): an overflow to
    ±inf, or an underflow that a comparison or product can see (:func:`._floats.float_hazards`),
    for inputs in their declared ranges."""
    from ._floats import float_hazards
    hz = float_hazards(u.plan, ob)
    ranges = ", ".join(f"{s.name} in [{s.lo:g}, {s.hi:g}]" for s in u.plan.signals if s.kind == "number")
    return f"floats can differ from the reals: {'; '.join(hz)} (inputs {ranges})" if hz else ""


def response(u: Unrolling, ob) -> Finding:
    n = ob.within_cycles or 0
    sev = ob.response.severity
    name = f"{ob.id}.response"
    if n >= u.k:
        return Finding("property", name, UNKNOWN,
                       f"within_cycles={n} needs more than --max-unroll {u.max_unroll} cycles")
    i = u.plan.obligations.index(ob)

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
            hazard = float_hazard(u, ob)
            if hazard:
                f.status, f.message = PROVED_REAL, f"{f.message}; {hazard}"
                cex = _float_counterexample(u, ob, name, sev)
                if cex is not None:
                    f.counterexample = cex
                    f.message += f"; in doubles: {cex.note}"
        return f
    return in_floats(_decision_check(
        u, name, bad, lambda t: {"final_override": True, "fired": [ob.id]},
        lambda d, t: not (d.override and d.response.severity >= sev and ob.id in d.violations),
        f"{what}{bound} => violation and override ({ob.response.value} or more)"
        + (f" by {u.plan.cycles(n)} after the trigger" if n else " in the same cycle"), only=i))


def _float_counterexample(u: Unrolling, ob, name: str, sev: int, tries: int = 400):
    """A one-cycle input (seeded search over the declared ranges) on which the real arithmetic of
    the proof says ``ob`` is violated and the :class:`Monitor`, computing in doubles, does not
    override for it; ``None`` if none is found (or ``ob`` is temporal, or not exactly evaluable)."""
    import random
    from fractions import Fraction

    from ..language._expr import TEMPORAL, Call
    from ._encode import risk_input_range
    from ._floats import exact_value
    from ._report import Counterexample
    roots = [r for r in (ob.when, ob.require) if r is not None]
    if any(isinstance(n, Call) and n.func in TEMPORAL for r in roots for n in walk(r)):
        return None
    rng = random.Random(f"ethimon-verify-floats:{u.spec.name}:{ob.id}")
    rlo, _ = risk_input_range(u.plan)
    for _ in range(tries):
        frame: dict[str, Any] = {}
        for sig in u.plan.signals:
            if sig.kind == "bool":
                frame[sig.name] = rng.random() < 0.5
            else:
                lo, hi = max(sig.lo, -1e300), min(sig.hi, 1e300)
                frame[sig.name] = rng.choice([lo, hi, (lo + hi) / 2] + [rng.uniform(lo, hi)] * 5)
        env = {k: (v if isinstance(v, bool) else Fraction(v)) for k, v in frame.items()}
        when = True if ob.when is None else exact_value(u.plan, ob.when, env)
        req = exact_value(u.plan, ob.require, env)
        if when is not True or req is not False:
            continue  # the reals do not say it must fire here (or cannot say exactly)
        frame["risk"] = rlo
        if u.plan.risk_plan.max_age_s is not None:
            frame["risk_age_s"] = 0.0
        d = Monitor(u.spec).step(frame)
        if d.faults or (d.override and d.response.severity >= sev and ob.id in d.violations):
            continue
        shown = ", ".join(f"{k} = {v!r}" for k, v in frame.items() if k in {s.name for s in u.plan.signals})
        return Counterexample(name, [frame], 0, {"final_override": True, "fired": [ob.id]}, [d.as_dict()],
                              True, f"{shown}: the reals violate {ob.id}, the Monitor (doubles) gives "
                                    f"{'no override' if not d.override else d.response.value} without it "
                                    f"(replayed)")
    return None


def resume_explained(u: Unrolling) -> Finding:
    def bad(dt, t):
        return z3.And(z3.Not(dt.override[t]), z3.Or([dt.risk_fires[t], *dt.violated[t]]))
    return _decision_check(
        u, "resume.explained", bad, lambda t: {"final_override": True},
        lambda d, t: not d.override,
        "no override => every obligation holds and R_e < tau")


def release_rule(u: Unrolling) -> Finding:
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
    rules = rules_of(u.plan)
    auto = [r for r in rules if not r.manual]
    manual = [r.name for r in rules if r.manual]
    conds = {"risk": f"R_e < tau - delta = {_fmt(u.below)}", "fault": "no fault"}
    parts = [f"{r.name} after {u.plan.cycles(r.hold)} of {conds.get(r.name, 'holding')}"
             for r in auto]
    msg = "a latched override resumes by itself only once each rule latched is released: " + (
        "; ".join(parts) if parts else "no rule releases automatically")
    if manual:
        msg += f"; manual (Monitor.acknowledge() only): {', '.join(manual)}"
    return _decision_check(
        u, "release.rule", bad, lambda t: {"final_override": True},
        lambda d, t: not d.override, msg)
