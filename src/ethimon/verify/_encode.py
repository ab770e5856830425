"""Translate a compiled :class:`~ethimon.compiler.Plan` into z3, unrolled over k cycles.

This module imports z3 at import time; :mod:`ethimon.verify` only imports it
after checking that z3 is installed.

The encoding follows the semantics documented in
:mod:`ethimon.testing._reference` (the definition both the compiled monitor and
the reference interpreter implement), over the same checked ASTs, windows and
types that ``ethimon.compiler._closures.build_machine`` compiles:

* every cycle ``t`` of a trace that starts at a reset (or just after a fault,
  which clears the history) gets one z3 variable per declared signal, bounded
  by its declared range, and one real ``R_t`` for R_e, bounded by the range
  the monitor accepts as a ``risk`` input (which contains every R_e the
  formula can produce, see the ``risk.bounds`` property);
* temporal operators are unrolled from their definitions (``held``, ``once``,
  ``since``, ``prev`` look back over the trace; windows are not full at its
  start);
* ``defined(node, t)`` is the condition under which evaluating ``node`` at
  ``t`` raises nothing (no division by zero, no ``sqrt`` of a negative, no
  negative ``separation_distance`` argument),
  honouring the short-circuit order of ``and``/``or``/``implies`` that both
  implementations use;
* with ``free_history=True`` the trace is a window cut out of a longer run
  instead: a temporal node whose look-back reaches before the first encoded
  cycle is a fresh unconstrained value (any history), and an unbounded
  ``since`` carries an unknown bit in. Such a trace over-approximates every
  run, so "no such window" is a proof about all runs of any length;
* the release bound ``τ − δ`` is the exact rational of the spec's decimals and R_e
  is read as the decimal it prints as (:func:`release_below`: ``R < cut``), not the
  float ``0.27 - 0.05 == 0.22000000000000003`` nor R_e's binary value;
* :func:`decision_trace` encodes the decision logic of ``Monitor.step``
  (severity, latch, hysteresis release) from a symbolic initial latch state.
"""

from __future__ import annotations

import struct
from dataclasses import dataclass, field
from fractions import Fraction

import z3

from ..compiler import plan_of
from ..compiler._plan import RISK_NAME, Plan
from ..language._expr import BINARY_OPS, TEMPORAL, Binary, BoolLit, Call, Name, Node, Num, Unary, separation_distance, walk
from ..language._visit import ExprVisitor

__all__ = ["Unrolled", "FloatUnrolled", "float_value", "DecisionTrace", "RuleInfo", "decision_trace", "rules_of", "lookback", "real", "release_below",
           "risk_input_range", "z3_value"]


def real(x: float) -> z3.ArithRef:
    """The exact rational value of a Python float as a z3 real."""
    f = Fraction(x)
    return z3.RealVal(f"{f.numerator}/{f.denominator}") if f.denominator != 1 else z3.RealVal(f.numerator)


def release_below(spec) -> z3.ArithRef:
    """The release test ``R_e < τ − δ`` as the monitor makes it: ``R < cut``, the plan's
    ``release_cut`` (R_e read as the decimal it prints as, against the exact τ − δ of the spec's
    decimals; for every float R_e the two tests agree). ``spec``: a Spec or its Plan."""
    return real(plan_of(spec).release_cut)


def z3_value(model: z3.ModelRef, expr) -> float | bool:
    """A concrete Python value of ``expr`` under ``model`` (reals become floats)."""
    if z3.is_fp(expr):
        return float_value(model, expr)
    v = model.eval(expr, model_completion=True)
    if z3.is_bool(v):
        return bool(z3.is_true(v))
    if z3.is_rational_value(v):
        f = v.as_fraction()
        return float(Fraction(f.numerator, f.denominator))
    if z3.is_algebraic_value(v):
        return float(Fraction(v.approx(20).as_fraction()))
    if z3.is_int_value(v):
        return float(v.as_long())
    raise TypeError(f"cannot read z3 value {v}")  # pragma: no cover


