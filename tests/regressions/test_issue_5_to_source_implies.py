"""Issue 5 (found by the verification suite): ``to_source`` dropped the parentheses of a
left-nested ``implies``, so ``(a implies b) implies c`` came back as ``a implies (b implies c)``."""

from ethimon.language._expr import Binary, parse_expr, to_source


def test_left_nested_implies_keeps_its_parentheses():
    tree = parse_expr("(a implies b) implies c")
    text = to_source(tree)
    assert text == "(a implies b) implies c"
    again = parse_expr(text)
    assert isinstance(again, Binary) and isinstance(again.left, Binary) and again.left.op == "implies"


def test_right_nested_implies_needs_none():
    assert to_source(parse_expr("a implies (b implies c)")) == "a implies b implies c"


def test_boolean_operands_of_equality_keep_their_parentheses():
    # found by the verification suite: '(b == not b)' does not parse, and
    # '(a and b == c)' parses as 'a and (b == c)'
    for text in ("b == (not b)", "(a and b) == c", "c != (a or b)", "(a implies b) == c"):
        tree = parse_expr(text)
        again = parse_expr(to_source(tree))
        assert isinstance(again, Binary) and again.op == tree.op
        assert to_source(again) == to_source(tree)
    assert to_source(parse_expr("(a and b) == c")) == "((a and b) == c)"
