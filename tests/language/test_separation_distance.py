"""``separation_distance(v_h, v_r, T_r, T_s, S_s, C, Z_d, Z_r)``: the protective separation distance of
ISO/TS 15066:2016 (clause 5.5.4, constant speeds) as a built-in expression function (issue 14, item 5).

Hand-computed values in the compiled monitor, the reference interpreter and the offline checker; units
and negative constants as located SpecErrors; a negative or NaN argument at run time as a fault; the z3
encoding (exact when linear, refuted definedness when a range allows a negative speed); the shipped cell.
"""

from __future__ import annotations

import math
import os

import numpy as np
import pytest

import ethimon
from ethimon.offline import check_trace, iter_rows
from ethimon.language._expr import SEPARATION_PARAMS, parse_expr, separation_distance, to_source
from ethimon.testing import ReferenceMonitor

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

HEAD = """ethimon: 1
name: ssm
signals:
  d:  {unit: m,   range: [0, 10]}
  vh: {unit: m/s, range: [0, 3]}
  vr: {unit: m/s, range: [0, 3]}
  tr: {unit: s,   range: [0, 1]}
constants:
  a_stop: {value: 2.5, unit: m/s^2}
  t_s:    {value: 0.3, unit: s}
  neg:    {value: -0.2, unit: m}
"""


def spec_with(require: str, *, head: str = HEAD, extra: str = "") -> ethimon.Spec:
    return ethimon.load_spec_text(f"{head}obligations:\n  - id: ssm\n    require: \"{require}\"\n"
                                  f"    response: stop_2\n{extra}")


SSM = "d >= separation_distance(vh, vr, 0.1, t_s, vr * vr / (2 * a_stop), 0.1, 0.04, 0.01)"


def frame(**kw):
    f = {"d": 5.0, "vh": 1.6, "vr": 0.5, "tr": 0.1, "p_unsafe": 0.0}
    f.update(kw)
    return f


def all_three(spec, frames):
    """Decisions of Monitor, ReferenceMonitor and the offline checker on ``frames`` (all must agree)."""
    m, r = ethimon.Monitor(spec), ReferenceMonitor(spec)
    got = [m.step(f) for f in frames]
    ref = [r.step(f) for f in frames]
    cols = {k: np.array([f[k] for f in frames], dtype=float) for k in frames[0]}
    off = check_trace(spec, cols)
    for t, (a, b) in enumerate(zip(got, ref)):
        assert (a.override, a.response, a.violations, bool(a.faults)) == \
               (b.override, b.response, b.violations, bool(b.faults)), t
        o = off.decision(t)
        assert o == a, (t, o, a)
        assert all((x != x and y != y) or x == y for x, y in zip(o.margins, a.margins)), (t, o.margins, a.margins)
    return got


def test_formula_by_hand():
    # S_h = 1.6 * (0.1 + 0.3) = 0.64, S_r = 0.5 * 0.1 = 0.05, S_s = 0.2, C = 0.1, Z_d + Z_r = 0.05
    assert separation_distance(1.6, 0.5, 0.1, 0.3, 0.2, 0.1, 0.04, 0.01) == pytest.approx(1.04, abs=1e-12)
    assert separation_distance(0, 0, 0, 0, 0, 0, 0, 0) == 0
    assert separation_distance(1, 2, 3, 4, 5, 6, 7, 8) == 1 * 7 + 2 * 3 + 5 + 6 + 7 + 8
    assert [p[0] for p in SEPARATION_PARAMS] == ["v_h", "v_r", "T_r", "T_s", "S_s", "C", "Z_d", "Z_r"]


def test_verdicts_and_margins_by_hand():
    spec = spec_with(SSM)
    # vr = 0.5: S_s = 0.25 / 5 = 0.05, S_p = 0.64 + 0.05 + 0.05 + 0.1 + 0.04 + 0.01 = 0.89
    # vr = 2.0: S_s = 4 / 5 = 0.8, S_p = 0.64 + 0.2 + 0.8 + 0.15 = 1.79
    frames = [frame(d=1.0, vr=0.5), frame(d=0.8, vr=0.5), frame(d=1.5, vr=2.0), frame(d=2.0, vr=2.0),
              frame(d=0.89, vr=0.5, vh=1.6)]
    got = all_three(spec, frames)
    assert [bool(d.violations) for d in got[:4]] == [False, True, True, False]
    assert got[1].override and got[1].violations == ("ssm",) and got[1].response is ethimon.Response.STOP_2
    for d, want in zip(got[:4], (1.0 - 0.89, 0.8 - 0.89, 1.5 - 1.79, 2.0 - 1.79)):
        assert d.margins[0] == pytest.approx(want, abs=1e-12)
    # the margin is d - S_p computed in the formula's order, bit for bit
    sp = 1.6 * (0.1 + 0.3) + 0.5 * 0.1 + 0.5 * 0.5 / (2 * 2.5) + 0.1 + 0.04 + 0.01
    assert got[0].margins[0] == 1.0 - sp
    assert bool(got[4].violations) == (not 0.89 >= sp)


