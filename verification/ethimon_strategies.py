"""Hypothesis strategies: random typed expression ASTs, random specs, random input traces.

Expressions are built as ASTs over a few signals (numbers ``x``, ``y``, ``z``,
boolean ``b`` and ``risk``), with every operator and every temporal operator
(``prev`` with and without an initial value, ``held``, ``once``, bounded and
unbounded ``since``) and every function (``abs``, ``sqrt``, ``min``, ``max``, and
``separation_distance`` compared with a risk-free operand: its result is in [m]),
rendered with :func:`~ethimon.language._expr.to_source` and compiled through
:func:`ethimon.load_spec_text`, exactly like a user's file.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import numpy as np
import yaml
from hypothesis import strategies as st

import ethimon
from ethimon.language._expr import Binary, BoolLit, Call, Name, Num, Unary, parse_expr, separation_distance, to_source

NUM_SIGNALS = {"x": (-5.0, 5.0), "y": (0.0, 10.0), "z": (-1.0, 1.0)}
BOOL_SIGNALS = ("b",)
RESPONSES = ("safe_pose", "stop_2", "stop_1", "stop_0")
NUMBERS = (0.0, 1.0, 2.0, 0.5, -1.0, 3.25, 10.0, -0.1, 0.45)
WINDOWS = (1, 2, 3, 4)


def _n(cls, *args):
    return cls(0, 0, *args)


num_leaf = st.one_of(st.sampled_from(sorted(NUM_SIGNALS) + ["risk"]).map(lambda s: _n(Name, s)),
                     st.sampled_from(NUMBERS).map(lambda v: _n(Num, v)))
bool_leaf = st.one_of(st.sampled_from(BOOL_SIGNALS).map(lambda s: _n(Name, s)),
                      st.booleans().map(lambda v: _n(BoolLit, v)))


def _const(node):
    """The value of a constant subtree (no signal, no temporal operator), as the compiler folds it; else None."""
    if isinstance(node, Num):
        return node.value
    if isinstance(node, Unary) and node.op == "-":
        v = _const(node.operand)
        return None if v is None else -v
    if isinstance(node, Binary) and node.op in ("+", "-", "*", "/"):
        a, b = _const(node.left), _const(node.right)
        if a is None or b is None or (node.op == "/" and b == 0):
            return None
        return a + b if node.op == "+" else a - b if node.op == "-" else a * b if node.op == "*" else a / b
    if isinstance(node, Call) and node.func in ("abs", "sqrt", "min", "max", "separation_distance"):
        vals = [_const(a) for a in node.args]
        if any(v is None for v in vals) or (node.func in ("sqrt", "separation_distance") and min(vals) < 0):
            return None
        return {"abs": abs, "sqrt": math.sqrt, "min": min, "max": max,
                "separation_distance": separation_distance}[node.func](*vals)
    return None


def _nonzero(node):
    """A divisor the compiler accepts: not a constant zero (``0``, ``-0``, ``1 - 1``: a SpecError)."""
    return _n(Num, 1.0) if _const(node) == 0 else node


def _nonneg(node):
    """A sqrt or separation_distance argument the compiler accepts: not a negative constant (a SpecError)."""
    v = _const(node)
    return _n(Call, "abs", (node,)) if v is not None and v < 0 else node


def _no_risk(node):
    """``node`` with ``risk`` read as ``y``: R_e is dimensionless [1], a separation distance is in [m]."""
    if isinstance(node, Name) and node.id == "risk":
        return _n(Name, "y")
    if isinstance(node, Unary):
        return _n(Unary, node.op, _no_risk(node.operand))
    if isinstance(node, Binary):
        return _n(Binary, node.op, _no_risk(node.left), _no_risk(node.right))
    if isinstance(node, Call):
        return _n(Call, node.func, tuple(_no_risk(a) for a in node.args))
    return node


def separation_calls(sub: st.SearchStrategy) -> st.SearchStrategy:
    """``separation_distance(...)`` of eight drawn arguments: leaves (constants, signals that can be
    negative: a fault at run time) or subexpressions, some under ``abs``; never a negative constant,
    never ``risk`` (its unit [1] is not a speed, a time or a distance)."""
    arg = st.one_of(num_leaf, sub, sub.map(lambda a: _n(Call, "abs", (a,))))
    return st.lists(arg.map(_no_risk), min_size=8, max_size=8).map(
        lambda args: _n(Call, "separation_distance", tuple(_nonneg(a) for a in args)))


def separation_comparisons(sub: st.SearchStrategy) -> st.SearchStrategy:
    """``lhs OP separation_distance(...)``: the result is in [m], so it is compared, never mixed with ``risk``."""
    return st.builds(lambda op, lhs, call: _n(Binary, op, _no_risk(lhs), call),
                     st.sampled_from(("<", "<=", ">", ">=")), sub, separation_calls(sub))


def num_expr(depth: int) -> st.SearchStrategy:
    """Number-valued ASTs of nesting depth <= ``depth``."""
    if depth <= 0:
        return num_leaf
    sub = num_expr(depth - 1)
    bsub = bool_expr(depth - 1)
    return st.one_of(
        num_leaf,
        sub.map(lambda a: _n(Unary, "-", a)),
        st.builds(lambda op, a, b: _n(Binary, op, a, _nonzero(b) if op == "/" else b),
                  st.sampled_from(("+", "-", "*", "/")), sub, sub),
        sub.map(lambda a: _n(Call, "abs", (a,))),
        sub.map(lambda a: _n(Call, "sqrt", (_nonneg(a),))),
        st.builds(lambda f, args: _n(Call, f, tuple(args)), st.sampled_from(("min", "max")),
                  st.lists(sub, min_size=2, max_size=3)),
        sub.map(lambda a: _n(Call, "prev", (a,))),
        st.builds(lambda a, i: _n(Call, "prev", (a, i)), sub, num_leaf),
        # a number that depends on a condition, through prev of a comparison's operands
        st.builds(lambda c, a: _n(Binary, "*", a, _n(Call, "prev", (a,))) if c else a, bsub.map(bool), sub),
    )


def bool_expr(depth: int) -> st.SearchStrategy:
    """Condition ASTs of nesting depth <= ``depth``."""
    if depth <= 0:
        return st.one_of(bool_leaf, st.builds(lambda op, a, b: _n(Binary, op, a, b),
                                              st.sampled_from(("<", "<=", ">", ">=", "==", "!=")),
                                              num_leaf, num_leaf))
    sub = bool_expr(depth - 1)
    nsub = num_expr(depth - 1)
    win = st.sampled_from(WINDOWS).map(lambda n: _n(Num, float(n)))
    return st.one_of(
        bool_leaf,
        st.builds(lambda op, a, b: _n(Binary, op, a, b),
                  st.sampled_from(("<", "<=", ">", ">=", "==", "!=")), nsub, nsub),
        separation_comparisons(nsub),
        sub.map(lambda a: _n(Unary, "not", a)),
        st.builds(lambda op, a, b: _n(Binary, op, a, b),
                  st.sampled_from(("and", "or", "implies", "==", "!=")), sub, sub),
        st.builds(lambda f, a, n: _n(Call, f, (a, n)), st.sampled_from(("held", "once")), sub, win),
        st.builds(lambda a, b: _n(Call, "since", (a, b)), sub, sub),
        st.builds(lambda a, b, n: _n(Call, "since", (a, b, n)), sub, sub, win),
        sub.map(lambda a: _n(Call, "prev", (a,))),
        st.builds(lambda a, i: _n(Call, "prev", (a, i)), sub, bool_leaf),
    )


@dataclass
class GenSpec:
    """A generated spec: its YAML text and the loaded, compiled :class:`ethimon.Spec`."""

    text: str
    spec: ethimon.Spec = field(repr=False)
    doc: dict = field(repr=False, default_factory=dict)

    @property
    def tau(self) -> float:
        return self.spec.risk.threshold


def spec_doc(draw, *, max_obligations: int = 3, depth: int = 3) -> dict:
    obligations = []
    for i in range(draw(st.integers(0, max_obligations))):
        ob: dict[str, Any] = {"id": f"ob{i}", "require": to_source(draw(bool_expr(depth)))}
        if draw(st.booleans()):
            ob["when"] = to_source(draw(bool_expr(depth - 1)))
        w = draw(st.sampled_from((None, None, 0, 1, 2, 3)))
        if w is not None:
            ob["within_cycles"] = w
        ob["response"] = draw(st.sampled_from(RESPONSES))
        rel = draw(release_forms())
        if rel is not None:
            ob["release"] = rel
        obligations.append(ob)
    weights = draw(st.one_of(st.just((0.6, 0.2, 0.2)),
                             st.tuples(*[st.sampled_from((0.0, 0.1, 0.3, 0.5, 0.8, 1.0))] * 3)
                             .filter(lambda w: sum(w) > 0)))  # all-zero weights are a SpecError
    risk: dict[str, Any] = {
        "alpha": weights[0], "beta": weights[1], "gamma": weights[2],
        "variance": draw(st.sampled_from(("sample", "population"))),
        "threshold": draw(st.sampled_from((0.3, 0.4, 0.5, 0.55, 0.6))),
        "response": draw(st.sampled_from(RESPONSES)),
        "release": {"mode": draw(st.sampled_from(("auto", "auto", "manual"))),
                    "hysteresis": draw(st.sampled_from((0.0, 0.05, 0.1))),
                    "hold_cycles": draw(st.integers(1, 4))},
    }
    if draw(st.booleans()):
        risk["max_age_s"] = 0.5
    signals: dict[str, Any] = {n: {"range": [lo, hi]} for n, (lo, hi) in NUM_SIGNALS.items()}
    signals.update({n: {"type": "bool"} for n in BOOL_SIGNALS})
    return {"ethimon": 1, "name": "generated", "signals": signals, "risk": risk,
            "on_fault": draw(on_fault_forms()), "obligations": obligations}


def release_forms() -> st.SearchStrategy:
    """A rule's ``release``: absent (the default for its response), a short form or a mapping."""
    return st.one_of(st.none(), st.none(), st.sampled_from(("auto", "manual")),
                     st.fixed_dictionaries({"mode": st.sampled_from(("auto", "manual"))},
                                           optional={"hold_cycles": st.integers(1, 4)}))


