"""One fact, one place (issue 13): the tables that several floors read are defined once."""

from __future__ import annotations

import ethimon
from ethimon.spec import SEVERITY_ORDER, Response
from ethimon.spec._expr import BINARY_OPS, COMPARISONS, Binary, parse_expr, walk


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
    from ethimon.spec import SafePose
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