def risk_input_range(plan: Plan) -> tuple[float, float]:
    """The interval of ``risk`` inputs the monitor accepts: the plan's ``risk_plan.accepted``, the
    one place it is written (``Monitor`` reads the same)."""
    return plan.risk_plan.accepted


def lookback(plan: Plan, node: Node) -> int:
    """Extra past cycles ``node`` reads (``None`` windows count as 1: their state is one bit)."""
    # derived from the operator table: each row's lookback (language/_operators.py, Operator.cycles_back)
    inner = max((lookback(plan, child) for child in node.children), default=0)
    row = node.row
    return inner if row is None else inner + row.cycles_back(node.ann.window)


class Unrolled(ExprVisitor):
    """z3 variables and expressions of one k-cycle trace of a plan (all inputs valid).

    Args:
        plan: the compiled plan (the same object the runtime builds its closures from).
        k: number of cycles to unroll.
        prefix: variable-name prefix (to put several traces in one solver).
        free_history: the first cycle is not a reset but any point of a longer run (see the module doc).
    """

    def _tables(self, plan: Plan, k: int, prefix: str, free_history: bool) -> None:
        """The per-trace tables both encodings fill (reals here, doubles in :class:`FloatUnrolled`)."""
        self.plan = plan
        self.k = k
        self.prefix = prefix
        self.free_history = free_history
        self._lb: dict[Node, int] = {}
        self.sig: list[dict[str, z3.ExprRef]] = []
        self.R: list = []
        self.domain: list[z3.BoolRef] = []
        self._ev: dict[tuple[Node, int], z3.ExprRef] = {}
        self._df: dict[tuple[Node, int], z3.BoolRef] = {}
        self._obdf: dict[tuple[int, int], z3.BoolRef] = {}
        self._alldf: list[z3.BoolRef] = []
        self._aux: list[z3.BoolRef] = []

    def __init__(self, plan: Plan, k: int, prefix: str = "", free_history: bool = False) -> None:
        self._tables(plan, k, prefix, free_history)
        rlo, rhi = risk_input_range(plan)
        for t in range(k):
            row: dict[str, z3.ExprRef] = {}
            for s in plan.signals:
                name = f"{prefix}{s.name}@{t}"
                if s.kind == "bool":
                    row[s.name] = z3.Bool(name)
                else:
                    v = z3.Real(name)
                    row[s.name] = v
                    self.domain += [v >= real(s.lo), v <= real(s.hi)]
            self.sig.append(row)
            r = z3.Real(f"{prefix}R_e@{t}")
            self.R.append(r)
            self.domain += [r >= real(rlo), r <= real(rhi)]

    @property
    def constraints(self) -> list[z3.BoolRef]:
        """Domain constraints plus definitions of auxiliary variables (``sqrt``)."""
        return self.domain + self._aux

    # -- values -------------------------------------------------------------------
    def ev(self, node: Node, t: int) -> z3.ExprRef:
        """The value of ``node`` at cycle ``t`` (``0 <= t < k``)."""
        key = (node, t)
        got = self._ev.get(key)
        if got is None:
            got = self._ev[key] = self._ev_new(node, t)
        return got

    def _ev_new(self, node: Node, t: int) -> z3.ExprRef:
        return self.visit(node, t)

    # the z3 back-end of the interpreter protocol: each visit_*(node, t) is the node's term at cycle t
    def visit_num(self, node: Num, t: int) -> z3.ExprRef:
        return real(node.value)

    def visit_bool(self, node: BoolLit, t: int) -> z3.ExprRef:
        return z3.BoolVal(node.value)

    def visit_name(self, node: Name, t: int) -> z3.ExprRef:
        if node.id in self.plan.constants:
            return real(self.plan.constants[node.id])
        if node.id == RISK_NAME:
            return self.R[t]
        return self.sig[t][node.id]

    def visit_neg(self, node: Unary, t: int) -> z3.ExprRef:
        return -self.ev(node.operand, t)

    def visit_not(self, node: Unary, t: int) -> z3.ExprRef:
        return z3.Not(self.ev(node.operand, t))

    def _apply(self, node: Binary, t: int) -> z3.ExprRef:
        """The parser's one table: the same ``operator`` call builds the z3 term."""
        return BINARY_OPS[node.op][1](self.ev(node.left, t), self.ev(node.right, t))

    visit_lt = visit_le = visit_gt = visit_ge = visit_eq = visit_ne = _apply
    visit_add = visit_sub = visit_mul = visit_div = _apply

    def visit_and(self, node: Binary, t: int) -> z3.ExprRef:
        return z3.And(self.ev(node.left, t), self.ev(node.right, t))

    def visit_or(self, node: Binary, t: int) -> z3.ExprRef:
        return z3.Or(self.ev(node.left, t), self.ev(node.right, t))

    def visit_implies(self, node: Binary, t: int) -> z3.ExprRef:
        return z3.Implies(self.ev(node.left, t), self.ev(node.right, t))

    def visit_abs(self, node: Call, t: int) -> z3.ExprRef:
        v = self.ev(node.args[0], t)
        return z3.If(v >= 0, v, -v)

    def visit_sqrt(self, node: Call, t: int) -> z3.ExprRef:
        v = self.ev(node.args[0], t)
        s = z3.Real(f"{self.prefix}sqrt#{node.ann.serial}@{t}")
        # s = sqrt(v) where defined; unconstrained otherwise (that case is a fault)
        self._aux.append(z3.Implies(v >= 0, z3.And(s >= 0, s * s == v)))
        return s

    def visit_separation_distance(self, node: Call, t: int) -> z3.ExprRef:
        # the same + and * as the monitor: linear in the signals while the times are
        # constants (exact), a product of reals when a time is a signal (z3's nonlinear arithmetic)
        return separation_distance(*(self.ev(a, t) for a in node.args))

    def _extremum(self, node: Call, t: int) -> z3.ExprRef:
        vals = [self.ev(a, t) for a in node.args]
        out = vals[0]
        for v in vals[1:]:
            # Python's min/max keep the first of equal values; equal reals are equal
            out = z3.If(v < out, v, out) if node.func == "min" else z3.If(v > out, v, out)
        return out

    visit_min = visit_max = _extremum

    # -- temporal operators, unrolled from their definitions --------------------------
    def _history(self, node: Call, t: int) -> z3.ExprRef | None:
        """With ``free_history``: the term of a temporal node whose look-back reaches before the first
        encoded cycle (any value a history could leave), else ``None``."""
        if not self.free_history:
            return None
        lb = self._lb.get(node)
        if lb is None:
            lb = self._lb[node] = lookback(self.plan, node)
        if t < lb:  # reads cycles before the window: any value a history could leave
            name = f"{self.prefix}hist#{node.ann.serial}@{t}"
            return z3.Bool(name) if node.ann.ty.kind == "bool" else z3.Real(name)
        return None

    def visit_prev(self, node: Call, t: int) -> z3.ExprRef:
        free = self._history(node, t)
        if free is not None:
            return free
        args = node.args
        if t == 0:
            if len(args) == 2:
                return self.ev(args[1], 0)
            return z3.BoolVal(False) if node.ann.ty.kind == "bool" else self.ev(args[0], 0)
        return self.ev(args[0], t - 1)

    def visit_held(self, node: Call, t: int) -> z3.ExprRef:
        free = self._history(node, t)
        if free is not None:
            return free
        n = node.ann.window
        if t + 1 < n:
            return z3.BoolVal(False)
        return z3.And([self.ev(node.args[0], j) for j in range(t - n + 1, t + 1)])

    def visit_once(self, node: Call, t: int) -> z3.ExprRef:
        free = self._history(node, t)
        if free is not None:
            return free
        n = node.ann.window
        return z3.Or([self.ev(node.args[0], j) for j in range(max(0, t - n + 1), t + 1)])

    def visit_since(self, node: Call, t: int) -> z3.ExprRef:
        free = self._history(node, t)
        if free is not None:
            return free
        a, b = node.args[0], node.args[1]
        n = node.ann.window
        if self.free_history and n is None:  # since(t) = b(t) or (a(t) and since(t - 1))
            return z3.Or(self.ev(b, t), z3.And(self.ev(a, t), self.ev(node, t - 1)))
        first = 0 if n is None else max(0, t - n + 1)
        terms = []
        for j in range(first, t + 1):
            terms.append(z3.And([self.ev(b, j)] + [self.ev(a, m) for m in range(j + 1, t + 1)]))
        return z3.Or(terms)

    # -- definedness ---------------------------------------------------------------
    def defined(self, node: Node, t: int) -> z3.BoolRef:
        """Evaluating ``node`` at ``t`` raises nothing (temporal nodes read stored state)."""
        key = (node, t)
        got = self._df.get(key)
        if got is None:
            got = self._df[key] = z3.simplify(self._df_new(node, t))
        return got

    def _df_new(self, node: Node, t: int) -> z3.BoolRef:
        """Read from the node's row: a leaf raises nothing; a temporal operator reads stored state;
        the connectives short-circuit left to right; a row that may raise adds its own condition
        (:data:`RAISE_FREE`, by row: a row that may raise without one is refused, never taken as
        defined); any other row is defined where its operands are."""
        row = node.row
        if row is None:
            if isinstance(node, (Num, BoolLit, Name)):
                return z3.BoolVal(True)
            raise TypeError(f"cannot encode {node!r}")  # pragma: no cover
        if row.family == "temporal":
            return z3.BoolVal(True)
        if row.family == "logic":
            da, db = self.defined(node.left, t), self.defined(node.right, t)
            left = self.ev(node.left, t)
            return z3.And(da, z3.Implies(z3.Not(left) if row.name == "or" else left, db))
        ds = [self.defined(a, t) for a in node.children]
        if row.kind == "unary":  # -x, not e: defined where the operand is
            return ds[0]
        if row.may_raise is not None:
            own = RAISE_FREE.get(row.name)
            if own is None:
                raise TypeError(f"the operator table says {row.label} may raise ({row.may_raise}), but the z3 "
                                f"encoder has no condition for it: add {row.name!r} to verify/_encode.py:RAISE_FREE")
            ds += own(self, node, t)
        return z3.And(ds)

    # what raises, in this encoding's arithmetic (reals here; IEEE doubles in FloatUnrolled)
    @staticmethod
    def _nonzero(v):
        return v != 0

    @staticmethod
    def _nonneg(v):
        return v >= 0

    @staticmethod
    def _sqrt_ok(v):
        return v >= 0

    def temporal_nodes(self, root: Node) -> list[Call]:
        """Temporal calls inside ``root`` (each has its arguments evaluated every cycle)."""
        return [n for n in walk(root) if isinstance(n, Call) and n.func in TEMPORAL]

    def obligation_defined(self, ob, t: int) -> z3.BoolRef:
        """Evaluating obligation ``ob`` at ``t`` raises nothing (its temporal updates included)."""
        key = (ob.index, t)
        got = self._obdf.get(key)
        if got is None:
            got = self._obdf[key] = self._obligation_defined(ob, t)
        return got

    def all_defined(self, upto: int) -> z3.BoolRef:
        """Every obligation can be evaluated at every cycle ``0 .. upto`` (no fault)."""
        while len(self._alldf) <= upto:
            t = len(self._alldf)
            now = [self.obligation_defined(ob, t) for ob in self.plan.obligations]
            self._alldf.append(z3.And(([self._alldf[-1]] if self._alldf else []) + now))
        return self._alldf[upto]

    def _obligation_defined(self, ob, t: int) -> z3.BoolRef:
        parts = []
        for root in (ob.when, ob.require):
            if root is None:
                continue
            for call in self.temporal_nodes(root):
                parts += [self.defined(a, t) for a in call.args]
        if ob.when is None:
            parts.append(self.defined(ob.require, t))
        elif ob.within_cycles:
            parts += [self.defined(ob.when, t), self.defined(ob.require, t)]
        else:
            parts += [self.defined(ob.when, t), z3.Implies(self.ev(ob.when, t), self.defined(ob.require, t))]
        return z3.And(parts)

    def decisive(self, eps: float = 1e-6) -> list[z3.BoolRef]:
        """Every ordering comparison of every obligation is at least ``eps`` from its boundary.

        For witnesses that must replay in the float :class:`~ethimon.Monitor`: a value exactly on a
        boundary (``0.79 >= 1.6 * (0.1 + 0.3) + 0.15``) can flip with rounding.
        """
        out = []
        for ob in self.plan.obligations:
            for root in (ob.when, ob.require):
                if root is None:
                    continue
                for n in walk(root):
                    if isinstance(n, Binary) and n.op in ("<", "<=", ">", ">="):
                        for t in range(self.k):
                            d = self.ev(n.left, t) - self.ev(n.right, t)
                            out.append(z3.Or(d >= real(eps), d <= -real(eps)))
        return out

    # -- obligations ------------------------------------------------------------------
    def violated(self, ob, t: int) -> z3.BoolRef:
        """Obligation ``ob`` is violated at ``t`` (documented semantics, bounded response included).

        With ``free_history`` a trigger before the first encoded cycle is not counted: that
        only removes violations, so a window that is clean in a real run stays clean here.
        """
        n = ob.within_cycles
        when = (lambda j: z3.BoolVal(True)) if ob.when is None else (lambda j: self.ev(ob.when, j))
        if not n:
            return z3.And(when(t), z3.Not(self.ev(ob.require, t)))
        terms = []
        for j in range(0, t - n + 1):
            terms.append(z3.And([when(j)] + [z3.Not(self.ev(ob.require, m)) for m in range(j, t + 1)]))
        return z3.Or(terms) if terms else z3.BoolVal(False)


