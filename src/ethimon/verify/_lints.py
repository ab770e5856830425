"""The lints of ``ethimon verify`` (imports z3): what an engineer would question in a spec that
the monitor runs as written (τ outside the reachable R_e, R_e not monotone, a latch that never
releases, release policies, vacuous or contradictory obligations, unbounded signals, the fault
latch shorter than a window, a safe pose outside the Panda's rated range, a stop 0/1 the brakes
cannot hold with the rated payload, a retreat uncapped near people, the confirm band). Each is a
function of the spec's :class:`~._unrolling.Unrolling`; :func:`lint_checks` lists them."""

from __future__ import annotations

import itertools
import time
from typing import Any

import z3

from ..compiler._risk_formula import risk_from_p_unsafe, two_class_risk
from ..runtime import Monitor
from ..language._expr import Name, walk
from .. import _robot
from ..language._robots import robot_of
from ._policy import manual_rules, release_policy_warnings
from ._checks import Check, _fmt
from ._encode import Unrolled, real, z3_value
from ._report import OK, SKIPPED, UNKNOWN, WARNING, Finding
from ._tiers import has_tiers, lint_confirm_band
from ._unrolling import Unrolling

__all__ = ["lint_checks", "window_search"]


def lint_checks(u: Unrolling) -> list[Check]:
    """Every lint of ``u``'s spec, in report order (each check gives one finding or more)."""
    return [Check("lint", "lint.tau_range", tau_range), Check("lint", "lint.risk_monotone", risk_monotone),
            Check("lint", "lint.release", release),
            Check("lint", "lint.release_policy", release_policy, timed=False),
            Check("lint", "lint.vacuous", vacuous, timed=False),
            Check("lint", "lint.contradiction", contradictions, timed=False),
            Check("lint", "lint.unbounded", unbounded, timed=False),
            Check("lint", "lint.fault_gap", fault_gap, timed=False),
            Check("lint", "lint.safe_pose_range", safe_pose_range, timed=False),
            Check("lint", "lint.brakes", brakes),
            Check("lint", "lint.retreat_uncapped", retreat_uncapped, timed=False)] + (
                [Check("lint", "lint.confirm_band", lint_confirm_band)] if has_tiers(u.full_spec) else [])


def tau_range(u: Unrolling) -> Finding:
    lo, hi = u.risk_range()
    tau = u.tau
    if tau > hi:
        return Finding("lint", "lint.tau_range", WARNING,
                       f"tau={_fmt(tau)} is above the largest reachable R_e={_fmt(hi)}: "
                       f"the risk rule can never fire")
    if tau <= lo:
        return Finding("lint", "lint.tau_range", WARNING,
                       f"tau={_fmt(tau)} is at or below the smallest reachable R_e={_fmt(lo)}: "
                       f"the risk rule fires every cycle")
    return Finding("lint", "lint.tau_range", OK, f"tau={_fmt(tau)} inside reachable R_e [{_fmt(lo)}, {_fmt(hi)}]")


def risk_monotone(u: Unrolling) -> Finding:
    """R_e should not fall when the classifier grows more sure the task is unsafe."""
    name = "lint.risk_monotone"
    r = u.plan.risk_plan
    if r.classes != 2:
        return Finding("lint", name, SKIPPED, f"checked for two classes only (K={r.classes})")
    q1, q2 = z3.Real("q1"), z3.Real("q2")

    def R(q):
        return two_class_risk(q, real(r.alpha), real(r.beta), real(r.gamma), r.variance, where=z3.If,
                              half=z3.RealVal("1/2"))
    st, model, why = u.budget.solve(q1 >= 0, q2 <= 1, q1 < q2, R(q1) > R(q2))
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


