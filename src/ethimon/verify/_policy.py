"""Release policies an engineer would question (no z3: ``ethimon lint`` reports them too)."""

from __future__ import annotations

from ..spec._model import MANUAL_BY_DEFAULT, Spec

__all__ = ["release_policy_warnings", "manual_rules"]


def release_policy_warnings(spec: Spec) -> list[str]:
    """One line per questionable release policy, with the defaults filled in.

    An automatic release after a stop of category 0 or 1 (an obligation's, or the
    risk rule's) restarts the task by itself after power was cut; an automatic
    fault release restarts it although nobody looked at the fault's cause.
    """
    out: list[str] = []
    for ob in spec.obligations:
        mode, hold = spec.obligation_release(ob)
        if ob.response in MANUAL_BY_DEFAULT and mode == "auto":
            out.append(f"obligation {ob.id!r}: response {ob.response} with release: auto (the task restarts by "
                       f"itself {hold} cycles after a stop that cut power; IEC 60204-1 wants a deliberate "
                       f"restart: release: manual)")
    r = spec.risk
    if r.response in MANUAL_BY_DEFAULT and r.release.mode == "auto":
        out.append(f"risk.response {r.response} with risk.release.mode auto (the task restarts by itself once "
                   f"R_e < tau - delta for {r.release.hold_cycles} cycles after a stop that cut power; set "
                   f"risk.release.mode: manual)")
    fmode, fhold = spec.fault_release()
    if fmode == "auto":
        why = ("after a stop that cut power" if spec.on_fault in MANUAL_BY_DEFAULT else
               "after a fault stop, although the fault's cause was never seen by anyone")
        out.append(f"on_fault release: auto: the task restarts by itself {fhold} cycles after the inputs come "
                   f"back, {why} (the default is manual)")
    return out


def manual_rules(spec: Spec) -> list[str]:
    """The rules whose latch waits for ``Monitor.acknowledge()`` (obligation ids, ``risk``, ``fault``)."""
    out = [ob.id for ob in spec.obligations if spec.obligation_release(ob)[0] == "manual"]
    if spec.risk.release.mode == "manual":
        out.append("risk")
    if spec.fault_release()[0] == "manual":
        out.append("fault")
    return out
