"""The interpreter protocol: one method per node kind, operator and function of the expression language.

Four back-ends interpret the AST of :mod:`ethimon.language._expr`: the compiled closures
(``compiler/_closures.py``, a visitor that returns closures, run once at compile time), the
reference interpreter (``testing/_reference.py``), the offline checker (``offline/_eval.py``,
numpy arrays) and the z3 encoder (``verify/_encode.py``). Each subclasses :class:`ExprVisitor`
and implements every method of :data:`PROTOCOL`; :meth:`ExprVisitor.visit` dispatches by a table
built once per class (by node type, then by operator or function name), never by an ``isinstance``
chain per call.

The methods are derived from the language's own tables (:data:`~ethimon.language._expr.BINARY_OPS`,
:data:`~ethimon.language._expr.FUNCTIONS`, :data:`UNARY_OPS`), and an entry added there without a
method here fails at import; a method added here is abstract, so a back-end that lacks it cannot be
instantiated; ``tests/compiler/test_interpreter_coverage.py`` names what each back-end lacks
(:func:`missing_methods`) and evaluates one expression per entry on all four.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from operator import attrgetter

from ._expr import BINARY_OPS, FUNCTIONS, TEMPORAL, Binary, BoolLit, Call, Name, Node, Num, Unary

__all__ = ["ExprVisitor", "PROTOCOL", "UNARY_OPS", "OP_WORDS", "method_of", "missing_methods"]

#: the parser's two unary operators (``-x``; ``not e``)
UNARY_OPS = ("-", "not")
#: the method word of each operator written with symbols (words such as ``and`` are their own)
OP_WORDS: dict[str, str] = {
    "-": "neg", "<": "lt", "<=": "le", ">": "gt", ">=": "ge", "==": "eq", "!=": "ne",
    "+": "add", "*": "mul", "/": "div",
}
_BINARY_WORDS = {**OP_WORDS, "-": "sub"}  # binary "-" is a subtraction, unary "-" a negation


def method_of(kind: str, key: str) -> str | None:
    """The visitor method of a leaf (``kind`` ``"leaf"``: ``num``, ``bool``, ``name``), a unary or
    binary operator (``"unary"``/``"binary"``, ``key`` the operator) or a function (``"call"``);
    ``None`` for an operator written with symbols that has no word in :data:`OP_WORDS`."""
    if kind == "leaf":
        return f"visit_{key}"
    if kind == "call":
        return f"visit_{key}" if key.isidentifier() else None
    words = OP_WORDS if kind == "unary" else _BINARY_WORDS
    word = words.get(key, key if key.isidentifier() else None)
    return None if word is None else f"visit_{word}"


def _protocol() -> dict[tuple[str, str], str | None]:
    """(kind, key) -> method name, read from the language's tables as they are now."""
    out: dict[tuple[str, str], str | None] = {("leaf", k): method_of("leaf", k) for k in ("num", "bool", "name")}
    out.update({("unary", op): method_of("unary", op) for op in UNARY_OPS})
    out.update({("binary", op): method_of("binary", op) for op in BINARY_OPS})
    out.update({("call", f): method_of("call", f) for f in FUNCTIONS})
    return out


#: every entry of the language -> the method each back-end implements (temporal operators included)
PROTOCOL: dict[tuple[str, str], str] = _protocol()  # type: ignore[assignment]
assert None not in PROTOCOL.values() and len(set(PROTOCOL.values())) == len(PROTOCOL), PROTOCOL
assert TEMPORAL <= set(FUNCTIONS)

_LEAVES = {Num: "num", BoolLit: "bool", Name: "name"}
_KEY = {Unary: ("unary", attrgetter("op")), Binary: ("binary", attrgetter("op")), Call: ("call", attrgetter("func"))}


