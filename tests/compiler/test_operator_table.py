"""Each operator is declared once (issue 33, item 2): ``ethimon.language.OPERATORS``.

The parser's and checker's arity, the temporal set, the binary operators, the margins, the
interpreter protocol, the type and unit checks and the z3 encoder's look-back are read from the
table. The proof: adding ``always_within(e, n)`` (a windowed operator) is one row, the back-ends'
``visit_always_within`` methods and one example; the row alone already gives it its arity, its
types, its window and its look-back, and every back-end that lacks the method fails the coverage
test (never a silent pass).
"""

from __future__ import annotations

import pytest

import ethimon
from ethimon.compiler import plan_of
from ethimon.errors import SpecError
from ethimon.language import OPERATORS, Operator
from ethimon.language._expr import (BINARY_OPS, COMPARISON_MARGINS, CONNECTIVE_MARGINS, FUNCTIONS, TEMPORAL, walk)
from ethimon.language._visit import ExprAnalysis, ExprVisitor, PROTOCOL, missing_methods

ALWAYS_WITHIN = Operator("always_within", "always_within", "call", "temporal", ("bool", "window"), "bool", "none",
                         "window", doc="always_within(e, n): e at each of the last n cycles")

SPEC = """ethimon: 1
name: always-within
rate_hz: 100
signals:
  x: {range: [0, 4]}
obligations:
  - {id: calm, require: "not always_within(x > 1, 3)"}
"""


@pytest.fixture
def always_within(monkeypatch):
    """The table with one more row, as if it were written in ``language/_operators.py``."""
    monkeypatch.setitem(OPERATORS, ALWAYS_WITHIN.name, ALWAYS_WITHIN)
    return ALWAYS_WITHIN


def _node(plan, func):
    return next(n for ob in plan.obligations for n in walk(ob.require) if getattr(n, "func", None) == func)


def test_a_new_row_is_checked_typed_and_windowed_by_the_table(always_within):
    plan = plan_of(ethimon.load_spec_text(SPEC))
    node = _node(plan, "always_within")
    assert plan.type_of(node).kind == "bool"
    assert node.ann.window == 3 and plan.temporal[node.ann.slot] is node
    # a window in seconds, the operand's kind and the arity come from the row too
    timed = _node(plan_of(ethimon.load_spec_text(SPEC.replace(", 3)", ", 0.05 s)"))), "always_within")
    assert timed.ann.seconds == 0.05 and timed.ann.window >= 1
    with pytest.raises(SpecError, match=r"always_within\(\) needs a boolean"):
        ethimon.load_spec_text(SPEC.replace("x > 1, 3", "x, 3"))
    with pytest.raises(SpecError, match=r"always_within\(\) takes 2 arguments, got 1"):
        ethimon.load_spec_text(SPEC.replace("x > 1, 3", "x > 1"))
    with pytest.raises(SpecError, match=r"the window of always_within\(\) must be a whole number"):
        ethimon.load_spec_text(SPEC.replace("x > 1, 3", "x > 1, x"))


def test_a_new_windowed_row_gets_its_lookback_without_editing_the_encoder(always_within):
    """The defect of issue 33: ``verify``'s look-back listed held/once/since by name, so a new
    windowed operator read 0 cycles back and a proof claimed more than it showed."""
    pytest.importorskip("z3")
    from ethimon.verify._encode import lookback
    plan = plan_of(ethimon.load_spec_text(SPEC))
    node = _node(plan, "always_within")
    assert lookback(plan, node) == 2  # n - 1, as for held(e, 3)
    assert lookback(plan, plan.obligations[0].require) == 2


def test_a_new_row_without_its_methods_fails_the_coverage_test(always_within):
    from tests.compiler.test_interpreter_coverage import _backends, coverage_problems, \
        test_every_backend_implements_every_entry
    problems = coverage_problems()
    for name in _backends():
        assert f"{name}: call 'always_within' -> visit_always_within" in problems
    assert any("no example expression" in p and "'always_within'" in p for p in problems)
    with pytest.raises(AssertionError, match="visit_always_within"):
        test_every_backend_implements_every_entry()


