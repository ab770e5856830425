"""Time in seconds (issue 34 item 2): a spec states its ``rate_hz``; windows (``held(e, 0.5 s)``, a
constant in s), ``within_s`` and ``hold_s`` become whole cycles at it, or the spec is refused with a
located error; a mapping at another rate is refused; cycle counts keep working."""

from __future__ import annotations

import pytest

from ethimon import Monitor
from ethimon._api import load_spec_text
from ethimon.compiler import plan_of
from ethimon.errors import SpecError
from ethimon.language._expr import Num, Seconds, parse_expr, to_source
from ethimon.language import seconds_to_cycles

BASE = """\
ethimon: 1
name: timed
rate_hz: 100
signals:
  d: {unit: m, range: [0, 10]}
  v: {unit: m/s, range: [0, 3]}
constants:
  t_grace: {value: 0.04, unit: s}
obligations:
  - id: slow
    when: d < 1.5
    require: v <= 0.25
    within_s: 0.06
  - id: dwell
    require: "not held(d < 0.3, 0.1 s)"
    release: {mode: auto, hold_s: 0.2}
  - id: grace
    require: "once(v < 0.1, t_grace) or d > 0.5"
"""


def _windows(plan) -> list:
    """Every temporal node's window in cycles, read from its annotation."""
    return [n.ann.window for n in plan.temporal]


def _seconds(plan) -> list:
    """The seconds the author wrote for each window in time (the annotation's, for printers)."""
    return [n.ann.seconds for n in plan.temporal if n.ann.seconds is not None]


def _refused(text: str) -> SpecError:
    with pytest.raises(SpecError) as info:
        load_spec_text(text)
    return info.value


def test_seconds_literal_parses_and_prints_as_written():
    for src in ("held(x, 0.5 s)", "held(x, 0.5s)", "held(x,0.5   s)"):
        node = parse_expr(src)
        w = node.args[1]
        assert isinstance(w, Seconds) and isinstance(w, Num) and w.value == 0.5
        assert to_source(node) == "held(x, 0.5 s)"
    neg = parse_expr("once(x, -2 s)").args[1]
    assert isinstance(neg, Seconds) and neg.value == -2.0
    assert type(parse_expr("held(x, 5)").args[1]) is Num  # a count stays a count


def test_seconds_become_whole_cycles_at_the_rate():
    spec = load_spec_text(BASE)
    plan = plan_of(spec)
    assert plan.rate_hz == 100.0 and spec.rate_hz == 100.0
    assert sorted(_windows(plan)) == [4, 10]  # t_grace 0.04 s, 0.1 s
    assert sorted(_seconds(plan)) == [0.04, 0.1]  # what the author wrote, for printers
    slow, dwell, _ = spec.obligations
    assert (slow.within_cycles, slow.within_s) == (6, 0.06)
    assert spec.obligation_release(dwell) == ("auto", 20)
    assert plan.obligations[0].within_cycles == 6 and plan.obligations[1].release_hold == 20
    at50 = load_spec_text(BASE.replace("rate_hz: 100", "rate_hz: 50"))
    assert sorted(_windows(plan_of(at50))) == [2, 5]
    assert at50.obligations[0].within_cycles == 3 and at50.obligation_release(at50.obligations[1])[1] == 10


def test_float_noise_is_tolerated():
    assert seconds_to_cycles(0.05, 100.0, "w") == 5
    assert seconds_to_cycles(0.07, 100.0, "w") == 7  # 7.000000000000001
    assert seconds_to_cycles(0.3, 10.0, "w") == 3  # 2.9999999999999996
    assert seconds_to_cycles(1 / 3, 30.0, "w") == 10


@pytest.mark.parametrize("old, new, where, words", [
    ("0.1 s)", "0.105 s)", (15, 33), "the window of held() is 0.105 s, 10.5 cycles at rate_hz 100"),
    ("within_s: 0.06", "within_s: 0.065", (13, 15), "within_s of obligation 'slow' is 0.065 s, 6.5 cycles"),
    ("hold_s: 0.2}", "hold_s: 0.205}", (16, 35), "the release hold_s of obligation 'dwell' is 0.205 s"),
    ("value: 0.04,", "value: 0.045,", (18, 29), "the window t_grace of once() is 0.045 s"),
    ("rate_hz: 100", "rate_hz: 30", (13, 15), "0.06 s, 1.8 cycles at rate_hz 30"),
])
def test_a_time_that_is_not_whole_cycles_is_refused_where_it_is_written(old, new, where, words):
    err = _refused(BASE.replace(old, new))
    assert (err.line, err.column) == where, str(err)
    assert words in str(err) and "not a whole number of cycles" in str(err)
    assert err.hint and "write" in err.hint  # the nearest whole times


def test_the_hint_names_the_nearest_whole_times():
    err = _refused(BASE.replace("0.1 s)", "0.105 s)"))
    assert "0.1 s (10 cycles) or 0.11 s (11 cycles)" in err.hint


