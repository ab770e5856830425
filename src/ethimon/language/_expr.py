"""The obligation expression language: tokenizer, parser and AST.

Grammar (lowest precedence first)::

    expr    := or ( "implies" expr )?            # right-associative
    or      := and ( "or" and )*
    and     := not ( "and" not )*
    not     := "not" not | cmp
    cmp     := sum ( ("<" | "<=" | ">" | ">=" | "==" | "!=") sum )?
    sum     := term ( ("+" | "-") term )*
    term    := unary ( ("*" | "/") unary )*
    unary   := "-" unary | primary
    primary := NUMBER "s"? | "true" | "false" | NAME | NAME "(" args? ")" | "(" expr ")"

Functions: ``abs(x)``, ``min(x, y, ...)``, ``max(x, y, ...)``, ``sqrt(x)``,
``separation_distance(v_h, v_r, T_r, T_s, S_s, C, Z_d, Z_r)`` (the protective
separation distance of ISO/TS 15066, see :func:`separation_distance`) and
the bounded past-time temporal operators ``prev(e[, init])``,
``held(e, n)``, ``once(e, n)``, ``since(a, b[, n])`` (integer cycle bounds, or
a time in seconds, ``held(e, 0.5 s)``: a number followed by the unit ``s``, a
:class:`Seconds` node, which the compiler turns into cycles at the spec's
``rate_hz`` and refuses anywhere but a window).

The parser is hand-written (no ``eval``); every node keeps the character
offsets of its source text so errors can point at file:line:column.

Expressions are ASCII: digits are ``0-9``, names ``[A-Za-z_][A-Za-z0-9_]*``,
whitespace is space, tab and line breaks (a non-ASCII digit such as ``٥`` or
``５``, or a no-break space, is a syntax error, never read as a number or a
blank).

Size limits (each a syntax error with a position, never a crash):
``MAX_EXPR_CHARS`` characters, ``MAX_EXPR_DEPTH`` levels of parentheses,
``not``, unary minus, ``implies`` and calls, ``MAX_CHAIN_TERMS`` terms in one
chain of ``+``/``-`` or of ``*``/``/``, and ``MAX_TREE_DEPTH`` levels in the
resulting tree. A chain of ``and`` (or of ``or``) is built as a balanced tree
(same value, same left-to-right short-circuit order, depth log2 of its
length), so its length is bounded only by ``MAX_EXPR_CHARS``; a chain of
``+``, ``-``, ``*`` or ``/`` keeps its left-to-right grouping (float rounding
depends on it), one tree level per term.
"""

from __future__ import annotations

import math
import re
import unicodedata
from dataclasses import dataclass

from ..errors import ExprSyntaxError
from ._operators import MARGIN_SHAPES, OPERATORS, SEPARATION_PARAMS, UNIT_RULES, Operator, operator_of, separation_distance

__all__ = [
    "Node", "Num", "Seconds", "BoolLit", "Name", "Unary", "Binary", "Call", "ExprSyntaxError",
    "parse_expr", "BINARY_OPS", "COMPARISON_MARGINS", "MARGIN_SHAPES", "comparison_margin",
    "CONNECTIVE_MARGINS", "connective_margin", "FUNCTIONS", "TEMPORAL", "walk", "to_source",
    "SEPARATION_PARAMS", "separation_distance", "is_temporal", "UNIT_RULES",
]


