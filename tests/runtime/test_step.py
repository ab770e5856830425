"""Issue 11: inputs that used to pass ``Monitor.step`` unusable (each returned override=False),
the exact release bound, and margins of bounded-response obligations that contradicted their verdicts.

The rule: a value is usable only if it converts to a finite built-in float (or a bool for a bool
signal) exactly once, at the boundary; everything downstream uses that copy; a non-finite R_e is a fault.

Issue 25, "the hot path back ahead": the fast paths of ``Monitor.step`` judge exactly as before.

``step`` reads built-in floats in range and bools in a tight loop and hands the first other value
(missing, NaN, out of range, another type) to the full reading; ``p_unsafe`` as a built-in float is
turned into R_e inline; margins are built in one tuple when no margin can raise (chosen at compile
time) and each one is guarded otherwise; all verdicts come from one call. These tests pin each hand-over
against the reference interpreter, the order of the faults, one read per input, and the guarded margins.
"""

from __future__ import annotations

import math
from fractions import Fraction
import numpy as np
import pytest
import ethimon
from ethimon.testing import ReferenceMonitor
from ethimon.language._model import Response
from collections.abc import Mapping
from ethimon.compiler._closures import build_machine
from ethimon.runtime._inputs import as_bool, as_number

SPEC = """
ethimon: 1
name: t
signals:
  d: {unit: m, range: [0, 10]}
  ok: {type: bool}
risk: {threshold: 0.5}
obligations:
  - {id: near, require: 'd > 0.5 and ok'}
"""


def mon(text: str = SPEC) -> ethimon.Monitor:
    return ethimon.Monitor(ethimon.load_spec_text(text))


def good(**kw):
    f = {"d": 2.0, "ok": True, "p_unsafe": 0.05}
    f.update(kw)
    return {k: v for k, v in f.items() if v is not None}


class NaNFloat(float):
    """A float subclass that holds NaN."""

    def __new__(cls):
        return super().__new__(cls, math.nan)


class AlwaysPasses:
    """An object whose every comparison is True (and that claims to be 0.5 as a float)."""

    def __lt__(self, o): return True
    def __le__(self, o): return True
    def __gt__(self, o): return True
    def __ge__(self, o): return True
    def __eq__(self, o): return True
    def __float__(self): return 0.5
    __hash__ = object.__hash__


class Interrupts(float):
    """A number whose conversion raises KeyboardInterrupt."""

    def __float__(self):
        raise KeyboardInterrupt


class FlipFlop:
    """A sequence that yields safe probabilities the first time and NaNs afterwards."""

    def __init__(self):
        self.reads = 0

    def __len__(self):
        return 2

    def __iter__(self):
        self.reads += 1
        return iter((0.0, 1.0) if self.reads == 1 else (math.nan, math.nan))


@pytest.mark.parametrize("frame", [
    good(d=np.bool_(True)),                        # numpy bool taken as a number
    good(d=np.True_),
    good(p_unsafe=np.bool_(False)),
    good(p_unsafe=None, risk=np.bool_(False)),
    good(p_unsafe=None, p=(True, False)),          # Python bools inside p
    good(p_unsafe=None, p=(np.bool_(True), np.bool_(False))),
    good(p_unsafe=None, p={0: 0.0, 1: math.nan}),  # a dict as p: keys validated, values read
    good(p_unsafe=None, p={0: 0.5, 1: 0.5}),
    good(p_unsafe=None, p={0.5, 0.25}),            # a set has no order
    good(d=NaNFloat()),                            # float subclass holding NaN
    good(p_unsafe=None, risk=NaNFloat()),
    good(p_unsafe=NaNFloat()),
    good(d=AlwaysPasses()),                        # comparisons that always pass
    good(p_unsafe=None, risk=AlwaysPasses()),
    good(p_unsafe=AlwaysPasses()),
    good(p_unsafe=None, p=(AlwaysPasses(), AlwaysPasses())),
    good(ok=AlwaysPasses()),
    good(d=Interrupts(1.0)),                       # KeyboardInterrupt raised while reading an input
    good(p_unsafe=Interrupts(0.1)),
])
def test_unusable_inputs_fail_closed(frame):
    d = mon().step(frame)
    assert d.override and d.faults, d
    assert d.response.severity >= Response.SAFE_POSE.severity
    assert d.risk is None or (d.risk.__class__ is float and math.isfinite(d.risk))


