"""Where the monitor's doubles can leave the reals: interval bounds per arithmetic term (no z3).

Besides overflow and underflow (below), :func:`rounding_hazards` bounds each comparison's rounding
error (a forward error bound per term) against how far the inputs' own precision moves its sides
(interval bounds on the derivatives): where rounding reaches more than 2^10 times that, absorption
(``(x + 1e16) - 1e16``), cancellation (``(y + 0.1) - y``) or a division that amplifies an error
decides the comparison on a region of inputs far wider than an ulp, and the proof is labelled
``proved (real arithmetic)`` naming the term. Rounding within that factor is the ordinary rounding
at a boundary that no real-arithmetic proof sees either way.

``ethimon verify`` proves its properties in real arithmetic; the monitor computes in IEEE-754
doubles. They differ by rounding (an ulp or so, which a proof with boundaries exactly on a
float cannot see either way), and by much more where a term *overflows* (a real value beyond
the largest double becomes ±inf) or *underflows* (a product or quotient of non-zero numbers
smaller than the smallest normal double becomes 0 or loses its digits). This module bounds
every arithmetic term of an obligation over the declared input ranges, exactly (rational
interval arithmetic), and reports the terms where that can happen *and matter*: an overflow
anywhere, an underflow that feeds a comparison with a side that can be 0 (``a * b > 0``) or a
product/quotient that amplifies it. A property proved over the reals for such an obligation is
reported as ``proved (real arithmetic)`` with these terms and ranges.
"""

from __future__ import annotations

import math
import sys
from fractions import Fraction

from ..compiler._plan import RISK_NAME
from ..language._expr import Binary, Call, Name, Num, Unary, separation_distance, to_source, walk
from ..language._visit import ExprVisitor

__all__ = ["float_hazards", "defined_in_doubles", "exact_value", "rounding_hazards", "SHOWN_DEFINED"]

MAX = Fraction(sys.float_info.max)
TINY = Fraction(sys.float_info.min)  # the smallest normal double: below it, digits are lost
HUGE = Fraction(2) ** 2000  # stands for "unbounded" (a quotient by an interval holding 0)
_AMPLIFY = Fraction(2) ** 52


class _I:
    """A closed interval of reals ``[lo, hi]`` and ``mz``, the smallest non-zero magnitude it can
    take (``Fraction(0)``: arbitrarily close to 0; ``None``: it is exactly 0)."""

    __slots__ = ("lo", "hi", "mz")

    def __init__(self, lo: Fraction, hi: Fraction, mz: Fraction | None | bool = True) -> None:
        self.lo, self.hi = lo, hi
        self.mz = _hull_mz(lo, hi) if mz is True else mz

    @property
    def mag(self) -> Fraction:
        return max(abs(self.lo), abs(self.hi))

    def has_zero(self) -> bool:
        return self.lo <= 0 <= self.hi

    def __add__(self, o: "_I") -> "_I":
        return _I(self.lo + o.lo, self.hi + o.hi)

    def __sub__(self, o: "_I") -> "_I":
        return _I(self.lo - o.hi, self.hi - o.lo)

    def __mul__(self, o: "_I") -> "_I":
        c = [self.lo * o.lo, self.lo * o.hi, self.hi * o.lo, self.hi * o.hi]
        mz = None if self.mz is None or o.mz is None else self.mz * o.mz
        return _I(min(c), max(c), mz)

    def __truediv__(self, o: "_I") -> "_I":
        if o.has_zero():
            return _I(-HUGE, HUGE, None if self.mz is None else Fraction(0))
        c = [self.lo / o.lo, self.lo / o.hi, self.hi / o.lo, self.hi / o.hi]
        mz = None if self.mz is None else self.mz / o.mag
        return _I(min(c), max(c), mz)


def _hull_mz(lo: Fraction, hi: Fraction) -> Fraction | None:
    if lo == hi == 0:
        return None
    if lo <= 0 <= hi:
        return Fraction(0)
    return min(abs(lo), abs(hi))


