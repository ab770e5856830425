"""Compiled :class:`Monitor` ≡ :class:`ReferenceMonitor` on random specs and random traces.

Covers every operator and temporal operator, windows that are not yet full
at the start of a trace, faults in the middle of a trace (which clear the
history), ``reset()``, ``release()`` and ``acknowledge()``, with release policies
drawn per rule (auto/manual, hold) and for faults.
"""

from __future__ import annotations

import math
import os

import pytest
from hypothesis import given, note, settings
from hypothesis import strategies as st

import ethimon
from ethimon.testing import ReferenceMonitor
from ethimon.language._expr import Binary, BoolLit, Name, Num, Unary, parse_expr, to_source
from ethimon_strategies import bool_expr, decision_key, num_expr, ops, specs

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHIPPED = [os.path.join(ROOT, "specs", f) for f in ("governor.yaml", "cobot_cell.yaml")]


def run_both(spec, trace):
    m, ref = ethimon.Monitor(spec), ReferenceMonitor(spec)
    for op in trace:
        if op[0] == "reset":
            m.reset()
            ref.reset()
            continue
        if op[0] == "release":
            m.release()
            ref.release()
            continue
        if op[0] == "acknowledge":
            x, y = m.acknowledge(), ref.acknowledge()
            note(f"acknowledge: monitor={x!r} reference={y!r}")
            assert x == y
            assert m.latched_rules == ref.latched_rules
            continue
        a, b = m.step(op[1]), ref.step(op[1])
        note(f"frame={op[1]!r}\n  monitor  ={a!r}\n  reference={b!r}")
        assert decision_key(a) == decision_key(b)
        assert m.latched == (ref.latched > 0)
        if not a.faults:  # margins: the O(1) compiled ones equal the definition's (bounded responses too)
            assert len(a.margins) == len(b.margins)
            for x, y in zip(a.margins, b.margins):
                assert (x != x and y != y) or x == y or math.isclose(x, y, rel_tol=1e-9, abs_tol=1e-12), (x, y)


@pytest.mark.slow
@settings(max_examples=2 * settings.default.max_examples)  # the core differential check
@given(st.data())
def test_compiled_equals_reference_on_random_specs(data):
    gen = data.draw(specs())
    note(gen.text)
    run_both(gen.spec, data.draw(ops(gen.spec, max_size=25)))


@pytest.mark.slow
@given(st.data())
def test_compiled_equals_reference_at_trace_start_and_after_faults(data):
    # short traces, many faults: windows are never full, history is cleared often
    gen = data.draw(specs(max_obligations=2, depth=2))
    note(gen.text)
    run_both(gen.spec, data.draw(ops(gen.spec, max_size=8, p_bad=0.3)))


@pytest.mark.slow
@given(st.data())
def test_compiled_equals_reference_on_shipped_specs(data):
    spec = ethimon.load_spec(data.draw(st.sampled_from(SHIPPED)))
    run_both(spec, data.draw(ops(spec, max_size=40, p_bad=0.05)))


def shape(node):
    """Structure of an AST, with ``-<number>`` folded the way the parser folds it."""
    if isinstance(node, Unary) and node.op == "-":
        inner = shape(node.operand)
        if inner[0] == "num":  # the parser folds '-' into a literal (also through parentheses)
            return ("num", -inner[1] + 0.0)
        return ("-", inner)
    if isinstance(node, Num):
        return ("num", node.value + 0.0)
    if isinstance(node, BoolLit):
        return ("bool", node.value)
    if isinstance(node, Name):
        return ("name", node.id)
    if isinstance(node, Unary):
        return (node.op, shape(node.operand))
    if isinstance(node, Binary):
        return (node.op, shape(node.left), shape(node.right))
    return (node.func, *map(shape, node.args))


@pytest.mark.slow
@given(st.one_of(bool_expr(3), num_expr(3)))
def test_to_source_round_trips(tree):
    text = to_source(tree)
    again = parse_expr(text)
    assert shape(again) == shape(tree)
    assert to_source(parse_expr(to_source(again))) == to_source(again)