class ExprVisitor(ABC):
    """Base of every interpreter of the expression AST: ``visit(node, *args)`` calls the method of
    ``node``'s kind, operator or function with ``(node, *args)`` and returns what it returns (a
    value, an array, a z3 term or a closure: the back-end's choice; ``args`` too, e.g. a cycle).

    The methods (:data:`PROTOCOL`): ``visit_num``, ``visit_bool``, ``visit_name``; ``visit_neg``,
    ``visit_not``; one per binary operator (``visit_lt`` ... ``visit_ne``, ``visit_add``,
    ``visit_sub``, ``visit_mul``, ``visit_div``, ``visit_and``, ``visit_or``, ``visit_implies``);
    one per function (``visit_abs``, ``visit_min``, ``visit_max``, ``visit_sqrt``,
    ``visit_separation_distance``) and temporal operator (``visit_prev``, ``visit_held``,
    ``visit_once``, ``visit_since``). Operators that share one implementation in a back-end are
    bound to it by name (``visit_lt = visit_le = ... = _compare``): a new operator is still one
    name each back-end must add.
    """

    #: per class: node type -> method, or node type -> (kind, key getter); key -> method
    _by_type: dict = {}
    _by_key: dict = {}

    def __init_subclass__(cls, **kwargs) -> None:
        super().__init_subclass__(**kwargs)
        cls._by_type = {t: getattr(cls, method_of("leaf", k)) for t, k in _LEAVES.items()}
        cls._by_key = {key: getattr(cls, name) for key, name in PROTOCOL.items() if key[0] != "leaf"}

    def visit(self, node: Node, *args):
        """Interpret ``node`` by the method of its kind (see the class docstring)."""
        t = type(node)
        method = self._by_type.get(t)
        if method is None:
            kind, key = _KEY.get(t, (None, None))
            method = self._by_key.get((kind, key(node))) if kind is not None else None
            if method is None:
                raise TypeError(f"{type(self).__name__} cannot interpret {node!r}")
        return method(self, node, *args)

    # -- leaves ----------------------------------------------------------------------
    @abstractmethod
    def visit_num(self, node: Num, *args): ...

    @abstractmethod
    def visit_bool(self, node: BoolLit, *args): ...

    @abstractmethod
    def visit_name(self, node: Name, *args):
        """A signal, a constant or ``risk`` (R_e)."""

    # -- unary operators -------------------------------------------------------------
    @abstractmethod
    def visit_neg(self, node: Unary, *args): ...

    @abstractmethod
    def visit_not(self, node: Unary, *args): ...

    # -- binary operators (BINARY_OPS) -----------------------------------------------
    @abstractmethod
    def visit_lt(self, node: Binary, *args): ...

    @abstractmethod
    def visit_le(self, node: Binary, *args): ...

    @abstractmethod
    def visit_gt(self, node: Binary, *args): ...

    @abstractmethod
    def visit_ge(self, node: Binary, *args): ...

    @abstractmethod
    def visit_eq(self, node: Binary, *args): ...

    @abstractmethod
    def visit_ne(self, node: Binary, *args): ...

    @abstractmethod
    def visit_add(self, node: Binary, *args): ...

    @abstractmethod
    def visit_sub(self, node: Binary, *args): ...

    @abstractmethod
    def visit_mul(self, node: Binary, *args): ...

    @abstractmethod
    def visit_div(self, node: Binary, *args): ...

    @abstractmethod
    def visit_and(self, node: Binary, *args): ...

    @abstractmethod
    def visit_or(self, node: Binary, *args): ...

    @abstractmethod
    def visit_implies(self, node: Binary, *args): ...

    # -- functions (FUNCTIONS) -------------------------------------------------------
    @abstractmethod
    def visit_abs(self, node: Call, *args): ...

    @abstractmethod
    def visit_min(self, node: Call, *args): ...

    @abstractmethod
    def visit_max(self, node: Call, *args): ...

    @abstractmethod
    def visit_sqrt(self, node: Call, *args): ...

    @abstractmethod
    def visit_separation_distance(self, node: Call, *args): ...

    # -- temporal operators (TEMPORAL) -----------------------------------------------
    @abstractmethod
    def visit_prev(self, node: Call, *args): ...

    @abstractmethod
    def visit_held(self, node: Call, *args): ...

    @abstractmethod
    def visit_once(self, node: Call, *args): ...

    @abstractmethod
    def visit_since(self, node: Call, *args): ...


_DECLARED = {name for name in vars(ExprVisitor) if name.startswith("visit_")} - {"visit"}
assert _DECLARED == set(PROTOCOL.values()), (
    f"the protocol and the language's tables differ: methods without an entry "
    f"{sorted(_DECLARED - set(PROTOCOL.values()))}, entries without a method {sorted(set(PROTOCOL.values()) - _DECLARED)}")


def missing_methods(cls: type) -> list[str]:
    """The entries of the language (read from its tables now) that visitor class ``cls`` does not
    implement: ``"kind key -> method"`` for a method it lacks or leaves abstract, or for an operator
    that has no method name at all. Empty: ``cls`` interprets the whole language."""
    out = []
    for (kind, key), name in _protocol().items():
        impl = getattr(cls, name, None) if name is not None else None
        if impl is None or getattr(impl, "__isabstractmethod__", False):
            out.append(f"{kind} {key!r} -> {name or '(no method name: add one to OP_WORDS)'}")
    return out
