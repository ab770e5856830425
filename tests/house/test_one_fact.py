"""One fact, one place (issue 13): the tables that several floors read are defined once."""

from __future__ import annotations

import math

import ethimon
from ethimon.language import SEVERITY_ORDER, Response
from ethimon.language._expr import BINARY_OPS, COMPARISONS, Binary, parse_expr, walk


def test_every_binary_operator_the_parser_builds_is_in_the_one_table():
    tree = parse_expr("a + b * c / d - e < f and g >= h or i <= j implies k == l and m != n and o > p")
    ops = {n.op for n in walk(tree) if isinstance(n, Binary)}
    assert ops == set(BINARY_OPS)
    assert {op for op, (kind, _) in BINARY_OPS.items() if kind == "cmp"} == set(COMPARISONS)


def test_the_table_computes_what_python_does():
    assert [BINARY_OPS[op][1](3.0, 2.0) for op in ("<", "<=", ">", ">=", "==", "!=", "+", "-", "*", "/")] == \
        [False, False, True, True, False, True, 5.0, 1.0, 6.0, 1.5]


def test_severity_order_is_the_response_order():
    assert SEVERITY_ORDER == tuple(Response)
    assert [r.severity for r in SEVERITY_ORDER] == list(range(len(Response)))
    from ethimon.sim._control import SEVERITY
    assert SEVERITY == {r.value: r.severity for r in Response}


def test_home_pose_is_one_tuple():
    from ethimon._robot import PANDA_HOME_JOINTS_RAD
    from ethimon.sim._arm import HOME_JOINTS_RAD
    from ethimon.language import SafePose
    assert HOME_JOINTS_RAD is PANDA_HOME_JOINTS_RAD
    assert tuple(SafePose().joints_rad) == PANDA_HOME_JOINTS_RAD


def test_one_error_prefix_in_the_cli():
    import pathlib
    src = pathlib.Path(ethimon.__file__).parent / "cli"
    for path in src.glob("*.py"):
        text = path.read_text(encoding="utf-8")
        if path.name != "_common.py":
            assert '"ethimon: error: ' not in text and "f\"ethimon: error: " not in text, path
            assert "def _err(" not in text, path


# -- the comparison margins: one table, read by the closures, the reference and the offline checker ----------

def _margins_three_ways(op: str, x: float, y: float, obligations: str = "") -> list[tuple[float, ...]]:
    """Margins of ``x <op> y`` (fused: no ``when``; and through ``rob``: under ``when``), or of the
    given obligations, by Monitor.step, the reference interpreter and the offline checker, each
    compiled after the table was read."""
    import numpy as np

    from ethimon.offline import check_trace
    from ethimon.testing import ReferenceMonitor
    obligations = obligations or (f'  - {{id: fused, require: "x {op} y"}}\n'
                                  f'  - {{id: rob, when: "b", require: "x {op} y"}}\n')
    spec = ethimon.load_spec_text(
        "ethimon: 1\nname: t\nsignals:\n  x: {range: [-10, 10]}\n  y: {range: [-10, 10]}\n  b: {type: bool}\n"
        f"obligations:\n{obligations}")
    frame = {"x": x, "y": y, "b": True, "p_unsafe": 0.0}
    offline = check_trace(spec, {k: np.array([v]) for k, v in frame.items()})
    return [ethimon.Monitor(spec).step(frame).margins, ReferenceMonitor(spec).step(frame).margins,
            tuple(float(m) for m in offline.margins[0])]


def _same_float(a: float, b: float) -> bool:  # equal, sign of zero included
    return a == b and math.copysign(1.0, a) == math.copysign(1.0, b)


PAIRS = [(1.0, 2.5), (2.5, 1.0), (2.0, 2.0), (-0.0, 0.0), (0.0, -0.0), (-10.0, 10.0)]


