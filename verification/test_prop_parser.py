"""Spec parser fuzz: random and mutated YAML only ever raises :class:`SpecError`, which points.

Every ``SpecError`` names the file; where the input has a position (any YAML
that parses, any syntax error PyYAML marks), it carries a 1-based line and
column inside the text.
"""

from __future__ import annotations

import os
import re
import time

import yaml
from hypothesis import given, note
from hypothesis import strategies as st

import ethimon
from ethimon.spec._yaml import parse_yaml_bytes
from ethimon_strategies import bool_expr, spec_doc

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PATH = "fuzz.yaml"


def _read(name: str) -> str:
    with open(os.path.join(ROOT, "specs", name), encoding="utf-8") as fh:
        return fh.read()


SHIPPED_TEXT = [_read("governor.yaml"), _read("cobot_cell.yaml")]

# messages that have no position by nature (the whole document is the problem)
_NO_POSITION = ("nested too deeply",)


def check_load(text: str) -> ethimon.SpecError | None:
    t0 = time.perf_counter()
    try:
        ethimon.load_spec_text(text, PATH)
        err = None
    except ethimon.SpecError as exc:
        err = exc
    # anything else propagates and fails the test
    assert time.perf_counter() - t0 < 5.0, "parsing took too long"
    if err is not None:
        note(str(err))
        assert err.path == PATH
        assert str(err).startswith(PATH)
        if err.line is None:
            assert any(m in err.message for m in _NO_POSITION), f"no position: {err}"
        else:
            n_lines = len(re.split("\r\n|[\n\r\x85\u2028\u2029]", text))  # YAML's line breaks
            assert 1 <= err.line <= n_lines + 1, (err.line, n_lines)
            assert err.column is None or err.column >= 1
        assert "Traceback" not in str(err)
    return err


yaml_chars = st.sampled_from(list("abcxyz_019 .-:,[]{}#&*!|>'\"%@`\t\n?<=()+/") + ["\n  ", ": ", "- ", "\u00e9"])


@given(st.text(max_size=300))
def test_random_text(text):
    check_load(text)


@given(st.lists(yaml_chars, max_size=200).map("".join))
def test_random_yaml_like_text(text):
    check_load(text)


@st.composite
def mutated(draw):
    text = draw(st.sampled_from(SHIPPED_TEXT))
    for _ in range(draw(st.integers(1, 4))):
        kind = draw(st.sampled_from(("delete", "insert", "replace", "dup_line", "swap_lines", "indent")))
        n = len(text)
        i = draw(st.integers(0, max(0, n - 1)))
        if kind == "delete":
            text = text[:i] + text[i + draw(st.integers(1, 20)):]
        elif kind == "insert":
            text = text[:i] + draw(st.lists(yaml_chars, min_size=1, max_size=8).map("".join)) + text[i:]
        elif kind == "replace":
            text = text[:i] + draw(yaml_chars) + text[i + 1:]
        else:
            lines = text.split("\n")
            j = draw(st.integers(0, len(lines) - 1))
            k = draw(st.integers(0, len(lines) - 1))
            if kind == "dup_line":
                lines.insert(k, lines[j])
            elif kind == "swap_lines":
                lines[j], lines[k] = lines[k], lines[j]
            else:
                lines[j] = draw(st.sampled_from(("  ", "\t", " "))) + lines[j]
            text = "\n".join(lines)
    return text


@given(mutated())
def test_mutated_shipped_specs(text):
    check_load(text)


scalars = st.one_of(st.none(), st.booleans(), st.integers(-10**6, 10**6), st.floats(allow_nan=True),
                    st.text(max_size=20))
keys = st.sampled_from(["ethimon", "name", "signals", "risk", "obligations", "id", "require", "when",
                        "range", "unit", "type", "threshold", "alpha", "release", "mode", "hold_cycles",
                        "within_cycles", "response", "constants", "value", "safe_pose", "joints_rad", "x",
                        "on_fault", "max_age_s", "classes", "bogus"])
documents = st.recursive(scalars, lambda kids: st.one_of(st.lists(kids, max_size=4),
                                                         st.dictionaries(keys, kids, max_size=5)),
                         max_leaves=25)


@given(documents, st.booleans())
def test_random_documents(doc, versioned):
    if versioned and isinstance(doc, dict):
        doc = {"ethimon": 1, "name": "fuzz", **doc}
    check_load(yaml.safe_dump(doc, allow_unicode=True))


@given(st.data())
def test_valid_specs_with_one_field_broken(data):
    doc = spec_doc(data.draw, max_obligations=2, depth=2)
    path = data.draw(st.sampled_from([("risk", "threshold"), ("risk", "release", "hold_cycles"),
                                      ("signals", "x", "range"), ("on_fault",), ("risk", "alpha"),
                                      ("signals", "b", "type"), ("name",)]))
    target = doc
    for p in path[:-1]:
        target = target[p]
    target[path[-1]] = data.draw(scalars | st.lists(scalars, max_size=3))
    check_load(yaml.safe_dump(doc, allow_unicode=True))


@given(st.data())
def test_random_expressions_point_into_the_file(data):
    doc = spec_doc(data.draw, max_obligations=1, depth=1)
    junk = data.draw(st.one_of(st.text(max_size=40), st.lists(st.sampled_from(
        ["x", "y", "b", "risk", "held(", "once(", "since(", ")", ",", "and", "or", "not", "implies", "<", "==",
         "+", "/", "0", "1.5", "prev(", "abs(", "min(", "foo", "3", " "]), max_size=12).map(" ".join)),
        label="require")
    doc["obligations"] = [{"id": "fuzzed", "require": junk}]
    err = check_load(yaml.safe_dump(doc, allow_unicode=True))
    if err is not None:
        assert err.line is not None and err.column is not None


@given(bool_expr(2))
def test_generated_expressions_compile(tree):
    from ethimon.spec._expr import to_source
    doc = {"ethimon": 1, "name": "e", "signals": {"x": {"range": [-5, 5]}, "y": {"range": [0, 10]},
                                                   "z": {"range": [-1, 1]}, "b": {"type": "bool"}},
           "obligations": [{"id": "o", "require": to_source(tree)}]}
    assert check_load(yaml.safe_dump(doc)) is None


@given(st.binary(max_size=200))
def test_random_bytes(raw):
    try:
        parse_yaml_bytes(raw, PATH, what="spec")
    except ethimon.SpecError as exc:
        assert exc.path == PATH
