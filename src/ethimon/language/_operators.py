"""The operator table: every operator and function of the expression language, declared once.

One :class:`Operator` row per entry says what every stage needs to know about it: how it is
written (``symbol``, ``kind``), its arguments (``args``: ``num``, ``bool``, ``any`` or
``window``, how many), its result type, its unit rule, how far into the past it reads
(``lookback``), whether evaluating it can raise (``may_raise``), its robustness margin and, for
arithmetic, the function of its values. From :data:`OPERATORS` are derived: the parser's and the
checker's arity (``FUNCTIONS``), the temporal set (``TEMPORAL``), the binary operator table
(``BINARY_OPS``), the margin tables, the interpreter protocol (``language/_visit.py``: one
``visit_<name>`` per row), the type and unit checks (``compiler/_typecheck.py``: one rule per
``unit`` value) and the z3 encoder's look-back (``verify/_encode.py``: :meth:`Operator.cycles_back`).

Adding an operator is one row here, one ``visit_<name>`` method per interpreter and one example in
``tests/compiler/test_interpreter_coverage.py``; a row whose method an interpreter lacks fails that
test, and a row whose unit rule the checker does not know fails at import.
"""

from __future__ import annotations

import math
import operator
from dataclasses import dataclass
from typing import Callable

__all__ = ["Operator", "OPERATORS", "ARG_KINDS", "RESULTS", "UNIT_RULES", "LOOKBACKS", "FAMILIES",
           "MARGIN_SHAPES", "SEPARATION_PARAMS", "separation_distance", "operator_of"]

#: what an argument may be: a number, a condition, either (the rule relates them), a window bound
ARG_KINDS = ("num", "bool", "any", "window")
#: the result type: a number, a condition, or the first argument's type (``prev``)
RESULTS = ("num", "bool", "arg")
#: the unit rules the type checker implements (``compiler/_typecheck.py``, one method each):
#: ``none`` (conditions only), ``same`` (operands in one unit; the result in it), ``keep`` (the
#: operand's unit), ``mul``/``div`` (product, quotient), ``sqrt`` (half the exponents),
#: ``compare`` (both sides of one kind, numbers in one unit), ``separation`` (ISO/TS 15066's
#: parameters, :data:`SEPARATION_PARAMS`), ``prev`` (the initial value of the operand's type)
UNIT_RULES = ("none", "same", "keep", "mul", "div", "sqrt", "compare", "separation", "prev")
#: how many past cycles it reads: none, exactly one (``prev``), its window bound (``n - 1``; an
#: unbounded ``since`` keeps one bit, so 1)
LOOKBACKS = ("none", "one", "window")
#: the family: how interpreters group it
FAMILIES = ("unary", "cmp", "arith", "logic", "function", "temporal")
#: the shapes of a comparison's margin (``a`` the left, ``b`` the right operand's value)
MARGIN_SHAPES = ("a - b", "b - a", "|a - b|", "-|a - b|")


