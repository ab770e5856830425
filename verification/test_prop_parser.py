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
import pytest
from hypothesis import example, given, note
from hypothesis import strategies as st

import ethimon
from ethimon.testing import ReferenceMonitor
from ethimon.language._yaml import parse_yaml_bytes
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


@pytest.mark.slow
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


@pytest.mark.slow
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


@pytest.mark.slow
@given(documents, st.booleans())
def test_random_documents(doc, versioned):
    if versioned and isinstance(doc, dict):
        doc = {"ethimon": 1, "name": "fuzz", **doc}
    check_load(yaml.safe_dump(doc, allow_unicode=True))


@pytest.mark.slow
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


@pytest.mark.slow
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
    from ethimon.language._expr import to_source
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


# -- size-stressing generators (issue 11) ---------------------------------------------------------
# The generators above stay small (±1e6, 12 tokens, 40 characters), so they never met a RecursionError
# on a 400-term 'and' chain, an OverflowError on held(x, 1e400) or a ValueError on a 4,300-digit
# 0x... integer. These reach the sizes and shapes at and past every limit.

from ethimon.language._expr import MAX_CHAIN_TERMS, MAX_EXPR_CHARS, MAX_EXPR_DEPTH, MAX_TREE_DEPTH  # noqa: E402

_BOUNDARY_COUNTS = sorted({1, 2, 3, MAX_CHAIN_TERMS - 1, MAX_CHAIN_TERMS, MAX_CHAIN_TERMS + 1,
                           MAX_TREE_DEPTH - 1, MAX_TREE_DEPTH, MAX_TREE_DEPTH + 1, 400, 600, 1000, 1300, 2500,
                           MAX_EXPR_CHARS // 4})
counts = st.one_of(st.sampled_from(_BOUNDARY_COUNTS), st.integers(1, MAX_EXPR_CHARS // 2))
STRESS_SIGNALS = {"x": {"range": [1, 2]}, "y": {"range": [-3, 3]}, "b": {"type": "bool"}}
STRESS_INPUT = {"x": 1.5, "y": 0.25, "b": True, "risk": 0.1}


def stress_doc(require: str, **extra) -> str:
    doc = {"ethimon": 1, "name": "stress", "signals": STRESS_SIGNALS, **extra,
           "obligations": [{"id": "o", "require": require}]}
    return yaml.safe_dump(doc, allow_unicode=True, sort_keys=False)


def runs(text: str) -> None:
    """A spec that loaded compiles into closures and a reference that agree and never crash."""
    spec = ethimon.load_spec_text(text, PATH)
    m, r = ethimon.Monitor(spec), ReferenceMonitor(spec)
    for _ in range(2):
        d, e = m.step(STRESS_INPUT), r.step(STRESS_INPUT)
        assert not any(f.kind == "internal" for f in d.faults), d.faults
        assert (d.override, d.violations, bool(d.faults)) == (e.override, e.violations, bool(e.faults))


@st.composite
def long_chains(draw):
    """``t1 op t2 op ... op tn``: a short drawn pattern of terms repeated to n (cheap to draw at any n)."""
    op = draw(st.sampled_from(("and", "or", "+", "-", "*", "/")))
    n = draw(counts)
    if op in ("and", "or"):
        terms = st.sampled_from(("b", "not b", "x < 2", "y >= 0", "true", "held(b, 2)", "(x > 1 or b)"))
    else:
        terms = st.sampled_from(("x", "1", "0.5", "x", "2", "abs(y) + 1"))  # no divisor is ever 0
    pattern = draw(st.lists(terms, min_size=1, max_size=6))
    body = f" {op} ".join((pattern * (n // len(pattern) + 1))[:n])
    return body if op in ("and", "or") else body + " > -1e300"
@pytest.mark.slow
@given(long_chains())
@example(" and ".join(["b"] * 400))
@example(" or ".join(["x < 2"] * 600))
@example(" and ".join(["b"] * 1000))
@example("+".join(["x"] * 400) + " > 0")
@example("*".join(["x"] * 600) + " > 0")
@example("-".join(["1"] * 1300) + " < x")
@example("/".join(["x"] * MAX_CHAIN_TERMS) + " > 0")
def test_long_chains_load_or_fail_cleanly(expr):
    loads_and_runs_or_fails_cleanly(expr, ("too long", "too deeply", "characters"))


def loads_and_runs_or_fails_cleanly(expr: str, reasons: tuple[str, ...]) -> None:
    """The spec around ``expr`` loads and steps, or is a located SpecError for one of ``reasons``."""
    text = stress_doc(expr)
    err = check_load(text)
    if err is None:
        runs(text)
    else:
        assert err.line is not None and err.column is not None
        assert any(m in err.message for m in reasons), err.message


NUM_WRAPPERS = ("({})", "-{}", "abs({})", "min({}, 2)", "{} + x", "x * {}", "prev({})", "sqrt(abs({}))",
                "{} < 3")
BOOL_WRAPPERS = ("({})", "not {}", "{} and b", "b or {}", "held({}, 2)", "once({}, 3)", "since(b, {})",
                 "({}) implies b", "prev({}, true)", "({}) == b")


@st.composite
def deep_nesting(draw):
    """Wrappers around wrappers (parentheses, not, minus, calls, chains): a drawn pattern repeated."""
    levels = draw(st.one_of(st.sampled_from((MAX_EXPR_DEPTH, MAX_TREE_DEPTH, 2 * MAX_TREE_DEPTH, 1000)),
                            st.integers(1, 3 * MAX_TREE_DEPTH)))
    num_pat = draw(st.lists(st.sampled_from(NUM_WRAPPERS[:-1]), min_size=1, max_size=5))
    bool_pat = draw(st.lists(st.sampled_from(BOOL_WRAPPERS), min_size=1, max_size=5))
    switch = draw(st.integers(0, levels))  # number wrappers below, then a comparison, then conditions
    expr = "x"
    for i in range(levels):
        w = num_pat[i % len(num_pat)] if i < switch else "{} < 3" if i == switch else bool_pat[i % len(bool_pat)]
        expr = w.format(expr)
        if len(expr) > MAX_EXPR_CHARS + 100:
            break
    return expr if switch < levels else f"{expr} < 3"


@pytest.mark.slow
@given(deep_nesting())
@example("(" * 40 + "x" + " + x)" * 40 + " < 3")
@example("not " * (MAX_EXPR_DEPTH + 1) + "b")
@example("((" + "+".join(["x"] * 90) + ") + " + "+".join(["x"] * 90) + ") < 3")
def test_deep_nesting_loads_or_fails_cleanly(expr):
    loads_and_runs_or_fails_cleanly(expr, ("too long", "too deeply", "characters", "must be a condition",
                                           "needs a", "square root", "division"))


digits = st.text("0123456789", min_size=1, max_size=5000)
huge_numbers = st.one_of(
    st.sampled_from(("1e400", "1e308", "1.7976931348623157e308", "1.8e308", "1e-400", "0." + "0" * 400 + "1")),
    digits,
    st.builds(lambda d, e: f"{d}e{e}", digits, st.integers(-2000, 2000)),
    st.builds(lambda d, f: f"{d}.{f}", digits, digits),
)


@given(huge_numbers, st.sampled_from(("x < {}", "held(x < 1, {})", "once(b, {})", "since(b, b, {})",
                                      "x / {} < 1", "sqrt({}) > x", "{} * {} > x", "-{} < x")))
def test_huge_numbers_in_expressions(num, template):
    check_load(stress_doc(template.format(num, num)))


yaml_ints = st.one_of(
    st.text("0123456789abcdef", min_size=1, max_size=6000).map(lambda d: "0x" + d),
    st.text("01", min_size=1, max_size=20000).map(lambda d: "0b" + d),
    st.text("01234567", min_size=1, max_size=6000).map(lambda d: "0" + d),
    st.text("0123456789", min_size=1, max_size=6000).map(lambda d: "1" + d),
    st.builds(lambda s, d: s + d, st.sampled_from(("-", "+", "")), st.sampled_from(("0x", "0b", "0", "1"))
              .flatmap(lambda p: st.just(p + "1" * 5000))),
)
INT_PLACES = (
    "constants:\n  c: {n}\n", "constants:\n  c: {{value: {n}}}\n", "risk: {{classes: {n}}}\n",
    "risk: {{unsafe_index: {n}}}\n", "risk: {{threshold: {n}}}\n", "risk:\n  release: {{hold_cycles: {n}}}\n",
    "signals:\n  x: {{range: [0, {n}]}}\n", "safe_pose: {{joints_rad: [{n}]}}\n",
    "obligations:\n  - {{id: o, require: 'true', within_cycles: {n}}}\n",
)


@given(yaml_ints, st.sampled_from(INT_PLACES), st.booleans())
def test_huge_integers_anywhere_in_a_spec(n, place, as_version):
    text = f"ethimon: {n}\nname: x\n" if as_version else "ethimon: 1\nname: x\n" + place.format(n=n)
    err = check_load(text)
    if err is not None:
        assert len(str(err)) < 1000, "the message echoes the whole number"


@given(yaml_ints, st.sampled_from(("at", "for_cycles", "cycles", "override_by_cycle")))
def test_huge_integers_in_scenarios(n, key):
    from ethimon.scenario import load_scenario_text
    entry = {"at": f"{{at: {n}, set: {{risk: 0.2}}}}", "for_cycles": f"{{at: 1, for_cycles: {n}, set: {{risk: 0.2}}}}"}
    text = (f"ethimon: 1\nname: s\nspec: spec.yaml\ncycles: {n if key == 'cycles' else 10}\ninputs: {{risk: 0.1}}\n"
            + (f"timeline:\n  - {entry[key]}\n" if key in entry else "")
            + (f"expect: {{override_by_cycle: {n}}}\n" if key == "override_by_cycle" else ""))
    try:
        load_scenario_text(text, PATH)
    except ethimon.SpecError as exc:
        assert exc.path == PATH and exc.line is not None and len(str(exc)) < 1000


# characters that look like digits or blanks but are not ASCII
look_alikes = st.one_of(
    st.characters(categories=("Nd",)).filter(lambda c: not c.isascii()),
    st.characters(categories=("Zs", "Zl", "Zp")).filter(lambda c: not c.isascii()),
    st.sampled_from("\u00a0\u2009\u202f\u3000\uff11\u0665\u06f5\u0966\u2264\u2212\ufeff"),
)


@given(st.sampled_from(("x < 15", "held(b, 12)", "x + 1 >= 2 and b", "y * 3 != 1")), look_alikes, st.data())
def test_non_ascii_in_expressions_is_never_read(expr, ch, data):
    i = data.draw(st.integers(0, len(expr)), label="at")
    src = expr[:i] + ch + expr[i:]
    err = check_load(stress_doc(src))
    assert err is not None, f"{src!r} loaded"
    assert err.line is not None and err.column is not None and err.hint


@given(st.sampled_from(("true", "false", "'1'", "'0.5'", "!!bool maybe", "yes", "'2'", "1.0", "2.5", "null")),
       st.sampled_from(("risk: {{threshold: {v}}}", "risk: {{classes: {v}}}", "risk: {{unsafe_index: {v}}}",
                        "risk:\n  release: {{hold_cycles: {v}}}", "signals:\n  s: {{range: [0, {v}]}}",
                        "constants:\n  c: {v}", "ethimon_version: {v}")))
def test_loose_types_are_never_coerced(value, place):
    if place.startswith("ethimon_version"):
        text = f"ethimon: {value}\nname: x\n"
    else:
        text = "ethimon: 1\nname: x\n" + place.format(v=value) + "\n"
    err = check_load(text)
    spec_value = None if err is not None else ethimon.load_spec_text(text, PATH)
    if spec_value is not None:  # only a real number of the right kind gets through
        assert value in ("1.0", "2.5") and "classes" not in place and "index" not in place \
            and "hold_cycles" not in place, text


@pytest.mark.slow
@given(st.integers(MAX_EXPR_DEPTH - 2, MAX_EXPR_DEPTH + 400), st.sampled_from(("(", "not (", "-(", "abs(")))
def test_deep_parentheses_are_refused_with_a_position(depth, opener):
    inner = "x" if opener != "not (" else "b"
    expr = opener * depth + inner + ")" * depth
    expr = expr if opener == "not (" else expr + " < 3"
    err = check_load(stress_doc(expr))
    if err is not None:
        assert err.line is not None and "too deeply" in err.message
    else:
        runs(stress_doc(expr))
