"""Safe YAML reading that keeps source positions.

PyYAML composes a node graph (with 0-based marks) using the *safe* resolver;
we then build plain Python values ourselves, so that

* only the YAML core types are accepted (any ``!!python/...`` or custom tag is
  an error, nothing is ever constructed or executed),
* duplicate mapping keys are errors,
* alias expansion is bounded (no "billion laughs"), nesting depth is bounded,
  and file size is bounded,
* every value's position is recorded in a :class:`SourceMap` keyed by its path
  (a tuple of keys and indices), so later stages can point at the user's text.
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass, field
from typing import Any

import yaml
from yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode

from .._files import open_regular
from ..errors import SpecError

__all__ = ["SourceMap", "Pos", "read_yaml", "parse_yaml_text", "MAX_BYTES", "MAX_NODES", "MAX_DEPTH"]

MAX_BYTES = 4 * 1024 * 1024
MAX_NODES = 200_000
MAX_DEPTH = 64

_STR = "tag:yaml.org,2002:str"
_INT = "tag:yaml.org,2002:int"
_FLOAT = "tag:yaml.org,2002:float"
_BOOL = "tag:yaml.org,2002:bool"
_NULL = "tag:yaml.org,2002:null"
_MAP = "tag:yaml.org,2002:map"
_SEQ = "tag:yaml.org,2002:seq"
_ALLOWED = {_STR, _INT, _FLOAT, _BOOL, _NULL, _MAP, _SEQ}


class _Loader(yaml.SafeLoader):
    """The safe loader, plus the YAML 1.2 core-schema float for plain scalars.

    YAML 1.1 (PyYAML) reads ``1e-3``, ``2e-1``, ``1e3`` and ``-5E+2`` (an exponent
    without a dot) as strings; they are numbers in YAML 1.2 and to every reader of
    a spec. A *plain* scalar matching the 1.2 float pattern is a float; a quoted
    ``'1e-3'`` (or an explicit ``!!str``) stays a string. Integers, ``.inf`` and
    ``.nan`` resolve as before (those resolvers come first).
    """


_Loader.add_implicit_resolver(
    _FLOAT, re.compile(r"^[-+]?(?:\.[0-9]+|[0-9]+(?:\.[0-9]*)?)(?:[eE][-+]?[0-9]+)?$"), list("-+0123456789."))


@dataclass(frozen=True)
class Pos:
    """A 1-based position of a YAML node, plus how its scalar was written."""

    line: int
    column: int
    style: str | None = None  # None plain, "'" / '"' quoted, "|" / ">" block

    def offset(self, text: str, index: int) -> tuple[int, int]:
        """Line and column of character ``index`` inside this scalar's value.

        Exact for plain and quoted single-line scalars and for literal block
        scalars (``|``) with the usual indentation; approximate otherwise.
        """
        if self.style in ("|", ">"):
            before = text[:index]
            nl = before.count("\n")
            last = before.rfind("\n")
            col_in = index - (last + 1)
            # block content starts on the next line, indented: we cannot see the
            # indentation here, so report column relative to the block's indent
            return self.line + 1 + nl, self.column + 2 + col_in
        quote = 1 if self.style in ("'", '"') else 0
        before = text[:index]
        nl = before.count("\n")
        if nl:
            return self.line + nl, index - before.rfind("\n")
        return self.line, self.column + quote + index


@dataclass
class SourceMap:
    """Positions of every value of one YAML document, keyed by path."""

    path: str
    positions: dict[tuple, Pos] = field(default_factory=dict)
    lines: list[str] = field(default_factory=list, repr=False)
    key_positions: dict[tuple, Pos] = field(default_factory=dict)

    def _find_in_block(self, start_line: int, text: str, index: int) -> tuple[int, int] | None:
        """Locate text[index:] inside a block scalar that starts at ``start_line``."""
        rest = text[index:].split("\n", 1)[0].strip()
        needle = rest[:24] or text[max(0, index - 1):index + 1].strip()
        if not needle:
            return None
        # which occurrence: count earlier occurrences in the value text
        nth = text[:index].replace("\n", " ").count(needle)
        seen = 0
        for ln in range(start_line, min(len(self.lines), start_line + text.count("\n") + 200)):
            src = self.lines[ln]  # 0-based list: line ln + 1
            col = src.find(needle)
            while col >= 0:
                if seen == nth:
                    return ln + 1, col + 1
                seen += 1
                col = src.find(needle, col + 1)
        return None

    def pos(self, loc: tuple) -> Pos | None:
        """Position of the value at ``loc``, or of its closest known ancestor."""
        loc = tuple(loc)
        while True:
            p = self.positions.get(loc)
            if p is not None:
                return p
            if not loc:
                return None
            loc = loc[:-1]

    def error(self, message: str, loc: tuple = (), *, hint: str | None = None,
              key: bool = False, index: int | None = None, text: str | None = None) -> SpecError:
        """Build a :class:`SpecError` pointing at ``loc`` (its key if ``key``)."""
        p = self.key_positions.get(tuple(loc)) if key else None
        if p is None:
            p = self.pos(loc)
        if p is None:
            return SpecError(message, path=self.path, hint=hint)
        line, col = p.line, p.column
        if index is not None and text is not None:
            line, col = p.offset(text, index)
            if p.style in ("|", ">") and self.lines:
                found = self._find_in_block(p.line, text, index)
                if found is not None:
                    line, col = found
        return SpecError(message, path=self.path, line=line, column=col, hint=hint)


def read_yaml(path: str | os.PathLike, *, what: str = "file",
              max_bytes: int = MAX_BYTES) -> tuple[Any, SourceMap]:
    """Read one YAML document from ``path`` safely.

    Returns:
        ``(data, source_map)`` where ``data`` is built from dicts, lists, str,
        int, float, bool and None only.

    Raises:
        SpecError: unreadable, too large, binary, non-UTF-8, empty, broken YAML,
            disallowed tags, duplicate keys, alias bombs, too deep nesting.
    """
    spath = os.fspath(path)
    try:
        with open_regular(spath, "rb", what=what, error=SpecError) as fh:  # never blocks on a FIFO
            size = os.fstat(fh.fileno()).st_size
            if size > max_bytes:
                raise _too_large(what, size, max_bytes, spath)
            raw = fh.read(max_bytes + 1)
        if len(raw) > max_bytes:  # it grew after the fstat
            raise _too_large(what, len(raw), max_bytes, spath)
    except OSError as exc:
        raise SpecError(f"cannot read {what}: {exc.strerror or exc}", path=spath) from None
    return parse_yaml_bytes(raw, spath, what=what)


def _too_large(what: str, size: int, limit: int, path: str) -> SpecError:
    return SpecError(f"{what} is too large ({size} bytes; limit {limit})", path=path,
                     hint="split it into smaller files")


def parse_yaml_bytes(raw: bytes, path: str, *, what: str = "file") -> tuple[Any, SourceMap]:
    """Decode and parse YAML bytes; see :func:`read_yaml`."""
    if b"\x00" in raw:
        nul = raw.index(b"\x00")
        line = raw.count(b"\n", 0, nul) + 1
        col = nul - (raw.rfind(b"\n", 0, nul) + 1) + 1
        raise SpecError(f"{what} looks binary (NUL byte)", path=path, line=line, column=col,
                        hint="ethimon reads UTF-8 YAML text")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        bad = exc.start
        line = raw.count(b"\n", 0, bad) + 1
        col = bad - (raw.rfind(b"\n", 0, bad) + 1) + 1
        raise SpecError(f"{what} is not valid UTF-8 (byte 0x{raw[bad]:02x})", path=path,
                        line=line, column=col, hint="save the file as UTF-8") from None
    if text.startswith("\ufeff"):
        text = text[1:]
    return parse_yaml_text(text, path, what=what)


def _refuse_deep_nesting(text: str, path: str, what: str) -> None:
    """Refuse a document nested deeper than :data:`MAX_DEPTH` from the scanner's tokens, before the composer
    recurses into it (it only gave up at Python's recursion limit: ~3 s of CPU for 5,000 brackets). Only
    texts that could be that deep are scanned: more than MAX_DEPTH brackets, or a line indented that far."""
    if text.count("[") + text.count("{") <= MAX_DEPTH and not any(
            len(ln) - len(ln.lstrip()) >= MAX_DEPTH for ln in text.splitlines()):
        return
    from yaml.tokens import (BlockEndToken, BlockMappingStartToken, BlockSequenceStartToken,
                             FlowMappingEndToken, FlowMappingStartToken, FlowSequenceEndToken,
                             FlowSequenceStartToken)
    opens = (BlockMappingStartToken, BlockSequenceStartToken, FlowMappingStartToken, FlowSequenceStartToken)
    closes = (BlockEndToken, FlowMappingEndToken, FlowSequenceEndToken)
    depth = 0
    try:
        for tok in yaml.scan(text, Loader=yaml.SafeLoader):
            if isinstance(tok, opens):
                depth += 1
                if depth > MAX_DEPTH:
                    m = tok.start_mark
                    raise SpecError(f"{what} is nested too deeply", path=path, line=m.line + 1,
                                    column=m.column + 1, hint=f"at most {MAX_DEPTH} levels are allowed")
            elif isinstance(tok, closes):
                depth -= 1
    except yaml.YAMLError:
        return  # the parser below reports it, located


def parse_yaml_text(text: str, path: str = "<string>", *, what: str = "file") -> tuple[Any, SourceMap]:
    """Parse YAML text (one document); see :func:`read_yaml`."""
    if not text.strip() or all(ln.strip().startswith("#") or not ln.strip() for ln in text.splitlines()):
        raise SpecError(f"{what} is empty", path=path, line=1, column=1,
                        hint="a spec starts with 'ethimon: 1' and 'name: ...'")
    smap = SourceMap(path, lines=text.splitlines())
    _refuse_deep_nesting(text, path, what)
    try:
        loader = _Loader(text)
        try:
            node = loader.get_single_node()
        finally:
            loader.dispose()
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        msg, hint = _yaml_message(exc)
        if mark is not None:
            raise SpecError(f"invalid YAML: {msg}", path=path, line=mark.line + 1,
                            column=mark.column + 1, hint=hint) from None
        raise SpecError(f"invalid YAML: {msg}", path=path, hint=hint) from None
    except yaml.reader.ReaderError as exc:  # a control character: unmarked, but its offset is known
        idx = min(max(int(exc.position), 0), len(text))
        line = text.count("\n", 0, idx) + 1
        col = idx - (text.rfind("\n", 0, idx) + 1) + 1
        ch = exc.character
        shown = f"U+{ch:04X}" if isinstance(ch, int) else repr(ch)
        raise SpecError(f"invalid YAML: control character {shown} is not allowed", path=path, line=line,
                        column=col, hint="remove it; ethimon reads printable UTF-8 text") from None
    except yaml.YAMLError as exc:
        raise SpecError(f"invalid YAML: {exc}", path=path) from None
    except RecursionError:
        raise SpecError(f"{what} is nested too deeply", path=path,
                        hint=f"at most {MAX_DEPTH} levels are allowed") from None
    if node is None:
        raise SpecError(f"{what} is empty", path=path, line=1, column=1)
    builder = _Builder(smap)
    try:
        data = builder.build(node, (), 0)
    except RecursionError:
        raise SpecError(f"{what} is nested too deeply", path=path,
                        hint=f"at most {MAX_DEPTH} levels are allowed") from None
    return data, smap


_FOUND = {"'<block mapping start>'": "a key", "'<block sequence start>'": "a list item ('- ')",
          "'-'": "a list item ('- ')", "'?'": "a '?'", "'<scalar>'": "a value", "'<block end>'": "the end of a block",
          "'<flow mapping start>'": "a '{'", "'<flow sequence start>'": "a '['", "'<alias>'": "an alias ('*...')",
          "'<anchor>'": "an anchor ('&...')", "'<tag>'": "a tag ('!...')"}
_INDENT_HINT = ("indent every key of a mapping, and every '- ' of a list, by the same number of spaces, "
                "and a nested block by more spaces than its parent key")


def _yaml_message(exc: yaml.MarkedYAMLError) -> tuple[str, str | None]:
    """PyYAML's error as plain words plus a hint (its own wording kept at the end, in brackets)."""
    problem = exc.problem or exc.context or "invalid YAML"
    raw = f"{exc.problem} ({exc.context})" if exc.context and exc.problem else problem
    ctx, pm = exc.context_mark, exc.problem_mark
    where = f"line {ctx.line + 1}, column {ctx.column + 1}" if ctx is not None else None
    m = re.match(r"expected <block end>, but found (.+)$", problem)
    if m is not None:
        found = _FOUND.get(m.group(1), m.group(1))
        block = "list" if exc.context and "collection" in exc.context else "mapping"
        col = f" at column {pm.column + 1}" if pm is not None else ""
        start = f"the {block} that starts at {where}" if where else f"the enclosing {block}"
        return f"bad indentation: {found}{col} does not line up with {start} [YAML parser: {raw}]", _INDENT_HINT
    if problem.startswith("did not find expected key") or problem.startswith("did not find expected '-'"):
        return f"bad indentation or a missing ':' [YAML parser: {raw}]", _INDENT_HINT
    if "mapping values are not allowed" in problem:
        return (f"unexpected ':' [YAML parser: {raw}]",
                "a value containing ': ' must be quoted; or this line is indented more than the key above it")
    if "could not find expected ':'" in problem:
        return f"a key without ':' [YAML parser: {raw}]", "each mapping entry needs 'key: value'"
    if "\\t" in problem or "tab" in problem:
        return raw, "indent with spaces, not tabs"
    if problem.startswith("found character") and "cannot start any token" in problem:
        return raw, "quote the value: '@' and '`' cannot start a plain YAML value"
    if problem.startswith("found undefined alias"):
        return raw, "'*name' refers to an anchor '&name' defined earlier; quote the value if '*' is meant literally"
    if "end of stream" in problem and exc.context and "quoted scalar" in exc.context:
        start = f" (opened at {where})" if where else ""
        return f"a quote is not closed{start} [YAML parser: {raw}]", "close the quote on the value"
    if re.match(r"expected ',' or '[\]}]'", problem):
        return (f"a '{{' or '[' list/mapping is not closed, or an item in it is not separated by ',' "
                f"[YAML parser: {raw}]", "quote values that contain ',', ':', '[' or '{'")
    return raw, None


_TRUE = frozenset({"yes", "true", "on", "y"})
_FALSE = frozenset({"no", "false", "off", "n"})
#: digits of an integer literal in any base (a 0x... of 4,300+ digits cannot even be printed)
MAX_INT_DIGITS = 400


def _short(text: str) -> str:
    return text if len(text) <= 40 else f"{text[:20]}...{text[-8:]}"


_FLOAT_SPECIAL = re.compile(r"^[-+]?(\.inf|\.Inf|\.INF)$|^\.(nan|NaN|NAN)$")


class _Builder:
    def __init__(self, smap: SourceMap) -> None:
        self.smap = smap
        self.count = 0

    def _pos(self, node: Node) -> Pos:
        m = node.start_mark
        style = getattr(node, "style", None) if isinstance(node, ScalarNode) else None
        return Pos(m.line + 1, m.column + 1, style)

    def _err(self, node: Node, msg: str, hint: str | None = None) -> SpecError:
        m = node.start_mark
        return SpecError(msg, path=self.smap.path, line=m.line + 1, column=m.column + 1, hint=hint)

    def build(self, node: Node, loc: tuple, depth: int) -> Any:
        self.count += 1
        if self.count > MAX_NODES:
            raise self._err(node, f"document expands to more than {MAX_NODES} values",
                            hint="YAML aliases that expand exponentially are refused")
        if depth > MAX_DEPTH:
            raise self._err(node, "document is nested too deeply",
                            hint=f"at most {MAX_DEPTH} levels are allowed")
        if node.tag not in _ALLOWED:
            raise self._err(node, f"YAML tag {node.tag!r} is not allowed",
                            hint="ethimon files use plain YAML values only; tags that construct objects are refused")
        if loc not in self.smap.positions:
            self.smap.positions[loc] = self._pos(node)
        if isinstance(node, ScalarNode):
            return self._scalar(node)
        if isinstance(node, SequenceNode):
            return [self.build(child, loc + (i,), depth + 1) for i, child in enumerate(node.value)]
        if isinstance(node, MappingNode):
            out: dict[Any, Any] = {}
            for knode, vnode in node.value:
                if knode.tag == "tag:yaml.org,2002:merge":
                    raise self._err(knode, "YAML merge keys ('<<') are not supported",
                                    hint="write the keys out")
                if not isinstance(knode, ScalarNode):
                    raise self._err(knode, "mapping keys must be plain scalars")
                key = self._scalar(knode)
                if isinstance(key, float) and math.isnan(key):
                    raise self._err(knode, "a mapping key cannot be NaN")
                if key in out:
                    first = self.smap.key_positions.get(loc + (key,))
                    where = f" (first at line {first.line})" if first else ""
                    raise self._err(knode, f"duplicate key {key!r}{where}",
                                    hint="each key may appear once in a mapping")
                self.smap.key_positions[loc + (key,)] = self._pos(knode)
                out[key] = self.build(vnode, loc + (key,), depth + 1)
            return out
        raise self._err(node, "unsupported YAML node")  # pragma: no cover

    def _scalar(self, node: ScalarNode) -> Any:
        tag, value = node.tag, node.value
        if tag == _STR:
            return value
        if tag == _NULL:
            return None
        if tag == _BOOL:
            word = value.lower()
            if word in _TRUE:
                return True
            if word in _FALSE:
                return False
            raise self._err(node, f"cannot read boolean {_short(value)!r}", hint="write true or false")
        if tag == _INT:
            v = value.replace("_", "")
            sign = -1 if v.startswith("-") else 1
            v = v.lstrip("+-")
            base, digits = 10, v
            if v[:2] in ("0b", "0x", "0o"):
                base, digits = {"0b": 2, "0x": 16, "0o": 8}[v[:2]], v[2:]
            elif v != "0" and v.startswith("0"):
                base = 8
            if len(digits) > MAX_INT_DIGITS:
                raise self._err(node, f"integer {_short(value)!r} is too long ({len(digits)} digits)",
                                hint=f"at most {MAX_INT_DIGITS} digits")
            try:
                if ":" in v or not digits:
                    raise ValueError(v)
                n = int(digits, base)
            except ValueError:
                raise self._err(node, f"cannot read integer {_short(value)!r}") from None
            return sign * n
        if tag == _FLOAT:
            v = value.replace("_", "").lower()
            if v in (".nan",):
                return math.nan
            if v in (".inf", "+.inf"):
                return math.inf
            if v == "-.inf":
                return -math.inf
            try:
                return float(v)
            except ValueError:
                raise self._err(node, f"cannot read number {_short(value)!r}") from None
        raise self._err(node, f"unsupported scalar tag {tag!r}")  # pragma: no cover
