"""Every back-end interprets every entry of the expression language (issue 24, item 2).

The four interpreters of the AST (the compiled closures, the reference interpreter, the offline
checker, the z3 encoder in both arithmetics) implement :class:`ethimon.language._visit.ExprVisitor`.
For every node kind, unary and binary operator (``BINARY_OPS``), function and temporal operator
(``FUNCTIONS``), all rows of ``OPERATORS``, this checks that each back-end has its method (introspection) and that one small
expression using it gives the same verdicts and margins on the monitor, the reference and the
offline checker, cycle by cycle, and the same values in z3 with the inputs pinned to the trace's.
A row added to the operator table without a back-end method fails here (shown with fake rows).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import ethimon
from ethimon.compiler import plan_of
from ethimon.compiler._closures import _Gen
from ethimon.offline import check_trace
from ethimon.offline._eval import Evaluator
from ethimon.language._expr import BINARY_OPS, FUNCTIONS, Binary, walk
from ethimon.language._operators import OPERATORS, Operator
from ethimon.language._visit import PROTOCOL, _protocol, missing_methods
from ethimon.testing import ReferenceMonitor
from ethimon.testing._reference import _Semantics

#: one obligation's ``require`` per method of the protocol, using that entry
EXAMPLES: dict[str, str] = {
    "visit_num": "x < 2.5",
    "visit_bool": "b or false",
    "visit_name": "x < k",
    "visit_neg": "-x < -1",
    "visit_not": "not b",
    "visit_lt": "x < y",
    "visit_le": "x <= y",
    "visit_gt": "x > y",
    "visit_ge": "x >= y",
    "visit_eq": "x == y",
    "visit_ne": "x != y",
    "visit_add": "x + y < 4",
    "visit_sub": "x - y < 0.5",
    "visit_mul": "x * y < 3",
    "visit_div": "x / y < 1",
    "visit_and": "b and x < 2",
    "visit_or": "b or x < 1",
    "visit_implies": "b implies x < 2",
    "visit_abs": "abs(x - y) < 1",
    "visit_min": "min(x, y, 2) < 1.5",
    "visit_max": "max(x, y) > 2",
    "visit_sqrt": "sqrt(x) < 1.2",
    "visit_separation_distance": "separation_distance(vh, 0.5, 0.1, 0.3, 0.2, 0.1, 0.04, 0.01) < 0.6",
    "visit_prev": "prev(x, 0) < x",
    "visit_held": "not held(x > 1, 2)",
    "visit_once": "not once(b, 3)",
    "visit_since": "not since(x > 0.5, b, 3)",
}

SIGNALS = """ethimon: 1
name: coverage
signals:
  x: {range: [0, 4]}
  y: {range: [0.5, 4]}
  vh: {unit: m/s, range: [0, 3]}
  b: {type: bool}
constants:
  k: 1.5