@dataclass(frozen=True)
class Operator:
    """One entry of the expression language.

    Attributes:
        name: the word of its interpreter method (``visit_<name>``): ``lt``, ``sub``, ``held``.
        symbol: how it is written: ``<``, ``-``, ``held``.
        kind: ``unary``, ``binary`` or ``call``.
        family: one of :data:`FAMILIES`.
        args: the kind of each argument (:data:`ARG_KINDS`); with ``variadic`` the last one repeats.
        result: :data:`RESULTS`.
        unit: the unit rule (:data:`UNIT_RULES`).
        lookback: :data:`LOOKBACKS`.
        may_raise: what makes evaluating it raise (an evaluation error, so the cycle fails closed),
            or ``None``: it raises only if an argument does.
        optional: how many trailing arguments may be left out (``prev(e[, init])``).
        variadic: the most arguments (the last kind repeating), ``0``: exactly ``len(args)``.
        fn: the function of its values (floats, numpy arrays or z3 terms) where one call computes it.
        margin: a comparison's margin shape (:data:`MARGIN_SHAPES`) or a connective's
            ``(combine, negate_left)``.
        doc: one line for the docs and error hints.
    """

    name: str
    symbol: str
    kind: str
    family: str
    args: tuple[str, ...]
    result: str
    unit: str
    lookback: str = "none"
    may_raise: str | None = None
    optional: int = 0
    variadic: int = 0
    fn: Callable | None = None
    margin: object = None
    doc: str = ""

    def __post_init__(self) -> None:
        bad = []
        if not self.name.isidentifier():
            bad.append(f"name {self.name!r} is not a word (it names the method visit_{self.name})")
        if self.kind not in ("unary", "binary", "call"):
            bad.append(f"kind {self.kind!r}")
        if self.family not in FAMILIES:
            bad.append(f"family {self.family!r}")
        if any(a not in ARG_KINDS for a in self.args):
            bad.append(f"args {self.args!r}")
        if self.result not in RESULTS:
            bad.append(f"result {self.result!r}")
        if self.unit not in UNIT_RULES:
            bad.append(f"unit rule {self.unit!r} (the checker knows {', '.join(UNIT_RULES)})")
        if self.lookback not in LOOKBACKS:
            bad.append(f"lookback {self.lookback!r}")
        if (self.lookback == "window") != ("window" in self.args):
            bad.append("a windowed lookback needs a window argument, and a window argument a windowed lookback")
        if (self.family == "temporal") != (self.lookback != "none"):
            bad.append("an operator that reads the past is temporal, and a temporal operator reads the past")
        if bad:
            raise ValueError(f"operator {self.symbol!r}: " + "; ".join(bad))

    @property
    def method(self) -> str:
        """The interpreter method every back-end implements for it."""
        return f"visit_{self.name}"

    @property
    def min_args(self) -> int:
        return len(self.args) - self.optional

    @property
    def max_args(self) -> int:
        return self.variadic or len(self.args)

    def arg_kind(self, i: int) -> str:
        """The kind of argument ``i`` (a variadic operator's last kind repeats)."""
        return self.args[min(i, len(self.args) - 1)]

    @property
    def label(self) -> str:
        """How messages name it: ``'<'``, ``unary '-'``, ``held()``."""
        if self.kind == "call":
            return f"{self.symbol}()"
        return "unary '-'" if self.name == "neg" else f"'{self.symbol}'"

    def cycles_back(self, window: int | None) -> int:
        """Past cycles it reads beyond its arguments' own look-back, for its bound ``window``
        (``None``: an unbounded window, whose state is one bit)."""
        if self.lookback == "none":
            return 0
        if self.lookback == "one":
            return 1
        return window - 1 if window is not None else 1


#: The parameters of ``separation_distance``, in call order: (symbol of ISO/TS 15066:2016, unit, meaning).
SEPARATION_PARAMS: tuple[tuple[str, str, str], ...] = (
    ("v_h", "m/s", "speed of the human toward the robot"),
    ("v_r", "m/s", "speed of the robot toward the human"),
    ("T_r", "s", "reaction time of the robot system"),
    ("T_s", "s", "stopping time of the robot"),
    ("S_s", "m", "stopping distance of the robot"),
    ("C", "m", "intrusion distance (ISO 13855, from reach)"),
    ("Z_d", "m", "position uncertainty of the human (sensor)"),
    ("Z_r", "m", "position uncertainty of the robot"),
)


def separation_distance(v_h, v_r, T_r, T_s, S_s, C, Z_d, Z_r):  # noqa: N803 - the standard's symbols
    """The protective separation distance S_p of ISO/TS 15066:2016, clause 5.5.4, with constant speeds.

    ``S_p = S_h + S_r + S_s + C + Z_d + Z_r`` (formula (1)) with ``S_h = v_h·(T_r + T_s)`` and
    ``S_r = v_r·T_r``: formula (2) when the human and the robot keep constant speeds over the
    reaction and stopping time (the integrals of the speeds become products). Summed left to
    right in exactly this order, with ``+`` and ``*`` only, so the same call gives the same
    float in the compiled monitor and the reference interpreter, the same array in the offline
    checker and the same term in the z3 encoder.

    The caller checks that every argument is ``>= 0`` (each backend in its own way): a negative
    (or NaN) argument is an evaluation error, never a silently smaller distance.

    Example:
        >>> round(separation_distance(1.6, 0.5, 0.1, 0.3, 0.2, 0.1, 0.04, 0.01), 12)
        1.04
    """
    return v_h * (T_r + T_s) + v_r * T_r + S_s + C + Z_d + Z_r