@dataclass(frozen=True, eq=False)
class Node:
    """A node of the expression tree: frozen, compared by identity (``eq=False``: a node is a
    dictionary key by identity, never by ``id()``).

    ``ann`` is what the checker (``compiler/_typecheck.py``) found out about the node: its type
    (and unit), a temporal node's window, ... (``compiler.Note``). ``None`` until the checker sets
    it, once (:meth:`annotate`); the tree of a compiled :class:`~ethimon.compiler.Plan` is
    annotated throughout, and every later stage reads the annotation from the node.
    """

    start: int
    end: int

    #: the checker's annotation (a class default, not a field: set once per node by :meth:`annotate`)
    ann = None

    def annotate(self, ann) -> None:
        """Set :attr:`ann` once: a second annotation of the same node is refused (a checked tree
        is frozen; a node belongs to the one plan whose checker annotated it)."""
        if "ann" in self.__dict__:
            raise ValueError(f"{type(self).__name__} at {self.start}..{self.end} is annotated already: "
                             "a checked tree is frozen (parse the text again to check it again)")
        object.__setattr__(self, "ann", ann)

    @property
    def children(self) -> tuple[Node, ...]:
        """The operands, left to right (a leaf has none)."""
        return ()

    @property
    def row(self) -> Operator | None:
        """This node's entry of :data:`~ethimon.language._operators.OPERATORS` (``None``: a leaf,
        or a call of an unknown function, which the checker refuses)."""
        return None


@dataclass(frozen=True, eq=False)
class Num(Node):
    value: float


@dataclass(frozen=True, eq=False)
class Seconds(Num):
    """A time in seconds, written ``0.5 s`` (or ``0.5s``): only a window of ``held``/``once``/``since``.

    A :class:`Num` (its ``value`` is the seconds the author wrote), so every walker that reads
    literals sees a number; the compiler turns it into whole cycles at the spec's ``rate_hz``."""


#: the one unit suffix a number may carry in an expression (a window in seconds)
SECONDS_SUFFIX = "s"


@dataclass(frozen=True, eq=False)
class BoolLit(Node):
    value: bool


@dataclass(frozen=True, eq=False)
class Name(Node):
    id: str


@dataclass(frozen=True, eq=False)
class Unary(Node):
    op: str  # "-" or "not"
    operand: Node

    @property
    def children(self) -> tuple[Node, ...]:
        return (self.operand,)

    @property
    def row(self) -> Operator | None:
        return operator_of("unary", self.op)


@dataclass(frozen=True, eq=False)
class Binary(Node):
    op: str
    left: Node
    right: Node

    @property
    def children(self) -> tuple[Node, ...]:
        return (self.left, self.right)

    @property
    def row(self) -> Operator | None:
        return operator_of("binary", self.op)


@dataclass(frozen=True, eq=False)
class Call(Node):
    func: str
    args: tuple[Node, ...]
    name_end: int = 0

    @property
    def children(self) -> tuple[Node, ...]:
        return self.args

    @property
    def row(self) -> Operator | None:
        return operator_of("call", self.func)


#: name -> (min args, max args): the functions of :data:`~ethimon.language._operators.OPERATORS`
FUNCTIONS: dict[str, tuple[int, int]] = {op.symbol: (op.min_args, op.max_args)
                                         for op in OPERATORS.values() if op.kind == "call"}
#: the operators that read the past (their rows' ``lookback`` is not ``"none"``)
TEMPORAL = frozenset(op.symbol for op in OPERATORS.values() if op.family == "temporal")
KEYWORDS = frozenset({"and", "or", "not", "implies", "true", "false"})
COMPARISONS = ("<=", ">=", "==", "!=", "<", ">")

#: The binary operators, derived from :data:`OPERATORS`: op -> (family, function of the two operand values).
#: ``cmp`` and ``arith`` apply the function to both values (Python floats in the reference
#: interpreter, z3 terms in the SMT encoder: the same ``operator`` call builds either);
#: ``logic`` connectives have no function, each interpreter short-circuits them its own way.
BINARY_OPS: dict[str, tuple[str, object]] = {op.symbol: (op.family, op.fn)
                                             for op in OPERATORS.values() if op.kind == "binary"}
assert set(COMPARISONS) == {op for op, (kind, _) in BINARY_OPS.items() if kind == "cmp"}

#: The comparison margins (robustness: > 0 holds, < 0 fails, the distance to the boundary), the
#: rows' ``margin``: op -> shape, one of ``MARGIN_SHAPES``, with ``a`` the left and ``b`` the right
#: operand's value. ``"b - a"`` subtracts in that order (never ``-(a - b)``: a tie is +0.0).
#: The compiled closures pick one specialised closure per shape at compile time; the reference
#: interpreter and the offline checker call :func:`comparison_margin` (floats or numpy arrays).
COMPARISON_MARGINS: dict[str, str] = {op.symbol: op.margin for op in OPERATORS.values() if op.family == "cmp"}
assert set(COMPARISON_MARGINS) == set(COMPARISONS) and set(COMPARISON_MARGINS.values()) <= set(MARGIN_SHAPES)


