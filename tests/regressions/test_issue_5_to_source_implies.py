"""Issue 5 (found by the verification suite): ``to_source`` dropped the parentheses of a
left-nested ``implies``, so ``(a implies b) implies c`` came back as ``a implies (b implies c)``."""

from ethimon.spec._expr import Binary, parse_expr, to_source


def test_left_nested_implies_keeps_its_parentheses():
    tree = parse_expr("(a implies b) implies c")
    text = to_source(tree)
    assert text == "(a implies b) implies c"
    again = parse_expr(text)
    assert isinstance(again, Binary) and isinstance(again.left, Binary) and again.left.op == "implies"


def test_right_nested_implies_needs_none():
    assert to_source(parse_expr("a implies (b implies c)")) == "a implies b implies c"