def _point(x: float) -> _I:
    f = Fraction(x)
    return _I(f, f)


class _Bounds(ExprVisitor):
    """Interval bounds of each numeric term over the declared input ranges: one method per entry of
    the operator table (the interpreter protocol, so a new operator cannot be left out silently:
    without its method this class cannot be instantiated, and the coverage test names it). A method
    returns the term's :class:`_I`, or ``None``: no bound (a condition, a window, an unbounded input)."""

    def __init__(self, plan) -> None:
        self.plan = plan
        self.memo: dict = {}  # node -> _I | None
        from ._encode import risk_input_range
        rlo, rhi = risk_input_range(plan)
        self.ranges = {s.name: _I(Fraction(s.lo), Fraction(s.hi)) for s in plan.signals if s.kind == "number"}
        self.ranges[RISK_NAME] = _I(Fraction(rlo), Fraction(rhi))

    def of(self, node) -> _I | None:
        if node not in self.memo:  # by identity (a node is never equal to another)
            self.memo[node] = _point(node.value) if isinstance(node, Num) else self.visit(node)
        return self.memo[node]

    def visit_num(self, node) -> _I:
        return _point(node.value)

    def visit_name(self, node) -> _I | None:
        if node.id in self.plan.constants:
            return _point(self.plan.constants[node.id])
        return self.ranges.get(node.id)

    def visit_neg(self, node) -> _I | None:
        v = self.of(node.operand)
        return None if v is None else _I(-v.hi, -v.lo, v.mz)

    def _arith(self, node) -> _I | None:
        """``+ - * /`` by the row's function: :class:`_I`'s operators."""
        a, b = self.of(node.left), self.of(node.right)
        return None if a is None or b is None else node.row.fn(a, b)

    visit_add = visit_sub = visit_mul = visit_div = _arith

    def _none(self, node) -> None:
        """A condition (comparisons, connectives, ``held``/``once``/``since``): no interval."""
        return None

    visit_bool = visit_not = _none
    visit_lt = visit_le = visit_gt = visit_ge = visit_eq = visit_ne = _none
    visit_and = visit_or = visit_implies = _none
    visit_held = visit_once = visit_since = _none

    def _args(self, node) -> list:
        return [self.of(x) for x in node.args]

    def visit_separation_distance(self, node) -> _I | None:
        args = self._args(node)
        return separation_distance(*args) if all(a is not None for a in args) else None

    def visit_abs(self, node) -> _I | None:
        a = self._args(node)[0]
        if a is None:
            return None
        lo = Fraction(0) if a.has_zero() else min(abs(a.lo), abs(a.hi))
        return _I(lo, a.mag, a.mz)

    def visit_sqrt(self, node) -> _I | None:
        a = self._args(node)[0]
        if a is None:
            return None
        return _I(Fraction(math.sqrt(max(0.0, float(max(a.lo, Fraction(0)))))),
                  Fraction(math.sqrt(float(min(max(a.hi, Fraction(0)), MAX)))))

    def _extremum(self, node) -> _I | None:
        args = self._args(node)
        if not args or any(a is None for a in args):
            return None
        pick = min if node.func == "min" else max
        return _I(pick(a.lo for a in args), pick(a.hi for a in args))

    visit_min = visit_max = _extremum

    def visit_prev(self, node) -> _I | None:
        args = self._args(node)
        if args[0] is None:
            return None
        if len(args) == 2 and args[1] is not None:
            return _I(min(args[0].lo, args[1].lo), max(args[0].hi, args[1].hi))
        return args[0]


def _show(x: Fraction) -> str:
    return "beyond the largest double" if abs(x) > MAX else f"{float(x):.6g}"