#: per row of the operator table that may raise (``may_raise``): the conditions under which it does
#: not, in the encoding's arithmetic (``_nonzero``, ``_sqrt_ok``, ``_nonneg``: reals in
#: :class:`Unrolled`, doubles in :class:`FloatUnrolled`)
RAISE_FREE = {
    "div": lambda enc, node, t: [enc._nonzero(enc.ev(node.right, t))],  # a divisor of 0
    "sqrt": lambda enc, node, t: [enc._sqrt_ok(enc.ev(node.args[0], t))],  # a negative argument
    "separation_distance": lambda enc, node, t: [enc._nonneg(enc.ev(a, t)) for a in node.args],
}

F64 = z3.Float64()
_RNE = z3.RNE()


def float_value(model: z3.ModelRef, expr) -> float:
    """The Python float an IEEE-754 double term ``expr`` has under ``model`` (bit for bit)."""
    bits = model.eval(z3.fpToIEEEBV(expr), model_completion=True).as_long()
    return struct.unpack("<d", struct.pack("<Q", bits))[0]


def _fpv(x: float) -> z3.FPRef:
    return z3.FPVal(float(x), F64)


class _F:
    """A double term with the arithmetic of Python floats (round to nearest even), for formulas
    written with ``+`` and ``*`` (``separation_distance``)."""

    __slots__ = ("e",)

    def __init__(self, e) -> None:
        self.e = e

    def __add__(self, o: "_F") -> "_F":
        return _F(z3.fpAdd(_RNE, self.e, o.e))

    def __mul__(self, o: "_F") -> "_F":
        return _F(z3.fpMul(_RNE, self.e, o.e))


