"""Compile-time helpers around a :class:`Plan`: find a spec's plan, and what an obligation reads.

A :class:`~ethimon.Spec` is plain data and never points at its plan. The plan
of a spec is found through :func:`plan_of`: the most recent plans, kept by the spec's identity
(a plan holds its spec, so a cached spec's address is never recycled; a hit is
checked with ``plan.spec is spec`` all the same), or compiled now. ``load_spec`` compiles through
it, so ``Monitor(load_spec(path))`` compiles once.
"""

from __future__ import annotations

import threading
from collections import OrderedDict

from ..spec._expr import TEMPORAL, Call, Name, walk
from ..spec import Spec
from ._plan import Plan
from ._typecheck import compile_plan

__all__ = ["plan_of", "stateless_slots"]

#: how many recently compiled plans are kept (each holds its spec: a bounded memory cost)
CACHE_SIZE = 32

_cache: OrderedDict[int, Plan] = OrderedDict()
_lock = threading.Lock()


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
    key = id(spec)
    with _lock:
        hit = _cache.get(key)
        if hit is not None and hit.spec is spec:
            _cache.move_to_end(key)
            return hit
    plan = compile_plan(spec)
    with _lock:
        _cache[key] = plan
        _cache.move_to_end(key)
        while len(_cache) > CACHE_SIZE:
            _cache.popitem(last=False)
    return plan


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
            if isinstance(node, Call) and node.func in TEMPORAL:
                return None
            if isinstance(node, Name) and node.id in slots:
                used.add(slots[node.id])
    return frozenset(used)