def test_a_new_row_is_one_method_in_each_back_end(always_within):
    """With ``visit_always_within`` the reference interpreter evaluates it (the others alike)."""
    from ethimon.testing import ReferenceMonitor
    from ethimon.testing._reference import _Semantics

    class WithAlwaysWithin(_Semantics):
        def visit_always_within(self, node, t):
            return self.visit_held(node, t)

    assert missing_methods(WithAlwaysWithin) == [] and missing_methods(_Semantics) != []
    spec = ethimon.load_spec_text(SPEC)
    ref = ReferenceMonitor(spec)
    ref._semantics = WithAlwaysWithin(ref)
    got = [ref.step({"x": x, "risk": 0.0}).violations for x in (2, 2, 2, 0, 2)]
    assert got == [(), (), ("calm",), (), ()]


def test_the_derived_tables_are_the_table():
    calls = [op for op in OPERATORS.values() if op.kind == "call"]
    assert FUNCTIONS == {op.symbol: (op.min_args, op.max_args) for op in calls}
    assert TEMPORAL == {op.symbol for op in OPERATORS.values() if op.lookback != "none"}
    assert BINARY_OPS == {op.symbol: (op.family, op.fn) for op in OPERATORS.values() if op.kind == "binary"}
    assert set(COMPARISON_MARGINS) | set(CONNECTIVE_MARGINS) == {
        op.symbol for op in OPERATORS.values() if op.margin is not None}
    assert set(PROTOCOL.values()) == {op.method for op in OPERATORS.values()} | {
        "visit_num", "visit_bool", "visit_name"}
    assert {name for name in vars(ExprVisitor) if name.startswith("visit_")} - {"visit"} == set(PROTOCOL.values())


@pytest.mark.parametrize("bad,match", [
    (dict(unit="angle"), "unit rule 'angle'"),
    (dict(lookback="none"), "windowed lookback"),
    (dict(args=("bool",), lookback="window"), "window argument"),
    (dict(family="function"), "reads the past"),
])
def test_a_row_that_contradicts_itself_is_refused(bad, match):
    fields = dict(name="w", symbol="w", kind="call", family="temporal", args=("bool", "window"), result="bool",
                  unit="none", lookback="window")
    with pytest.raises(ValueError, match=match):
        Operator(**{**fields, **bad})


def test_the_analysis_base_defaults_to_the_operands():
    """An analysis overrides what it cares about; every other entry (a new row too) visits the
    operands and combines their results."""

    class Depth(ExprAnalysis):
        def visit_num(self, node):
            return 1

        visit_bool = visit_name = visit_num

        def combine(self, node, results):
            return 1 + max(results)

    from ethimon.language import parse_expr
    assert Depth().visit(parse_expr("held(x > 1, 3) and not (y + 1 < 2)")) == 5


def test_may_raise_rows_are_the_encoders_definedness():
    """Every row that says it may raise has a definedness condition in the z3 encoder, and no other
    row has one (a new row that can raise without one would let ``verify`` prove a cycle that
    fails closed)."""
    z3 = pytest.importorskip("z3")
    from ethimon.verify._encode import Unrolled
    examples = {"div": "x / y < 1", "sqrt": "sqrt(y - 1) < 1",
                "separation_distance": "separation_distance(y - 1, 0, 0, 0, 0, 0, 0, 0) < 1"}
    raising = {op.name for op in OPERATORS.values() if op.may_raise}
    assert raising == set(examples)
    spec = ethimon.load_spec_text("ethimon: 1\nname: df\nsignals:\n  x: {range: [0, 4]}\n  y: {range: [-4, 4]}\n"
                                  "obligations:\n" + "".join(f"  - {{id: {k}, require: \"{v}\"}}\n"
                                                             for k, v in examples.items()))
    plan = plan_of(spec)
    enc = Unrolled(plan, 1)
    for ob in plan.obligations:
        s = z3.Solver()
        s.add(enc.constraints)
        s.add(z3.Not(enc.defined(ob.require, 0)))
        assert s.check() == z3.sat, ob.id  # some input in range makes it raise


def test_a_new_may_raise_row_makes_the_compiled_machine_guard_it(monkeypatch):
    """The closures' ``_may_raise`` named ``/``, ``sqrt`` and ``separation_distance``: a new row that
    can raise (``log``) was compiled as if it never raised."""
    from ethimon.compiler._closures import _may_raise
    from ethimon.language import parse_expr
    monkeypatch.setitem(OPERATORS, "log", Operator("log", "log", "call", "function", ("num",), "num", "keep",
                                                    may_raise="an argument <= 0"))
    assert _may_raise(parse_expr("log(x) < 1"))
    assert _may_raise(parse_expr("x / y < 1")) and not _may_raise(parse_expr("abs(x) < 1"))


