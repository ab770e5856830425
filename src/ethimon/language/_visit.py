"""The interpreter protocol: one method per node kind, operator and function of the expression language.

Four back-ends interpret the AST of :mod:`ethimon.language._expr`: the compiled closures
(``compiler/_closures.py``, a visitor that returns closures, run once at compile time), the
reference interpreter (``testing/_reference.py``), the offline checker (``offline/_eval.py``,
numpy arrays) and the z3 encoder (``verify/_encode.py``). Each subclasses :class:`ExprVisitor`
and implements every method of :data:`PROTOCOL`; :meth:`ExprVisitor.visit` dispatches by a table
built once per class (by node type, then by operator or function name), never by an ``isinstance``
chain per call.

The methods are derived from the operator table (:data:`~ethimon.language._operators.OPERATORS`):
one abstract ``visit_<name>`` per row, generated on :class:`ExprVisitor`, so a back-end that lacks
one cannot be instantiated; ``tests/compiler/test_interpreter_coverage.py`` names what each back-end
lacks (:func:`missing_methods`, read from the table now) and evaluates one expression per entry on
all four. :class:`ExprAnalysis` is the base of analyses that care about a few entries: every
method defaults to visiting the operands.
"""

from __future__ import annotations

from abc import ABC, abstractmethod, update_abstractmethods
from operator import attrgetter

from ._expr import Binary, BoolLit, Call, Name, Node, Num, Unary
from ._operators import OPERATORS, Operator

__all__ = ["ExprVisitor", "ExprAnalysis", "PROTOCOL", "UNARY_OPS", "OP_WORDS", "method_of", "missing_methods"]

#: the parser's two unary operators (``-x``; ``not e``), read from the table
UNARY_OPS = tuple(op.symbol for op in OPERATORS.values() if op.kind == "unary")
#: the method word of each operator written with symbols (words such as ``and`` are their own), read
#: from the table (unary ``-`` is ``neg``; binary ``-`` is ``sub``, see :func:`method_of`)
OP_WORDS: dict[str, str] = {op.symbol: op.name for op in OPERATORS.values()
                            if op.kind != "call" and op.symbol != op.name and op.name != "sub"}
_LEAF_KEYS = ("num", "bool", "name")


def method_of(kind: str, key: str) -> str | None:
    """The visitor method of a leaf (``kind`` ``"leaf"``: ``num``, ``bool``, ``name``), a unary or
    binary operator (``"unary"``/``"binary"``, ``key`` the operator) or a function (``"call"``);
    ``None`` for an entry that is not in :data:`~ethimon.language._operators.OPERATORS`."""
    if kind == "leaf":
        return f"visit_{key}"
    for op in OPERATORS.values():
        if op.kind == kind and op.symbol == key:
            return op.method
    return None


def _protocol() -> dict[tuple[str, str], str | None]:
    """(kind, key) -> method name, read from the operator table as it is now."""
    out: dict[tuple[str, str], str | None] = {("leaf", k): f"visit_{k}" for k in _LEAF_KEYS}
    out.update({(op.kind, op.symbol): op.method for op in OPERATORS.values()})
    return out


#: every entry of the language -> the method each back-end implements (temporal operators included)
PROTOCOL: dict[tuple[str, str], str] = _protocol()  # type: ignore[assignment]
assert None not in PROTOCOL.values() and len(set(PROTOCOL.values())) == len(PROTOCOL), PROTOCOL

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
        cls._by_key = {key: getattr(cls, name) for key, name in _protocol().items()
                       if key[0] != "leaf" and hasattr(cls, name)}

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

    # one abstract visit_<name> per row of the operator table: generated below (_declare)


def _abstract(op: Operator):
    def method(self, node, *args): ...
    method.__name__ = method.__qualname__ = op.method
    method.__doc__ = f"{op.kind} {op.symbol!r}" + (f": {op.doc}" if op.doc else "")
    return abstractmethod(method)


def _declare(cls: type) -> None:
    """One abstract ``visit_<name>`` per row of the operator table on ``cls`` (the protocol)."""
    for op in OPERATORS.values():
        if op.method not in vars(cls):
            setattr(cls, op.method, _abstract(op))
    update_abstractmethods(cls)


_declare(ExprVisitor)
_DECLARED = {name for name in vars(ExprVisitor) if name.startswith("visit_")} - {"visit"}
assert _DECLARED == set(PROTOCOL.values()), (
    f"the protocol and the operator table differ: methods without an entry "
    f"{sorted(_DECLARED - set(PROTOCOL.values()))}, entries without a method {sorted(set(PROTOCOL.values()) - _DECLARED)}")


class ExprAnalysis(ExprVisitor):
    """Base of an analysis of the AST that cares about a few entries only: every method defaults to
    :meth:`generic`, which visits the node's operands (:attr:`~ethimon.language._expr.Node.children`)
    and hands their results to :meth:`combine` (default: ``None``). Override the methods of the
    entries that matter and :meth:`combine`; an entry added to the table later is covered by the
    default (an interpreter, which must evaluate every entry, subclasses :class:`ExprVisitor`).
    """

    def visit(self, node: Node, *args):
        method = self._by_type.get(type(node))
        if method is None:
            kind, key = _KEY.get(type(node), (None, None))
            method = self._by_key.get((kind, key(node))) if kind is not None else None
            if method is None:
                return self.generic(node, *args)
        return method(self, node, *args)

    def generic(self, node: Node, *args):
        """Visit the operands of ``node`` and combine their results."""
        return self.combine(node, [self.visit(child, *args) for child in node.children], *args)

    def combine(self, node: Node, results: list, *args):
        return None


for _name in ("visit_num", "visit_bool", "visit_name", *PROTOCOL.values()):
    if _name not in vars(ExprAnalysis):
        setattr(ExprAnalysis, _name, ExprAnalysis.generic)
update_abstractmethods(ExprAnalysis)


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
