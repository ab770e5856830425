"""Compile-time helpers around a :class:`Plan`: find a spec's plan, and what an obligation reads.

No hidden cache: a spec carries its own compiled plan. :func:`plan_of` compiles a
:class:`~ethimon.Spec` once and sets the plan on it (a private holder that is no part of the
spec's value: ``==``, copies and pickles ignore it); ``load_spec`` compiles through it, so
``Monitor(load_spec(path))`` never compiles again, however many specs are alive. A copy of a
spec (``model_copy``, ``deepcopy``, a pickle) is another spec and compiles its own plan.
"""

from __future__ import annotations

from ..language._expr import Name, is_temporal, walk
from ..language import Spec
from ._plan import Plan
from ._typecheck import compile_plan

__all__ = ["plan_of", "spec_without_tiers", "stateless_slots"]

def plan_of(spec: Spec | Plan) -> Plan:
    """The compiled :class:`Plan` of a spec (a plan is returned as is).

    Raises:
        TypeError: neither a Spec nor a Plan.
        SpecError: the spec does not compile (names, types, units, windows).
    """
    if isinstance(spec, Plan):
        return spec
    if not isinstance(spec, Spec):
        raise TypeError(f"Monitor needs a Spec from ethimon.load_spec() or a compiled Plan, "
                        f"got {type(spec).__name__}")
    carried = spec._compiled.plan
    if carried is not None and carried.spec is spec:  # a model_copy shares its original's holder
        return carried
    plan = compile_plan(spec)
    # a new holder (never mutate a shared one); two threads racing here both compile the same plan
    spec._compiled = type(spec._compiled)(plan)
    return plan


def spec_without_tiers(spec: Spec) -> Spec:
    """``spec`` without its tiers (confirm band, judges, ``judge_may_hold_above_tau``): the base rule
    ``ethimon verify`` proves its decision-trace properties on. The spec itself when it has none
    (``Plan.tiers.on``); else a copy, which compiles its own plan."""
    if not plan_of(spec).tiers.on:
        return spec
    risk = spec.risk.model_copy(update={"confirm_threshold": None, "judge": None, "judges": None,
                                        "judge_may_hold_above_tau": None})
    return spec.model_copy(update={"risk": risk})


def stateless_slots(plan: Plan, ob) -> frozenset[int] | None:
    """Input slots an obligation reads, or ``None`` if it keeps state across cycles.

    Stateless obligations (no temporal operator, no ``within_cycles``) can be
    judged on a fault cycle from the inputs that are valid.
    """
    if ob.within_cycles:
        return None
    slots = plan.slots
    used = set()
    for root in (ob.when, ob.require):
        if root is None:
            continue
        for node in walk(root):
            if is_temporal(node):
                return None
            if isinstance(node, Name) and node.id in slots:
                used.add(slots[node.id])
    return frozenset(used)
