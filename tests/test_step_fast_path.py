"""Issue 25, "the hot path back ahead": the fast paths of ``Monitor.step`` judge exactly as before.

``step`` reads built-in floats in range and bools in a tight loop and hands the first other value
(missing, NaN, out of range, another type) to the full reading; ``p_unsafe`` as a built-in float is
turned into R_e inline; margins are built in one tuple when no margin can raise (chosen at compile
time) and each one is guarded otherwise; all verdicts come from one call. These tests pin each hand-over
against the reference interpreter, the order of the faults, one read per input, and the guarded margins.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import pytest

import ethimon
from ethimon.compiler._closures import build_machine
from ethimon.runtime._inputs import as_bool, as_number
from ethimon.testing import ReferenceMonitor


def key(d) -> tuple:
    """What must agree with the reference (its fault reasons are worded generically)."""
    return (d.cycle, d.override, d.response, tuple(d.violations), d.risk, d.latched, bool(d.faults),
            d.awaiting_release)


RANGES = {"a": (0.0, 10.0), "b": (0.0, 10.0), "c": (-5.0, 5.0)}


def expected_fault(name, v):
    """The fault kind the boundary rule gives signal ``name`` = ``v`` (None: usable)."""
    if v is None:
        return "missing"
    if name == "ok":
        return None if as_bool(v) is not None else "invalid"
    f = as_number(v)
    if f is None:
        return "invalid"
    lo, hi = RANGES[name]
    return None if lo <= f <= hi else "range"

SPEC = """
ethimon: 1
name: fast
signals:
  a: {unit: m, range: [0, 10]}
  ok: {type: bool}
  b: {unit: m, range: [0, 10]}
  c: {unit: m, range: [-5, 5]}
obligations:
  - {id: s1, require: "a <= 8"}
  - {id: s2, when: "not ok", require: "b <= 1", within_cycles: 3}
  - {id: s3, require: "b >= 0.5 or a <= 2"}
  - {id: s4, require: "once(c > 4, 3) implies a <= 1"}
  - {id: s5, require: "a != c and 2 < b"}
"""

DIV = """
ethimon: 1
name: div
signals:
  x: {unit: m, range: [0, 10]}
  y: {unit: m, range: [0, 10]}
obligations:
  - {id: guarded, require: "y <= 0 or x / y < 2"}
  - {id: plain, require: "x <= 9"}
"""


def good(**kw):
    f = {"a": 1.0, "ok": True, "b": 3.0, "c": 0.5, "p_unsafe": 0.05}
    f.update(kw)
    return {k: v for k, v in f.items() if v is not None}


class CountingMapping(Mapping):
    """A mapping that counts how often each key is read."""

    def __init__(self, d):
        self.d, self.reads = dict(d), {}

    def __getitem__(self, k):
        self.reads[k] = self.reads.get(k, 0) + 1
        return self.d[k]

    def get(self, k, default=None):
        self.reads[k] = self.reads.get(k, 0) + 1
        return self.d.get(k, default)

    def __iter__(self):
        return iter(self.d)

    def __len__(self):
        return len(self.d)


BAD = [None, math.nan, -1.0, 11.0, 3, np.float32(2.5), np.float64(2.5), True, "1", 1e400]


@pytest.mark.parametrize("where", ["a", "ok", "b", "c"])
@pytest.mark.parametrize("value", BAD, ids=repr)
def test_the_first_other_value_is_judged_as_the_reference_does(where, value):
    """Each signal position (first, a bool, middle, last) with each kind of value: same decision
    as the reference interpreter, on this cycle and the next good one (history, latches)."""
    spec = ethimon.load_spec_text(SPEC)
    m, ref = ethimon.Monitor(spec), ReferenceMonitor(spec)
    if where == "ok" and value in (3, True):
        value = 0.0 if value == 3 else 1  # numbers that are truth values: 0.0 and 1 pass as bools
    frames = [good(), good(**{where: value}), good(), good(b=0.2, ok=False), good(**{where: value})]
    for f in frames:
        d, e = m.step(f), ref.step(f)
        assert key(d) == key(e), (f, d, e)
        kind = expected_fault(where, f.get(where))
        assert [(x.kind, x.subject) for x in d.faults] == ([] if kind is None else [(kind, where)])


def test_faults_keep_the_order_of_the_signals():
    m = ethimon.Monitor(ethimon.load_spec_text(SPEC))
    d = m.step({"a": 1.0, "ok": "yes", "b": math.nan, "p_unsafe": 0.05})  # c missing
    assert [(f.kind, f.subject) for f in d.faults] == [("invalid", "ok"), ("invalid", "b"), ("missing", "c")]


@pytest.mark.parametrize("bad", [{}, {"b": math.nan}, {"a": np.float64(1.0)}, {"p_unsafe": np.float64(0.05)},
                                 {"p_unsafe": None, "p": [0.95, 0.05]}, {"p_unsafe": None, "risk": 0.1}])
def test_every_input_is_read_once_per_cycle(bad):
    m = ethimon.Monitor(ethimon.load_spec_text(SPEC))
    f = CountingMapping({k: v for k, v in {**good(), **bad}.items() if v is not None})
    m.step(f)
    assert f.reads and max(f.reads.values()) == 1, f.reads


@pytest.mark.parametrize("q", [0.0, 0.05, 0.3, 0.5, 0.5000000000000001, 0.77, 1.0])
def test_p_unsafe_inline_equals_the_full_reading(q):
    """The inline R_e of a built-in float p_unsafe is the same float as the full path's (an
    np.float64 p_unsafe takes the full path) and as the reference's."""
    for variance in ("population", "sample"):
        spec = ethimon.load_spec_text(SPEC + f"risk: {{variance: {variance}, threshold: 0.9}}\n")
        r1 = ethimon.Monitor(spec).step(good(p_unsafe=q)).risk
        r2 = ethimon.Monitor(spec).step(good(p_unsafe=np.float64(q))).risk
        r3 = ReferenceMonitor(spec).step(good(p_unsafe=q)).risk
        assert r1 == r2 == r3 and type(r1) is float


