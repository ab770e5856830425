"""Vectorised evaluation of a plan's expressions over many cycles at once.

The cycles evaluated together are given as sorted original cycle numbers plus
segment starts: a segment is a run of cycles with no fault in between, the
history a :class:`~ethimon.Monitor` keeps (it clears it on every fault). Every
array here is indexed by position in that list.

Each expression node gives ``(value, err)``: the value on every cycle (garbage
where the monitor would raise), and where evaluating it raises the way the
compiled closures evaluate it (``and``/``or``/``implies`` short-circuit, a
division by zero, the square root of a negative number or a negative argument
of ``separation_distance`` raises), ``None`` if
it cannot raise. The temporal operators follow the compiled state machines
(:mod:`ethimon.compiler._machines`), written as scans that are linear in the
trace and independent of the window length:

* ``prev``: a shift; the initial value at each segment start;
* ``held(e, n)``: the run of ``e`` since its last false cycle (a running maximum
  of indices) reaches ``n``;
* ``once(e, n)``: the last cycle with ``e`` lies within the window and the segment;
* ``since(a, b[, n])``: the last ``b`` lies in the segment (and the window) and no
  cycle after it had ``not a``;
* bounded response: the first trigger after the last cycle that met ``require``
  is ``n`` cycles old or more.
"""

from __future__ import annotations

import math

import numpy as np

from ..language._expr import (COMPARISON_MARGINS, CONNECTIVE_MARGINS, TEMPORAL, Binary, BoolLit, Call, Name, Node, Num,
                          Unary, comparison_margin, separation_distance)
from ..language._visit import ExprVisitor

__all__ = ["Evaluator", "TEMPORAL_FUNCS"]

TEMPORAL_FUNCS = tuple(sorted(TEMPORAL))  # the parser's set of temporal operators
INF = math.inf
#: numpy's function of each comparison and arithmetic operator of ``BINARY_OPS``
_ELEMENTWISE = {"<": np.less, "<=": np.less_equal, ">": np.greater, ">=": np.greater_equal, "==": np.equal,
                "!=": np.not_equal, "+": np.add, "-": np.subtract, "*": np.multiply, "/": np.divide}


def _or(a, b):
    if a is None:
        return b
    if b is None:
        return a
    return a | b


def last_index(mask: np.ndarray, idx: np.ndarray) -> np.ndarray:
    """For each position, the last position ``<= i`` where ``mask`` holds (-1 if none)."""
    return np.maximum.accumulate(np.where(mask, idx, idx.dtype.type(-1)))