def comparison_margin(op: str, a, b):
    """The margin of ``a <op> b`` by :data:`COMPARISON_MARGINS` (Python floats or numpy arrays)."""
    shape = COMPARISON_MARGINS[op]
    if shape == "a - b":
        return a - b
    if shape == "b - a":
        return b - a
    if shape == "|a - b|":
        return abs(a - b)
    return -abs(a - b)


#: The connectives' margins, the rows' ``margin``: op -> (how the two margins combine, whether the
#: left operand's margin is negated first). ``"min"``/``"max"`` are Python's ``min(l, r)``/``max(l, r)``:
#: the left margin unless the right one is strictly smaller/larger (so a NaN on the left is kept, a
#: NaN on the right is not; the offline checker picks the same way with ``numpy.where``).
#: ``not e`` negates the margin of ``e``.
CONNECTIVE_MARGINS: dict[str, tuple[str, bool]] = {op.symbol: op.margin for op in OPERATORS.values()
                                                   if op.family == "logic"}
assert set(CONNECTIVE_MARGINS) == {op for op, (kind, _) in BINARY_OPS.items() if kind == "logic"}


def connective_margin(op: str, left: float, right: float) -> float:
    """The margin of ``l <op> r`` from the two operands' margins by :data:`CONNECTIVE_MARGINS`."""
    combine, negate_left = CONNECTIVE_MARGINS[op]
    if negate_left:
        left = -left
    return min(left, right) if combine == "min" else max(left, right)


# ASCII only: in a str pattern, \d and \s would also match "٥", "５" and U+00A0
_TOKEN = re.compile(r"""
    (?P<ws>[ \t\r\n]+)
  | (?P<num>(?:[0-9]+\.[0-9]*|\.[0-9]+|[0-9]+)(?:[eE][-+]?[0-9]+)?)
  | (?P<name>[A-Za-z_][A-Za-z0-9_]*)
  | (?P<op><=|>=|==|!=|<|>|\+|-|\*|/|\(|\)|,)
""", re.VERBOSE | re.ASCII)

MAX_EXPR_CHARS = 20_000
MAX_EXPR_DEPTH = 48
#: terms in one chain of + and - (or of * and /): each adds a tree level
MAX_CHAIN_TERMS = 100
#: levels of the expression tree (chains, nesting and calls together)
MAX_TREE_DEPTH = 160


@dataclass(frozen=True)
class _Tok:
    kind: str
    text: str
    start: int
    end: int


def _tokenize(src: str) -> list[_Tok]:
    toks: list[_Tok] = []
    i, n = 0, len(src)
    while i < n:
        m = _TOKEN.match(src, i)
        if m is None:
            ch = src[i]
            hint = None
            if ch == "&":
                hint = "write 'and'"
            elif ch == "|":
                hint = "write 'or'"
            elif ch == "!":
                hint = "write 'not' (or '!=' for inequality)"
            elif ch == "=":
                hint = "compare with '=='"
            elif ch in "[]{}":
                hint = "windows are written held(x, n) / once(x, n)"
            elif not ch.isascii():
                raise _non_ascii(src, i)
            raise ExprSyntaxError(f"unexpected character {ch!r}", i, hint)
        kind = m.lastgroup
        if kind != "ws":
            text = m.group()
            if kind == "name" and text in KEYWORDS:
                kind = text
            toks.append(_Tok(kind, text, i, m.end()))
        i = m.end()
    toks.append(_Tok("eof", "", n, n))
    return toks