def test_the_three_compute_the_tables_margins():
    from ethimon.language._expr import COMPARISON_MARGINS, comparison_margin
    assert COMPARISON_MARGINS["<"] == "b - a" and COMPARISON_MARGINS[">="] == "a - b"
    assert comparison_margin("<", 2.0, 2.0) == 0.0 and math.copysign(1.0, comparison_margin("<", 2.0, 2.0)) == 1.0
    for op in COMPARISONS:
        for x, y in PAIRS:
            want = comparison_margin(op, x, y)
            for who, margins in zip(("compiled", "reference", "offline"), _margins_three_ways(op, x, y)):
                assert all(_same_float(m, want) for m in margins), (op, x, y, who, margins, want)


def test_the_three_read_the_one_table(monkeypatch):
    """Rewrite the table (every operator's margin negated): all three follow it, none keeps its own copy."""
    from ethimon.language._expr import COMPARISON_MARGINS, MARGIN_SHAPES, comparison_margin
    other = {"a - b": "b - a", "b - a": "a - b", "|a - b|": "-|a - b|", "-|a - b|": "|a - b|"}
    assert set(other) == set(MARGIN_SHAPES)
    before = {op: _margins_three_ways(op, 1.0, 2.5) for op in COMPARISONS}
    for op in COMPARISONS:
        monkeypatch.setitem(COMPARISON_MARGINS, op, other[COMPARISON_MARGINS[op]])
    for op in COMPARISONS:
        want = comparison_margin(op, 1.0, 2.5)
        got = _margins_three_ways(op, 1.0, 2.5)
        assert got != before[op], op
        for who, margins in zip(("compiled", "reference", "offline"), got):
            assert all(_same_float(m, want) for m in margins), (op, who, margins, want)


def test_the_three_read_the_one_connective_table(monkeypatch):
    """``and``/``or``/``implies`` combine the operands' margins as CONNECTIVE_MARGINS says (rewritten here)."""
    from ethimon.language._expr import CONNECTIVE_MARGINS, connective_margin
    assert connective_margin("and", 1.5, 2.5) == 1.5 and connective_margin("or", 1.5, 2.5) == 2.5
    assert connective_margin("implies", 1.5, 2.5) == 2.5 and connective_margin("implies", -3.0, 2.5) == 3.0
    obligations = "".join(f'  - {{id: o{i}, require: "x < y {op} y <= 5"}}\n'
                          for i, op in enumerate(CONNECTIVE_MARGINS))
    x, y = 1.0, 2.5  # the comparisons' margins: 1.5 and 2.5
    want = tuple(connective_margin(op, 1.5, 2.5) for op in CONNECTIVE_MARGINS)
    assert want == (1.5, 2.5, 2.5)
    assert _margins_three_ways("", x, y, obligations) == [want] * 3
    for op, (combine, negate_left) in list(CONNECTIVE_MARGINS.items()):
        monkeypatch.setitem(CONNECTIVE_MARGINS, op, ("max" if combine == "min" else "min", not negate_left))
    rewritten = tuple(connective_margin(op, 1.5, 2.5) for op in CONNECTIVE_MARGINS)
    assert rewritten == (2.5, -1.5, 1.5)
    assert _margins_three_ways("", x, y, obligations) == [rewritten] * 3


def test_no_margin_table_is_written_again():
    """The three margin functions name no comparison or connective themselves: they read the tables."""
    import inspect

    from ethimon.compiler._closures import _fused_comparison, _Gen
    from ethimon.offline._eval import Evaluator
    from ethimon.testing import ReferenceMonitor
    for fn in (_Gen.rob, _fused_comparison, ReferenceMonitor.rob, Evaluator._rob):
        text = inspect.getsource(fn)
        for literal in ('"<"', '"<="', '">"', '">="', '"=="', '"!="', '"and"', '"or"', '"implies"'):
            assert literal not in text, (fn.__qualname__, literal)
        assert "COMPARISON_MARGINS" in text or "comparison_margin" in text, fn.__qualname__
    for fn in (_Gen.rob, ReferenceMonitor.rob, Evaluator._rob):
        assert "CONNECTIVE_MARGINS" in inspect.getsource(fn), fn.__qualname__
