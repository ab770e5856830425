"""ethimon.offline.check_trace: each operator, bad inputs, the latch, internal faults, shipped specs.

Every test compares with ``Monitor.step`` over the same cycles (the definition
the offline checker must equal) and, where the answer is easy to state, with
the expected verdicts written out by hand.
"""

from __future__ import annotations

import math
import os
import subprocess
import sys

import numpy as np
import pytest

import ethimon
from ethimon.offline import check_trace, iter_rows

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def make_spec(obligations: str, *, risk: str = "", signals: str | None = None) -> ethimon.Spec:
    sig = signals or "x: {range: [-10, 10]}\n  y: {range: [-10, 10]}\n  b: {type: bool}"
    text = f"ethimon: 1\nname: t\nsignals:\n  {sig}\n{risk}\nobligations:\n{obligations}"
    return ethimon.load_spec_text(text)


def stepped(spec, columns, length=None):
    """Monitor.step over the rows of ``columns`` (the definition)."""
    m = ethimon.Monitor(spec)
    return [m.step(r) for r in iter_rows(spec, columns, length=length)]


def assert_same(spec, columns, **kw):
    res = check_trace(spec, columns, **kw)
    ref = stepped(spec, columns, kw.get("length"))
    assert res.n_cycles == len(ref)
    for t, d in enumerate(ref):
        got = res.decision(t)
        assert got == d, (t, got, d)
        assert all((a != a and b != b) or a == b for a, b in zip(got.margins, d.margins)), (t, got.margins, d.margins)
    return res


def cols(n, **kw):
    out = {"p_unsafe": np.full(n, 0.05)}
    out.update({k: np.asanyarray(v) for k, v in kw.items()})
    return out


B = np.array([1, 1, 0, 1, 1, 1, 0, 0, 1, 1, 1, 1], bool)


# -- operators ---------------------------------------------------------------------------------

def test_invariant_and_arithmetic():
    spec = make_spec('  - {id: s1, require: "abs(x) + 2 * y <= 3 and sqrt(abs(y)) < 2"}')
    x = np.array([0.0, 1.0, -3.0, 2.5, 0.0])
    y = np.array([1.0, 1.0, 1.0, 0.0, 5.0])
    res = assert_same(spec, cols(5, x=x, y=y, b=np.ones(5, bool)))
    assert res.violated[:, 0].tolist() == [False, False, True, False, True]
    assert res.margins[0, 0] == 1.0  # 3 - (0 + 2), the smaller of the two sides' robustness


@pytest.mark.parametrize("expr, expected", [
    ("held(b, 3)", [0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1]),
    ("once(not b, 2)", [0, 0, 1, 1, 0, 0, 1, 1, 1, 0, 0, 0]),
    ("since(b, not b)", [0, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1]),
    ("since(b, not b, 3)", [0, 0, 1, 1, 1, 0, 1, 1, 1, 1, 0, 0]),
    ("prev(b)", [0, 1, 1, 0, 1, 1, 1, 0, 0, 1, 1, 1]),
    ("prev(b, true)", [1, 1, 1, 0, 1, 1, 1, 0, 0, 1, 1, 1]),
])
def test_temporal_operators(expr, expected):
    spec = make_spec(f'  - {{id: o, require: "not ({expr})"}}')
    res = assert_same(spec, cols(12, x=np.zeros(12), y=np.zeros(12), b=B))
    assert res.violated[:, 0].astype(int).tolist() == expected


def test_prev_of_a_number_starts_with_itself():
    spec = make_spec('  - {id: o, require: "x - prev(x) <= 1"}\n  - {id: p, require: "prev(x, 5) <= x"}')
    x = np.array([3.0, 3.5, 5.0, 5.0, 1.0])
    res = assert_same(spec, cols(5, x=x, y=x, b=np.ones(5, bool)))
    assert res.violated[:, 0].tolist() == [False, False, True, False, False]
    assert res.violated[:, 1].tolist() == [True, False, False, False, True]


@pytest.mark.parametrize("n", [1, 3, 50])
def test_bounded_response(n):
    # contact at 2 and 40; the stop comes 4 cycles after the first and never after the second
    contact = np.zeros(100, bool)
    contact[[2, 40]] = True
    speed = np.full(100, 1.0)
    speed[6:40] = 0.0
    spec = make_spec(f'  - {{id: s2, when: "b", require: "x <= 0.1", within_cycles: {n}}}')
    res = assert_same(spec, cols(100, x=speed, y=speed, b=contact))
    v = res.violated[:, 0]
    first = {1: 3, 3: 5, 50: 90}[n]
    assert res.summary()["s2"]["first_violation"] == first
    assert v[first:].all() if n == 50 else v[first]