def _non_ascii(src: str, i: int) -> ExprSyntaxError:
    ch = src[i]
    name = unicodedata.name(ch, "")
    shown = f"U+{ord(ch):04X}" + (f" {name}" if name else "")
    if ch.isdigit() or ch.isdecimal():
        hint = "expressions use the ASCII digits 0-9 only"
    elif ch.isspace():
        hint = "use a plain space"
    elif ch in "≤≥≠−×÷":
        hint = "write <=, >=, !=, -, * or / (ASCII)"
    else:
        hint = "expressions are ASCII: names are letters, digits and '_'"
    return ExprSyntaxError(f"unexpected character {ch!r} ({shown})", i, hint)


class _Parser:
    def __init__(self, src: str) -> None:
        self.src = src
        self.toks = _tokenize(src)
        self.i = 0
        self.depth = 0
        self.heights: dict[Node, int] = {}  # node (by identity) -> levels of its tree (1 for a leaf)

    @property
    def tok(self) -> _Tok:
        return self.toks[self.i]

    def take(self) -> _Tok:
        t = self.toks[self.i]
        self.i += 1
        return t

    def expect(self, kind: str, what: str) -> _Tok:
        t = self.tok
        if t.kind != kind:
            found = "end of expression" if t.kind == "eof" else repr(t.text)
            raise ExprSyntaxError(f"expected {what}, found {found}", t.start)
        return self.take()

    def height(self, node: Node) -> int:
        return self.heights.get(node, 1)

    def binary(self, op: str, left: Node, right: Node, at: int) -> Binary:
        """A Binary node, refused if the tree gets deeper than ``MAX_TREE_DEPTH``."""
        h = 1 + max(self.height(left), self.height(right))
        if h > MAX_TREE_DEPTH:
            raise ExprSyntaxError(f"expression is nested or chained too deeply (more than {MAX_TREE_DEPTH} "
                                  "levels)", at, _SPLIT_HINT)
        node = Binary(left.start, right.end, op, left, right)
        self.heights[node] = h
        return node

    def wrap(self, node: Node, child: Node, at: int) -> Node:
        h = 1 + self.height(child)
        if h > MAX_TREE_DEPTH:
            raise ExprSyntaxError(f"expression is nested or chained too deeply (more than {MAX_TREE_DEPTH} "
                                  "levels)", at, _SPLIT_HINT)
        self.heights[node] = h
        return node

    def balanced(self, op: str, terms: list[Node], ops: list[_Tok]) -> Node:
        """``terms[0] op terms[1] op ...`` as a balanced tree (for associative ``and``/``or``).

        Evaluation is left to right with the same short-circuit as the left-nested
        chain; a chain of three keeps the left-nested shape ``(a op b) op c``.
        """
        if len(terms) == 1:
            return terms[0]
        mid = len(terms) - len(terms) // 2
        left = self.balanced(op, terms[:mid], ops[:mid - 1])
        right = self.balanced(op, terms[mid:], ops[mid:])
        return self.binary(op, left, right, ops[mid - 1].start)

    def _enter(self) -> None:
        self.depth += 1
        if self.depth > MAX_EXPR_DEPTH:
            raise ExprSyntaxError("expression is nested too deeply", self.tok.start,
                                  f"at most {MAX_EXPR_DEPTH} levels")

    def parse(self) -> Node:
        if not self.src.strip():
            raise ExprSyntaxError("empty expression", 0, "write a condition such as 'human_distance > 0.5'")
        node = self.expr()
        if self.tok.kind != "eof":
            t = self.tok
            hint = None
            if t.kind in ("num", "name", "("):
                hint = "an operator ('and', 'or', '<', '+', ...) is missing"
            raise ExprSyntaxError(f"unexpected {t.text!r}", t.start, hint)
        return node

    def expr(self) -> Node:
        self._enter()
        left = self.or_()
        if self.tok.kind == "implies":
            t = self.take()
            right = self.expr()
            left = self.binary("implies", left, right, t.start)
        self.depth -= 1
        return left

    def or_(self) -> Node:
        terms, ops = [self.and_()], []
        while self.tok.kind == "or":
            ops.append(self.take())
            terms.append(self.and_())
        return self.balanced("or", terms, ops)

    def and_(self) -> Node:
        terms, ops = [self.not_()], []
        while self.tok.kind == "and":
            ops.append(self.take())
            terms.append(self.not_())
        return self.balanced("and", terms, ops)

    def not_(self) -> Node:
        if self.tok.kind == "not":
            t = self.take()
            self._enter()
            operand = self.not_()
            self.depth -= 1
            return self.wrap(Unary(t.start, operand.end, "not", operand), operand, t.start)
        return self.cmp()

    def cmp(self) -> Node:
        left = self.sum()
        if self.tok.kind == "op" and self.tok.text in COMPARISONS:
            t = self.take()
            right = self.sum()
            if self.tok.kind == "op" and self.tok.text in COMPARISONS:
                raise ExprSyntaxError("comparisons cannot be chained", self.tok.start,
                                      "write 'a < b and b < c'")
            return self.binary(t.text, left, right, t.start)
        return left

    def sum(self) -> Node:
        return self.chain(("+", "-"), self.term)

    def term(self) -> Node:
        return self.chain(("*", "/"), self.unary)

    def chain(self, symbols: tuple[str, str], operand) -> Node:
        """A left-nested chain ``a op b op c ...`` of at most ``MAX_CHAIN_TERMS`` terms."""
        first = operand()
        terms, ops = [first], []
        while self.tok.kind == "op" and self.tok.text in symbols:
            ops.append(self.take())
            terms.append(operand())
        if len(terms) > MAX_CHAIN_TERMS:
            raise ExprSyntaxError(
                f"chain of '{symbols[0]}'/'{symbols[1]}' is too long: {len(terms)} terms, the limit is "
                f"{MAX_CHAIN_TERMS}", ops[MAX_CHAIN_TERMS - 1].start, _SPLIT_HINT)
        left = first
        for t, right in zip(ops, terms[1:]):
            left = self.binary(t.text, left, right, t.start)
        return left

    def unary(self) -> Node:
        if self.tok.kind == "op" and self.tok.text == "-":
            t = self.take()
            self._enter()
            operand = self.unary()
            self.depth -= 1
            if isinstance(operand, Num):
                return type(operand)(t.start, operand.end, -operand.value)  # -0.5 s stays in seconds
            return self.wrap(Unary(t.start, operand.end, "-", operand), operand, t.start)
        return self.primary()

    def primary(self) -> Node:
        t = self.tok
        if t.kind == "num":
            self.take()
            value = float(t.text)
            if not math.isfinite(value):
                raise ExprSyntaxError(f"number {_shorten(t.text)} is too large", t.start,
                                      "the largest number is about 1.8e308")
            if self.tok.kind == "name" and self.tok.text == SECONDS_SUFFIX:  # 0.5 s: a time in seconds
                unit = self.take()
                return Seconds(t.start, unit.end, value)
            return Num(t.start, t.end, value)
        if t.kind in ("true", "false"):
            self.take()
            return BoolLit(t.start, t.end, t.kind == "true")
        if t.kind == "name":
            self.take()
            if self.tok.kind == "op" and self.tok.text == "(":
                return self.call(t)
            return Name(t.start, t.end, t.text)
        if t.kind == "op" and t.text == "(":
            self.take()
            self._enter()
            inner = self.expr()
            self.depth -= 1
            self.expect_close(t.start)
            return inner
        if t.kind == "eof":
            raise ExprSyntaxError("expression ends too early", t.start, "an operand is missing")
        raise ExprSyntaxError(f"unexpected {t.text!r}", t.start, "an operand is missing")

    def expect_close(self, open_at: int) -> _Tok:
        t = self.tok
        if t.kind == "op" and t.text == ")":
            return self.take()
        if t.kind == "eof":
            raise ExprSyntaxError("unclosed '('", open_at, "add ')'")
        raise ExprSyntaxError(f"expected ')', found {t.text!r}", t.start)

    def call(self, name: _Tok) -> Node:
        open_tok = self.take()  # "("
        args: list[Node] = []
        self._enter()
        if not (self.tok.kind == "op" and self.tok.text == ")"):
            while True:
                args.append(self.expr())
                if self.tok.kind == "op" and self.tok.text == ",":
                    self.take()
                    continue
                break
        self.depth -= 1
        close = self.expect_close(open_tok.start)
        node = Call(name.start, close.end, name.text, tuple(args), name.end)
        h = 1 + max((self.height(a) for a in args), default=0)
        if h > MAX_TREE_DEPTH:
            raise ExprSyntaxError(f"expression is nested or chained too deeply (more than {MAX_TREE_DEPTH} "
                                  "levels)", name.start, _SPLIT_HINT)
        self.heights[node] = h
        return node