def window_max(x: np.ndarray, w: int) -> np.ndarray:
    """``max(x[i-w+1 .. i])`` for every ``i`` (the window clipped at 0): van Herk/Gil-Werman, O(len) for any ``w``."""
    n = len(x)
    if n == 0:
        return x.copy()
    if w >= n:
        return np.maximum.accumulate(x)
    blocks = -(-n // w)
    pad = np.full(blocks * w, -INF)
    pad[:n] = x
    b = pad.reshape(blocks, w)
    pre = np.maximum.accumulate(b, axis=1).ravel()
    suf = np.maximum.accumulate(b[:, ::-1], axis=1)[:, ::-1].ravel()
    out = pre[:n].copy()
    np.maximum(suf[:n - w + 1], pre[w - 1:n], out=out[w - 1:])
    return out


def clamp_scan(lo: np.ndarray, hi: np.ndarray, block: int = 32) -> tuple[np.ndarray, np.ndarray]:
    """Inclusive prefix composition of the clamps ``x ↦ min(max(x, lo[i]), hi[i])`` (``lo <= hi``).

    Applying clamp ``f`` then clamp ``g`` is the clamp ``(clip(lo_f, lo_g, hi_g), clip(hi_f, lo_g, hi_g))``;
    the identity is ``(-inf, +inf)``. Blocked: a log-step scan inside blocks of ``block``, the
    same scan over the block totals, then one pass to apply each block's prefix.
    """
    n = len(lo)
    nb = -(-n // block)
    L = np.full(nb * block, -INF)
    H = np.full(nb * block, INF)
    L[:n] = lo
    H[:n] = hi
    L = L.reshape(nb, block)
    H = H.reshape(nb, block)
    k = 1
    while k < block:
        cl, ch = L[:, k:], H[:, k:]
        nl = np.minimum(np.maximum(L[:, :-k], cl), ch)
        nh = np.minimum(np.maximum(H[:, :-k], cl), ch)
        cl[...] = nl
        ch[...] = nh
        k *= 2
    if nb == 1:
        return L.ravel()[:n], H.ravel()[:n]
    tl, th = clamp_scan(L[:, -1].copy(), H[:, -1].copy(), block)
    pl = np.empty(nb)
    ph = np.empty(nb)
    pl[0], ph[0] = -INF, INF
    pl[1:], ph[1:] = tl[:-1], th[:-1]
    lo_out = np.minimum(np.maximum(pl[:, None], L), H)
    hi_out = np.minimum(np.maximum(ph[:, None], L), H)
    return lo_out.ravel()[:n], hi_out.ravel()[:n]


class Evaluator(ExprVisitor):
    """Values of every node of a plan on a set of cycles (see the module docstring)."""

    def __init__(self, plan, inputs, cycles: np.ndarray, starts: np.ndarray) -> None:
        self.plan = plan
        self.n = n = len(cycles)
        self.idx = np.arange(n, dtype=np.int32 if n < 2 ** 31 - 1 else np.int64)
        self.starts = starts
        self.single = n == 0 or not starts[1:].any()  # one segment: seg_first is 0 everywhere
        if self.single:
            self.seg_first = np.zeros(n, self.idx.dtype)
            self.pos = self.idx
        else:
            self.seg_first = np.maximum.accumulate(np.where(starts, self.idx, 0))
            self.pos = self.idx - self.seg_first
        everything = n == inputs.n  # every cycle, in order: the columns themselves
        self.env: dict[str, np.ndarray] = {s.name: inputs.values[s.name] if everything else
                                           inputs.values[s.name][cycles] for s in plan.signals}
        self.env["risk"] = inputs.risk if everything else inputs.risk[cycles]
        self.consts = plan.constants
        self.memo: dict[Node, tuple] = {}
        self.rmemo: dict[Node, tuple] = {}
        self.update_err = None  # where a temporal operator's arguments raise

    # -- values -------------------------------------------------------------------
    def full(self, v, kind: str) -> np.ndarray:
        dtype = bool if kind == "bool" else np.float64
        a = np.asarray(v, dtype=dtype)
        return np.broadcast_to(a, (self.n,)) if a.ndim == 0 else a

    def ev(self, node: Node):
        key = node  # by identity (a node is never equal to another)
        got = self.memo.get(key)
        if got is None:
            got = self._ev(node)
            self.memo[key] = got
        return got

    def _ev(self, node: Node):
        return self.visit(node)

    # the offline back-end of the interpreter protocol: each visit_* gives ``(value, err)``
    def visit_num(self, node: Num):
        return np.float64(node.value), None

    def visit_bool(self, node: BoolLit):
        return np.bool_(node.value), None

    def visit_name(self, node: Name):
        if node.id in self.consts:
            return np.float64(self.consts[node.id]), None
        return self.env[node.id], None

    def visit_neg(self, node: Unary):
        v, e = self.ev(node.operand)
        return np.negative(v), e

    def visit_not(self, node: Unary):
        v, e = self.ev(node.operand)
        return np.logical_not(v), e

    def _elementwise(self, node: Binary):
        """A comparison or arithmetic: numpy's function of the operator on both arrays."""
        (lv, le), (rv, re) = self.ev(node.left), self.ev(node.right)
        return _ELEMENTWISE[node.op](lv, rv), _or(le, re)

    visit_lt = visit_le = visit_gt = visit_ge = visit_eq = visit_ne = _elementwise
    visit_add = visit_sub = visit_mul = _elementwise

    def visit_div(self, node: Binary):
        v, e = self._elementwise(node)
        return v, _or(e, self.full(self.ev(node.right)[0] == 0.0, "bool"))

    def visit_and(self, node: Binary):
        (lv, le), (rv, re) = self.ev(node.left), self.ev(node.right)
        return np.logical_and(lv, rv), _or(le, None if re is None else lv & re)

    def visit_or(self, node: Binary):
        (lv, le), (rv, re) = self.ev(node.left), self.ev(node.right)
        return np.logical_or(lv, rv), _or(le, None if re is None else ~lv & re)

    def visit_implies(self, node: Binary):
        (lv, le), (rv, re) = self.ev(node.left), self.ev(node.right)
        return np.logical_or(np.logical_not(lv), rv), _or(le, None if re is None else lv & re)

    def _args(self, node: Call):
        """The arguments' values and where any of them raises."""
        vals = [self.ev(a) for a in node.args]
        e = None
        for _, ae in vals:
            e = _or(e, ae)
        return vals, e

    def visit_abs(self, node: Call):
        vals, e = self._args(node)
        return np.abs(vals[0][0]), e

    def visit_sqrt(self, node: Call):
        vals, e = self._args(node)
        x = vals[0][0]
        return np.sqrt(x), _or(e, self.full(x < 0.0, "bool"))

    def visit_separation_distance(self, node: Call):  # an argument that is not >= 0 (negative, NaN) raises
        vals, e = self._args(node)
        with np.errstate(invalid="ignore", over="ignore"):
            for v, _ in vals:
                if np.ndim(v) or not v >= 0.0:  # a constant is >= 0 (the compiler checks)
                    e = _or(e, self.full(~(np.asarray(v) >= 0.0), "bool"))
            return separation_distance(*(v for v, _ in vals)), e

    def visit_min(self, node: Call):
        vals, e = self._args(node)
        cur = vals[0][0]
        for v, _ in vals[1:]:  # Python's min: keep the first unless a later one is strictly smaller
            cur = np.where(v < cur, v, cur)
        return cur, e

    def visit_max(self, node: Call):
        vals, e = self._args(node)
        cur = vals[0][0]
        for v, _ in vals[1:]:  # Python's max: keep the first unless a later one is strictly larger
            cur = np.where(v > cur, v, cur)
        return cur, e

    # -- temporal operators ------------------------------------------------------
    def _operands(self, node: Call, count: int) -> list:
        """The first ``count`` arguments' values (not the window bound); where they raise is an
        update error (the monitor updates every temporal operator every cycle)."""
        args = [self.ev(a) for a in node.args[:count]]
        for _, e in args:
            self.update_err = _or(self.update_err, e)
        return args

    def visit_prev(self, node: Call):
        args = self._operands(node, 2)
        kind = node.ann.ty.kind
        cur = self.full(args[0][0], kind)
        out = np.empty(self.n, dtype=cur.dtype)
        out[1:] = cur[:-1]
        st = self.starts
        if len(args) == 2:
            out[st] = self.full(args[1][0], kind)[st]
        elif kind == "bool":
            out[st] = False
        else:
            out[st] = cur[st]
        return out, None

    def visit_held(self, node: Call):
        e = self.full(self._operands(node, 1)[0][0], "bool")
        idx = self.idx
        base = last_index(~e, idx)
        if not self.single:
            base = np.maximum(base, self.seg_first - 1)
        return idx - base >= node.ann.window, None

    def visit_once(self, node: Call):
        e = self.full(self._operands(node, 1)[0][0], "bool")
        n = node.ann.window
        return last_index(e, self.idx) >= np.maximum(self.seg_first, self.idx - (n - 1)), None

    def visit_since(self, node: Call):
        (av, _), (bv, _) = self._operands(node, 2)
        a, b = self.full(av, "bool"), self.full(bv, "bool")
        idx, n = self.idx, node.ann.window
        lb = last_index(b, idx)
        out = (lb >= self.seg_first) & (last_index(~a, idx) <= lb)
        if n is not None:
            out &= idx - lb < n
        return out, None

    def touch_temporal(self) -> None:
        """Evaluate every temporal operator (the monitor updates them all every cycle)."""
        for node in self.plan.temporal:
            self.ev(node)

    # -- obligations -------------------------------------------------------------
    def obligation(self, ob) -> tuple[np.ndarray, np.ndarray | None]:
        """``(violated, err)`` of one obligation, as its compiled closure judges it."""
        rv, re = self.ev(ob.require)
        req = self.full(rv, "bool")
        n = ob.within_cycles
        if not n:
            if ob.when is None:
                return ~req, re
            wv, we = self.ev(ob.when)
            w = self.full(wv, "bool")
            return w & ~req, _or(we, None if re is None else w & re)
        if ob.when is None:
            w, we = np.ones(self.n, bool), None
        else:
            wv, we = self.ev(ob.when)
            w = self.full(wv, "bool")
        idx = self.idx
        base = last_index(req, idx)  # last cycle that met require
        if not self.single:
            base = np.maximum(base, self.seg_first - 1)
        nxt = np.empty(self.n + 1, dtype=idx.dtype)  # first trigger at or after each position
        nxt[-1] = self.n
        nxt[:-1] = np.minimum.accumulate(np.where(w, idx, self.n)[::-1])[::-1]
        return nxt[base + 1] <= idx - n, _or(we, re)

    # -- margins -----------------------------------------------------------------
    def rob(self, node: Node):
        key = node  # by identity (a node is never equal to another)
        got = self.rmemo.get(key)
        if got is None:
            got = self._rob(node)
            self.rmemo[key] = got
        return got

    def _rob(self, node: Node):
        """Robustness ``(value, err)`` as the compiled margins compute it (no short-circuit)."""
        if isinstance(node, Binary):
            op = node.op
            if op in COMPARISON_MARGINS and node.left.ann.ty.kind == "num":
                (a, ae), (b, be) = self.ev(node.left), self.ev(node.right)
                return self.full(comparison_margin(op, a, b), "num"), _or(ae, be)
            if op in CONNECTIVE_MARGINS:  # Python's min/max elementwise: the right where strictly smaller/larger
                combine, negate_left = CONNECTIVE_MARGINS[op]
                (f, fe), (g, ge) = self.rob(node.left), self.rob(node.right)
                if negate_left:
                    f = -f
                pick = (g < f) if combine == "min" else (g > f)
                return np.where(pick, g, f), _or(fe, ge)
        if isinstance(node, Unary) and node.op == "not":
            f, fe = self.rob(node.operand)
            return -f, fe
        v, e = self.ev(node)
        return np.where(self.full(v, "bool"), INF, -INF), e

    def margin(self, ob) -> np.ndarray:
        """The obligation's margin on every cycle (NaN where it cannot be computed)."""
        rr, re = self.rob(ob.require)
        a = we = None
        if ob.when is not None:
            rw, we = self.rob(ob.when)
            a = -rw
        n = ob.within_cycles
        if not n:
            out = rr if a is None else np.where(rr > a, rr, a)  # Python's max(-rw, rr)
            err = _or(re, we)
            return out if err is None else np.where(err, np.nan, out)
        # a bounded response treats a term that raised like a NaN term
        if re is not None:
            rr = np.where(re, np.nan, rr)
        if a is None:
            a = np.full(self.n, -INF)
        elif we is not None:
            a = np.where(we, np.nan, a)
        return self._bounded_margin(a, rr, n)

    def _bounded_margin(self, a: np.ndarray, b: np.ndarray, n: int) -> np.ndarray:
        """``M(t) = min(max(M(t−1), b(t)), max(a(t−n), max b(t−n..t)))`` per segment, +inf for the first
        ``n`` cycles, NaN from the first due window holding a NaN (as ``_machines.bounded_margin``).

        ``x ↦ min(max(x, lo), hi)`` with ``lo <= hi`` is a clamp, and clamps compose into clamps,
        so the recurrence is a prefix scan (:func:`clamp_scan`); a segment's first cycle is the
        constant +inf, which also cuts the scan at every segment boundary.
        """
        idx, sf, pos = self.idx, self.seg_first, self.pos
        due = pos >= n
        if self.single:  # the trigger that falls due at each position: n cycles back
            lag = None
            cand = np.empty_like(a)
            cand[n:] = a[:max(self.n - n, 0)]
            cand[:n] = a[:n]
        else:
            lag = np.where(due, idx - n, idx)
            cand = a[lag]
        nan_b = np.isnan(b)
        nan_a = np.isnan(a)
        unknown = None
        if nan_b.any() or nan_a.any():
            cb = np.concatenate(([0], np.cumsum(nan_b)))
            ca = np.concatenate(([0], np.cumsum(nan_a)))
            if lag is None:
                lag = np.where(due, idx - n, idx)
            unknown = due & ((cb[idx + 1] - cb[sf] > 0) | (ca[lag + 1] - ca[sf] > 0))
            b = np.where(nan_b, -INF, b)
        top = window_max(b, n + 1)
        ok = due if unknown is None else due & ~unknown
        hi = np.where(ok, np.where(top > cand, top, cand), INF)
        lo = np.where(ok, b, INF)
        if unknown is not None:
            lo = np.where(np.isnan(lo), 0.0, lo)
            hi = np.where(np.isnan(hi), 0.0, hi)
        _, out = clamp_scan(lo, hi)
        out = np.where(due, out, INF)
        return out if unknown is None else np.where(unknown, np.nan, out)