def test_margins_without_division_are_unguarded_and_with_one_guarded():
    plain = build_machine(ethimon.compiler.plan_of(ethimon.load_spec_text(SPEC)))
    div = build_machine(ethimon.compiler.plan_of(ethimon.load_spec_text(DIV)))
    assert plain.margins_raise is False and div.margins_raise is True


def test_a_margin_that_raises_is_nan_and_the_others_are_computed():
    spec = ethimon.load_spec_text(DIV)
    m, ref = ethimon.Monitor(spec), ReferenceMonitor(spec)
    for f in ({"x": 1.0, "y": 0.0, "p_unsafe": 0.05}, {"x": 9.5, "y": 0.0, "p_unsafe": 0.05},
              {"x": 1.0, "y": 2.0, "p_unsafe": 0.05}):
        d, e = m.step(f), ref.step(f)
        assert key(d) == key(e)
        for x, y in zip(d.margins, e.margins):
            assert x == y or (math.isnan(x) and math.isnan(y))
    d = ethimon.Monitor(spec).step({"x": 9.5, "y": 0.0, "p_unsafe": 0.05})
    assert math.isnan(d.margins[0]) and d.margins[1] == -0.5 and d.violations == ("plain",)


def test_margins_of_max_and_min_keep_nan_and_signed_zero_as_the_builtins():
    """max/min of two are written out; a tie of +0.0/-0.0 and a NaN operand come out as max()/min() give."""
    spec = ethimon.load_spec_text("""
ethimon: 1
name: z
signals:
  a: {unit: m, range: [-5, 5]}
  b: {unit: m, range: [-5, 5]}
obligations:
  - {id: o, require: "a >= 0 or b <= 0"}
  - {id: n, require: "a >= 0 and b <= 0"}
  - {id: i, require: "a >= 1 implies b <= 0"}
""")
    m, ref = ethimon.Monitor(spec), ReferenceMonitor(spec)
    for a, b in [(0.0, 0.0), (-0.0, 0.0), (0.0, -0.0), (1.0, 1.0), (-1.0, 2.0), (3.0, -3.0)]:
        f = {"a": a, "b": b, "p_unsafe": 0.05}
        d, e = m.step(f), ref.step(f)
        assert key(d) == key(e)
        assert [math.copysign(1.0, x) for x in d.margins] == [math.copysign(1.0, x) for x in e.margins], f
        assert d.margins == e.margins


def test_violations_come_in_obligation_order_from_the_one_verdict_call():
    m = ethimon.Monitor(ethimon.load_spec_text(SPEC))
    d = m.step(good(a=9.0, b=0.1))  # s1 (a > 8), s3 (b < 0.5 and a > 2), s5 (b <= 2)
    assert d.violations == ("s1", "s3", "s5")
