"""Compile stage 2: turn a checked :class:`Plan` into closures for the runtime.

Every expression node becomes a zero-argument closure that reads input slots
(``vals``) and temporal-operator results (``tv``). Common shapes
(``signal < constant``, ``signal < signal``) get specialised closures, so a
typical comparison is one Python call. Temporal operators become O(1) state
machines (counters, no buffers) updated once per cycle, inner operators first,
so short-circuiting ``and``/``or`` can never skip a state update.

No source text is generated and nothing is ``eval``-ed: closures are built
from the checked AST only.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from ..language._expr import (BINARY_OPS, COMPARISON_MARGINS, CONNECTIVE_MARGINS, Binary, BoolLit, Call, Name,
                          Node, Num, Unary, is_temporal, separation_distance, walk)
from ..language._visit import ExprVisitor
from ._machines import bounded_margin, held_machine, once_machine, prev_machine, since_machine
from ._plan import Plan

__all__ = ["Machine", "build_machine"]

INF = math.inf
_NEGATIVE = "separation_distance() argument is negative or not a number"


@dataclass
class Machine:
    """Closures and state of one monitor instance (built by :func:`build_machine`)."""

    vals: list
    tv: list
    updates: tuple[Callable[[], None], ...]
    resets: tuple[Callable[[], None], ...]
    violated: tuple[Callable[[], bool], ...]
    margins: tuple[Callable[[], float], ...]
    margins_raise: bool = True  # some margin closure may raise (then the monitor guards each one)
    #: (obligation id, probe) per bounded response: the probe is true while its ``when`` has fired and
    #: ``require`` has not been met within ``within_cycles`` yet (a deadline running)
    pending: tuple[tuple[str, Callable[[], bool]], ...] = ()

    def reset(self) -> None:
        """Forget every temporal state and pending response (a fresh trace)."""
        for r in self.resets:
            r()


# operand descriptors: ("c", value) | ("r", list, index) | ("f", fn)


def _as_fn(d) -> Callable[[], object]:
    if d[0] == "f":
        return d[1]
    if d[0] == "c":
        v = d[1]
        return lambda: v
    lst, i = d[1], d[2]
    return lambda: lst[i]


def _cmp(op: str, a, b):
    ka, kb = a[0], b[0]
    if ka == "r" and kb == "c":
        lst, i, c = a[1], a[2], b[1]
        if op == "<":
            return lambda: lst[i] < c
        if op == "<=":
            return lambda: lst[i] <= c
        if op == ">":
            return lambda: lst[i] > c
        if op == ">=":
            return lambda: lst[i] >= c
        if op == "==":
            return lambda: lst[i] == c
        return lambda: lst[i] != c
    if ka == "c" and kb == "r":
        flip = {"<": ">", "<=": ">=", ">": "<", ">=": "<=", "==": "==", "!=": "!="}[op]
        return _cmp(flip, b, a)
    if ka == "r" and kb == "r":
        la, i, lb, j = a[1], a[2], b[1], b[2]
        if op == "<":
            return lambda: la[i] < lb[j]
        if op == "<=":
            return lambda: la[i] <= lb[j]
        if op == ">":
            return lambda: la[i] > lb[j]
        if op == ">=":
            return lambda: la[i] >= lb[j]
        if op == "==":
            return lambda: la[i] == lb[j]
        return lambda: la[i] != lb[j]
    if kb == "c":
        f, c = _as_fn(a), b[1]
        if op == "<":
            return lambda: f() < c
        if op == "<=":
            return lambda: f() <= c
        if op == ">":
            return lambda: f() > c
        if op == ">=":
            return lambda: f() >= c
        if op == "==":
            return lambda: f() == c
        return lambda: f() != c
    if ka == "c":
        flip = {"<": ">", "<=": ">=", ">": "<", ">=": "<=", "==": "==", "!=": "!="}[op]
        return _cmp(flip, b, a)
    f, g = _as_fn(a), _as_fn(b)
    if op == "<":
        return lambda: f() < g()
    if op == "<=":
        return lambda: f() <= g()
    if op == ">":
        return lambda: f() > g()
    if op == ">=":
        return lambda: f() >= g()
    if op == "==":
        return lambda: f() == g()
    return lambda: f() != g()


def _arith(op: str, a, b):
    if a[0] == "r" and b[0] == "c":
        lst, i, c = a[1], a[2], b[1]
        if op == "+":
            return lambda: lst[i] + c
        if op == "-":
            return lambda: lst[i] - c
        if op == "*":
            return lambda: lst[i] * c
        return lambda: lst[i] / c
    if a[0] == "c" and b[0] == "r":
        c, lst, i = a[1], b[1], b[2]
        if op == "+":
            return lambda: c + lst[i]
        if op == "-":
            return lambda: c - lst[i]
        if op == "*":
            return lambda: c * lst[i]
        return lambda: c / lst[i]
    if a[0] == "r" and b[0] == "r":
        la, i, lb, j = a[1], a[2], b[1], b[2]
        if op == "+":
            return lambda: la[i] + lb[j]
        if op == "-":
            return lambda: la[i] - lb[j]
        if op == "*":
            return lambda: la[i] * lb[j]
        return lambda: la[i] / lb[j]
    f, g = _as_fn(a), _as_fn(b)
    if op == "+":
        return lambda: f() + g()
    if op == "-":
        return lambda: f() - g()
    if op == "*":
        return lambda: f() * g()
    return lambda: f() / g()


class _Gen(ExprVisitor):
    """The closures back-end of the interpreter protocol: each ``visit_*`` returns the zero-argument
    closure of its node (built once, at compile time); a temporal operator's also builds its state
    machine (:mod:`._machines`), kept in ``machines`` by its index in ``plan.temporal``."""

    def __init__(self, plan: Plan) -> None:
        self.plan = plan
        self.vals: list = [0.0] * plan.n_slots
        self.tv: list = [False] * len(plan.temporal)
        self.slots = plan.slots
        self.consts = plan.constants
        self.pending: list[tuple[str, Callable[[], bool]]] = []
        self.machines: list = [None] * len(plan.temporal)  # (update, reset) per temporal node

    # -- values --------------------------------------------------------------
    def d(self, node: Node):
        """Operand descriptor of ``node`` (a constant or a slot is read inline by the closure above it)."""
        if isinstance(node, (Num, BoolLit)):
            return ("c", node.value)
        if isinstance(node, Name):
            if node.id in self.consts:
                return ("c", self.consts[node.id])
            return ("r", self.vals, self.slots[node.id])
        if is_temporal(node):
            return ("r", self.tv, node.ann.slot)
        if isinstance(node, Unary) and node.op == "-" and isinstance(node.operand, Num):
            return ("c", -node.operand.value)
        return ("f", self.fn(node))

    def fn(self, node: Node) -> Callable[[], object]:
        """The closure of ``node``: :meth:`visit` (the protocol's dispatch, at compile time)."""
        return self.visit(node)

    def _leaf(self, node: Node) -> Callable[[], object]:
        return _as_fn(self.d(node))

    visit_num = visit_bool = visit_name = _leaf

    def visit_neg(self, node: Unary) -> Callable[[], object]:
        f = self.fn(node.operand)
        return lambda: -f()

    def visit_not(self, node: Unary) -> Callable[[], object]:
        f = self.fn(node.operand)
        return lambda: not f()

    def _compare(self, node: Binary) -> Callable[[], bool]:
        return _cmp(node.op, self.d(node.left), self.d(node.right))

    visit_lt = visit_le = visit_gt = visit_ge = visit_eq = visit_ne = _compare

    def _arithmetic(self, node: Binary) -> Callable[[], float]:
        return _arith(node.op, self.d(node.left), self.d(node.right))

    visit_add = visit_sub = visit_mul = visit_div = _arithmetic

    def visit_and(self, node: Binary) -> Callable[[], object]:
        f, g = self.fn(node.left), self.fn(node.right)
        return lambda: f() and g()

    def visit_or(self, node: Binary) -> Callable[[], object]:
        f, g = self.fn(node.left), self.fn(node.right)
        return lambda: f() or g()

    def visit_implies(self, node: Binary) -> Callable[[], object]:
        f, g = self.fn(node.left), self.fn(node.right)
        return lambda: (not f()) or g()

    def visit_abs(self, node: Call) -> Callable[[], float]:
        g = self.fn(node.args[0])
        return lambda: abs(g())

    def visit_sqrt(self, node: Call) -> Callable[[], float]:
        g = self.fn(node.args[0])
        return lambda: math.sqrt(g())

    def visit_min(self, node: Call) -> Callable[[], float]:
        args = [self.fn(a) for a in node.args]
        if len(args) == 2:
            g, h = args
            return lambda: min(g(), h())
        return lambda: min([g() for g in args])

    def visit_max(self, node: Call) -> Callable[[], float]:
        args = [self.fn(a) for a in node.args]
        if len(args) == 2:
            g, h = args
            return lambda: max(g(), h())
        return lambda: max([g() for g in args])

    def visit_separation_distance(self, node: Call) -> Callable[[], float]:
        return self.separation(node)

    # -- temporal operators: a state machine each, read through its slot of ``tv`` ----------
    def _temporal(self, node: Call, build) -> Callable[[], object]:
        k = node.ann.slot
        if self.machines[k] is None:
            self.machines[k] = build(k)
        return _as_fn(("r", self.tv, k))

    def visit_held(self, node: Call) -> Callable[[], object]:
        return self._temporal(node, lambda k: held_machine(self.fn(node.args[0]), self.tv, k,
                                                           node.ann.window))

    def visit_once(self, node: Call) -> Callable[[], object]:
        return self._temporal(node, lambda k: once_machine(self.fn(node.args[0]), self.tv, k,
                                                           node.ann.window))

    def visit_since(self, node: Call) -> Callable[[], object]:
        return self._temporal(node, lambda k: since_machine(self.fn(node.args[0]), self.fn(node.args[1]), self.tv,
                                                            k, node.ann.window))

    def visit_prev(self, node: Call) -> Callable[[], object]:
        def build(k):
            e = self.fn(node.args[0])
            init = self.fn(node.args[1]) if len(node.args) == 2 else None
            return prev_machine(e, init, node.ann.ty.kind == "bool", self.tv, k)
        return self._temporal(node, build)

    def separation(self, node: Call) -> Callable[[], float]:
        """``separation_distance(...)``: evaluate every argument, raise if one is not ``>= 0``
        (a fault, like ``sqrt`` of a negative), else the formula of
        :func:`~ethimon.language._expr.separation_distance` in its order.

        Constant arguments (checked ``>= 0`` by the compiler) are read once; with constant times
        and offsets (the usual shape) ``T_r + T_s`` is computed once (the formula's first step,
        so the same float). No allocation per cycle.
        """
        ds = [self.d(a) for a in node.args]
        if all(d[0] == "c" for d in ds):
            v = separation_distance(*(d[1] for d in ds))
            return lambda: v
        if all(ds[i][0] == "c" for i in (2, 3, 5, 6, 7)):  # the times and the offsets are constants
            f_h, f_r, f_s = _as_fn(ds[0]), _as_fn(ds[1]), _as_fn(ds[4])
            T_r, T_s, C, Z_d, Z_r = (ds[i][1] for i in (2, 3, 5, 6, 7))  # noqa: N806 - the standard's symbols
            t_rs = T_r + T_s  # the formula's first operation: the same float

            def sp_consts() -> float:
                v_h = f_h()
                v_r = f_r()
                S_s = f_s()  # noqa: N806
                if not (v_h >= 0.0 and v_r >= 0.0 and S_s >= 0.0):
                    raise ValueError(_NEGATIVE)
                return v_h * t_rs + v_r * T_r + S_s + C + Z_d + Z_r
            return sp_consts
        f0, f1, f2, f3, f4, f5, f6, f7 = (_as_fn(d) for d in ds)

        def sp() -> float:
            v_h = f0()  # one by one: a tuple unpacking of eight would allocate a tuple every cycle
            v_r = f1()
            T_r = f2()  # noqa: N806 - the standard's symbols
            T_s = f3()  # noqa: N806
            S_s = f4()  # noqa: N806
            C = f5()  # noqa: N806
            Z_d = f6()  # noqa: N806
            Z_r = f7()  # noqa: N806
            if not (v_h >= 0.0 and v_r >= 0.0 and T_r >= 0.0 and T_s >= 0.0 and S_s >= 0.0 and C >= 0.0
                    and Z_d >= 0.0 and Z_r >= 0.0):
                raise ValueError(_NEGATIVE)
            return v_h * (T_r + T_s) + v_r * T_r + S_s + C + Z_d + Z_r
        return sp

    # -- robustness (margins) ------------------------------------------------
    def rob(self, node: Node) -> Callable[[], float]:
        """Quantitative robustness: > 0 satisfied, < 0 violated; ±inf for boolean leaves.

        Operands that are a slot or a constant are read inline (one call per comparison, not
        three); ``max``/``min`` of two are written out as the built-ins compute them (the first
        argument unless the second is strictly greater/smaller), so every float is the same.
        """
        if isinstance(node, Binary):
            op = node.op
            if op in COMPARISON_MARGINS and node.left.ann.ty.kind == "num":
                return _margin_closure(COMPARISON_MARGINS[op], self.d(node.left), self.d(node.right))
            if op in CONNECTIVE_MARGINS:
                return _connective_closure(*CONNECTIVE_MARGINS[op], self.rob(node.left), self.rob(node.right))
        if isinstance(node, Unary) and node.op == "not":
            f = self.rob(node.operand)
            return lambda: -f()
        d = self.d(node)
        if d[0] == "r":
            lst, i = d[1], d[2]
            return lambda: INF if lst[i] else -INF
        if d[0] == "c":
            v = INF if d[1] else -INF
            return lambda: v
        b = d[1]
        return lambda: INF if b() else -INF

    # -- temporal operators ----------------------------------------------------

    def obligation(self, ob) -> tuple[Callable[[], bool], Callable[[], None] | None]:
        req = self.fn(ob.require)
        when = self.fn(ob.when) if ob.when is not None else None
        n = ob.within_cycles
        if not n:
            if when is None:
                rq = ob.require
                if isinstance(rq, Binary) and rq.op in ("or", "and", "implies"):  # one call less
                    f, g = self.fn(rq.left), self.fn(rq.right)
                    if rq.op == "or":
                        return (lambda: not (f() or g())), None
                    if rq.op == "and":
                        return (lambda: not (f() and g())), None
                    return (lambda: not ((not f()) or g())), None
                return (lambda: not req()), None
            return (lambda: bool(when()) and not req()), None
        pend = -1

        def violated() -> bool:
            nonlocal pend
            w = True if when is None else when()
            if req():
                pend = -1
            elif pend >= 0:
                if pend < n:
                    pend += 1
            elif w:
                pend = 0
            return pend >= n

        def rst() -> None:
            nonlocal pend
            pend = -1
        self.pending.append((ob.id, lambda: 0 <= pend < n))
        return violated, rst


def build_machine(plan: Plan) -> Machine:
    """Build fresh closures and state for one monitor instance."""
    g = _Gen(plan)
    for node in plan.temporal:  # children first; visiting one builds its state machine
        g.visit(node)
    updates = [u for u, _ in g.machines]
    resets = [r for _, r in g.machines]
    violated, margins = [], []
    mbuf = [math.nan] * len(plan.obligations)
    may_raise = False
    for k, ob in enumerate(plan.obligations):
        fused = _fused_comparison(g, ob, mbuf, k)
        if fused is not None:  # verdict and margin from one evaluation of both sides
            violated.append(fused)
            margins.append(lambda k=k: mbuf[k])
            continue
        v, r = g.obligation(ob)
        violated.append(v)
        if r is not None:
            resets.append(r)
        rw = g.rob(ob.when) if ob.when is not None else None
        rr = g.rob(ob.require)
        raise_w = ob.when is not None and _may_raise(ob.when)
        raise_r = _may_raise(ob.require)
        if ob.within_cycles:  # guards its own terms (never raises)
            mf, mr = bounded_margin(rw, rr, ob.within_cycles, raise_w, raise_r)
            margins.append(mf)
            resets.append(mr)
            continue
        may_raise = may_raise or raise_w or raise_r
        if rw is not None:
            def both(rw=rw, rr=rr) -> float:  # max(-rw(), rr()) as the built-in computes it
                a = -rw()
                b = rr()
                return b if b > a else a
            margins.append(both)
        else:
            margins.append(rr)
    return Machine(g.vals, g.tv, tuple(updates), tuple(resets), tuple(violated), tuple(margins), may_raise,
                   tuple(g.pending))


def _may_raise(node: Node) -> bool:
    """Whether evaluating ``node`` can raise on finite float inputs: an operator whose row in the
    operator table says so (``may_raise``: a division by zero, ``sqrt`` of a negative, a negative
    ``separation_distance`` argument) somewhere in it. ``+ - *``, comparisons, connectives,
    ``abs``/``min``/``max`` and slot reads never raise (overflow gives inf, inf - inf NaN: values,
    not exceptions)."""
    for n in walk(node):
        row = n.row
        if row is not None and row.may_raise:
            return True
    return False




def _margin_closure(shape: str, a, b) -> Callable[[], float]:
    """The margin of ``a <op> b`` for the shape ``COMPARISON_MARGINS[op]``, chosen here at compile time;
    ``a``, ``b`` are operand descriptors (a slot or a constant is read inline, same arithmetic)."""
    ka, kb = a[0], b[0]
    if ka == "r" and kb == "c":
        lst, i, c = a[1], a[2], b[1]
        if shape == "b - a":
            return lambda: c - lst[i]
        if shape == "a - b":
            return lambda: lst[i] - c
        if shape == "-|a - b|":
            return lambda: -abs(lst[i] - c)
        assert shape == "|a - b|", shape
        return lambda: abs(lst[i] - c)
    if ka == "c" and kb == "r":
        c, lst, i = a[1], b[1], b[2]
        if shape == "b - a":
            return lambda: lst[i] - c
        if shape == "a - b":
            return lambda: c - lst[i]
        if shape == "-|a - b|":
            return lambda: -abs(c - lst[i])
        assert shape == "|a - b|", shape
        return lambda: abs(c - lst[i])
    if ka == "r" and kb == "r":
        la, i, lb, j = a[1], a[2], b[1], b[2]
        if shape == "b - a":
            return lambda: lb[j] - la[i]
        if shape == "a - b":
            return lambda: la[i] - lb[j]
        if shape == "-|a - b|":
            return lambda: -abs(la[i] - lb[j])
        assert shape == "|a - b|", shape
        return lambda: abs(la[i] - lb[j])
    f, g = _as_fn(a), _as_fn(b)
    if shape == "b - a":
        return lambda: g() - f()
    if shape == "a - b":
        return lambda: f() - g()
    if shape == "-|a - b|":
        return lambda: -abs(f() - g())
    assert shape == "|a - b|", shape
    return lambda: abs(f() - g())


def _connective_closure(combine: str, negate_left: bool, f: Callable[[], float],
                        g: Callable[[], float]) -> Callable[[], float]:
    """The margin of a connective, ``CONNECTIVE_MARGINS[op]`` read here at compile time; ``min``/``max``
    of the two written out as the built-ins compute them (keep the first unless the second is
    strictly smaller/greater), so NaN and ±0.0 come out the same."""
    if combine == "min":
        if negate_left:
            def mn_neg() -> float:
                a = -f()
                b = g()
                return b if b < a else a
            return mn_neg

        def mn() -> float:
            a = f()
            b = g()
            return b if b < a else a
        return mn
    assert combine == "max", combine
    if negate_left:
        def mx_neg() -> float:
            a = -f()
            b = g()
            return b if b > a else a
        return mx_neg

    def mx() -> float:
        a = f()
        b = g()
        return b if b > a else a
    return mx



def _fused_comparison(g: _Gen, ob, mbuf: list, k: int):
    """For ``require: <num> <cmp> <num>`` (no ``when``, no ``within_cycles``): one closure
    that evaluates both sides once, stores the margin in ``mbuf[k]`` and returns the verdict.

    The margin is read by the monitor after every obligation was judged in the cycle.
    """
    req = ob.require
    if ob.when is not None or ob.within_cycles or not isinstance(req, Binary):
        return None
    op = req.op
    if op not in COMPARISON_MARGINS or req.left.ann.ty.kind != "num":
        return None
    da, db = g.d(req.left), g.d(req.right)
    if da[0] == "r" and db[0] == "c":  # slot <op> constant, the usual shape: both read inline
        return _fused_slot_const(op, da[1], da[2], db[1], mbuf, k)
    f, h = g.fn(req.left), g.fn(req.right)
    holds = BINARY_OPS[op][1]  # the operator's function (a C call, as cheap as the inline comparison)
    shape = COMPARISON_MARGINS[op]  # read here, once: the closure below has the margin's shape inline
    if shape == "b - a":
        def violated() -> bool:
            a = f()
            b = h()
            mbuf[k] = b - a
            return not holds(a, b)
    elif shape == "a - b":
        def violated() -> bool:
            a = f()
            b = h()
            mbuf[k] = a - b
            return not holds(a, b)
    elif shape == "-|a - b|":
        def violated() -> bool:
            a = f()
            b = h()
            mbuf[k] = -abs(a - b)
            return not holds(a, b)
    else:
        assert shape == "|a - b|", shape

        def violated() -> bool:
            a = f()
            b = h()
            mbuf[k] = abs(a - b)
            return not holds(a, b)
    return violated


def _fused_slot_const(op: str, lst: list, i: int, c, mbuf: list, k: int):
    """:func:`_fused_comparison` for ``slot <op> constant``: the margin of ``COMPARISON_MARGINS[op]``
    and the verdict ``not (a <op> c)`` (the same comparison as ``BINARY_OPS[op]``), no calls."""
    if op == "<=":
        def violated() -> bool:
            a = lst[i]
            mbuf[k] = c - a
            return not a <= c
    elif op == "<":
        def violated() -> bool:
            a = lst[i]
            mbuf[k] = c - a
            return not a < c
    elif op == ">=":
        def violated() -> bool:
            a = lst[i]
            mbuf[k] = a - c
            return not a >= c
    elif op == ">":
        def violated() -> bool:
            a = lst[i]
            mbuf[k] = a - c
            return not a > c
    elif op == "==":
        def violated() -> bool:
            a = lst[i]
            mbuf[k] = -abs(a - c)
            return not a == c
    else:
        assert op == "!=", op

        def violated() -> bool:
            a = lst[i]
            mbuf[k] = abs(a - c)
            return not a != c
    assert {"<=": "b - a", "<": "b - a", ">=": "a - b", ">": "a - b", "==": "-|a - b|",
            "!=": "|a - b|"}[op] == COMPARISON_MARGINS[op]
    return violated
