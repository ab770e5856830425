"""``separation_distance``: compiled ≡ reference ≡ offline on random specs that use it.

Every generated spec has an obligation ``lhs >= separation_distance(...)`` (maybe under a ``when``,
a bounded response, or inside a larger condition), with arguments that are constants, signals
that are never negative (``y``, ``abs(x)``), or random subexpressions that can be negative at run
time (then evaluating the rule raises: a fault, the same cycle in all three). The general random
specs of :mod:`ethimon_strategies` draw the function as well; this suite makes sure it is always there.
"""

from __future__ import annotations

import yaml
import pytest
from hypothesis import given, note
from hypothesis import strategies as st

import ethimon
from ethimon.language._expr import Binary, Call, Name, Num, to_source
from ethimon_strategies import (GenSpec, _n, _no_risk, bool_expr, frame, num_expr, ops, separation_calls,
                                spec_doc)
from test_prop_equivalence import run_both
from test_prop_offline import assert_equal_to_monitor, object_columns

SAFE_ARGS = st.one_of(st.sampled_from((0.0, 0.05, 0.1, 0.3, 1.6, 2.5)).map(lambda v: _n(Num, v)),
                      st.just(_n(Name, "y")), st.just(_n(Call, "abs", (_n(Name, "x"),))))


@st.composite
def separation_specs(draw) -> GenSpec:
    if draw(st.booleans()):  # arguments that are never negative: no faults, only verdicts and margins
        call = _n(Call, "separation_distance", tuple(draw(st.lists(SAFE_ARGS, min_size=8, max_size=8))))
    else:
        call = draw(separation_calls(num_expr(1)))
    lhs = _no_risk(draw(st.one_of(st.just(_n(Name, "y")), num_expr(1))))
    op = draw(st.sampled_from((">=", ">", "<", "<=")))
    cond = _n(Binary, op, lhs, call)
    shape = draw(st.sampled_from(("alone", "alone", "and", "or", "held")))
    if shape in ("and", "or"):
        cond = _n(Binary, shape, cond, draw(bool_expr(1)))
    elif shape == "held":
        cond = _n(Call, "held", (cond, _n(Num, 2.0)))
    doc = spec_doc(draw, max_obligations=1, depth=2)
    ob = {"id": "ssm", "require": to_source(cond), "response": draw(st.sampled_from(("stop_2", "stop_1")))}
    if draw(st.booleans()):
        ob["when"] = to_source(draw(bool_expr(1)))
    w = draw(st.sampled_from((None, None, 1, 3)))
    if w is not None:
        ob["within_cycles"] = w
    doc["obligations"] = [ob] + doc["obligations"]
    text = yaml.safe_dump(doc, sort_keys=False)
    return GenSpec(text, ethimon.load_spec_text(text, "<generated>"), doc)


@pytest.mark.slow
@given(st.data())
def test_compiled_equals_reference_with_separation_distance(data):
    gen = data.draw(separation_specs())
    note(gen.text)
    assert "separation_distance(" in gen.text
    run_both(gen.spec, data.draw(ops(gen.spec, max_size=20)))


@pytest.mark.slow
@given(st.data())
def test_offline_equals_monitor_with_separation_distance(data):
    gen = data.draw(separation_specs())
    note(gen.text)
    frames = data.draw(st.lists(frame(gen.spec, p_bad=0.03), min_size=1, max_size=25))
    assert_equal_to_monitor(gen.spec, object_columns(frames), frames)


@pytest.mark.slow
def test_the_strategy_reaches_both_outcomes():
    """The generated rules are not all faults nor all fault-free (the property would be weak)."""
    seen = set()

    @given(separation_specs(), st.data())
    def probe(gen, data):
        m = ethimon.Monitor(gen.spec)
        for f in data.draw(st.lists(frame(gen.spec, p_bad=0.0), min_size=3, max_size=6)):
            d = m.step(f)
            seen.add("fault" if d.faults else "violated" if "ssm" in d.violations else "held")

    probe()
    assert {"fault", "held"} <= seen, seen
