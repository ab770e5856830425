"""Whether a reloaded spec weakens monitoring, judged field by field."""

from __future__ import annotations

from typing import Any

from ..compiler._risk_formula import release_bound
from ..spec import Response, Spec

__all__ = ["CANNOT_TELL", "weakenings"]


def _sev(response: Any) -> int:
    return Response(response).severity


#: the reason attached to every change whose direction :func:`weakenings` cannot judge
CANNOT_TELL = "cannot tell whether this change weakens monitoring"


def _same_text(a: str | None, b: str | None) -> bool:
    """Equal condition texts up to whitespace (``x>=1`` and ``x >= 1`` still differ: not judged)."""
    if a is None or b is None:
        return a is b
    return " ".join(a.split()) == " ".join(b.split())


def _release_weaker(what: str, old: tuple[str, int], new: tuple[str, int]) -> list[str]:
    """A rule's release (mode, hold_cycles; defaults filled in) made easier."""
    if old[0] == "manual" and new[0] == "auto":
        return [f"{what}: release manual -> auto (its latch now releases by itself)"]
    if new[1] < old[1]:
        return [f"{what}: release hold_cycles lowered {old[1]} -> {new[1]}"]
    return []


def weakenings(old: Spec, new: Spec, *, loop_max_age_s: float | None = None) -> tuple[list[str], list[str]]:
    """How ``new`` weakens monitoring compared with ``old``, judged field by field.

    Weaker (each one line in the first list): an obligation removed; an
    obligation's response less severe, a ``when`` added where there was none,
    ``within_cycles`` added or raised; τ raised; a risk weight (α, β, γ) lowered
    or the variance changed from sample to population (R_e smaller); the unsafe
    class or the number of classes changed; ``risk.response`` or ``on_fault``
    less severe; release mode manual → auto (the risk rule's, an obligation's
    or the fault latch's, defaults filled in) or a rule's hold lowered; the release bound τ − δ raised
    (hysteresis shrunk relative to τ) or ``hold_cycles`` lowered; the effective
    estimate age limit removed or raised (``risk.max_age_s``, else the loop's
    ``loop_max_age_s``); a signal's range widened or removed; the safe pose's
    joint-speed limit or tolerance raised.

    Cannot be judged field by field, so counted as possible weakenings too (in the
    first list, each ending in :data:`CANNOT_TELL`; the second list repeats just
    these): the text of a ``require`` or ``when`` that changed (beyond
    whitespace), a constant's value, a signal's type, the safe pose's joints, the
    estimator settings, the ``risk.allow`` opt-outs. ``require: 'true'`` or a
    constant ``min_d: -1`` would otherwise switch a check off unnoticed.

    Returns:
        ``(weakenings, cannot_tell)``; ``cannot_tell`` is a sublist of ``weakenings``.
    """
    weak: list[str] = []
    unjudged: list[str] = []
    old_obs = {o.id: o for o in old.obligations}
    new_obs = {o.id: o for o in new.obligations}
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
        ow, nw = o.within_cycles or 0, n.within_cycles or 0
        if nw > ow:
            weak.append(f"obligation {oid}: within_cycles {ow} -> {nw} (more cycles to respond)")
        weak += _release_weaker(f"obligation {oid}", old.obligation_release(o), new.obligation_release(n))
    ro, rn = old.risk, new.risk
    if rn.threshold > ro.threshold:
        weak.append(f"risk.threshold raised {ro.threshold!r} -> {rn.threshold!r} (overrides fire at a higher R_e)")
    for w in ("alpha", "beta", "gamma"):
        if getattr(rn, w) < getattr(ro, w):
            weak.append(f"risk.{w} lowered {getattr(ro, w)!r} -> {getattr(rn, w)!r} (R_e smaller)")
    if ro.variance == "sample" and rn.variance == "population":
        weak.append("risk.variance sample -> population (R_e smaller)")
    if ro.classes != rn.classes or ro.unsafe_index % ro.classes != rn.unsafe_index % rn.classes:
        weak.append(f"risk classes/unsafe_index changed ({ro.classes}/{ro.unsafe_index} -> "
                    f"{rn.classes}/{rn.unsafe_index}): what counts as unsafe is redefined")
    if _sev(rn.response) < _sev(ro.response):
        weak.append(f"risk.response {ro.response} -> {rn.response} (less severe)")
    if _sev(new.on_fault) < _sev(old.on_fault):
        weak.append(f"on_fault {old.on_fault} -> {new.on_fault} (less severe)")
    weak += _release_weaker("on_fault", old.fault_release(), new.fault_release())
    if ro.release.mode == "manual" and rn.release.mode == "auto":
        weak.append("release mode manual -> auto (a latched override now releases by itself)")
    elif rn.release.mode == "auto":
        bo = release_bound(ro.threshold, ro.release.hysteresis)[0]
        bn = release_bound(rn.threshold, rn.release.hysteresis)[0]
        if bn > bo:
            weak.append(f"release bound τ − δ raised {float(bo):g} -> {float(bn):g} (hysteresis "
                        f"{ro.release.hysteresis!r} -> {rn.release.hysteresis!r}: a latch releases at a higher R_e)")
        if rn.release.hold_cycles < ro.release.hold_cycles:
            weak.append(f"release hold_cycles lowered {ro.release.hold_cycles} -> {rn.release.hold_cycles}")
    ao = ro.max_age_s if ro.max_age_s is not None else loop_max_age_s
    an = rn.max_age_s if rn.max_age_s is not None else loop_max_age_s
    if ao is not None and (an is None or an > ao):
        weak.append(f"risk.max_age_s {ao!r} -> {'none' if an is None else repr(an)} (older estimates accepted)")
    for name, so in old.signals.items():
        sn = new.signals.get(name)
        if sn is None:
            continue  # an obligation reading it changed or was removed, and is reported there
        if sn.type != so.type:
            unjudged.append(f"signal {name}: type {so.type} -> {sn.type}")
        elif so.range is not None and (sn.range is None or sn.range[0] < so.range[0] or sn.range[1] > so.range[1]):
            weak.append(f"signal {name}: range {list(so.range)} -> {list(sn.range) if sn.range else 'none'} "
                        "(values that faulted are now accepted)")
    for name, c in old.constants.items():
        if new.constants.get(name) != c:
            unjudged.append(f"constant {name} changed or removed")
    po, pn = old.safe_pose, new.safe_pose
    if pn.max_joint_speed_rad_s > po.max_joint_speed_rad_s:
        weak.append(f"safe_pose.max_joint_speed_rad_s raised {po.max_joint_speed_rad_s!r} -> "
                    f"{pn.max_joint_speed_rad_s!r}")
    if pn.tolerance_rad > po.tolerance_rad:
        weak.append(f"safe_pose.tolerance_rad raised {po.tolerance_rad!r} -> {pn.tolerance_rad!r}")
    if pn.joints_rad != po.joints_rad:
        unjudged.append("safe_pose.joints_rad changed")
    if rn.estimator != ro.estimator:
        unjudged.append("risk.estimator settings changed")
    if getattr(rn, "allow", None) != getattr(ro, "allow", None):
        unjudged.append("risk.allow opt-outs changed")
    co, cn = ro.confirm_threshold, rn.confirm_threshold
    if co is not None and (cn is None or cn > co):
        weak.append(f"risk.confirm_threshold {co!r} -> {'none' if cn is None else repr(cn)} (fewer texts held "
                    f"for a confirmation)")
    jo, jn = ro.judge, rn.judge
    if jo is None and jn is not None and cn is not None:
        weak.append("risk.judge added (its safe verdict executes texts in the confirm band)")
    elif jo is not None and jn is None:
        weak.append("risk.judge removed (no unsafe verdict can stop a text below tau_confirm)")
    elif jo is not None and jn is not None and jn != jo:
        if (jn.safe_below > jo.safe_below or jn.unsafe_from > jo.unsafe_from) or (
                jn.model_copy(update={"safe_below": jo.safe_below, "unsafe_from": jo.unsafe_from}) != jo):
            unjudged.append("risk.judge settings changed")
    unjudged = [f"{u}: {CANNOT_TELL}" for u in unjudged]
    return weak + unjudged, unjudged