_SPLIT_HINT = ("each term of a '+', '-', '*' or '/' chain adds a level; group terms with parentheses, "
               "e.g. (a + b) + (c + d), or split the rule into several obligations")


def _shorten(text: str) -> str:
    return text if len(text) <= 24 else f"{text[:10]}...{text[-6:]} ({len(text)} characters)"


def parse_expr(src: str) -> Node:
    """Parse expression text into an AST.

    Raises:
        ExprSyntaxError: with the character index of the problem.

    Example:
        >>> to_source(parse_expr("held(d < 0.5, 3) implies not (v > 1)"))
        'held((d < 0.5), 3) implies not (v > 1)'
    """
    if len(src) > MAX_EXPR_CHARS:
        raise ExprSyntaxError(f"expression is too long ({len(src)} characters)", MAX_EXPR_CHARS,
                              f"at most {MAX_EXPR_CHARS}")
    return _Parser(src).parse()


def is_temporal(node: Node) -> bool:
    """Whether ``node`` is a temporal operator (its row reads the past), by the operator table now."""
    row = node.row
    return row is not None and row.family == "temporal"


def walk(node: Node):
    """Yield ``node`` and all its descendants, parents first."""
    stack = [node]
    while stack:
        n = stack.pop()
        yield n
        if isinstance(n, Unary):
            stack.append(n.operand)
        elif isinstance(n, Binary):
            stack.extend((n.right, n.left))
        elif isinstance(n, Call):
            stack.extend(reversed(n.args))