def window_search(u: Unrolling, goal, ids, s: int) -> tuple[str, Any]:
    """Is there a run with ``s`` consecutive fault-free cycles at each of which ``goal(enc, t)`` holds?

    ``ids`` are the obligations ``goal`` talks about; ``P`` (:meth:`Unrolling.window_cycles`) cycles
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
    P = u.window_cycles(ids)
    if P + s > u.max_unroll:
        return "unknown", (f"needs {P + s} cycles of unrolling ({s} in the window, {P} of history), more than "
                           f"--max-unroll {u.max_unroll}")
    why_unknown = ""

    def attempt(p: int, free: bool = False):
        enc = u.trace(p + s, prefix=f"w{'f' if free else p}.", free_history=free)
        goals = [enc.all_defined(p + s - 1)] + [goal(enc, t) for t in range(p, p + s)]
        st, model, why = u.budget.solve(*goals, enc=enc)
        if st == "sat" and not free:  # prefer a run whose comparisons are clear of their boundaries
            st2, model2, _ = u.budget.solve(*goals, *enc.decisive(), enc=enc)
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


def _replay_release(u: Unrolling, frames: list[dict[str, Any]]) -> tuple[bool, int]:
    """Replay a cycle where the risk rule fires (R_e at its largest reachable value) and
    then ``frames`` in a fresh Monitor: is the risk rule's latch released at the end?"""
    first = dict(frames[0])
    first["risk"] = max(u.tau, u.risk_range()[0])
    seq = [first] + frames
    m = Monitor(u.spec)
    ds = [m.step(f) for f in seq]
    return ("risk" in ds[0].violations and "risk" not in m.latched_rules), len(seq) - 1


def release(u: Unrolling) -> Finding:
    """Can the risk rule's latch auto-release (``hold_cycles`` cycles in a row with R_e < τ − δ,
    and, so that the override can end, every obligation held)?

    Only a run replayed in the real Monitor makes it "reachable"; "never" is a proof over runs
    of any length (:func:`window_search`); anything else is ``unknown``.
    """
    rel = u.plan.risk_rule
    name = "lint.release"
    if rel.manual:
        return Finding("lint", name, WARNING, "risk.release.mode is manual: the risk rule's latch never "
                                              "releases by itself (only Monitor.acknowledge(), release() "
                                              "or reset())")
    lo, hi = u.risk_range()
    bound = f"R_e < tau - delta = {_fmt(u.below)}"
    if u.below_float < lo:
        return Finding("lint", name, WARNING,
                       f"release needs {bound}, but the smallest reachable R_e is {_fmt(lo)}: a latched "
                       f"override never auto-releases")
    hold = rel.hold
    ids = [ob.id for ob in u.plan.obligations]
    below = real(u.below_float)  # R_e arrives as a float: below the exact bound <=> at most this float

    def goal(enc: Unrolled, t: int):
        return z3.And([enc.R[t] <= below, enc.R[t] >= real(lo), enc.R[t] <= real(hi)]
                      + [z3.Not(enc.violated(ob, t)) for ob in u.plan.obligations])
    never = (f"no run has {hold} consecutive cycles with {bound} and every obligation held "
             f"(checked over runs of any length): a latched override never auto-releases")
    P = u.window_cycles(ids)
    if P + hold <= u.max_unroll:
        st, info = window_search(u, goal, ids, hold)
        if st == "unsat":
            return Finding("lint", name, WARNING, never)
        if st == "unknown":
            return Finding("lint", name, UNKNOWN, f"release not decided: {info}")
        enc, model, p = info
        frames = u.frames(model, enc, p + hold - 1)
    else:
        # too long to unroll: a shorter window that no run has is still a proof ...
        short = u.max_unroll - P
        if short >= 1:
            st, _ = window_search(u, goal, ids, short)
            if st == "unsat":
                return Finding("lint", name, WARNING,
                               never.replace(f"{hold} consecutive", f"even {short} consecutive"))
        # ... and a run that repeats one input is a witness once its windows are full
        enc = u.trace(P + 1, prefix="wc.")
        same = [enc.sig[t][sg] == enc.sig[0][sg] for t in range(1, P + 1) for sg in enc.sig[0]]
        same += [enc.R[t] == enc.R[0] for t in range(1, P + 1)]
        st, model, why = u.budget.solve(*same, enc.all_defined(P), goal(enc, P), *enc.decisive(), enc=enc)
        if st == "unsat":
            st, model, why = u.budget.solve(*same, enc.all_defined(P), goal(enc, P), enc=enc)
        if st != "sat":
            return Finding("lint", name, UNKNOWN,
                           f"release not decided: hold_cycles={hold} needs {P + hold} cycles of unrolling "
                           f"(> --max-unroll {u.max_unroll}) and no constant input releases"
                           + (f" (z3: {why})" if why else ""))
        frames = u.frames(model, enc, 0) * (P + hold)
    ok, at = _replay_release(u, frames)
    if not ok:
        return Finding("lint", name, UNKNOWN, "release not decided: the solver's run did not release when "
                                              "replayed in the Monitor")
    return Finding("lint", name, OK, f"release reachable: {hold} cycles with {bound} and every obligation "
                                     f"held (a run replayed in the Monitor releases at cycle {at}: the risk "
                                     f"rule's latch)")


