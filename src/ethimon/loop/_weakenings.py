"""Whether a reloaded spec weakens monitoring, judged field by field.

Every rule's release (mode, hold), response, τ and the exact release bound τ − δ are read from the
two compiled plans (``Plan.rules()``, ``Plan.threshold``,
``Plan.release_exact``), never resolved again from the specs; so are the rest of the risk rule
(``Plan.risk_plan``), the tiers and the judges (``Plan.tiers``), the estimator settings
(``Plan.estimator``) and the restart block (``Plan.restart``). Only ``risk.allow`` is compared as the
specs write it (see :func:`weakenings`).
"""

from __future__ import annotations

import dataclasses
from typing import Any

from ..compiler import JudgePlan, Plan, plan_of
from ..language import Response, Spec
from ..language._expr import Name, walk

__all__ = ["CANNOT_TELL", "weakenings", "unmapped_latches"]


def _sev(response: Any) -> int:
    return Response(response).severity


#: the reason attached to every change whose direction :func:`weakenings` cannot judge
CANNOT_TELL = "cannot tell whether this change weakens monitoring"


def _same_text(a: str | None, b: str | None) -> bool:
    """Equal condition texts up to whitespace (``x>=1`` and ``x >= 1`` still differ: not judged)."""
    if a is None or b is None:
        return a is b
    return " ".join(a.split()) == " ".join(b.split())


def _meaning(m: tuple | None) -> str:
    if m is None:
        return "nothing"
    if m[0] == "signal":
        return f"a {m[1]} signal"
    if m[0] == "constant":
        return f"the constant {m[1]!r}"
    return "R_e (" + ", ".join(f"{k}={v!r}" for k, v in zip(("alpha", "beta", "gamma", "variance", "classes",
                                                             "unsafe_index"), m[1])) + ")"


def _release_weaker(what: str, old: Any, new: Any) -> list[str]:
    """A rule's release made easier: ``old``/``new`` are its ``RuleRelease`` in each plan (mode, hold)."""
    if old.manual and not new.manual:
        return [f"{what}: release manual -> auto (its latch now releases by itself)"]
    if new.hold < old.hold:
        return [f"{what}: release hold_cycles lowered {old.hold} -> {new.hold}"]
    return []


def _rules(plan: Plan) -> dict[str, Any]:
    """Every latch of ``plan`` by name (``Plan.rules()``)."""
    return {r.name: r for r in plan.rules()}


def _risk_inputs(plan: Plan) -> tuple[float, float]:
    """The interval of ``risk`` inputs the monitor accepts for ``plan`` (as ``Monitor`` computes it)."""
    return plan.risk_plan.accepted


def _formula(plan: Plan) -> tuple:
    r = plan.risk_plan
    return (r.alpha, r.beta, r.gamma, r.variance, r.classes, r.unsafe_index % r.classes)


def _one_judge(plan: Plan) -> JudgePlan | None:
    """The spec's ``risk.judge`` (``None``: none, or a panel written as ``risk.judges``)."""
    t = plan.tiers
    return t.judges[0] if t.judges and not t.consensus else None


def _panel(plan: Plan) -> tuple[JudgePlan, ...] | None:
    """The spec's ``risk.judges`` (``None``: not written)."""
    return plan.tiers.judges if plan.tiers.consensus else None


def _meanings(spec: Spec) -> dict[str, dict[str, tuple]]:
    """Per obligation id, what each name its ``when``/``require`` read stands for in ``spec``:
    ``("signal", type)``, ``("constant", value)`` or ``("risk", formula)`` (names resolved, not text)."""
    plan = plan_of(spec)
    consts = {k: (c if isinstance(c, (int, float)) else c.value) for k, c in spec.constants.items()}
    out: dict[str, dict[str, tuple]] = {}
    for ob in plan.obligations:
        names: dict[str, tuple] = {}
        for root in (ob.when, ob.require):
            if root is None:
                continue
            for n in walk(root):
                if isinstance(n, Name) and n.id not in names:
                    if n.id in spec.signals:
                        names[n.id] = ("signal", spec.signals[n.id].type)
                    elif n.id in consts:
                        names[n.id] = ("constant", float(consts[n.id]))
                    else:  # the built-in R_e
                        names[n.id] = ("risk", _formula(plan))
        out[ob.id] = names
    return out