obligations:
"""

#: x, y, vh, b per cycle: equal and unequal x/y, b on and off, x crossing 1 and 2
TRACE = [(0.5, 1.0, 0.2, False), (1.5, 1.5, 0.4, True), (2.5, 1.0, 0.1, False), (3.0, 2.0, 0.6, False),
         (1.0, 1.0, 0.3, True), (0.25, 3.5, 0.0, False), (2.0, 0.5, 0.5, True), (2.2, 2.2, 0.2, False)]


def _spec() -> ethimon.Spec:
    obs = "".join(f"  - {{id: {name[len('visit_'):]}, require: \"{text}\"}}\n" for name, text in EXAMPLES.items())
    return ethimon.load_spec_text(SIGNALS + obs)


def _frames() -> list[dict]:
    return [{"x": x, "y": y, "vh": vh, "b": b, "risk": 0.1} for x, y, vh, b in TRACE]


def _backends() -> dict[str, type]:
    out = {"closures": _Gen, "reference": _Semantics, "offline": Evaluator}
    from ethimon.verify._floats import _Bounds  # the float interval bounds (no z3)
    out["float bounds"] = _Bounds
    try:
        from ethimon.verify._encode import FloatUnrolled, Unrolled
    except ImportError:  # z3 is the verify extra
        return out
    return {**out, "z3 reals": Unrolled, "z3 doubles": FloatUnrolled}


def coverage_problems() -> list[str]:
    """What some back-end lacks, or an entry of the language (its tables now) without an example here."""
    problems = [f"{name}: {m}" for name, cls in _backends().items() for m in missing_methods(cls)]
    for (kind, key), method in _protocol().items():
        if method not in EXAMPLES:
            problems.append(f"{kind} {key!r} -> {method}: no example expression in EXAMPLES")
    return problems


def test_every_backend_implements_every_entry():
    assert coverage_problems() == []
    assert set(EXAMPLES) >= set(PROTOCOL.values())
    assert set(_protocol().values()) <= set(EXAMPLES)
    assert {key for kind, key in PROTOCOL if kind == "binary"} == set(BINARY_OPS)
    assert {key for kind, key in PROTOCOL if kind == "call"} == set(FUNCTIONS)


@pytest.mark.parametrize("row,method", [
    (Operator("fake", "fake", "call", "function", ("num",), "num", "keep"), "visit_fake"),       # a function
    (Operator("xor", "xor", "binary", "logic", ("bool", "bool"), "bool", "none"), "visit_xor"),  # a word
    (Operator("approx", "~=", "binary", "cmp", ("num", "num"), "bool", "same"), "visit_approx"),  # symbols
])
def test_an_entry_without_backend_methods_fails(monkeypatch, row, method):
    monkeypatch.setitem(OPERATORS, row.name, row)
    problems = coverage_problems()
    for name in _backends():
        assert any(p.startswith(f"{name}: ") and method in p for p in problems), (name, problems)
    assert any("no example expression" in p and repr(row.symbol) in p for p in problems)
    with pytest.raises(AssertionError, match=method):
        test_every_backend_implements_every_entry()


def test_an_operator_row_without_a_method_word_is_refused():
    with pytest.raises(ValueError, match="not a word"):
        Operator("<>", "<>", "binary", "cmp", ("num", "num"), "bool", "same")


def test_visit_dispatches_by_table_not_by_isinstance():
    import inspect

    from ethimon.language._visit import ExprVisitor
    src = inspect.getsource(ExprVisitor.visit)
    assert "isinstance" not in src and "_by_type" in src and "_by_key" in src
    assert set(_Gen._by_key.values()) <= {getattr(_Gen, m) for m in PROTOCOL.values()}


def _pairs(spec):
    mon = ethimon.Monitor(spec, margins=True)
    ref = ReferenceMonitor(spec)
    return [(mon.step(f), ref.step(f)) for f in _frames()]


def test_each_entry_agrees_on_monitor_reference_and_offline():
    spec = _spec()
    pairs = _pairs(spec)
    assert not any(d.faults for d, _ in pairs)
    for t, (d, r) in enumerate(pairs):
        assert d.violations == r.violations, t
        assert d.margins == r.margins or all(a == b or (a != a and b != b) for a, b in zip(d.margins, r.margins)), t
    cols = {k: np.array([f[k] for f in _frames()]) for k in ("x", "y", "vh", "b", "risk")}
    off = check_trace(spec, cols)
    ids = off.obligation_ids
    for t, (d, _) in enumerate(pairs):
        assert off.violations_at(t) == d.violations, t
        assert list(off.margins[t]) == list(d.margins), t
    # every example is exercised: each obligation is violated at some cycle and holds at another
    plan = plan_of(spec)
    for k, ob in enumerate(plan.obligations):
        seen = {ob.id in d.violations for d, _ in pairs}
        assert seen == {True, False}, (ids[k], seen)


def test_each_entry_agrees_in_z3_at_the_trace_point():
    z3 = pytest.importorskip("z3")
    from ethimon.verify._encode import FloatUnrolled, Unrolled, real, z3_value
    spec = _spec()
    plan = plan_of(spec)
    ref = ReferenceMonitor(spec)
    for f in _frames():
        ref.step(f)
    assert len(ref.history) == len(TRACE)
    for cls in (Unrolled, FloatUnrolled):
        enc = cls(plan, len(TRACE))
        s = z3.Solver()
        s.add(enc.constraints)
        for t, (x, y, vh, b) in enumerate(TRACE):
            row = enc.sig[t]
            s.add(row["b"] == z3.BoolVal(b))
            for name, v in (("x", x), ("y", y), ("vh", vh)):
                s.add(row[name] == (real(v) if cls is Unrolled else z3.FPVal(v, z3.Float64())))
        terms = []  # (node, t, term): every obligation's require and its numeric left operand
        for ob in plan.obligations:
            nodes = [ob.require] + [n for n in walk(ob.require) if isinstance(n, Binary)
                                    and plan.type_of(n.left).kind == "num"][:1]
            for t in range(len(TRACE)):
                for node in nodes:
                    target = node.left if node is not ob.require else node
                    terms.append((ob.id, target, t, enc.ev(target, t)))
        s.add(enc.constraints)  # the auxiliary definitions (sqrt) the terms added
        assert s.check() == z3.sat, cls.__name__
        model = s.model()
        for oid, node, t, term in terms:
            want = ref.ev(node, t)
            got = z3_value(model, term)
            if isinstance(want, bool):
                assert got is want, (cls.__name__, oid, t)
            else:
                assert math.isclose(got, want, rel_tol=1e-12, abs_tol=1e-12), (cls.__name__, oid, t, got, want)