def to_source(node: Node) -> str:
    """Render an AST back to (fully parenthesised where needed) source text."""
    if isinstance(node, Num):
        v = node.value
        text = repr(int(v)) if v == int(v) and abs(v) < 1e15 else repr(v)
        return f"{text} s" if isinstance(node, Seconds) else text
    if isinstance(node, BoolLit):
        return "true" if node.value else "false"
    if isinstance(node, Name):
        return node.id
    if isinstance(node, Unary):
        inner = to_source(node.operand)
        self_paren = isinstance(node.operand, Binary) and node.operand.op not in ("and", "or", "implies")
        if not isinstance(node.operand, (Num, Name, Call, BoolLit)) and not self_paren:
            inner = f"({inner})"
        return f"not {inner}" if node.op == "not" else f"-{inner}"
    if isinstance(node, Binary):
        left, right = to_source(node.left), to_source(node.right)
        if node.op in ("and", "or", "implies"):
            wrap = lambda n, s: s if not isinstance(n, Binary) or n.op not in ("and", "or", "implies") else f"({s})"  # noqa: E731
            if node.op == "implies":
                if isinstance(node.left, Binary) and node.left.op == "implies":
                    left = f"({left})"  # implies is right-associative
                return f"{left} implies {right}"
            return f"{wrap(node.left, left)} {node.op} {wrap(node.right, right)}"
        # a boolean operand of ==/!= binds looser than the comparison: keep its parentheses
        loose = lambda n, s: f"({s})" if (isinstance(n, Unary) and n.op == "not") or (  # noqa: E731
            isinstance(n, Binary) and n.op in ("and", "or", "implies")) else s
        return f"({loose(node.left, left)} {node.op} {loose(node.right, right)})"
    if isinstance(node, Call):
        return f"{node.func}({', '.join(to_source(a) for a in node.args)})"
    raise TypeError(node)  # pragma: no cover