def on_fault_forms() -> st.SearchStrategy:
    """``on_fault``: a response, or ``{response, release}`` (either key optional)."""
    return st.one_of(st.sampled_from(RESPONSES),
                     st.fixed_dictionaries({}, optional={"response": st.sampled_from(RESPONSES),
                                                         "release": release_forms().filter(lambda r: r is not None)}))


@st.composite
def specs(draw, max_obligations: int = 3, depth: int = 3) -> GenSpec:
    """Random specs that compile (the generator is typed, so any SpecError is a bug)."""
    doc = spec_doc(draw, max_obligations=max_obligations, depth=depth)
    text = yaml.safe_dump(doc, sort_keys=False)
    return GenSpec(text, ethimon.load_spec_text(text, "<generated>"), doc)


# -- traces ------------------------------------------------------------------------------------------

def _num_value(lo: float, hi: float) -> st.SearchStrategy:
    mid = (lo + hi) / 2
    return st.one_of(st.sampled_from((lo, hi, 0.0 if lo <= 0 <= hi else lo, mid, 1.0 if lo <= 1 <= hi else hi)),
                     st.floats(lo, hi, allow_nan=False))


class FloatSub(float):
    """A float subclass (a usable number: converted to a built-in float once)."""


class NaNFloat(float):
    """A float subclass holding NaN (unusable)."""

    def __new__(cls):
        return super().__new__(cls, math.nan)

    def __repr__(self) -> str:
        return "NaNFloat()"