def _tier_changes(po: Plan, pn: Plan, weak: list[str], unjudged: list[str]) -> None:
    """The tiers, old -> new (appended to ``weak`` / ``unjudged``): risk.confirm_threshold, risk.judge,
    risk.judges and risk.judge_may_hold_above_tau."""
    co, cn = po.tiers.confirm_threshold, pn.tiers.confirm_threshold
    if co is not None and (cn is None or cn > co):
        weak.append(f"risk.confirm_threshold {co!r} -> {'none' if cn is None else repr(cn)} (fewer texts held "
                    f"for a confirmation)")
    jo, jn = _one_judge(po), _one_judge(pn)
    if jo is None and jn is not None and cn is not None:
        weak.append("risk.judge added (its safe verdict executes texts in the confirm band)")
    elif jo is not None and jn is None:
        weak.append("risk.judge removed (no unsafe verdict can stop a text below tau_confirm)")
    elif jo is not None and jn is not None and jn != jo:
        if (jn.safe_below > jo.safe_below or jn.unsafe_from > jo.unsafe_from) or (
                dataclasses.replace(jn, safe_below=jo.safe_below, unsafe_from=jo.unsafe_from) != jo):
            unjudged.append("risk.judge settings changed")
    if _panel(po) != _panel(pn):  # risk.judges (consensus): a changed panel cannot be told field by field
        unjudged.append("risk.judges changed")
    ho, hn = po.tiers.hold_ceiling, pn.tiers.hold_ceiling
    if hn is not None and (ho is None or hn > ho):
        weak.append("risk.judge_may_hold_above_tau added or its ceiling raised (a safe verdict holds an R_e >= tau "
                    "stop for a person)")


def _restart_changes(po: Plan, pn: Plan, weak: list[str], unjudged: list[str]) -> None:
    """The ``restart:`` block (issue 32 item 4): GovernedLoop gates restarts only with one."""
    old, new = po.restart, pn.restart
    if old is not None and new is None:
        weak.append("restart block removed (an accepted acknowledgement now releases at once: no start awaited)")
        return
    if old is None or new is None:
        return
    so, sn = old.standstill, new.standstill
    if so is not None and sn is None:
        weak.append(f"restart.standstill {so} removed (acknowledgements no longer wait for the robot's "
                    "report that the stop completed)")
    elif so != sn and so is not None:
        unjudged.append(f"restart.standstill {so} -> {sn}")
    if old.start != new.start:
        unjudged.append(f"restart.start {old.start} -> {new.start}")


