"""Issue 11: inputs that used to pass ``Monitor.step`` unusable (each returned override=False),
the exact release bound, and margins of bounded-response obligations that contradicted their verdicts.

The rule: a value is usable only if it converts to a finite built-in float (or a bool for a bool
signal) exactly once, at the boundary; everything downstream uses that copy; a non-finite R_e is a fault.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest

import ethimon
from ethimon.testing import ReferenceMonitor
from ethimon.language._model import Response

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
    import ethimon.runtime._monitor as mm
    monkeypatch.setattr(mm, "risk_from_probs", lambda *a, **k: math.nan)
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
    assert (lo, hi) == (m._rlo, m._rhi)
    assert not m.step({"risk": hi}).faults and m.step({"risk": math.nextafter(hi, math.inf)}).faults