class AlwaysPasses:
    """Not a number, but every comparison with it is True (unusable)."""

    def __lt__(self, o): return True  # noqa: E704
    def __le__(self, o): return True  # noqa: E704
    def __gt__(self, o): return True  # noqa: E704
    def __ge__(self, o): return True  # noqa: E704
    def __eq__(self, o): return True  # noqa: E704
    def __float__(self): return 0.5  # noqa: E704
    __hash__ = object.__hash__

    def __repr__(self) -> str:
        return "AlwaysPasses()"


class ClaimsFloat:
    """Claims to be a float through ``__class__`` and passes every comparison (unusable)."""

    __class__ = property(lambda self: float)  # type: ignore[assignment]

    def __float__(self): return 0.5  # noqa: E704
    def __lt__(self, o): return True  # noqa: E704
    def __le__(self, o): return True  # noqa: E704
    def __gt__(self, o): return True  # noqa: E704
    def __ge__(self, o): return True  # noqa: E704

    def __repr__(self) -> str:
        return "ClaimsFloat()"


# valid numbers arrive as built-in floats mostly, sometimes as other real types (converted exactly)
NUMBER_TYPES = (float, float, float, float, np.float64, FloatSub, Fraction)
BAD_NUMBERS = (math.nan, math.inf, -math.inf, 1e9, -1e9, "0.5", True, None, np.bool_(True), np.bool_(False),
               NaNFloat(), AlwaysPasses(), np.float64("nan"), [0.5], ClaimsFloat(), 10 ** 400)