def float_hazards(plan, ob) -> list[str]:
    """The terms of obligation ``ob`` whose double result can leave the reals by more than rounding,
    for inputs in their declared ranges, each with the range of its real value (empty: none)."""
    b = _Bounds(plan)
    parent: dict = {}  # node -> (its parent, the parent's operands)
    roots = [r for r in (ob.when, ob.require) if r is not None]
    for root in roots:
        for n in walk(root):
            kids = (n.left, n.right) if isinstance(n, Binary) else (n.operand,) if isinstance(n, Unary) else \
                tuple(n.args) if isinstance(n, Call) else ()
            for k in kids:
                parent[k] = (n, kids)
    out: list[str] = []
    for root in roots:
        for n in walk(root):
            if not (isinstance(n, Binary) and n.op in ("+", "-", "*", "/")) and not (
                    isinstance(n, Call) and n.func == "separation_distance"):
                continue
            v = b.of(n)
            if v is None:
                continue
            text = to_source(n)
            up = parent.get(n)
            p, kids = up if up is not None else (None, ())
            others = [b.of(k) for k in kids if k is not n]
            compared = isinstance(p, Binary) and p.op in ("<", "<=", ">", ">=", "==", "!=")
            if v.mag > MAX:
                # ±inf keeps the sign, so a comparison with a finite side decides as the reals do;
                # anything computed from the inf (inf / 1e308, inf - inf, 0 * inf) does not
                if not compared or any(o is None or o.mag > MAX for o in others):
                    out.append(f"{text} can overflow to ±inf and is computed with further (its real value "
                               f"reaches {_show(v.lo)} .. {_show(v.hi)})")
                continue
            if not (isinstance(n, Binary) and n.op in ("*", "/")) or v.mz is None or v.mz >= TINY or p is None:
                continue
            if compared:
                if any(o is not None and (o.has_zero() or (o.mz is not None and o.mz < TINY * _AMPLIFY))
                       for o in others):
                    out.append(f"{text} can underflow to 0 or a subnormal (non-zero real values down to "
                               f"{_show(v.mz) if v.mz else '0'}) and is compared with a side that can be 0")
            elif isinstance(p, Binary) and p.op in ("*", "/"):
                if (p.op == "/" and p.right is n) or any(
                        o is not None and (o.mag > _AMPLIFY if p.op == "*" else o.has_zero() or
                                           (o.mz is not None and o.mz < 1 / _AMPLIFY)) for o in others):
                    out.append(f"{text} can underflow to 0 or a subnormal, and {to_source(p)} amplifies the "
                               "lost digits")
    # rounding that decides a comparison otherwise (absorption, cancellation, division); an error bound
    # made infinite by an overflow or a divisor reaching 0 is already named above
    out += [h for h in rounding_hazards(plan, ob) if not (out and "up to inf" in h)]
    return out


_EPS = Fraction(2) ** -52


def _sub(node) -> list:
    return list(walk(node))


def _clean(b: _Bounds, node) -> tuple[bool, Fraction, int]:
    """``(no overflow anywhere in node, largest magnitude M of any term, number of rounding steps n)``."""
    m, n = Fraction(0), 0
    for x in _sub(node):
        v = b.of(x)
        if v is None:
            return False, m, n
        if v.mag > MAX / 4:
            return False, m, n
        m = max(m, v.mag)
        if isinstance(x, (Binary, Unary, Call)):
            n += 1 + (8 if isinstance(x, Call) else 0)
    return True, m, n


def _sign_safe(b: _Bounds, node) -> bool:
    """Every term of ``node`` is >= 0 over the reals and built without subtraction: its double is
    >= 0 too (rounding to nearest never flips a sign; an underflow gives +0)."""
    for x in _sub(node):
        v = b.of(x)
        if v is None or v.lo < 0:
            return False
        if isinstance(x, Unary) or (isinstance(x, Binary) and x.op == "-"):
            return False
        if isinstance(x, Binary) and x.op == "/" and not _nonzero(b, x.right):
            return False
    return True


def _nonzero(b: _Bounds, node) -> bool:
    """The double of ``node`` is non-zero for every in-range input: its real value stays farther from
    0 than the rounding of all its steps can move it, and nothing in it overflows or underflows."""
    v = b.of(node)
    if v is None or v.has_zero() or v.mz is None:
        return False
    ok, m, n = _clean(b, node)
    if not ok:
        return False
    for x in _sub(node):  # an underflow inside loses the relative accuracy the bound relies on
        w = b.of(x)
        if isinstance(x, Binary) and x.op in ("*", "/") and (w.mz is None or w.mz < TINY * 4):
            if w.mz is not None:
                return False
    return v.mz > 4 * (n + 1) * _EPS * max(m, Fraction(1)) and v.mz >= TINY * 4