def weakenings(old: Spec, new: Spec, *, loop_max_age_s: float | None = None) -> tuple[list[str], list[str]]:
    """How ``new`` weakens monitoring compared with ``old``, judged field by field.

    Weaker (each one line in the first list): an obligation removed; an
    obligation's response less severe, a ``when`` added where there was none,
    ``within_cycles`` added or raised; τ raised; a risk weight (α, β, γ) lowered
    or the variance changed from sample to population (R_e smaller); the unsafe
    class or the number of classes changed; ``risk.response`` or ``on_fault``
    less severe; release mode manual → auto (the risk rule's, an obligation's
    or the fault latch's, defaults filled in) or a rule's hold lowered; the release bound τ − δ raised
    (hysteresis shrunk relative to τ) or ``hold_cycles`` lowered; the effective estimate age limit
    removed or raised (``risk.max_age_s``, else the loop's ``loop_max_age_s``); a signal's range widened
    or removed; a signal removed (whether or not an obligation reads it: its missing/type/range check
    failed closed) or replaced by a constant of the same name; the ``risk`` inputs the
    monitor accepts widened below τ; the safe pose's joint-speed limit or tolerance raised; the
    ``restart:`` block or its ``standstill`` input removed. Release parameters are compared for every
    rule in every mode (a manual rule's ``hold_cycles`` and the risk rule's bound τ − δ are what
    ``acknowledge()`` waits for).

    Conditions are judged on meaning: an obligation whose text is unchanged still
    counts as changed when a name in it resolves to something else (a signal now a
    constant, a constant's value, R_e's formula for a condition reading ``risk``).

    Cannot be judged field by field, so counted as possible weakenings too (in the
    first list, each ending in :data:`CANNOT_TELL`; the second list repeats just
    these): the text of a ``require`` or ``when`` that changed (beyond
    whitespace), what a name in an unchanged text stands for, a signal's type, the safe pose's joints, the
    estimator settings, the ``risk.allow`` opt-outs, ``restart.start``/``standstill`` changed. ``require: 'true'`` or a
    constant ``min_d: -1`` would otherwise switch a check off unnoticed.

    Returns:
        ``(weakenings, cannot_tell)``; ``cannot_tell`` is a sublist of ``weakenings``.
    """
    weak: list[str] = []
    unjudged: list[str] = []
    po, pn = plan_of(old), plan_of(new)  # the releases, τ and τ − δ as the monitors run them
    old_rules, new_rules = _rules(po), _rules(pn)
    old_obs = {o.id: o for o in old.obligations}
    new_obs = {o.id: o for o in new.obligations}
    try:
        old_names, new_names = _meanings(old), _meanings(new)
    except Exception as exc:  # noqa: BLE001 - a spec that does not compile cannot be judged
        old_names, new_names = {}, {}
        unjudged.append(f"names could not be resolved ({type(exc).__name__}: {exc})")
    for oid, o in old_obs.items():
        n = new_obs.get(oid)
        if n is None:
            weak.append(f"obligation {oid} removed")
            continue
        if _sev(n.response) < _sev(o.response):
            weak.append(f"obligation {oid}: response {o.response} -> {n.response} (less severe)")
        if o.when is None and n.when is not None:
            weak.append(f"obligation {oid}: when added ({n.when!r}): require is no longer checked every cycle")
        elif n.when is not None and not _same_text(o.when, n.when):
            unjudged.append(f"obligation {oid}: when changed ({o.when!r} -> {n.when!r})")
        if not _same_text(o.require, n.require):
            unjudged.append(f"obligation {oid}: require changed ({o.require!r} -> {n.require!r})")
        else:
            on, nn = old_names.get(oid, {}), new_names.get(oid, {})
            for name in sorted(set(on) | set(nn)):
                a, b = on.get(name), nn.get(name)
                if a != b and a is not None and b is not None and a[0] == b[0] == "constant":
                    unjudged.append(f"obligation {oid}: constant {name} changed {a[1]!r} -> {b[1]!r}")
                elif a != b:
                    unjudged.append(f"obligation {oid}: {name} means {_meaning(a)} -> {_meaning(b)} "
                                    "(same text, another meaning)")
        ow, nw = o.within_cycles or 0, n.within_cycles or 0
        if nw > ow:
            weak.append(f"obligation {oid}: within_cycles {ow} -> {nw} (more cycles to respond)")
        weak += _release_weaker(f"obligation {oid}", old_rules[oid], new_rules[oid])
    ro, rn = po.risk_plan, pn.risk_plan  # the risk rule as each plan resolved it
    if pn.threshold > po.threshold:
        weak.append(f"risk.threshold raised {ro.threshold!r} -> {rn.threshold!r} (overrides fire at a higher R_e)")
    for w in ("alpha", "beta", "gamma"):
        if getattr(rn, w) < getattr(ro, w):
            weak.append(f"risk.{w} lowered {getattr(ro, w)!r} -> {getattr(rn, w)!r} (R_e smaller)")
    if ro.variance == "sample" and rn.variance == "population":
        weak.append("risk.variance sample -> population (R_e smaller)")
    if ro.classes != rn.classes or ro.unsafe_index % ro.classes != rn.unsafe_index % rn.classes:
        weak.append(f"risk classes/unsafe_index changed ({ro.classes}/{ro.unsafe_index} -> "
                    f"{rn.classes}/{rn.unsafe_index}): what counts as unsafe is redefined")
    risk_o, risk_n = po.risk_rule, pn.risk_rule
    if risk_n.severity < risk_o.severity:
        weak.append(f"risk.response {risk_o.response.value} -> {risk_n.response.value} (less severe)")
    if pn.fault_rule.severity < po.fault_rule.severity:
        weak.append(f"on_fault {old.on_fault} -> {new.on_fault} (less severe)")
    weak += _release_weaker("on_fault", po.fault_rule, pn.fault_rule)
    if risk_o.manual and not risk_n.manual:
        weak.append("release mode manual -> auto (a latched override now releases by itself)")
    # in every mode: an automatic latch releases, a manual one may be acknowledged, once R_e < τ − δ
    # has held hold_cycles cycles
    bo, bn = po.release_exact, pn.release_exact
    if bn > bo:
        weak.append(f"release bound τ − δ raised {float(bo):g} -> {float(bn):g} (hysteresis "
                    f"{ro.hysteresis!r} -> {rn.hysteresis!r}: a latch releases at a higher R_e)")
    if risk_n.hold < risk_o.hold:
        weak.append(f"release hold_cycles lowered {risk_o.hold} -> {risk_n.hold}")
    (olo, ohi), (nlo, nhi) = _risk_inputs(po), _risk_inputs(pn)
    if nlo < min(olo, pn.threshold) or (nhi > ohi and ohi < pn.threshold):
        weak.append(f"accepted risk inputs widened [{olo:g}, {ohi:g}] -> [{nlo:g}, {nhi:g}] (an R_e that "
                    "faulted is now accepted without an override)")
    ao = ro.max_age_s if ro.max_age_s is not None else loop_max_age_s
    an = rn.max_age_s if rn.max_age_s is not None else loop_max_age_s
    if ao is not None and (an is None or an > ao):
        weak.append(f"risk.max_age_s {ao!r} -> {'none' if an is None else repr(an)} (older estimates accepted)")
    for name, so in old.signals.items():
        sn = new.signals.get(name)
        if sn is None:
            if name in new.constants:
                weak.append(f"signal {name} replaced by a constant (it is no longer read, so its "
                            "missing/type/range checks no longer fail closed)")
            else:
                weak.append(f"signal {name} removed (its missing/type/range checks failed closed, whether "
                            "or not an obligation reads it)")
            continue
        if sn.type != so.type:
            unjudged.append(f"signal {name}: type {so.type} -> {sn.type}")
        elif so.range is not None and (sn.range is None or sn.range[0] < so.range[0] or sn.range[1] > so.range[1]):
            weak.append(f"signal {name}: range {list(so.range)} -> {list(sn.range) if sn.range else 'none'} "
                        "(values that faulted are now accepted)")
    # a constant matters only through the conditions that read it: judged above, by meaning
    so, sn = old.safe_pose, new.safe_pose
    if sn.max_joint_speed_rad_s > so.max_joint_speed_rad_s:
        weak.append(f"safe_pose.max_joint_speed_rad_s raised {so.max_joint_speed_rad_s!r} -> "
                    f"{sn.max_joint_speed_rad_s!r}")
    if sn.tolerance_rad > so.tolerance_rad:
        weak.append(f"safe_pose.tolerance_rad raised {so.tolerance_rad!r} -> {sn.tolerance_rad!r}")
    if sn.joints_rad != so.joints_rad:
        unjudged.append("safe_pose.joints_rad changed")
    if pn.estimator != po.estimator:
        unjudged.append("risk.estimator settings changed")
    # the one read of the specs' risk blocks: the opt-outs are the author's written reasons, compared as
    # text (what an opt-out lets through, τ or the weights, is compared above, from the plans)
    if new.risk.allow != old.risk.allow:
        unjudged.append("risk.allow opt-outs changed")
    _tier_changes(po, pn, weak, unjudged)
    _restart_changes(po, pn, weak, unjudged)
    unjudged = [f"{u}: {CANNOT_TELL}" for u in unjudged]
    return weak + unjudged, unjudged