def test_keyboard_interrupt_in_a_comparison_does_not_escape_step():
    m = mon()
    d = m.step(good(d=Interrupts(1.0)))
    assert d.override and any("KeyboardInterrupt" in f.message or "must be a number" in f.message for f in d.faults)


def test_a_hostile_mapping_does_not_escape_step():
    class Boom(dict):
        def get(self, k, default=None):
            raise KeyboardInterrupt
    d = mon().step(Boom())
    assert d.override and d.faults


def test_sequence_read_twice_gives_the_first_reading():
    spec = SPEC.replace("risk: {threshold: 0.5}", "risk: {threshold: 0.5, classes: 2}")
    m, ref = mon(spec), ReferenceMonitor(ethimon.load_spec_text(spec))
    d = m.step(good(p_unsafe=None, p=FlipFlop()))
    # read once: (0, 1) → R_e = 0.6·1 + 0.2·0 + 0.2·0.5 = 0.7 ≥ τ: override for risk, no NaN anywhere
    assert d.risk == pytest.approx(0.7) and d.override and d.violations == ("risk",) and not d.faults
    assert ref.step(good(p_unsafe=None, p=FlipFlop())).risk == d.risk


def test_iterator_p_is_read_once():
    d = mon().step(good(p_unsafe=None, p=iter([0.9, 0.1])))
    assert not d.faults and d.risk == pytest.approx(0.6 * 0.1 + 0.2 * 0.1 + 0.2 * 2 * 0.4 ** 2)


@pytest.mark.parametrize("value", [np.float64(2.0), np.float32(2.0), np.int64(2), 2, Fraction(2), 2.0])
def test_real_numbers_of_other_types_are_converted_once(value):
    d = mon().step(good(d=value))
    assert not d.override and not d.faults


@pytest.mark.parametrize("value", [True, np.bool_(True), 1, 1.0, np.int8(1)])
def test_bool_signal_accepts_truth_values(value):
    d = mon().step(good(ok=value))
    assert not d.override and not d.faults


@pytest.mark.parametrize("value", [2, 0.5, "true", np.float64(math.nan), None])
def test_bool_signal_rejects_other_values(value):
    d = mon().step(good(ok=value))
    assert d.override and d.faults


def test_converted_copy_is_what_the_obligations_see():
    """A numpy float32 is converted with float() once; the margin is computed from that float."""
    m = mon()
    d = m.step(good(d=np.float32(0.25)))
    assert d.override and d.violations == ("near",)
    assert d.margins[0] == pytest.approx(float(np.float32(0.25)) - 0.5)
    assert type(d.margins[0]) is float


# ------------------------------------------------------------ release bound τ − δ, exactly
RELEASE = """
ethimon: 1
name: rel
risk: {threshold: 0.27, release: {mode: auto, hysteresis: 0.05, hold_cycles: 3}}
"""


@pytest.mark.parametrize("impl", [ethimon.Monitor, ReferenceMonitor])
def test_release_needs_risk_strictly_below_the_exact_bound(impl):
    m = impl(ethimon.load_spec_text(RELEASE))
    assert m.step({"risk": 0.6}).override
    # 0.27 − 0.05 is 0.22 as the spec writes it; R_e = 0.22 is not below it (float subtraction said it was)
    assert all(m.step({"risk": 0.22}).override for _ in range(10))
    ds = [m.step({"risk": 0.21999999999999997}) for _ in range(3)]
    assert [d.override for d in ds] == [True, True, False]


# ------------------------------------------------------------ margins agree with verdicts
BOUNDED = """
ethimon: 1
name: b
signals:
  x: {range: [0, 1]}
  a: {type: bool}
obligations:
  - {id: resp, when: x >= 0.75, require: a, within_cycles: 2}
"""


def test_bounded_response_margin_has_the_sign_of_its_verdict():
    m = mon(BOUNDED)
    ds = [m.step({"x": x, "a": False, "p_unsafe": 0.0}) for x in (0.9, 0.2, 0.2)]
    assert [d.violations for d in ds] == [(), (), ("resp",)]
    assert ds[0].margins[0] > 0 and ds[1].margins[0] > 0  # no trigger is 2 cycles old yet
    assert ds[2].margins[0] < 0                          # was +0.55 (that cycle's max(-when, require))
    assert ds[2].margins[0] == pytest.approx(-0.15)      # max(−(0.9 − 0.75), require = −inf)