def _nonneg(b: _Bounds, node) -> bool:
    v = b.of(node)
    if v is None or v.lo < 0:
        return False
    ok, m, n = _clean(b, node)
    if not ok:
        return False
    return _sign_safe(b, node) or v.lo > 4 * (n + 1) * _EPS * max(m, Fraction(1))


def defined_in_doubles(plan, ob) -> bool:
    """Whether interval bounds alone show that evaluating ``ob`` in doubles raises nothing for any
    in-range input (every divisor non-zero, every sqrt and separation_distance argument >= 0), with
    no short-circuit assumed. ``False``: not shown this way (the IEEE-754 model decides)."""
    b = _Bounds(plan)
    for root in (ob.when, ob.require):
        if root is None:
            continue
        for n in walk(root):
            row = n.row
            if row is None or row.may_raise is None:
                continue
            shown = SHOWN_DEFINED.get(row.name)  # a row that may raise with no entry: not shown
            if shown is None or not shown(b, n):
                return False
    return True


#: per row of the operator table that may raise (its ``may_raise``), how interval bounds show that
#: it does not: a new such row without an entry is never shown defined here (the IEEE-754 model
#: decides), and ``tests/compiler/test_operator_table.py`` matches the keys to the table
SHOWN_DEFINED = {
    "div": lambda b, n: _nonzero(b, n.right),  # a divisor of 0
    "sqrt": lambda b, n: _nonneg(b, n.args[0]),  # a negative argument
    "separation_distance": lambda b, n: all(_nonneg(b, a) for a in n.args),  # a negative argument
}


# ---------------------------------------------------------------- rounding that can flip a comparison
#: unit roundoff of a double (round to nearest): each operation's relative error is at most this
_U = 2.0 ** -53
#: a comparison's rounding error up to this many times what the inputs' own precision (an ulp of
#: each input) moves its sides is ordinary rounding at a boundary; beyond it, absorption or
#: cancellation decides it, on a region of inputs far wider than an ulp
_FLIP_RATIO = 2.0 ** 10
_CMP = ("<", "<=", ">", ">=", "==", "!=")
_ONE = Fraction(1)


def _f(x: Fraction) -> float:
    return math.inf if abs(x) > MAX else float(abs(x))


def _pow2(b: "_Bounds", node) -> bool:
    """A constant power of two (multiplying or dividing by it is exact barring over/underflow)."""
    v = b.of(node)
    if v is None or v.lo != v.hi or v.lo == 0 or not (isinstance(node, Num) or isinstance(node, Name)):
        return False
    m = abs(v.lo)
    return m.numerator & (m.numerator - 1) == 0 and m.denominator & (m.denominator - 1) == 0


