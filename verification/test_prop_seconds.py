"""Property: a spec whose windows are in seconds means the same at 50 and 100 Hz (issue 34 item 2).

For random windows (whole at both rates: multiples of 20 ms) and random piecewise-constant inputs
changing on the 20 ms grid, each rule's violation episodes at 50 Hz and at 100 Hz are as many and
start and end within one 50 Hz cycle of each other (``held``, ``once``, ``since`` and ``within_s``,
one temporal level: the two rates sample the same T seconds at instants up to one fine cycle apart).
"""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from ethimon import Monitor
from ethimon._api import load_spec_text

SPEC = """\
ethimon: 1
name: prop_seconds
rate_hz: {rate}
signals: {{x: {{type: bool}}, y: {{type: bool}}}}
obligations:
  - id: h
    require: "not held(x, {w1} s)"
  - id: o
    require: "not once(x, {w2} s) or y"
  - id: s
    require: "since(not x, y, {w3} s) or x"
  - id: w
    when: x
    require: y
    within_s: {w4}
"""
GRID = 0.02
RULES = ("h", "o", "s", "w")


def _episodes(flags: list[bool], rate: int) -> list[tuple[float, float]]:
    out, start = [], None
    for k, f in enumerate(flags + [False]):
        if f and start is None:
            start = k
        elif not f and start is not None:
            out.append((start / rate, k / rate))
            start = None
    return out


def _violations(text: str, rate: int, xs: list[bool], ys: list[bool]) -> dict[str, list]:
    mon = Monitor(load_spec_text(text))
    per = rate // 50  # cycles per 20 ms step of the trace
    flags: dict[str, list[bool]] = {r: [] for r in RULES}
    for x, y in zip(xs, ys):
        for _ in range(per):
            v = mon.step({"x": x, "y": y, "p_unsafe": 0.0}).violations
            for r in RULES:
                flags[r].append(r in v)
    return {r: _episodes(f, rate) for r, f in flags.items()}


@pytest.mark.slow
@given(w=st.lists(st.integers(1, 12), min_size=4, max_size=4),
       trace=st.lists(st.tuples(st.booleans(), st.booleans(), st.integers(1, 8)), min_size=1, max_size=12))
def test_windows_in_seconds_mean_the_same_at_50_and_100_hz(w, trace):
    xs, ys = [], []
    for x, y, steps in trace:  # each piece lasts steps * 20 ms
        xs += [x] * steps
        ys += [y] * steps
    secs = [f"{k * GRID:.2f}" for k in w]
    secs[3] = f"{(w[3] - 1) * GRID:.2f}"  # within_s may be 0
    runs = {rate: _violations(SPEC.format(rate=rate, w1=secs[0], w2=secs[1], w3=secs[2], w4=secs[3]), rate, xs, ys)
            for rate in (50, 100)}
    for r in RULES:
        a, b = runs[50][r], runs[100][r]
        assert len(a) == len(b), (r, a, b)
        for (a0, a1), (b0, b1) in zip(a, b):
            assert abs(a0 - b0) <= GRID + 1e-9 and abs(a1 - b1) <= GRID + 1e-9, (r, a, b)