class FloatUnrolled(Unrolled):
    """:class:`Unrolled` in the monitor's own arithmetic: every number an IEEE-754 double
    (z3 ``Float64``, round to nearest even, as Python floats compute), so that division by a
    float zero (``1/(a*b)`` with ``a = b = 1e-200``: the product underflows to 0), overflow to
    infinity and NaN are modelled. Signals are finite doubles in their declared range, R_e a
    finite double in the range the monitor accepts. Used for what the reals cannot show: whether
    evaluation raises (:meth:`obligation_defined`); ``free_history`` is not supported.
    """

    def __init__(self, plan: Plan, k: int, prefix: str = "") -> None:
        self._tables(plan, k, prefix, False)
        rlo, rhi = risk_input_range(plan)

        def bounded(v, lo, hi):
            c = [z3.Not(z3.fpIsNaN(v)), z3.Not(z3.fpIsInf(v))]
            if lo > -1.8e308:
                c.append(z3.fpGEQ(v, _fpv(lo)))
            if hi < 1.8e308:
                c.append(z3.fpLEQ(v, _fpv(hi)))
            return c
        for t in range(k):
            row: dict[str, z3.ExprRef] = {}
            for sg in plan.signals:
                name = f"{prefix}{sg.name}@{t}"
                if sg.kind == "bool":
                    row[sg.name] = z3.Bool(name)
                else:
                    v = z3.FP(name, F64)
                    row[sg.name] = v
                    self.domain += bounded(v, sg.lo, sg.hi)
            self.sig.append(row)
            r = z3.FP(f"{prefix}R_e@{t}", F64)
            self.R.append(r)
            self.domain += bounded(r, rlo, rhi)

    # the protocol's methods whose double arithmetic differs from the reals (the rest are Unrolled's)
    def visit_num(self, node: Num, t: int) -> z3.ExprRef:
        return _fpv(node.value)

    def visit_name(self, node: Name, t: int) -> z3.ExprRef:
        if node.id in self.plan.constants:
            return _fpv(self.plan.constants[node.id])
        return super().visit_name(node, t)

    def visit_neg(self, node: Unary, t: int) -> z3.ExprRef:
        return z3.fpNeg(self.ev(node.operand, t))

    def visit_add(self, node: Binary, t: int) -> z3.ExprRef:
        return z3.fpAdd(_RNE, self.ev(node.left, t), self.ev(node.right, t))

    def visit_sub(self, node: Binary, t: int) -> z3.ExprRef:
        return z3.fpSub(_RNE, self.ev(node.left, t), self.ev(node.right, t))

    def visit_mul(self, node: Binary, t: int) -> z3.ExprRef:
        return z3.fpMul(_RNE, self.ev(node.left, t), self.ev(node.right, t))

    def visit_div(self, node: Binary, t: int) -> z3.ExprRef:
        return z3.fpDiv(_RNE, self.ev(node.left, t), self.ev(node.right, t))

    def visit_eq(self, node: Binary, t: int) -> z3.ExprRef:
        return z3.fpEQ(self.ev(node.left, t), self.ev(node.right, t))  # IEEE: -0.0 == 0.0, NaN == NaN is false

    def visit_ne(self, node: Binary, t: int) -> z3.ExprRef:
        return z3.Not(z3.fpEQ(self.ev(node.left, t), self.ev(node.right, t)))
    # <, <=, >, >=: Unrolled's BINARY_OPS call builds z3's fp.lt & co., false on NaN as in Python

    def visit_abs(self, node: Call, t: int) -> z3.ExprRef:
        return z3.fpAbs(self.ev(node.args[0], t))

    def visit_sqrt(self, node: Call, t: int) -> z3.ExprRef:
        return z3.fpSqrt(_RNE, self.ev(node.args[0], t))

    def visit_separation_distance(self, node: Call, t: int) -> z3.ExprRef:
        return separation_distance(*(_F(self.ev(a, t)) for a in node.args)).e

    @staticmethod
    def _nonzero(v):
        return z3.Not(z3.fpIsZero(v))  # x / -0.0 raises ZeroDivisionError too

    @staticmethod
    def _nonneg(v):
        return z3.fpGEQ(v, _fpv(0.0))  # false on NaN: a NaN argument is an evaluation error too

    @staticmethod
    def _sqrt_ok(v):
        return z3.Not(z3.fpLT(v, _fpv(0.0)))  # math.sqrt(nan) is nan, math.sqrt(-1e-300) raises