class _Err:
    """A forward bound on the absolute rounding error of each term's double (``E``) and interval
    bounds on its partial derivatives by each input (``D``), over the declared input ranges."""

    def __init__(self, plan) -> None:
        self.b = _Bounds(plan)
        self.plan = plan
        self.memo: dict = {}  # node -> (error bound, derivatives) | None
        self.own: dict = {}  # node -> each operation's own rounding bound

    def of(self, node) -> tuple[float, dict] | None:
        if node not in self.memo:
            self.memo[node] = self._of(node)
        return self.memo[node]

    def rnd(self, node, exact: bool = False) -> float:
        v = self.b.of(node)
        r = 0.0 if exact else _U * _f(v.mag)
        self.own[node] = r
        return r

    def sens(self, d: dict) -> float:
        """How far the inputs' own precision (an ulp each) moves a term with derivatives ``d``."""
        return sum(_f(iv.mag) * _U * _f(self.b.ranges[k].mag) for k, iv in d.items())

    def _of(self, node):
        b = self.b
        if isinstance(node, Num):
            return 0.0, {}
        if isinstance(node, Name):
            if node.id in self.plan.constants:
                return 0.0, {}
            return (0.0, {node.id: _I(_ONE, _ONE)}) if node.id in b.ranges else None
        if b.of(node) is None:
            return None
        if isinstance(node, Unary):
            got = self.of(node.operand)
            return None if got is None else (got[0], {k: _I(-d.hi, -d.lo) for k, d in got[1].items()})
        if isinstance(node, Binary):
            la, lb = self.of(node.left), self.of(node.right)
            if la is None or lb is None:
                return None
            (ea, da), (eb, db) = la, lb
            A, B, V = b.of(node.left), b.of(node.right), b.of(node)
            zero = _I(Fraction(0), Fraction(0))
            if node.op in ("+", "-"):
                sign = 1 if node.op == "+" else -1
                d = {k: (da.get(k, zero) + db.get(k, zero)) if sign > 0 else (da.get(k, zero) - db.get(k, zero))
                     for k in {*da, *db}}
                return ea + eb + self.rnd(node), d
            if node.op == "*":
                d = {k: da.get(k, zero) * B + A * db.get(k, zero) for k in {*da, *db}}
                exact = _pow2(b, node.left) or _pow2(b, node.right)
                return _f(A.mag) * eb + _f(B.mag) * ea + ea * eb + self.rnd(node, exact), d
            if node.op == "/":
                if B.has_zero():
                    # exact operands: one correctly rounded quotient (relative error 2^-53, a boundary
                    # rounding); a divisor reaching 0 is the .defined property's question. Rounded
                    # operands divided by a divisor near 0: no bound
                    return None if ea == 0 and eb == 0 else (math.inf, {})
                mzb = float(min(abs(B.lo), abs(B.hi)))
                if eb >= mzb:
                    return math.inf, {}
                d = {k: da.get(k, zero) / B - (V * db.get(k, zero)) / B for k in {*da, *db}}
                return (ea + _f(V.mag) * eb) / (mzb - eb) + self.rnd(node, _pow2(b, node.right)), d
            return None
        if isinstance(node, Call):
            args = [self.of(a) for a in node.args]
            if any(a is None for a in args):
                return None
            if node.func == "abs":
                e, d = args[0]
                return e, {k: _I(-iv.mag, iv.mag) for k, iv in d.items()}
            if node.func in ("min", "max", "prev"):
                keys = {k for _, d in args for k in d}
                d = {}
                for k in keys:
                    ivs = [dd.get(k, _I(Fraction(0), Fraction(0))) for _, dd in args]
                    d[k] = _I(min(iv.lo for iv in ivs), max(iv.hi for iv in ivs))
                return max(e for e, _ in args), d
            if node.func == "sqrt":
                a = b.of(node.args[0])
                if a.lo <= 0:
                    return None
                lo, hi = math.sqrt(float(a.lo)), math.sqrt(_f(a.hi))
                e, d = args[0]
                k = _I(Fraction(1 / (2 * hi)) if hi < math.inf else Fraction(0), Fraction(1 / (2 * lo)))
                return e / (2 * lo) + self.rnd(node), {n: iv * k for n, iv in d.items()}
        return None


def rounding_hazards(plan, ob) -> list[str]:
    """The comparisons of obligation ``ob`` that rounding can decide otherwise than the reals by more
    than the inputs' own precision, for inputs in their declared ranges: absorption (a term added to
    one far larger loses its digits), cancellation (a difference of rounded terms that the inputs
    barely move), a division that amplifies an operand's error. Each names the term (empty: none)."""
    er = _Err(plan)
    b = er.b
    out: list[str] = []
    for root in (ob.when, ob.require):
        if root is None:
            continue
        for p in walk(root):
            if not (isinstance(p, Binary) and p.op in _CMP):
                continue
            lft, rgt = er.of(p.left), er.of(p.right)
            if lft is None or rgt is None:
                continue
            e = lft[0] + rgt[0]
            if e == 0:
                continue
            diff = b.of(p.left) - b.of(p.right)
            if e < math.inf and (float(diff.lo) > e or float(diff.hi) < -e):
                continue  # decided with a margin no rounding reaches
            zero = _I(Fraction(0), Fraction(0))
            d = {k: lft[1].get(k, zero) - rgt[1].get(k, zero) for k in {*lft[1], *rgt[1]}}
            s = er.sens(d)
            if e <= _FLIP_RATIO * s:
                continue
            out.append(_name_flip(er, p, e, s))
    return out