def test_windows_are_flat_and_exact_at_length_1000():
    rng = np.random.default_rng(1)
    n = 5000
    b = np.repeat(rng.random(n // 50) < 0.5, 50)
    spec = make_spec('  - {id: h, require: "not held(b, 1000)"}\n'
                     '  - {id: o, when: "once(not b, 1000)", require: "x < 5"}\n'
                     '  - {id: r, when: "b", require: "not b", within_cycles: 999}')
    assert_same(spec, cols(n, x=rng.uniform(0, 10, n), y=np.zeros(n), b=b))


# -- bad and missing inputs -----------------------------------------------------------------------

def test_nan_inf_out_of_range_missing_fail_closed_like_step():
    spec = make_spec('  - {id: s1, require: "x <= 5"}')
    x = np.array([1.0, np.nan, np.inf, 11.0, 2.0, 6.0])
    b = np.ma.masked_array([True, True, True, True, False, True], [0, 0, 0, 0, 1, 0])
    res = assert_same(spec, cols(6, x=x, y=np.zeros(6), b=b))
    assert res.fault.tolist() == [False, True, True, True, True, False]
    assert res.violated[:, 0].tolist() == [False, False, False, False, False, True]
    # worded by the monitor itself (assert_same compared them): one reason, naming the input
    assert len(res.faults_at(1)) == 1 and "'x'" in str(res.faults_at(1)[0])
    assert [str(f) for f in res.faults_at(4)] == ["signal 'b' is missing"]
    assert res.faults_at(0) == ()


def test_a_missing_column_is_a_missing_input_every_cycle():
    spec = make_spec('  - {id: s1, require: "x <= 5"}')
    res = assert_same(spec, {"x": np.zeros(3), "b": np.ones(3, bool), "p_unsafe": np.zeros(3)})
    assert res.fault.all() and ["signal 'y' is missing" == str(f) for f in res.faults_at(2)] == [True]
    res = assert_same(spec, {}, length=2)
    assert res.fault.all() and res.override.all()


def test_object_columns_and_wrong_types():
    spec = make_spec('  - {id: s1, require: "x <= 5"}')
    n = 5
    x = [1.0, None, "2", True, 3]
    b = np.array([True, 0.5, 1, 0, np.nan], dtype=object)
    res = assert_same(spec, {"x": x, "y": np.zeros(n), "b": b, "risk": [0.1, 0.2, None, 0.9, "x"]})
    assert res.fault.tolist() == [False, True, True, True, True]


def test_risk_inputs_p_matrix_p_unsafe_and_risk_column():
    spec = make_spec('  - {id: s1, require: "risk < 0.9"}', risk="risk: {threshold: 0.5}")
    q = np.array([0.1, 0.9, 0.5, np.nan, 0.3])
    p = np.stack([1 - q, q], axis=1)
    assert_same(spec, {"x": np.zeros(5), "y": np.zeros(5), "b": np.ones(5, bool), "p": p})
    assert_same(spec, {"x": np.zeros(5), "y": np.zeros(5), "b": np.ones(5, bool), "p_unsafe": q})
    r = np.ma.masked_array([0.1, 0.95, 0.2, 0.3, 2.0], [0, 0, 1, 0, 0])
    res = assert_same(spec, {"x": np.zeros(5), "y": np.zeros(5), "b": np.ones(5, bool), "risk": r, "p_unsafe": q})
    assert res.risk_violated.tolist() == [False, True, False, False, False]
    assert math.isnan(res.risk[4]) and res.decision(4).risk is None


def test_stale_risk_estimate_and_the_age_limit_argument():
    spec = make_spec('  - {id: s1, require: "x <= 5"}', risk="risk: {max_age_s: 0.5}")
    c = cols(4, x=np.zeros(4), y=np.zeros(4), b=np.ones(4, bool), risk_age_s=np.array([0.1, 0.6, np.nan, 0.5]))
    res = assert_same(spec, c)
    assert res.fault.tolist() == [False, True, True, False]
    plain = make_spec('  - {id: s1, require: "x <= 5"}')
    res = check_trace(plain, c, max_age_s=0.5)
    assert res.fault.tolist() == [False, True, True, False]
    assert not check_trace(plain, c).fault.any()  # without a limit, risk_age_s is not read


def test_stateless_obligations_are_judged_on_fault_cycles():
    # risk missing (a fault, safe_pose) while a stop-0 force rule is violated: stop_0 wins
    spec = make_spec('  - {id: force, require: "x <= 5", response: stop_0}\n'
                     '  - {id: tmp, require: "not held(b, 2)", response: stop_2}',
                     risk="on_fault: safe_pose")
    pu = np.ma.masked_array([0.1, 0.1, 0.1], [0, 1, 1])
    res = assert_same(spec, {"x": np.array([0.0, 9.0, 0.0]), "y": np.zeros(3), "b": np.ones(3, bool),
                             "p_unsafe": pu})
    assert res.violations_at(1) == ("force",)
    assert res.response_at(1) == ethimon.Response.STOP_0


def test_fault_clears_the_history():
    spec = make_spec('  - {id: h, require: "not held(b, 3)"}')
    x = np.zeros(8)
    x[3] = np.nan
    res = assert_same(spec, cols(8, x=x, y=np.zeros(8), b=np.ones(8, bool)))
    assert res.violated[:, 0].tolist() == [False, False, True, False, False, False, True, True]


# -- latch and release -------------------------------------------------------------------------------

def test_risk_latch_releases_below_the_exact_hysteresis_bound():
    spec = make_spec('  - {id: s1, require: "x <= 5"}',
                     risk="risk: {threshold: 0.27, response: stop_2, "
                          "release: {mode: auto, hysteresis: 0.05, hold_cycles: 2}}")
    r = np.array([0.1, 0.3, 0.22, 0.1, 0.22, 0.1, 0.1, 0.1])
    res = assert_same(spec, {"x": np.zeros(8), "y": np.zeros(8), "b": np.ones(8, bool), "risk": r})
    # 0.22 is not below 0.27 - 0.05 (exactly 0.22): the count restarts there
    assert res.override.astype(int).tolist() == [0, 1, 1, 1, 1, 1, 0, 0]
    assert res.response.tolist() == [0, 2, 2, 2, 2, 2, 0, 0]
    assert res.latched.astype(int).tolist() == [0, 0, 1, 1, 1, 1, 0, 0]


def test_one_latch_per_rule_auto_and_manual():
    # s1 (stop_2) releases by itself after 2 clean cycles; s2 (stop_1) is manual by default
    spec = make_spec('  - {id: s1, require: "x <= 5", response: stop_2, release: {mode: auto, hold_cycles: 2}}\n'
                     '  - {id: s2, require: "x <= 8", response: stop_1, release: {mode: manual, hold_cycles: 2}}')
    x = np.array([0.0, 6.0, 0.0, 0.0, 0.0, 9.0, 0.0, 0.0, 0.0])
    res = assert_same(spec, cols(9, x=x, y=np.zeros(9), b=np.ones(9, bool)))
    assert res.override.astype(int).tolist() == [0, 1, 1, 0, 0, 1, 1, 1, 1]
    assert res.response.tolist() == [0, 2, 2, 0, 0, 3, 3, 3, 3]
    assert res.latched.astype(int).tolist() == [0, 0, 1, 0, 0, 0, 1, 1, 1]
    assert res.awaiting_release.astype(int).tolist() == [0, 0, 0, 0, 0, 0, 0, 1, 1]


def test_manual_release_never_releases():
    spec = make_spec('  - {id: s1, require: "x <= 5", release: manual}')
    x = np.zeros(20)
    x[3] = 9.0
    res = assert_same(spec, cols(20, x=x, y=np.zeros(20), b=np.ones(20, bool)))
    assert not res.override[:3].any() and res.override[3:].all() and res.latched[4:].all()
    assert not res.awaiting_release[:13].any() and res.awaiting_release[13:].all()  # hold: 10 cycles


def test_a_fault_latches_until_acknowledged_by_default():
    spec = make_spec('  - {id: s1, require: "x <= 5"}')
    x = np.zeros(6)
    x[1] = np.nan
    res = assert_same(spec, cols(6, x=x, y=np.zeros(6), b=np.ones(6, bool)))
    assert res.override.tolist() == [False] + [True] * 5 and res.latched[2:].all()


# -- internal faults -----------------------------------------------------------------------------------

def test_division_by_zero_is_an_internal_fault_worded_by_the_monitor():
    spec = make_spec('  - {id: d, require: "x / y < 2"}\n  - {id: h, require: "not held(b, 2)"}')
    y = np.array([1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0])
    res = assert_same(spec, cols(8, x=np.ones(8), y=y, b=np.ones(8, bool)))
    assert res.internal_error.tolist() == [False, False, True, True, True, False, False, False]
    assert res.violated[:, 1].tolist() == [False, True, False, False, False, False, True, True]
    assert res.fallback_cycles == 0
    (fault,) = res.faults_at(3)
    assert "ZeroDivisionError" in str(fault)


def test_errors_that_depend_on_the_history_fall_back_to_the_monitor():
    # prev(y, 1) is 1 on a segment's first cycle and 0 after it: every second cycle raises
    spec = make_spec('  - {id: d, require: "x / prev(y, 1) < 2"}')
    n = 60
    res = assert_same(spec, cols(n, x=np.ones(n), y=np.zeros(n), b=np.ones(n, bool)))
    assert res.internal_error.tolist() == [t % 2 == 1 for t in range(n)]
    assert res.fallback_cycles > 0 and "Monitor.step" in res.fallback_reason


def test_a_short_circuit_skips_the_division():
    spec = make_spec('  - {id: d, require: "y == 0 or x / y < 2"}')
    res = assert_same(spec, cols(3, x=np.ones(3), y=np.array([0.0, 1.0, 0.25]), b=np.ones(3, bool)))
    assert not res.fault.any() and res.violated[:, 0].tolist() == [False, False, True]
    assert math.isnan(res.margins[0, 0])  # the margin has no short-circuit: it cannot be computed


# -- shipped specs -------------------------------------------------------------------------------------

def cobot_trace(n: int, seed: int = 0) -> dict[str, np.ndarray]:
    rng = np.random.default_rng(seed)
    t = np.arange(n)
    phase = t % 500
    d = np.where((phase >= 100) & (phase < 200), 3.0 - 0.025 * np.minimum(phase - 100, 200 - phase) * 2, 3.0)
    force = np.where(phase == 250, 150.0, np.where((phase >= 300) & (phase < 308), 80.0, rng.uniform(0, 5, n)))
    cols = {"human_distance": d + rng.uniform(-0.01, 0.01, n), "ee_speed": rng.uniform(0.05, 0.4, n),
            "contact_force": force, "joint_speed_max": rng.uniform(0, 2.2, n),
            "p_unsafe": np.where((phase >= 400) & (phase < 420), 0.7, 0.05)}
    cols["ee_speed"][rng.random(n) < 0.003] = np.nan
    return cols


@pytest.mark.parametrize("name", ["cobot_cell.yaml", "governor.yaml"])
def test_shipped_specs_on_a_generated_trace(name):
    spec = ethimon.load_spec(os.path.join(ROOT, "specs", name))
    trace = cobot_trace(3000)
    trace.update({s: np.full(3000, 0.5) for s in spec.signals if s not in trace})
    res = assert_same(spec, trace)
    assert res.override.any() and not res.override.all()
    summary = res.summary()
    assert set(summary) == set(res.obligation_ids) | {"risk"}


# -- API -------------------------------------------------------------------------------------------------

def test_column_shape_errors_name_the_column():
    spec = make_spec('  - {id: s1, require: "x <= 5"}')
    with pytest.raises(ValueError, match="column 'y' has 2 values, but the trace has 3"):
        check_trace(spec, {"x": np.zeros(3), "y": np.zeros(2)})
    with pytest.raises(ValueError, match="column 'x' has shape"):
        check_trace(spec, {"x": np.zeros((3, 2))})
    with pytest.raises(ValueError, match="pass length="):
        check_trace(spec, {"unrelated": np.zeros(3)})
    with pytest.raises(ValueError, match="method"):
        check_trace(spec, {}, length=1, method="fast")


def test_step_method_and_empty_trace():
    spec = make_spec('  - {id: s1, when: "b", require: "x <= 5", within_cycles: 2}')
    c = cols(30, x=np.linspace(0, 10, 30), y=np.zeros(30), b=np.ones(30, bool))
    a, b = check_trace(spec, c), check_trace(spec, c, method="step")
    assert b.method == "step" and b.fallback_cycles == 30
    assert np.array_equal(a.override, b.override) and np.array_equal(a.violated, b.violated)
    assert check_trace(spec, {}, length=0).n_cycles == 0


@pytest.mark.slow
def test_import_rules():
    code = ("import sys, ethimon; assert 'ethimon.offline' not in sys.modules; import ethimon.offline; "
            "bad = [m for m in sys.modules if m.split('.')[:2] in (['ethimon', 'cli'], ['ethimon', 'loop'], "
            "['ethimon', 'scenario'], ['ethimon', 'sim'], ['ethimon', 'replay']) or m in ('torch', 'pybullet')]; "
            "print(bad); assert not bad, bad")
    subprocess.run([sys.executable, "-c", code], check=True, cwd=ROOT)


def test_confirm_band_firings_are_reported_like_the_monitor():
    """Regression: check_trace stepped a confirm-band spec through Monitor but dropped the tier rules
    from Decision.violations (the monitor says ('confirm',), offline said ())."""
    spec = ethimon.load_spec_text(
        "ethimon: 1\nname: band\nsignals: {}\nrisk: {threshold: 0.576, confirm_threshold: 0.299}\n")
    q = np.array([0.05, 0.7, 0.7, 0.05, 0.95, 0.05])       # R_e 0.496: in [0.299, 0.576); 0.95: above τ
    res = assert_same(spec, {"p_unsafe": q})
    assert res.violations_at(1) == ("confirm",) and res.decision(1).violations == ("confirm",)
    assert "risk" in res.violations_at(4)
