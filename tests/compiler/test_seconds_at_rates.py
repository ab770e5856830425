"""A spec written in seconds means the same at 50 and 100 Hz, or is refused (issue 34 item 2, done-when).

One scenario, given in time (piecewise constant inputs that change on a 20 ms grid; a sample at the
instant of a change still reads the old value, so the sample at the end of each 20 ms piece reads that
piece at both rates), is sampled at 50 Hz and at 100 Hz and stepped through the same spec compiled at
each rate. At every instant both rates sample (each 20 ms) the same rules are violated (a window
of T s holds the same T s of input at both rates), and the override episodes, with their response
and latched rules, start and end within one 50 Hz cycle of each other (a release hold of T s counts
the 100 Hz cycles in between too, whose windows straddle the pieces). A time that is not a whole number of cycles at the spec's rate is refused instead; a
mapping at another rate is refused too.
"""

from __future__ import annotations

import pytest

from ethimon import Monitor
from ethimon._api import load_spec_text
from ethimon.errors import SpecError
from ethimon.io import check_against_spec, load_mapping_text

SPEC = """\
ethimon: 1
name: cell_in_seconds
rate_hz: {rate}
signals:
  d: {{unit: m, range: [0, 10]}}
  v: {{unit: m/s, range: [0, 3]}}
  f: {{unit: N, range: [0, 1000]}}
constants:
  t_recent: {{value: 0.2, unit: s}}
risk: {{release: {{mode: auto, hysteresis: 0.05, hold_s: 0.1}}}}
on_fault: stop_1
obligations:
  - id: slow_near_human
    when: d < 1.5
    require: v <= 0.25
    within_s: 0.06
  - id: clamping
    require: "not held(f > 65, 0.1 s)"
    response: stop_2
    release: {{mode: auto, hold_s: 0.2}}
  - id: recent_fast
    require: "not (once(v > 2.0, t_recent) and d < 0.5)"
  - id: calm
    require: "since(d > 0.8, v < 0.1, 0.5 s) or d > 2"
"""

# (from time s, inputs from then on): every change on the 20 ms grid of the slower rate
TIMELINE = [
    (0.00, {"d": 4.0, "v": 0.05, "f": 0.0}),
    (0.50, {"d": 1.0, "v": 0.5}),          # near a person too fast: slow_near_human after 0.06 s
    (0.70, {"v": 0.2}),
    (1.00, {"f": 80.0}),                    # held for 0.14 s: clamping after 0.1 s
    (1.14, {"f": 10.0}),
    (1.40, {"v": 2.5}),                     # fast, then a person close within 0.2 s
    (1.50, {"v": 0.05, "d": 0.4}),
    (1.80, {"d": 1.2}),
    (2.20, {"d": 4.0}),
]
DURATION = 3.0


def _inputs(t: float) -> dict:
    cur: dict = {"p_unsafe": 0.0}
    for at, values in TIMELINE:
        if at == 0 or t > at + 1e-9:  # the value over (at, next at]
            cur.update(values)
    return cur


def _run(rate: int) -> list:
    mon = Monitor(load_spec_text(SPEC.format(rate=rate)))
    return [mon.step(_inputs(k / rate)) for k in range(int(DURATION * rate))]


def _episodes(flags: list[bool], rate: int) -> list[tuple[float, float]]:
    """Maximal runs of True as (start s, end s), the end the time of the first False cycle."""
    out, start = [], None
    for k, f in enumerate(flags + [False]):
        if f and start is None:
            start = k
        elif not f and start is not None:
            out.append((start / rate, k / rate))
            start = None
    return out


def _same_in_seconds(a: list, b: list, tol: float) -> bool:
    return len(a) == len(b) and all(abs(x0 - y0) <= tol + 1e-9 and abs(x1 - y1) <= tol + 1e-9
                                    for (x0, x1), (y0, y1) in zip(a, b))


def test_a_spec_in_seconds_gives_the_same_verdicts_at_50_and_100_hz():
    runs = {rate: _run(rate) for rate in (50, 100)}
    fine = runs[100][::2]  # the instants both rates sample
    assert len(fine) == len(runs[50])
    for d50, d100 in zip(runs[50], fine):
        assert d50.violations == d100.violations, (d50, d100)
    # ... and as episodes in seconds, the override and its latches too
    tol = 1 / 50
    for rule in ("slow_near_human", "clamping", "recent_fast", "calm"):
        eps = {rate: _episodes([rule in d.violations for d in ds], rate) for rate, ds in runs.items()}
        assert eps[50], f"{rule} never fires: the scenario tests nothing"
        assert _same_in_seconds(eps[50], eps[100], tol), (rule, eps)
    over = {rate: _episodes([d.override for d in ds], rate) for rate, ds in runs.items()}
    assert len(over[50]) >= 2 and _same_in_seconds(over[50], over[100], tol), over
    for response in ("safe_pose", "stop_2"):
        eps = {rate: _episodes([d.response.value == response for d in ds], rate) for rate, ds in runs.items()}
        assert eps[50] and _same_in_seconds(eps[50], eps[100], tol), (response, eps)


def test_counted_in_cycles_the_same_spec_changes_meaning_with_the_rate():
    """What the seconds fix: the clamping window written as 5 cycles is 0.1 s at 50 Hz, 0.05 s at 100 Hz."""
    text = SPEC.replace("0.1 s)", "5)")
    at = {}
    for rate in (50, 100):
        mon = Monitor(load_spec_text(text.format(rate=rate)))
        at[rate] = next(k / rate for k in range(int(DURATION * rate))
                        if "clamping" in mon.step(_inputs(k / rate)).violations)
    assert at[100] < at[50] - 0.03


@pytest.mark.parametrize("rate", [30, 40, 60])
def test_at_a_rate_where_a_time_is_not_whole_cycles_the_spec_is_refused(rate):
    with pytest.raises(SpecError) as info:
        load_spec_text(SPEC.format(rate=rate))
    assert "not a whole number of cycles" in str(info.value) and info.value.line is not None


MAPPING = """\
ethimon: 1
rate_hz: {rate}
max_age_s: 0.1
signals:
  d: {{topic: /d, field: data}}
  v: {{topic: /v, field: data}}
  f: {{topic: /f, field: data}}
  p_unsafe: {{topic: /p, field: data}}
"""


def test_a_mapping_at_another_rate_is_refused():
    spec = load_spec_text(SPEC.format(rate=100))
    check_against_spec(load_mapping_text(MAPPING.format(rate=100)), spec)
    check_against_spec(load_mapping_text(MAPPING.format(rate="100.0")), spec)
    with pytest.raises(SpecError) as info:
        check_against_spec(load_mapping_text(MAPPING.format(rate=50), "map.yaml"), spec)
    err = info.value
    assert (err.path, err.line) == ("map.yaml", 2)
    assert "rate_hz 50" in str(err) and "rate_hz 100" in str(err) and "rate_hz: 100" in err.hint


def test_a_spec_without_rate_hz_takes_a_mapping_at_any_rate():
    spec = load_spec_text(SPEC.format(rate=100).replace("rate_hz: 100\n", "")
                          .replace("0.1 s", "10").replace("0.5 s", "50").replace("within_s: 0.06", "within_cycles: 6")
                          .replace("hold_s: 0.1", "hold_cycles: 10").replace("hold_s: 0.2", "hold_cycles: 20")
                          .replace("{value: 0.2, unit: s}", "20"))
    for rate in (50, 100, 1000):
        check_against_spec(load_mapping_text(MAPPING.format(rate=rate)), spec)