def test_human_speed_raises_the_distance():
    spec = spec_with(SSM)
    still, walking = all_three(spec, [frame(d=0.5, vh=0.0, vr=0.5), frame(d=0.5, vh=1.6, vr=0.5)])
    # vh = 0: S_p = 0.05 + 0.05 + 0.1 + 0.05 = 0.25 < 0.5
    assert not still.override and still.margins[0] == pytest.approx(0.25, abs=1e-12)
    assert walking.override


def test_a_time_that_is_a_signal():
    spec = spec_with("d >= separation_distance(vh, vr, tr, t_s, 0.2, 0.1, 0.04, 0.01)")
    got = all_three(spec, [frame(d=1.0, tr=0.1), frame(d=1.0, tr=0.5)])
    # tr = 0.1: 0.64 + 0.05 + 0.35 = 1.04; tr = 0.5: 1.6 * 0.8 + 0.25 + 0.35 = 1.88
    assert got[0].override and got[0].margins[0] == pytest.approx(-0.04, abs=1e-12)
    assert got[1].margins[0] == pytest.approx(-0.88, abs=1e-12)


def test_all_constant_call_is_folded():
    spec = spec_with("d >= separation_distance(1, 2, 3, 4, 5, 6, 7, 8)")  # 7 + 6 + 26 = 39
    assert ethimon.Monitor(spec).step(frame(d=10)).margins[0] == pytest.approx(10 - 39)
    with pytest.raises(ethimon.SpecError, match="division by zero"):  # folded: a constant 0 divisor
        spec_with("d / separation_distance(0, 0, 0, 0, 0, 0, 0, 0) >= 1")


def test_bounded_response_and_when():
    spec = ethimon.load_spec_text(HEAD + """obligations:
  - id: ssm
    when: "vr > 0.1"
    require: "d >= separation_distance(vh, vr, 0.1, t_s, 0.0, 0.1, 0.04, 0.01)"
    within_cycles: 2
    response: safe_pose
""")
    frames = [frame(d=0.5), frame(d=0.5), frame(d=0.5), frame(d=0.5, vr=0.0), frame(d=0.5, vr=0.0)]
    got = all_three(spec, frames)
    assert [d.override for d in got[:3]] == [False, False, True]


@pytest.mark.parametrize("bad", [dict(vh=-0.1), dict(vr=-1e-9), dict(vh=math.nan)])
def test_a_negative_argument_at_run_time_is_a_fault(bad):
    wide = HEAD.replace("vh: {unit: m/s, range: [0, 3]}", "vh: {unit: m/s, range: [-3, 3]}").replace(
        "vr: {unit: m/s, range: [0, 3]}", "vr: {unit: m/s, range: [-3, 3]}")
    spec = spec_with(SSM, head=wide, extra="on_fault: stop_1\n")
    m, r = ethimon.Monitor(spec), ReferenceMonitor(spec)
    f = frame(**bad)
    a, b = m.step(f), r.step(f)
    assert a.override and a.faults and a.response is ethimon.Response.STOP_1
    assert b.override and b.faults and b.response is ethimon.Response.STOP_1
    if not math.isnan(bad.get("vh", 0.0)):  # NaN is refused at the input boundary already
        assert "separation_distance" in a.faults[0].message
        # an argument computed to a negative value (not an input) is caught the same way
        spec2 = spec_with("d >= separation_distance(vh - 2, vr, 0.1, t_s, 0.2, 0.1, 0.04, 0.01)")
        assert ethimon.Monitor(spec2).step(frame(vh=1.0)).faults
        all_three(spec2, [frame(vh=1.0), frame(vh=2.5), frame(vh=1.9)])


def _err(require: str) -> ethimon.SpecError:
    with pytest.raises(ethimon.SpecError) as exc:
        spec_with(require)
    return exc.value