@dataclass
class DecisionTrace:
    """The decision of every cycle of an unrolled trace, as z3 terms.

    The latch is one per rule (``rules``: the obligations in order, then ``"risk"``,
    then ``"fault"``), each with its start state (``lat0``/``cnt0``: latched, count of
    consecutive cycles its release condition held) and its state after each cycle
    (``lat[t]``/``cnt[t]``); ``cond[t][k]``: rule ``k``'s release condition at ``t``.
    ``L0``/``latched_after``: the most severe latched response (0: none); ``C0``/
    ``clean_after``: the sum of the counts (0 exactly when every count is 0).
    """

    enc: Unrolled
    L0: z3.ArithRef
    C0: z3.ArithRef
    init: list[z3.BoolRef]
    violated: list[list[z3.BoolRef]]  # [t][obligation]
    risk_fires: list[z3.BoolRef]
    sev: list[z3.ArithRef]
    override: list[z3.BoolRef]
    response: list[z3.ArithRef]  # severity of the response (0 = none)
    latched_after: list[z3.ArithRef]
    clean_after: list[z3.ArithRef]
    rules: list[RuleInfo] = field(default_factory=list)
    lat0: list[z3.BoolRef] = field(default_factory=list)
    cnt0: list[z3.ArithRef] = field(default_factory=list)
    lat: list[list[z3.BoolRef]] = field(default_factory=list)  # [t][rule]
    cnt: list[list[z3.ArithRef]] = field(default_factory=list)
    cond: list[list[z3.BoolRef]] = field(default_factory=list)

    def start_with(self, names) -> list[z3.BoolRef]:
        """Start with exactly the rules ``names`` latched, every count 0 (``["fault"]``: right
        after a fault cycle that fired nothing else; ``[]``: a fresh monitor)."""
        names = set(names)
        return [z3.And(l0 if r.name in names else z3.Not(l0), c0 == 0)
                for r, l0, c0 in zip(self.rules, self.lat0, self.cnt0)]