# -- issue 33 item 2, the rest: interval bounds and definedness from the table, nothing silent ------

LOG = Operator("log", "log", "call", "function", ("num",), "num", "keep", fn=None, may_raise="an argument <= 0")
LOG_SPEC = """\
ethimon: 1
name: logs
signals:
  x: {range: [0.5, 4]}
obligations:
  - {id: small, require: "log(x) < 1"}
"""


def test_a_new_row_without_its_interval_method_cannot_be_bounded(always_within):
    """The float interval bounds were an ``isinstance`` chain with a ``None`` fall-through: a new
    operator got no bound and no word about it. Now they are a back-end of the protocol."""
    from ethimon.verify._floats import _Bounds
    plan = plan_of(ethimon.load_spec_text(SPEC))
    assert "call 'always_within' -> visit_always_within" in " ".join(missing_methods(_Bounds))
    with pytest.raises(TypeError, match="cannot interpret"):  # loud, never a silent "no bound"
        _Bounds(plan).of(_node(plan, "always_within"))


def test_a_new_may_raise_row_is_never_shown_defined_in_doubles(monkeypatch):
    """``defined_in_doubles`` named ``/``, ``sqrt`` and ``separation_distance``: a new row that can raise
    was taken as defined for every input."""
    from ethimon.verify._floats import SHOWN_DEFINED, _Bounds, defined_in_doubles
    monkeypatch.setitem(OPERATORS, LOG.name, LOG)
    monkeypatch.setattr(_Bounds, "visit_log", lambda self, node: None, raising=False)
    plan = plan_of(ethimon.load_spec_text(LOG_SPEC))
    assert "log" not in SHOWN_DEFINED
    assert defined_in_doubles(plan, plan.obligations[0]) is False  # not shown: the IEEE-754 model decides


def test_a_new_may_raise_row_without_a_z3_condition_is_refused(monkeypatch):
    """The z3 encoder's definedness listed ``/``, ``sqrt`` and ``separation_distance`` by name: a new
    row that can raise was encoded as always defined, so ``verify`` proved a cycle that fails closed."""
    pytest.importorskip("z3")
    from ethimon.verify._encode import RAISE_FREE, Unrolled
    monkeypatch.setitem(OPERATORS, LOG.name, LOG)

    class WithLog(Unrolled):
        def visit_log(self, node, t):
            return self.ev(node.args[0], t)

    plan = plan_of(ethimon.load_spec_text(LOG_SPEC))
    enc = WithLog(plan, 1)
    with pytest.raises(TypeError, match="RAISE_FREE"):
        enc.defined(plan.obligations[0].require, 0)
    monkeypatch.setitem(RAISE_FREE, "log", lambda e, node, t: [e.ev(node.args[0], t) > 0])
    assert str(enc.defined(plan.obligations[0].require, 0)) != "True"


def test_every_may_raise_row_has_its_definedness_everywhere():
    pytest.importorskip("z3")
    from ethimon.verify._encode import RAISE_FREE
    from ethimon.verify._floats import SHOWN_DEFINED
    raising = {op.name for op in OPERATORS.values() if op.may_raise}
    assert set(RAISE_FREE) == raising == set(SHOWN_DEFINED)


def test_always_within_is_one_row_its_methods_and_one_example(always_within, monkeypatch):
    """The acceptance test of issue 33: the row (fixture), one ``visit_always_within`` per back-end
    (here bound to each back-end's ``held``, which it equals) and one example close the coverage
    check; forgetting any one method is named by it (above, and for the float bounds here)."""
    from tests.compiler import test_interpreter_coverage as cov
    backends = cov._backends()
    monkeypatch.setitem(cov.EXAMPLES, "visit_always_within", "not always_within(x > 1, 2)")
    for cls in backends.values():
        monkeypatch.setattr(cls, "visit_always_within", cls.visit_held, raising=False)
    assert cov.coverage_problems() == []
    from ethimon.verify._floats import _Bounds
    monkeypatch.delattr(_Bounds, "visit_always_within")
    assert cov.coverage_problems() == ["float bounds: call 'always_within' -> visit_always_within"]