BAD_BOOLS = ("yes", 2, None, math.nan, 0.5, np.float64(0.5), AlwaysPasses(), "True")
GOOD_BOOLS = (True, False, 0, 1, np.bool_(True), np.bool_(False))
BAD_RISK = (math.nan, -0.5, 1.5, None, "high", np.bool_(False), np.bool_(True), NaNFloat(), AlwaysPasses(),
            ClaimsFloat())


@st.composite
def frame(draw, spec: ethimon.Spec, *, p_bad: float = 0.05, late_risk: bool = True) -> dict[str, Any]:
    """One cycle's inputs: mostly valid, sometimes a missing/NaN/out-of-range/wrong-type value."""
    f: dict[str, Any] = {}
    cut = 1000 - int(p_bad * 1000)
    bad = lambda: draw(st.integers(0, 999)) >= cut  # noqa: E731  (shrinks towards valid input)
    for name, sig in spec.signals.items():
        if sig.type == "bool":
            v = draw(st.sampled_from(BAD_BOOLS)) if bad() else draw(st.sampled_from(GOOD_BOOLS))
        else:
            lo, hi = sig.range if sig.range is not None else (-100.0, 100.0)
            v = draw(st.sampled_from(BAD_NUMBERS)) if bad() else draw(st.sampled_from(NUMBER_TYPES))(
                draw(_num_value(lo, hi)))
        if v is not None:
            f[name] = v
    kind = draw(st.sampled_from(("risk", "p_unsafe", "p_unsafe", "p")))
    if bad():
        if kind == "p" and draw(st.booleans()):  # a p of the right length that is still unusable
            q = draw(st.sampled_from((0.0, 0.3, 1.0)))
            f["p"] = draw(st.sampled_from(({0: 1.0 - q, 1: q}, (True, False), (np.bool_(False), np.bool_(True)),
                                           (AlwaysPasses(), AlwaysPasses()), (1.0 - q, NaNFloat()),
                                           [ClaimsFloat(), ClaimsFloat()], [1.0 - q, math.nan])))
        else:
            f[kind] = draw(st.sampled_from(BAD_RISK))
            if f[kind] is None:
                del f[kind]
    else:
        q = draw(st.one_of(st.sampled_from((0.0, 0.5, 1.0, 0.55, 0.7, 0.9)), st.floats(0, 1)))
        if kind == "p":
            p = draw(st.sampled_from((tuple, tuple, list, np.array)))((1.0 - q, q))
            f["p"] = p
        elif kind == "risk":
            f["risk"] = draw(st.one_of(st.floats(0, 1), st.sampled_from((0.1, 0.45, 0.5, 0.6, 0.7))))
        else:
            f["p_unsafe"] = q
    if spec.risk.max_age_s is not None:
        if late_risk and bad():
            f["risk_age_s"] = draw(st.sampled_from((spec.risk.max_age_s * 2, math.nan, -1.0, None, np.bool_(False),
                                                    NaNFloat(), AlwaysPasses())))
            if f["risk_age_s"] is None:
                del f["risk_age_s"]
        else:
            f["risk_age_s"] = draw(st.floats(0, spec.risk.max_age_s))
    return f


@st.composite
def ops(draw, spec: ethimon.Spec, *, min_size: int = 1, max_size: int = 30, p_bad: float = 0.05):
    """A trace: mostly ``("step", frame)``, sometimes ``("reset",)``, ``("release",)`` or
    ``("acknowledge",)``."""
    n = draw(st.integers(min_size, max_size))
    out = []
    last = None
    for _ in range(n):
        r = draw(st.integers(0, 39))
        if r in (36, 37):
            out.append(("acknowledge",))
        elif r == 38:
            out.append(("reset",))
        elif r == 39:
            out.append(("release",))
        elif last is not None and r < 20:
            # hold the previous inputs, changing one: conditions persist across windows
            f = dict(last)
            fresh = draw(frame(spec, p_bad=p_bad))
            if fresh:
                key = draw(st.sampled_from(sorted(fresh)))
                f[key] = fresh[key]
            else:
                f = fresh
            out.append(("step", f))
            last = f
        else:
            last = draw(frame(spec, p_bad=p_bad))
            out.append(("step", last))
    return out


def valid_frames(spec: ethimon.Spec, min_size: int = 1, max_size: int = 20):
    """Traces of valid inputs only."""
    return st.lists(frame(spec, p_bad=0.0), min_size=min_size, max_size=max_size)


def decision_key(d) -> tuple:
    """What must agree between two monitors (fault reasons are worded differently)."""
    return (d.cycle, d.override, d.response, tuple(d.violations), d.risk, d.latched, bool(d.faults),
            d.awaiting_release)