def _rule_identity(plan: Plan, name: str) -> tuple | None:
    """What a latch of rule ``name`` means in ``plan``: its response and its release as the plan resolved
    them (``Plan.rules()``; ``None``: no such rule). The judges (one, or a panel: ``Plan.tiers.judges``)
    are part of the ``judge`` and ``confirm`` rules' identity."""
    judges, tc = plan.tiers.judges or None, plan.tiers.confirm_threshold
    if (name == "judge" and judges is None) or (name == "confirm" and tc is None):
        return None
    rule = _rules(plan).get(name)
    if rule is None:
        return None
    if name == "confirm":  # the confirm band [τ_confirm, τ): stop_2, released by a confirmation
        # released by a confirmation or by the judge's safe verdict: another judge is another release
        return (rule.response.value, "band", tc, plan.threshold, judges)
    ident = (rule.response.value, rule.mode, rule.hold)
    if name == "risk":
        return ident + (plan.release_exact,)
    if name == "judge":  # the judge's unsafe verdict: the risk rule's response and release
        return ident + (plan.release_exact, judges)
    return ident


def unmapped_latches(old: Spec, new: Spec, latched) -> list[str]:
    """The latched rules of ``old`` (names as in ``Monitor.latched_rules``) that a reload to ``new``
    cannot carry by identity: the same rule must exist with the same response and the same release
    (mode, hold_cycles; for the risk rule also its bound τ − δ). Empty: every latch carries over."""
    out = []
    po, pn = plan_of(old), plan_of(new)
    for name in latched:
        if name == "pending":  # the pending hold is every monitor's, the same in each (stop 2, by itself)
            continue
        a, b = _rule_identity(po, name), _rule_identity(pn, name)
        if b is None:
            out.append(f"{name}: latched, and the new spec has no such rule")
        elif a != b:
            out.append(f"{name}: latched as (response, release) {_show(a)}, the new spec has {_show(b)}")
    return out


def _show(ident: tuple | None) -> str:
    def one(x) -> str:
        if isinstance(x, (str, int, float)) or x is None:
            return str(x)
        if hasattr(x, "numerator"):
            return f"bound {float(x):g}"
        # the judges (Plan.tiers.judges): one (risk.judge) or a panel (risk.judges)
        return ("judges " if len(x) > 1 else "judge ") + "+".join(j.url for j in x)
    return "none" if ident is None else "(" + ", ".join(one(x) for x in ident) + ")"
