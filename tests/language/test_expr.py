import pytest

from ethimon.language._expr import Binary, Call, ExprSyntaxError, Name, Num, Unary, parse_expr, to_source


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


def test_and_or_chains_are_balanced_and_keep_order():
    from ethimon.language._expr import walk
    n = 1000
    e = parse_expr(" and ".join(f"a{i}" for i in range(n)))
    names = [x.id for x in walk(e) if isinstance(x, Name)]
    assert names == [f"a{i}" for i in range(n)]  # left to right, as written

    def height(x):
        return 1 + max((height(c) for c in (x.left, x.right)), default=0) if isinstance(x, Binary) else 1
    assert height(e) <= 12  # log2(1000) + 1, not 1000
    three = parse_expr("a or b or c")  # short chains keep the left-nested shape
    assert three.op == "or" and three.left.op == "or" and isinstance(three.right, Name)


def test_arithmetic_chains_stay_left_nested_up_to_the_limit():
    from ethimon.language._expr import MAX_CHAIN_TERMS
    e = parse_expr(" - ".join(["x"] * MAX_CHAIN_TERMS))
    depth = 0
    while isinstance(e, Binary):
        assert isinstance(e.right, Name)
        e, depth = e.left, depth + 1
    assert depth == MAX_CHAIN_TERMS - 1
    src = " * ".join(["x"] * (MAX_CHAIN_TERMS + 5))
    with pytest.raises(ExprSyntaxError) as info:
        parse_expr(src)
    assert f"{MAX_CHAIN_TERMS + 5} terms, the limit is {MAX_CHAIN_TERMS}" in info.value.message
    assert src[info.value.index] == "*" and info.value.index == src.index("*") + 4 * (MAX_CHAIN_TERMS - 1)


@pytest.mark.parametrize("src,index", [("x < 1\u0665", 5), ("x <\u00a01", 3), ("\uff11 > x", 0), ("x\u3000< 1", 1)])
def test_non_ascii_is_a_syntax_error(src, index):
    with pytest.raises(ExprSyntaxError) as info:
        parse_expr(src)
    assert info.value.index == index and "U+" in info.value.message and info.value.hint


@pytest.mark.parametrize("num", ["1e400", "9" * 400, "1.5e309"])
def test_non_finite_literals_are_syntax_errors(num):
    with pytest.raises(ExprSyntaxError) as info:
        parse_expr(f"x < {num}")
    assert info.value.index == 4 and "too large" in info.value.message
    assert parse_expr("x < 1e-400").right.value == 0.0  # underflow to 0 is a number


def test_length_limit():
    from ethimon.language._expr import MAX_EXPR_CHARS
    src = " or ".join(["x"] * (MAX_EXPR_CHARS // 5 + 1))
    assert len(src) > MAX_EXPR_CHARS
    with pytest.raises(ExprSyntaxError, match="too long"):
        parse_expr(src)
