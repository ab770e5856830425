import pytest

from ethimon.spec._expr import Binary, Call, ExprSyntaxError, Name, Num, Unary, parse_expr, to_source


def test_precedence_and_associativity():
    e = parse_expr("a or b and not c implies d implies e")
    assert isinstance(e, Binary) and e.op == "implies"
    assert isinstance(e.right, Binary) and e.right.op == "implies"  # right-associative
    assert e.left.op == "or" and e.left.right.op == "and"
    assert isinstance(e.left.right.right, Unary)
    arith = parse_expr("1 + 2 * x - y / 4 < 3")
    assert arith.op == "<" and arith.left.op == "-" and arith.left.left.right.op == "*"


def test_negative_literal_folds_and_calls_parse():
    e = parse_expr("max(-1, x, 2.5e-1) >= abs(-y)")
    assert isinstance(e.left, Call) and e.left.func == "max" and isinstance(e.left.args[0], Num)
    assert e.left.args[0].value == -1.0 and e.left.args[2].value == 0.25
    assert isinstance(e.right.args[0], Unary)


def test_positions_are_character_offsets():
    src = "held(d < 0.5, 3)"
    e = parse_expr(src)
    assert (e.start, e.end) == (0, len(src))
    d = e.args[0].left
    assert isinstance(d, Name) and src[d.start:d.end] == "d"


@pytest.mark.parametrize("src,index,hint", [
    ("a && b", 2, "and"),
    ("a || b", 2, "or"),
    ("x = 1", 2, "=="),
    ("(a < b", 0, ")"),
    ("a < b < c", 6, "a < b and b < c"),
    ("a b", 2, "operator"),
    ("", 0, None),
    ("a <", 3, None),
    ("f(a,", 4, None),
])
def test_syntax_errors_point_at_the_problem(src, index, hint):
    with pytest.raises(ExprSyntaxError) as info:
        parse_expr(src)
    assert info.value.index == index
    if hint:
        assert hint in (info.value.hint or "")


def test_depth_and_length_limits():
    with pytest.raises(ExprSyntaxError):
        parse_expr("(" * 200 + "x" + ")" * 200)
    with pytest.raises(ExprSyntaxError):
        parse_expr("x + " * 2000 + "x")


def test_round_trip():
    src = "held((d < 0.5), 3) implies not (v > 1)"
    assert to_source(parse_expr(to_source(parse_expr(src)))) == to_source(parse_expr(src))