def test_bounded_response_margin_is_quantitative_and_recovers():
    spec = BOUNDED.replace("a: {type: bool}", "v: {range: [0, 3]}").replace("require: a", "require: v <= 0.25")
    m = mon(spec)
    trace = [(0.9, 1.0), (0.2, 0.8), (0.2, 0.5), (0.2, 0.1), (0.2, 2.0)]
    ds = [m.step({"x": x, "v": v, "p_unsafe": 0.0}) for x, v in trace]
    assert [bool(d.violations) for d in ds] == [False, False, True, False, False]
    # cycle 2: trigger at 0 (when margin 0.15) and require margins −0.75, −0.55, −0.25 → max(−0.15, −0.25)
    assert ds[2].margins[0] == pytest.approx(-0.15)
    assert ds[3].margins[0] == pytest.approx(0.15)  # require met at 3 (margin +0.15) discharges trigger 0
    ref = ReferenceMonitor(ethimon.load_spec_text(spec))
    for (x, v), d in zip(trace, ds):
        assert ref.step({"x": x, "v": v, "p_unsafe": 0.0}).margins == pytest.approx(d.margins)


def test_non_finite_risk_is_a_fault(monkeypatch):
    """R_e is checked after it is computed, whatever produced it."""
    import ethimon.runtime._risk_input as ri
    monkeypatch.setattr(ri, "risk_from_probs", lambda *a, **k: math.nan)
    d = mon().step(good(p_unsafe=None, p=(0.5, 0.5)))
    assert d.override and d.risk is None and any("not finite" in f.message for f in d.faults)


# ------------------------------------------------------------ found in review
class Liar:
    """Claims to be a float through __class__ and passes every comparison."""

    __class__ = property(lambda self: float)  # type: ignore[assignment]

    def __float__(self): return 0.0  # noqa: E704
    def __le__(self, o): return True  # noqa: E704
    def __ge__(self, o): return o < 0.5  # noqa: E704
    def __gt__(self, o): return True  # noqa: E704
    def __lt__(self, o): return True  # noqa: E704


@pytest.mark.parametrize("impl", [ethimon.Monitor, ReferenceMonitor])
@pytest.mark.parametrize("frame", [good(d=Liar()), good(p_unsafe=None, risk=Liar()), good(p_unsafe=Liar()),
                                   good(p_unsafe=None, p=[Liar(), Liar()]), good(ok=Liar())])
def test_an_object_claiming_to_be_a_float_is_not_one(impl, frame):
    d = impl(ethimon.load_spec_text(SPEC)).step(frame)
    assert d.override and d.faults
    assert d.risk is None or type(d.risk) is float


@pytest.mark.parametrize("value", [Fraction(10 ** 400), 10 ** 400, -(10 ** 400)])
def test_numbers_too_large_for_a_float_are_not_numbers(value):
    d = mon().step(good(d=value))
    assert d.override and any(f.kind == "invalid" and "must be a number" in f.message for f in d.faults), d.faults


@pytest.mark.parametrize("p", [[0.9, 0.1], (0.9, 0.1), (np.float64(0.9), 0.1), np.array([0.9, 0.1])])
def test_p_fast_path_and_slow_path_agree(p):
    d = mon().step(good(p_unsafe=None, p=p))
    assert not d.faults and d.risk == pytest.approx(0.6 * 0.1 + 0.2 * 0.1 + 0.2 * 2 * 0.4 ** 2)


@pytest.mark.parametrize("p", [[0.9, math.nan], (0.9, 0.2), [0.5, 0.5, 0.0], (True, 0.0), [Liar(), 1.0]])
def test_p_fast_path_still_refuses(p):
    d = mon().step(good(p_unsafe=None, p=p))
    assert d.override and d.faults


def test_bounded_margin_that_cannot_be_computed_is_nan_like_the_reference():
    spec = ethimon.load_spec_text("""
ethimon: 1
name: nanm
signals: {x: {range: [0, 1]}, y: {range: [0, 1]}}
obligations:
  - {id: r, when: x >= 0.75, require: 'y <= 0 or x / y < 2', within_cycles: 2}
""")
    m, ref = ethimon.Monitor(spec), ReferenceMonitor(spec)
    for x, y in ((0.9, 0.0), (0.9, 0.1), (0.9, 0.1)):
        a, b = m.step({"x": x, "y": y, "p_unsafe": 0.0}), ref.step({"x": x, "y": y, "p_unsafe": 0.0})
        assert a.violations == b.violations == ()
        mg, rg = a.margins[0], b.margins[0]
        assert (mg != mg and rg != rg) or mg == rg, (mg, rg)
        assert mg != mg or mg >= 0  # never a negative margin on a satisfied cycle


