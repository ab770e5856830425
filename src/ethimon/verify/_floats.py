"""Where the monitor's doubles can leave the reals: interval bounds per arithmetic term (no z3).

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

__all__ = ["float_hazards", "defined_in_doubles"]

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


class _Bounds:
    def __init__(self, plan) -> None:
        self.plan = plan
        self.memo: dict[int, _I | None] = {}
        from ._encode import risk_input_range
        rlo, rhi = risk_input_range(plan)
        self.ranges = {s.name: _I(Fraction(s.lo), Fraction(s.hi)) for s in plan.signals if s.kind == "number"}
        self.ranges[RISK_NAME] = _I(Fraction(rlo), Fraction(rhi))

    def of(self, node) -> _I | None:
        key = id(node)
        if key not in self.memo:
            self.memo[key] = self._of(node)
        return self.memo[key]

    def _of(self, node) -> _I | None:
        if isinstance(node, Num):
            return _point(node.value)
        if isinstance(node, Name):
            if node.id in self.plan.constants:
                return _point(self.plan.constants[node.id])
            return self.ranges.get(node.id)
        if isinstance(node, Unary):
            v = self.of(node.operand)
            return None if v is None or node.op == "not" else _I(-v.hi, -v.lo, v.mz)
        if isinstance(node, Binary):
            a, b = self.of(node.left), self.of(node.right)
            if a is None or b is None or node.op not in ("+", "-", "*", "/"):
                return None
            return {"+": a.__add__, "-": a.__sub__, "*": a.__mul__, "/": a.__truediv__}[node.op](b)
        if isinstance(node, Call):
            args = [self.of(x) for x in node.args]
            f = node.func
            if f == "separation_distance" and all(a is not None for a in args):
                return separation_distance(*args)
            if f == "abs" and args[0] is not None:
                a = args[0]
                lo = Fraction(0) if a.has_zero() else min(abs(a.lo), abs(a.hi))
                return _I(lo, a.mag, a.mz)
            if f == "sqrt" and args[0] is not None:
                a = args[0]
                return _I(Fraction(math.sqrt(max(0.0, float(max(a.lo, Fraction(0)))))),
                          Fraction(math.sqrt(float(min(max(a.hi, Fraction(0)), MAX)))))
            if f in ("min", "max") and args and all(a is not None for a in args):
                pick = min if f == "min" else max
                return _I(pick(a.lo for a in args), pick(a.hi for a in args))
            if f == "prev" and args[0] is not None:
                if len(args) == 2 and args[1] is not None:
                    return _I(min(args[0].lo, args[1].lo), max(args[0].hi, args[1].hi))
                return args[0]
        return None


def _show(x: Fraction) -> str:
    return "beyond the largest double" if abs(x) > MAX else f"{float(x):.6g}"


def float_hazards(plan, ob) -> list[str]:
    """The terms of obligation ``ob`` whose double result can leave the reals by more than rounding,
    for inputs in their declared ranges, each with the range of its real value (empty: none)."""
    b = _Bounds(plan)
    parent: dict[int, tuple] = {}
    roots = [r for r in (ob.when, ob.require) if r is not None]
    for root in roots:
        for n in walk(root):
            kids = (n.left, n.right) if isinstance(n, Binary) else (n.operand,) if isinstance(n, Unary) else \
                tuple(n.args) if isinstance(n, Call) else ()
            for k in kids:
                parent[id(k)] = (n, kids)
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
            up = parent.get(id(n))
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
            if isinstance(n, Binary) and n.op == "/" and not _nonzero(b, n.right):
                return False
            if isinstance(n, Call) and n.func == "sqrt" and not _nonneg(b, n.args[0]):
                return False
            if isinstance(n, Call) and n.func == "separation_distance" and not all(_nonneg(b, a) for a in n.args):
                return False
    return True