@pytest.mark.parametrize("drop, where", [
    ((), (12, 15)),  # within_s, the first time the model resolves
    (("    within_s: 0.06\n",), (14, 35)),  # then hold_s
    (("    within_s: 0.06\n", "    release: {mode: auto, hold_s: 0.2}\n"), (13, 33)),  # then the windows
])
def test_seconds_without_rate_hz_say_state_rate_hz(drop, where):
    text = BASE.replace("rate_hz: 100\n", "")
    for line in drop:
        text = text.replace(line, "")
    err = _refused(text)
    assert "states no rate_hz" in str(err) and "state rate_hz" in err.hint
    assert (err.line, err.column) == where, str(err)


def test_a_window_in_seconds_without_rate_hz_is_located_in_the_expression():
    text = ("ethimon: 1\nname: t\nsignals: {d: {unit: m}}\nobligations:\n"
            "  - id: a\n    require: \"held(d > 0.5, 0.05 s)\"\n")
    err = _refused(text)
    assert (err.line, err.column) == (6, 29) and "states no rate_hz" in str(err)


@pytest.mark.parametrize("require, words", [
    ("d > 1 s", "only a window of held(), once() or since()"),
    ("held(d > 0.5, 0 s)", "makes no sense"),
    ("held(d > 0.5, -0.5 s)", "makes no sense"),
    ("held(d > 0.5, 0.000000000001 s)", "less than one cycle"),
    ("held(d > 0.5, 20000 s)", "too long"),
])
def test_seconds_where_they_cannot_be(require, words):
    text = BASE.replace('"not held(d < 0.3, 0.1 s)"', f'"{require}"')
    assert words in str(_refused(text))


def test_within_cycles_and_within_s_must_agree():
    both = BASE.replace("within_s: 0.06", "within_s: 0.06\n    within_cycles: 5")
    assert "give one of within_cycles and within_s" in _refused(both).hint
    same = load_spec_text(BASE.replace("within_s: 0.06", "within_s: 0.06\n    within_cycles: 6"))
    assert same.obligations[0].within_cycles == 6


def test_a_resolved_spec_round_trips_through_its_dump():
    from ethimon.language import Spec
    spec = load_spec_text(BASE)
    again = Spec.model_validate(spec.model_dump(by_alias=True))
    assert again.model_dump() == spec.model_dump()


def test_cycle_counts_keep_working_without_rate_hz():
    text = ("ethimon: 1\nname: t\nsignals: {d: {unit: m}}\nconstants: {n: 3}\nobligations:\n"
            "  - id: a\n    require: \"held(d > 0.5, 5) or once(d > 1, n)\"\n    within_cycles: 2\n")
    spec = load_spec_text(text)
    assert spec.rate_hz is None and sorted(_windows(plan_of(spec))) == [3, 5]
    assert _seconds(plan_of(spec)) == []
    # ... and with a rate stated too: counts are counts
    spec = load_spec_text(text.replace("name: t\n", "name: t\nrate_hz: 50\n"))
    assert sorted(_windows(plan_of(spec))) == [3, 5] and spec.obligations[0].within_cycles == 2


def test_rate_hz_is_checked():
    for bad in ("0", "-5", "true", "'100'", "1e9"):
        err = _refused(BASE.replace("rate_hz: 100", f"rate_hz: {bad}"))
        assert err.line == 3, str(err)


def test_a_monitor_runs_a_spec_in_seconds():
    m = Monitor(load_spec_text(BASE))
    for _ in range(9):
        assert not m.step({"d": 0.2, "v": 0.05, "p_unsafe": 0.0}).override
    assert m.step({"d": 0.2, "v": 0.05, "p_unsafe": 0.0}).violations == ("dwell",)  # 10 cycles = 0.1 s


def test_printers_give_the_time_beside_the_cycles():
    assert plan_of(load_spec_text(BASE)).cycles(6) == "6 cycles (0.06 s at 100 Hz)"
    assert plan_of(load_spec_text(BASE.replace("rate_hz: 100", "rate_hz: 50"))).cycles(1) == "1 cycle (0.02 s at 50 Hz)"
    text = "ethimon: 1\nname: t\nsignals: {d: {unit: m}}\nobligations: [{id: a, require: d > 1}]\n"
    assert plan_of(load_spec_text(text)).cycles(3) == "3 cycles"  # no rate stated: cycles only


def test_the_example_in_seconds_means_what_the_shipped_spec_in_cycles_means():
    from pathlib import Path

    from ethimon import load_spec
    root = Path(__file__).resolve().parents[2]
    secs, cycles = load_spec(root / "examples/specs-in-seconds/cobot_cell.yaml"), load_spec(root / "specs/cobot_cell.yaml")
    assert secs.rate_hz == 100.0 and cycles.rate_hz is None
    ps, pc = plan_of(secs), plan_of(cycles)
    assert sorted(_windows(ps), key=str) == sorted(_windows(pc), key=str)
    assert [o.within_cycles for o in ps.obligations] == [o.within_cycles for o in pc.obligations]
    assert ps.rules() == pc.rules()
    assert [o.require_text for o in ps.obligations] != [o.require_text for o in pc.obligations]  # written in s