@pytest.mark.parametrize("require, words, at", [
    ("d >= separation_distance(vh, vr, d, t_s, 0.2, 0.1, 0.04, 0.01)", ("T_r", "[s]", "[m]"), "d, t_s"),
    ("d >= separation_distance(vh, vr, 0.1, t_s, vr, 0.1, 0.04, 0.01)", ("S_s", "[m]", "[m/s]"), "vr, 0.1, 0.04"),
    ("d >= separation_distance(d, vr, 0.1, t_s, 0.2, 0.1, 0.04, 0.01)", ("v_h", "[m/s]"), "d, vr"),
    ("d >= separation_distance(vh, vr, 0.1, t_s, vr * vr / 5, 0.1, 0.04, 0.01)", ("S_s", "m^2/s^2"), "vr * vr"),
    ("d >= separation_distance(vh, vr, 0.1, t_s, 0.2, 0.1, 0.04, t_s)", ("Z_r", "[s]"), "t_s)"),
    ("d >= separation_distance(vh, vr, 0.1, -0.3, 0.2, 0.1, 0.04, 0.01)", ("T_s", "negative constant"), "-0.3"),
    ("d >= separation_distance(vh, vr, 0.1, t_s, 0.2, neg, 0.04, 0.01)", ("C", "always -0.2"), "neg"),
    ("d >= separation_distance(vh, vr, 0.1, t_s, 0.2, 0.1, 0.04 - 0.05, 0.01)", ("Z_d", "negative"), "0.04 -"),
    ("d >= separation_distance(vh, vr, 0.1, t_s, 0.2, 0.1, 0.04)", ("takes 8 arguments, got 7",), "separation"),
    ("d >= separation_distance(vh, d < 1, 0.1, t_s, 0.2, 0.1, 0.04, 0.01)", ("v_r", "boolean"), "d < 1"),
    ("vr >= separation_distance(vh, vr, 0.1, t_s, 0.2, 0.1, 0.04, 0.01)", ("unit mismatch", "[m/s] vs [m]"), "vr >="),
    ("d >= separation_distanc(vh, vr, 0.1, t_s, 0.2, 0.1, 0.04, 0.01)", ("did you mean 'separation_distance'",),
     "separation"),
])
def test_bad_calls_are_located_spec_errors(require, words, at):
    e = _err(require)
    text = str(e)
    for w in words:
        assert w in text, text
    assert e.line == 14  # the require line of spec_with's document
    line = f"    require: \"{require}\""
    assert line[e.column - 1:].startswith(at), (e.column, line)
    if "did you mean" not in text:
        assert e.hint


def test_unit_hint_lists_the_signature():
    e = _err("d >= separation_distance(vh, vr, d, t_s, 0.2, 0.1, 0.04, 0.01)")
    assert "v_h [m/s], v_r [m/s], T_r [s], T_s [s], S_s [m], C [m], Z_d [m], Z_r [m]" in e.hint


def test_reserved_name_and_round_trip():
    with pytest.raises(ethimon.SpecError, match="built-in name"):
        ethimon.load_spec_text("ethimon: 1\nname: t\nsignals:\n  separation_distance: {unit: m}\n"
                               "obligations:\n  - {id: a, require: \"separation_distance > 0\"}\n")
    src = "d >= separation_distance(vh, vr, 0.1, t_s, (vr * vr) / (2 * a_stop), 0.1, 0.04, 0.01)"
    assert to_source(parse_expr(to_source(parse_expr(src)))) == to_source(parse_expr(src))


# -- z3 ------------------------------------------------------------------------------------------

def _verify(spec):
    pytest.importorskip("z3")
    from ethimon.verify import verify_spec
    return verify_spec(spec)


@pytest.mark.slow
def test_verify_linear_and_nonlinear_forms():
    rep = _verify(spec_with("d >= separation_distance(vh, vr, 0.1, t_s, 0.2, 0.1, 0.04, 0.01)"))
    assert rep.finding("ssm.defined").status == "proved"
    # exact: the rule is satisfiable (d = 10 is above any S_p here) and can be violated (d = 0)
    assert rep.finding("lint.vacuous").status == "ok"
    rep = _verify(spec_with("d >= separation_distance(vh, vr, tr, t_s, vr * vr / (2 * a_stop), 0.1, 0.04, 0.01)"))
    assert rep.finding("ssm.defined").status == "proved"


@pytest.mark.slow
def test_verify_refutes_a_range_that_allows_a_negative_speed():
    wide = HEAD.replace("vh: {unit: m/s, range: [0, 3]}", "vh: {unit: m/s, range: [-3, 3]}")
    rep = _verify(spec_with(SSM, head=wide))
    f = rep.finding("ssm.defined")
    assert f.status == "refuted" and f.counterexample.confirmed
    assert f.counterexample.frames[-1]["vh"] < 0
    assert "separation_distance" in f.message


# -- the shipped cell ----------------------------------------------------------------------------

def test_cobot_cell_uses_the_function_and_matches_the_old_formula():
    spec = ethimon.load_spec(os.path.join(ROOT, "specs", "cobot_cell.yaml"))
    ob = next(o for o in spec.obligations if o.id == "separation")
    assert "separation_distance(" in ob.require
    c = {k: v.value for k, v in spec.constants.items()}
    assert (c["z_d"], c["z_r"]) == (0.04, 0.01)  # the former combined uncertainty Z = 0.05 m, split
    rng = np.random.default_rng(7)
    v = rng.uniform(0.0, 3.0, 400)
    dist = rng.uniform(0.0, 3.0, 400)
    cols = {"human_distance": dist, "ee_speed": v, "contact_force": np.zeros(400),
            "joint_speed_max": np.zeros(400), "p_unsafe": np.zeros(400)}
    res = check_trace(spec, cols)
    m = ethimon.Monitor(spec)
    for t, row in enumerate(iter_rows(spec, cols)):
        d = m.step(row)
        old = 1.6 * (0.1 + 0.3) + v[t] * 0.1 + v[t] * v[t] / (2 * 2.5) + 0.1 + 0.05
        assert d.margins[0] == pytest.approx(dist[t] - old, abs=1e-15)  # differs by at most an ulp
        assert ("separation" in d.violations) == (dist[t] < old)
        assert res.decision(t) == d