@dataclass(frozen=True)
class RuleInfo:
    """One latching rule: ``name`` (obligation id, ``"risk"`` or ``"fault"``), its response
    severity, whether its release is manual, and its ``hold_cycles``."""

    name: str
    sev: int
    manual: bool
    hold: int


def rules_of(plan) -> list[RuleInfo]:
    """Every latching rule of a plan, in the monitor's order, as the plan resolved them."""
    return [RuleInfo(ob.id, ob.response.severity, ob.manual, ob.release_hold) for ob in plan.obligations] + [
        RuleInfo(r.name, r.severity, r.manual, r.hold) for r in (plan.risk_rule, plan.fault_rule)]


def _max(a, b):
    return z3.If(a >= b, a, b)


def decision_trace(enc: Unrolled, *, fresh: bool = False, prefix: str = "",
                   only: int | None = None) -> DecisionTrace:
    """Encode ``Monitor.step``'s decision logic over ``enc``'s cycles.

    With ``only=i`` just obligation ``i`` is encoded; the other obligations are one
    free severity (0 to 4) each cycle for their verdicts and one for their latches,
    and their verdicts free booleans. That admits every real trace (and more), so a
    property proved over it holds for the spec: a small problem instead of one with
    every obligation in it.

    The trace starts with a symbolic latch state (per rule: latched or not, and its
    count, below its hold for an automatic release, up to it for a manual one), which
    covers a fresh monitor (``fresh=True`` pins it to nothing latched) and the state
    right after any fault (a fault clears the temporal history but keeps the latches).

    Per rule, at a cycle: if it fires (the obligation is violated, R_e ≥ τ) it is
    latched with count 0; else, if latched, its count goes up by one when its release
    condition holds (not violated; R_e < τ − δ; for the fault rule any cycle of the
    trace, which has no faults) and to 0 otherwise; an automatic rule whose count
    reaches its hold is released; a manual one keeps the count at its hold (ready for
    ``acknowledge()``). Override: some rule latched; response: the most severe one.
    """
    plan = enc.plan
    tau = real(plan.threshold)
    below = release_below(plan)
    rules = rules_of(plan)
    n = len(plan.obligations)
    ri = n
    encoded = [only is None or i == only for i in range(n)] + [True, True]
    zero = z3.IntVal(0)
    lat0 = [z3.Bool(f"{prefix}latched#{k}@start") for k in range(n + 2)]
    cnt0 = [z3.Int(f"{prefix}count#{k}@start") for k in range(n + 2)]
    init: list[z3.BoolRef] = []
    for k, r in enumerate(rules):
        if fresh or not encoded[k]:
            init += [z3.Not(lat0[k]), cnt0[k] == 0]
        else:
            init += [cnt0[k] >= 0, cnt0[k] <= (r.hold if r.manual else r.hold - 1),
                     z3.Implies(z3.Not(lat0[k]), cnt0[k] == 0)]

    def most_severe(lats, extra=None):
        s = zero if extra is None else extra
        for r, lk in zip(rules, lats):
            s = _max(s, z3.If(lk, z3.IntVal(r.sev), zero))
        return s
    L0 = most_severe(lat0)
    C0 = z3.Sum(cnt0) if cnt0 else zero
    out = DecisionTrace(enc, L0, C0, init, [], [], [], [], [], [], [], rules, lat0, cnt0)
    lat, cnt = list(lat0), list(cnt0)
    for t in range(enc.k):
        viol = [enc.violated(ob, t) if encoded[i] else z3.Bool(f"{prefix}viol#{i}@{t}")
                for i, ob in enumerate(plan.obligations)]
        fires = enc.R[t] >= tau
        sev: z3.ArithRef = zero
        others = None
        if only is not None and n > 1:
            sev = z3.Int(f"{prefix}others@{t}")
            held = z3.Int(f"{prefix}others_latched@{t}")
            out.init += [sev >= 0, sev <= 4, held >= 0, held <= 4]
            others = _max(sev, held)
        for i, (ob, v) in enumerate(zip(plan.obligations, viol)):
            if encoded[i]:
                sev = _max(sev, z3.If(v, z3.IntVal(ob.response.severity), zero))
        sev = _max(sev, z3.If(fires, z3.IntVal(rules[ri].sev), zero))
        fired = viol + [fires, z3.BoolVal(False)]
        cond = [z3.Not(v) for v in viol] + [enc.R[t] < below, z3.BoolVal(True)]
        new_lat, new_cnt = [], []
        for k, r in enumerate(rules):
            if not encoded[k]:
                new_lat.append(z3.BoolVal(False))
                new_cnt.append(zero)
                continue
            f, lk, ck = fired[k], lat[k], cnt[k]
            c1 = z3.If(cond[k], ck + 1, zero)
            if r.manual:
                new_lat.append(z3.Or(f, lk))
                new_cnt.append(z3.If(f, zero, z3.If(lk, z3.If(c1 >= r.hold, z3.IntVal(r.hold), c1), zero)))
            else:
                rel = z3.And(lk, z3.Not(f), c1 >= r.hold)
                keep = z3.And(lk, z3.Not(f), z3.Not(rel))
                new_lat.append(z3.And(z3.Or(f, lk), z3.Not(rel)))
                new_cnt.append(z3.If(keep, c1, zero))
        latched_sev = most_severe(new_lat, others)
        override = latched_sev > 0
        out.violated.append(viol)
        out.risk_fires.append(fires)
        out.sev.append(sev)
        out.override.append(override)
        out.response.append(latched_sev)
        out.latched_after.append(latched_sev)
        out.clean_after.append(z3.Sum(new_cnt))
        out.lat.append(new_lat)
        out.cnt.append(new_cnt)
        out.cond.append(cond)
        lat, cnt = new_lat, new_cnt
    return out