@pytest.mark.parametrize("classes,weights", [(2, (0.6, 0.2, 0.2)), (3, (0.6, 0.2, 0.2)), (3, (1.0, 1.0, 1.0)),
                                             (4, (0.9, 0.5, 1.0))])
def test_verify_assumes_the_risk_inputs_the_monitor_accepts(classes, weights):
    """verify's encoding of the ``risk`` input must cover what Monitor.step accepts (any K): a narrower
    range would let a proof skip inputs the monitor runs on."""
    from ethimon.verify._encode import risk_input_range
    a, b, g = weights
    spec = ethimon.load_spec_text(f"{{ethimon: 1, name: k, risk: {{classes: {classes}, alpha: {a}, beta: {b}, "
                                  f"gamma: {g}, threshold: 0.5, allow: {{weights: test}}}}}}")
    m = ethimon.Monitor(spec)
    lo, hi = risk_input_range(m.plan)
    assert (lo, hi) == (m._risk.lo, m._risk.hi)
    assert not m.step({"risk": hi}).faults and m.step({"risk": math.nextafter(hi, math.inf)}).faults


# -------- Issue 25, "the hot path back ahead": the fast paths of ``Monitor.step`` judge exactly as before.

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

FAST_SPEC = """
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


def good_cycle(**kw):
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
    spec = ethimon.load_spec_text(FAST_SPEC)
    m, ref = ethimon.Monitor(spec), ReferenceMonitor(spec)
    if where == "ok" and value in (3, True):
        value = 0.0 if value == 3 else 1  # numbers that are truth values: 0.0 and 1 pass as bools
    frames = [good_cycle(), good_cycle(**{where: value}), good_cycle(), good_cycle(b=0.2, ok=False), good_cycle(**{where: value})]
    for f in frames:
        d, e = m.step(f), ref.step(f)
        assert key(d) == key(e), (f, d, e)
        kind = expected_fault(where, f.get(where))
        assert [(x.kind, x.subject) for x in d.faults] == ([] if kind is None else [(kind, where)])


def test_faults_keep_the_order_of_the_signals():
    m = ethimon.Monitor(ethimon.load_spec_text(FAST_SPEC))
    d = m.step({"a": 1.0, "ok": "yes", "b": math.nan, "p_unsafe": 0.05})  # c missing
    assert [(f.kind, f.subject) for f in d.faults] == [("invalid", "ok"), ("invalid", "b"), ("missing", "c")]


@pytest.mark.parametrize("bad", [{}, {"b": math.nan}, {"a": np.float64(1.0)}, {"p_unsafe": np.float64(0.05)},
                                 {"p_unsafe": None, "p": [0.95, 0.05]}, {"p_unsafe": None, "risk": 0.1}])
def test_every_input_is_read_once_per_cycle(bad):
    m = ethimon.Monitor(ethimon.load_spec_text(FAST_SPEC))
    f = CountingMapping({k: v for k, v in {**good_cycle(), **bad}.items() if v is not None})
    m.step(f)
    assert f.reads and max(f.reads.values()) == 1, f.reads


@pytest.mark.parametrize("q", [0.0, 0.05, 0.3, 0.5, 0.5000000000000001, 0.77, 1.0])
def test_p_unsafe_inline_equals_the_full_reading(q):
    """The inline R_e of a built-in float p_unsafe is the same float as the full path's (an
    np.float64 p_unsafe takes the full path) and as the reference's."""
    for variance in ("population", "sample"):
        spec = ethimon.load_spec_text(FAST_SPEC + f"risk: {{variance: {variance}, threshold: 0.9}}\n")
        r1 = ethimon.Monitor(spec).step(good_cycle(p_unsafe=q)).risk
        r2 = ethimon.Monitor(spec).step(good_cycle(p_unsafe=np.float64(q))).risk
        r3 = ReferenceMonitor(spec).step(good_cycle(p_unsafe=q)).risk
        assert r1 == r2 == r3 and type(r1) is float


def test_margins_without_division_are_unguarded_and_with_one_guarded():
    plain = build_machine(ethimon.compiler.plan_of(ethimon.load_spec_text(FAST_SPEC)))
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
    m = ethimon.Monitor(ethimon.load_spec_text(FAST_SPEC))
    d = m.step(good_cycle(a=9.0, b=0.1))  # s1 (a > 8), s3 (b < 0.5 and a > 2), s5 (b <= 2)
    assert d.violations == ("s1", "s3", "s5")