def _row(name, symbol, kind, family, args, result, unit, lookback="none", **kw) -> Operator:
    return Operator(name, symbol, kind, family, tuple(args), result, unit, lookback, **kw)


_N, _B = "num", "bool"

#: Every operator and function of the language, by its method word (``OPERATORS["held"]``).
OPERATORS: dict[str, Operator] = {op.name: op for op in (
    # unary operators
    _row("neg", "-", "unary", "unary", [_N], "num", "keep", fn=operator.neg, doc="-x: the negation"),
    _row("not", "not", "unary", "unary", [_B], "bool", "none", doc="not e"),
    # comparisons: numbers in one unit (== and != also compare two conditions)
    _row("lt", "<", "binary", "cmp", [_N, _N], "bool", "same", fn=operator.lt, margin="b - a"),
    _row("le", "<=", "binary", "cmp", [_N, _N], "bool", "same", fn=operator.le, margin="b - a"),
    _row("gt", ">", "binary", "cmp", [_N, _N], "bool", "same", fn=operator.gt, margin="a - b"),
    _row("ge", ">=", "binary", "cmp", [_N, _N], "bool", "same", fn=operator.ge, margin="a - b"),
    _row("eq", "==", "binary", "cmp", ["any", "any"], "bool", "compare", fn=operator.eq, margin="-|a - b|"),
    _row("ne", "!=", "binary", "cmp", ["any", "any"], "bool", "compare", fn=operator.ne, margin="|a - b|"),
    # arithmetic
    _row("add", "+", "binary", "arith", [_N, _N], "num", "same", fn=operator.add),
    _row("sub", "-", "binary", "arith", [_N, _N], "num", "same", fn=operator.sub),
    _row("mul", "*", "binary", "arith", [_N, _N], "num", "mul", fn=operator.mul),
    _row("div", "/", "binary", "arith", [_N, _N], "num", "div", fn=operator.truediv,
         may_raise="a divisor of 0"),
    # connectives: short-circuit, left to right; margin (combine, negate the left margin first)
    _row("and", "and", "binary", "logic", [_B, _B], "bool", "none", margin=("min", False)),
    _row("or", "or", "binary", "logic", [_B, _B], "bool", "none", margin=("max", False)),
    _row("implies", "implies", "binary", "logic", [_B, _B], "bool", "none", margin=("max", True)),
    # functions
    _row("abs", "abs", "call", "function", [_N], "num", "keep", fn=abs, doc="abs(x)"),
    _row("min", "min", "call", "function", [_N, _N], "num", "same", variadic=16, fn=min,
         doc="min(x, y, ...): 2 to 16 numbers in one unit"),
    _row("max", "max", "call", "function", [_N, _N], "num", "same", variadic=16, fn=max,
         doc="max(x, y, ...): 2 to 16 numbers in one unit"),
    _row("sqrt", "sqrt", "call", "function", [_N], "num", "sqrt", fn=math.sqrt,
         may_raise="a negative argument", doc="sqrt(x)"),
    # temporal operators: bounded past time, one O(1) state each
    _row("prev", "prev", "call", "temporal", ["any", "any"], "arg", "prev", "one", optional=1,
         doc="prev(e[, init]): e one cycle ago (init, default false / 0, at the first cycle)"),
    _row("held", "held", "call", "temporal", [_B, "window"], "bool", "none", "window",
         doc="held(e, n): e at each of the last n cycles"),
    _row("once", "once", "call", "temporal", [_B, "window"], "bool", "none", "window",
         doc="once(e, n): e at some cycle of the last n"),
    _row("since", "since", "call", "temporal", [_B, _B, "window"], "bool", "none", "window", optional=1,
         doc="since(a, b[, n]): b at some cycle j (within the last n) and a at every cycle after j"),
    # ISO/TS 15066 (listed last: the order of the functions in messages)
    _row("separation_distance", "separation_distance", "call", "function", [_N] * 8, "num", "separation",
         fn=separation_distance, may_raise="a negative argument",
         doc="separation_distance(v_h, v_r, T_r, T_s, S_s, C, Z_d, Z_r): ISO/TS 15066's S_p [m]"),
)}


def operator_of(kind: str, symbol: str) -> Operator | None:
    """The row of a unary or binary operator or a function as written (``("binary", "-")``), or ``None``."""
    for op in OPERATORS.values():
        if op.kind == kind and op.symbol == symbol:
            return op
    return None