def _name_flip(er: _Err, p, e: float, s: float) -> str:
    """What in comparison ``p`` rounds past the inputs' precision: absorption, cancellation, division."""
    b = er.b
    found: list[str] = []
    for side in (p.left, p.right):
        for n in walk(side):
            if not (isinstance(n, Binary) and n.op in ("+", "-", "/")):
                continue
            got = er.of(n)
            if got is None:
                continue
            kids = [er.of(n.left), er.of(n.right)]
            if n.op in ("+", "-"):
                big = _f(b.of(n).mag)
                for k in (n.left, n.right):
                    m = _f(b.of(k).mag)
                    if 0 < m and m * _FLIP_RATIO < big:
                        found.append(f"absorption in {to_source(n)} ({to_source(k)}, up to {m:.3g}, is added to a "
                                     f"term up to {big:.3g} and loses its low digits)")
                        break
            e_in = sum(x[0] for x in kids if x is not None)
            if e_in > 0 and e_in > _FLIP_RATIO * er.sens(got[1]):
                what = "cancellation" if n.op in ("+", "-") else "division"
                found.append(f"{what} in {to_source(n)} (its operands' rounding, up to {e_in:.3g}, is what the "
                             f"inputs barely move)" if what == "cancellation" else
                             f"division in {to_source(n)} (it amplifies its operands' rounding, up to {e_in:.3g})")
    why = "; ".join(reversed(dict.fromkeys(found))) or "rounding"  # innermost first
    return (f"{why}: the doubles of {to_source(p)} can be off by up to {e:.3g}, where the inputs' own precision "
            f"moves them by {s:.3g}, so the monitor can decide it otherwise than the reals")


def exact_value(plan, node, env: dict):
    """The exact (rational) value of ``node`` for inputs ``env`` (Fractions and bools), as the proof's real
    arithmetic has it; ``None`` where it is not exact or not covered (sqrt, temporal functions, a division by 0)."""
    if isinstance(node, Num):
        return Fraction(node.value)
    if isinstance(node, Name):
        if node.id in plan.constants:
            return Fraction(plan.constants[node.id])
        return env.get(node.id)
    if type(node).__name__ == "BoolLit":
        return bool(node.value)
    if isinstance(node, Unary):
        v = exact_value(plan, node.operand, env)
        if v is None:
            return None
        return (not v) if node.op == "not" else -v
    if isinstance(node, Binary):
        a = exact_value(plan, node.left, env)
        if a is None:
            return None
        if node.op in ("and", "or", "implies"):
            c = exact_value(plan, node.right, env)
            if c is None:
                return None
            return (a and c) if node.op == "and" else (a or c) if node.op == "or" else ((not a) or c)
        c = exact_value(plan, node.right, env)
        if c is None:
            return None
        op = node.op
        if op == "/":
            return None if c == 0 else a / c
        fns = {"+": lambda: a + c, "-": lambda: a - c, "*": lambda: a * c, "<": lambda: a < c,
               "<=": lambda: a <= c, ">": lambda: a > c, ">=": lambda: a >= c, "==": lambda: a == c,
               "!=": lambda: a != c}
        return fns[op]() if op in fns else None
    if isinstance(node, Call) and node.func in ("abs", "min", "max"):
        args = [exact_value(plan, a, env) for a in node.args]
        if any(a is None for a in args):
            return None
        return abs(args[0]) if node.func == "abs" else (min(args) if node.func == "min" else max(args))
    return None
