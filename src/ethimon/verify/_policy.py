"""Release policies an engineer would question (no z3: ``ethimon lint`` reports them too)."""

from __future__ import annotations

from ..compiler import Plan, plan_of
from ..language._model import MANUAL_BY_DEFAULT, Spec

__all__ = ["release_policy_warnings", "manual_rules"]


def release_policy_warnings(spec: Spec | Plan) -> list[str]:
    """One line per questionable release policy, as the plan resolved them (defaults filled in).

    An automatic release after a stop of category 0 or 1 (an obligation's, or the
    risk rule's) restarts the task by itself after power was cut; an automatic
    fault release restarts it although nobody looked at the fault's cause.
    """
    plan = plan_of(spec)
    out: list[str] = []
    for ob in plan.obligations:
        if ob.response.value in MANUAL_BY_DEFAULT and not ob.manual:
            out.append(f"obligation {ob.id!r}: response {ob.response.value} with release: auto (the task restarts "
                       f"by itself {ob.release_hold} cycles after a stop that cut power; IEC 60204-1 wants a "
                       f"deliberate restart: release: manual)")
    r = plan.risk_rule
    if r.response.value in MANUAL_BY_DEFAULT and not r.manual:
        out.append(f"risk.response {r.response.value} with risk.release.mode auto (the task restarts by itself "
                   f"once R_e < tau - delta for {r.hold} cycles after a stop that cut power; set "
                   f"risk.release.mode: manual)")
    f = plan.fault_rule
    if not f.manual:
        why = ("after a stop that cut power" if f.response.value in MANUAL_BY_DEFAULT else
               "after a fault stop, although the fault's cause was never seen by anyone")
        out.append(f"on_fault release: auto: the task restarts by itself {f.hold} cycles after the inputs come "
                   f"back, {why} (the default is manual)")
    if plan.restart is not None and plan.restart.standstill is None and plan.manual_rules:
        out.append("restart: no restart.standstill input: GovernedLoop cannot tell whether a stop has completed "
                   "(standstill, brakes engaged, power state settled), so the integrator must gate "
                   "acknowledgements on it (or name the robot's bool report as restart.standstill)")
    return out


def manual_rules(spec: Spec | Plan) -> list[str]:
    """The rules whose latch waits for ``Monitor.acknowledge()`` (obligation ids, ``risk``, ``fault``)."""
    return list(plan_of(spec).manual_rules)