def release_policy(u: Unrolling) -> list[Finding]:
    """Release policies an engineer would question (:func:`release_policy_warnings`: an
    automatic release after a stop of category 0 or 1, an automatic fault release); else,
    as information, which rules wait for an operator (the integration must offer
    ``Monitor.acknowledge()``)."""
    name = "lint.release_policy"
    out = [Finding("lint", name, WARNING, w) for w in release_policy_warnings(u.plan)]
    manual = manual_rules(u.plan)
    if not out:
        out.append(Finding("lint", name, OK, (
            f"manual release for {', '.join(manual)}: the integration must offer an operator "
            f"acknowledgement (Monitor.acknowledge(); refused while a rule still fails)") if manual else
            "every rule releases automatically; none is a stop of category 0 or 1"))
    return out


def vacuous(u: Unrolling) -> list[Finding]:
    """Each obligation can be violated by some fault-free run from a reset (one incremental solver)."""
    t0 = time.perf_counter()
    out: list[Finding] = []
    obs = u.plan.obligations
    if obs:
        k = min(max(u.need[ob.id] for ob in obs), u.max_unroll)
        enc = u.trace(k, prefix="v.")
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
            ms = u.budget.check_ms()
            if ms <= 0:
                out.append(u.budget.unreached("lint", "lint.vacuous",
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


def _components(u: Unrolling) -> dict[str, int]:
    """Obligations that share no signal (nor R_e) through any chain get different numbers."""
    parent: dict[str, str] = {}

    def find(x: str) -> str:
        while parent.setdefault(x, x) != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x
    for ob in u.plan.obligations:
        names = [f"ob:{ob.id}"] + [f"sig:{n.id}" for root in (ob.when, ob.require) if root is not None
                                   for n in walk(root) if isinstance(n, Name)]
        for n in names[1:]:
            parent[find(n)] = find(names[0])
    return {ob.id: hash(find(f"ob:{ob.id}")) for ob in u.plan.obligations}


def contradictions(u: Unrolling) -> list[Finding]:
    """Obligations that cannot hold together (for a few cycles in a row: response windows take time to close)."""
    t0 = time.perf_counter()
    obs = u.plan.obligations
    out: list[Finding] = []

    def holds(subset):
        return lambda enc, t: z3.And([z3.Not(enc.violated(ob, t)) for ob in subset])

    def cycles(subset) -> int:
        return u.window_cycles([ob.id for ob in subset]) + 1

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
    st_all, why_all = window_search(u, holds(obs), [ob.id for ob in obs], n_all)
    if st_all == "sat":
        return done([Finding("lint", "lint.contradiction", OK,
                             f"the obligations can all hold together{in_a_row(n_all)}")])
    # find the culprits: each obligation alone, then pairs that share a signal
    alone_ok, undecided = [], 0
    for i, ob in enumerate(obs):
        if u.budget.out_of_budget():
            out.append(u.budget.unreached("lint", "lint.unsatisfiable", f"{len(obs) - i} obligations not checked"))
            return done(out)
        n = cycles([ob])
        st, _ = window_search(u, holds([ob]), [ob.id], n)
        if st == "unsat":
            out.append(Finding("lint", f"lint.unsatisfiable.{ob.id}", WARNING,
                               f"obligation {ob.id!r} cannot hold{in_a_row(n) or ' for any input'} inside the "
                               f"ranges ({overrides(n)})"))
        elif st == "sat":
            alone_ok.append(ob)
        else:
            undecided += 1
    comp = _components(u)
    pairs = [(a, b) for a, b in itertools.combinations(alone_ok, 2) if comp[a.id] == comp[b.id]]
    for i, (a, b) in enumerate(pairs):
        if u.budget.out_of_budget():
            out.append(u.budget.unreached("lint", "lint.contradiction",
                                          f"{len(pairs) - i} of {len(pairs)} pairs of obligations not checked"))
            return done(out)
        n = cycles([a, b])
        st, _ = window_search(u, holds([a, b]), [a.id, b.id], n)
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


def unbounded(u: Unrolling) -> list[Finding]:
    out = [Finding("lint", f"lint.unbounded.{s.name}", WARNING,
                   f"signal {s.name!r} has no range: only NaN/infinity fail closed, any other value is trusted")
           for s in u.plan.signals if s.kind == "number" and s.name in u.spec.signals
           and u.spec.signals[s.name].range is None]
    return out or [Finding("lint", "lint.unbounded", OK, "every numeric signal has a declared range")]


def safe_pose_range(u: Unrolling) -> list[Finding]:
    """The safe pose inside the rated joint range of the spec's robot (``robot:``, the Franka
    Panda by default; ``ethimon._robot`` reads its description): outside it the real arm aborts
    the motion and the simulation refuses the spec; ``ethimon lint`` reports it as an error. One
    warning naming each joint, its value and the rated limits, at the spec's file:line:column
    when known. A spec that names its robot has a safe pose of its joint count (a load error
    otherwise); one that names none and gives another count is a Panda spec with a warning."""
    name = "lint.safe_pose_range"
    robot = robot_of(u.spec)
    joints = tuple(u.spec.safe_pose.joints_rad)
    if len(joints) != robot.n_joints:
        return [Finding("lint", name, WARNING, f"safe_pose.joints_rad has {len(joints)} values; the "
                        f"{robot.title} (robot: {u.spec.robot}, the default) has {robot.n_joints} joints: "
                        "name the spec's robot (robot: ur5e, or the path of a robot YAML file; docs/robots.md)")]
    problem = robot.safe_pose_problem(joints)
    if problem is None:
        return [Finding("lint", name, OK, f"the safe pose lies inside the {robot.title}'s rated joint range")]
    where = ""
    src = getattr(u.spec, "source", None)
    if src is not None:  # the first joint outside its range, in the spec file
        err = src.error(problem, ("safe_pose", "joints_rad", robot.out_of_range(joints)[0][0] - 1))
        if err.line is not None:
            where = f"{err.location}: "
    return [Finding("lint", name, WARNING, f"{where}{problem} (an error for 'ethimon lint' and "
                    f"'check --sim'; {robot.source('position_min_rad')})")]


def retreat_uncapped(u: Unrolling) -> list[Finding]:
    """A spec that can send the arm to its safe pose but states no near-human speed rule
    (``when: human_distance < D``, ``require: ee_speed <= V``) leaves the retreat uncapped
    near people on a real cell (issue 32 item 5: a governor-only cell's fold passed a helper
    with a link at 0.41 m/s). The simulation caps it at its own 0.25 m/s within 1.5 m
    (``ethimon.sim._rules.RETREAT_NEAR_HUMAN_DEFAULT``); the pattern is the one the sim reads."""
    import re
    name = "lint.retreat_uncapped"
    spec = u.spec
    num = r"([A-Za-z_][A-Za-z0-9_]*|[0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)"
    when = (re.compile(rf"^\s*human_distance\s*<=?\s*{num}\s*$"),
            re.compile(rf"^\s*{num}\s*>=?\s*human_distance\s*$"))
    req = re.compile(rf"^\s*ee_speed\s*<=?\s*{num}\s*$")
    obs = list(getattr(spec, "obligations", ()) or ())
    capped = [ob.id for ob in obs if any(w.match(getattr(ob, "when", None) or "") for w in when)
              and req.match(getattr(ob, "require", "") or "")]
    if capped:
        return [Finding("lint", name, OK, f"retreats near people are capped by {capped[0]!r}")]
    resp = [str(getattr(getattr(spec, "risk", None), "response", "") or "")]
    resp += [str(getattr(ob, "response", "") or "") for ob in obs]
    resp.append(str(getattr(spec, "on_fault", "") or ""))
    if not any(r.endswith("safe_pose") for r in resp):
        return [Finding("lint", name, OK, "no response sends the arm to its safe pose")]
    return [Finding("lint", name, WARNING,
                    "a response sends the arm to its safe pose but no rule caps its speed near people "
                    "(when: human_distance < D, require: ee_speed <= V): on a real cell the retreat "
                    "moves at the safe pose's joint speed past anyone beside it; the simulation caps "
                    "it at its own 0.25 m/s within 1.5 m. Add such a rule (cobot_cell's slow_near_human)")]


def brakes(u: Unrolling) -> Finding:
    """A stop 0/1 cuts motor power and leaves the arm to its brakes: over a grid of poses (the
    spec's safe pose and joints 2-6 across their rated ranges, where gravity loads the joints),
    the gravity load of arm + the rated payload (3 kg at the grasp point) against each joint's
    brake holding torque (``ethimon._robot.BRAKE_TABLE``, estimates, stated per number), with
    the project's safety factor ``ethimon._robot.BRAKE_SAFETY_FACTOR`` (1.5: a brake must hold
    1.5 x the load; the simulator escalates a stop 0/1 with less margin to a powered stop 2).
    Names the rules that cut power, the poses where a brake holds the load with less than the
    factor and the largest payload the brakes hold with the factor at every pose."""
    name = "lint.brakes"
    plan = u.plan
    cuts = [ob.id for ob in plan.obligations if ob.response.value in ("stop_0", "stop_1")]
    if plan.risk_rule.response.value in ("stop_0", "stop_1"):
        cuts.append("risk")
    if plan.fault_rule.response.value in ("stop_0", "stop_1"):
        cuts.append("on_fault")
    if not cuts:
        return Finding("lint", name, OK, "no rule cuts motor power (stop 0/1): the brakes never hold the arm alone")
    robot = robot_of(u.spec)
    if robot.name != "panda" or robot.path != _robot.PANDA.path:  # the gravity model is the Panda's
        return Finding("lint", name, SKIPPED,
                       f"{', '.join(cuts)} cut motor power (stop 0/1), but ethimon has a gravity model of the "
                       f"Franka Panda only: whether the {robot.title}'s brakes hold arm + its rated "
                       f"{robot.payload_kg:g} kg is not checked (holding torques: {robot.source('brake_holding_n_m')})")
    factor = _robot.BRAKE_SAFETY_FACTOR
    # a brake "holds" a load when its holding torque is at least factor x the load
    holding = tuple(h / factor for h in _robot.BRAKE_HOLDING_N_M)
    kg, off = _robot.RATED_PAYLOAD_KG, _robot.PAYLOAD_OFFSET_M
    worst: tuple[float, tuple[float, ...], int, float] | None = None  # (payload held, pose, joint, load)
    falls = []
    n = 0
    for q in _brake_grid(tuple(u.spec.safe_pose.joints_rad)):
        n += 1
        a, per_kg = _robot.gravity_torque_parts(q, off)  # the load is linear in the payload's mass
        for j in range(7):
            slope = per_kg[j]
            if abs(a[j]) > holding[j]:
                m_max = 0.0
            elif abs(slope) < 1e-12:
                continue
            else:  # the largest m >= 0 with |a + slope m| <= holding
                m_max = max(0.0, (holding[j] - a[j] * (1 if slope > 0 else -1)) / abs(slope))
            if worst is None or m_max < worst[0]:
                worst = (m_max, q, j + 1, abs(a[j] + slope * kg))
            if m_max < kg:
                falls.append((q, j + 1, abs(a[j] + slope * kg), _robot.BRAKE_HOLDING_N_M[j]))
    assert worst is not None
    pose = ", ".join(f"{v:.2f}" for v in worst[1])
    who = ", ".join(cuts)
    if falls:
        q, j, load, h = max(falls, key=lambda f: f[2] / f[3])
        where = ", ".join(f"{v:.2f}" for v in q)
        return Finding("lint", name, WARNING,
                       f"{who} cut motor power (stop 0/1), and at {len(falls)} of {n} poses the brakes "
                       f"cannot hold arm + the rated {kg:g} kg with the safety factor {factor:g} "
                       f"(ethimon._robot.BRAKE_SAFETY_FACTOR, the project's choice): the arm would sink "
                       f"or fall (worst: joint {j} needs {load:.1f} N·m at [{where}] rad, its brake holds "
                       f"{h:g} N·m, {h / max(load, 1e-9):.2f} x; from {worst[0]:.2f} kg at [{pose}] a "
                       f"brake is under the factor). The simulation refuses such a power-off and holds "
                       f"powered (a stop 2); a real cell needs stronger brakes, a lighter payload or "
                       f"stop 2 for these rules")
    return Finding("lint", name, OK,
                   f"the brakes hold arm + the rated {kg:g} kg with the safety factor {factor:g} at all "
                   f"{n} grid poses after a stop 0/1 ({who}); the first falls under the factor from "
                   f"{worst[0]:.2f} kg (joint {worst[2]} at [{pose}] rad; holding torques are estimates: "
                   f"ethimon._robot.BRAKE_TABLE)")


def fault_gap(u: Unrolling) -> list[Finding]:
    """The fault latch's hold must cover every obligation's window: a fault clears the
    history, so a shorter hold lets the arm resume (by itself, or on an acknowledgement
    that is accepted) before a windowed obligation can see its violation again."""
    mode, hold = u.plan.fault_rule.mode, u.plan.fault_rule.hold
    how = "resume by itself" if mode == "auto" else "be acknowledged and resume"
    out = []
    for ob in u.plan.obligations:
        need = u.need[ob.id]
        if need > 1 and hold < need:
            out.append(Finding(
                "lint", f"lint.fault_gap.{ob.id}", WARNING,
                f"after a fault clears the history, {ob.id!r} needs {need} cycles to fire again but the "
                f"fault latch's hold_cycles={hold}: the arm can {how} while it is still violated"))
    return out or [Finding("lint", "lint.fault_gap", OK,
                           "the fault latch's hold_cycles covers every obligation's window after a fault")]


def _brake_grid(safe: tuple[float, ...]) -> list[tuple[float, ...]]:
    """The safe pose and joints 2-6 over their rated ranges (7, 3, 7, 3, 5 values; joints 1 and 7
    turn about axes that do not change the gravity load of a payload on the flange axis)."""
    def span(j: int, k: int) -> list[float]:
        lo, hi = _robot.RATED_Q_MIN[j], _robot.RATED_Q_MAX[j]
        return [lo + (hi - lo) * i / (k - 1) for i in range(k)]
    grid = [safe] if len(safe) == 7 else []
    for q2, q3, q4, q5, q6 in itertools.product(span(1, 7), span(2, 3), span(3, 7), span(4, 3), span(5, 5)):
        grid.append((0.0, q2, q3, q4, q5, q6, 0.0))
    return grid
