"""Property: a spec whose windows are in seconds means the same at 50 and 100 Hz (issue 34 item 2).

For random windows (whole at both rates: multiples of 20 ms) and random piecewise-constant inputs
changing on the 20 ms grid (a sample at the instant of a change still reads the old value, so the
sample that ends each 20 ms piece reads that piece at both rates), the same rules are violated at
every instant both rates sample (``held``, ``once``, ``since``, ``within_s``): a window of T s holds
the same T s of input at 50 Hz and at 100 Hz.
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


def _violations(text: str, rate: int, pieces: list[tuple[bool, bool]]) -> list[tuple[str, ...]]:
    """The violations at each 20 ms instant: piece k is read by the cycles in (20(k-1), 20k] ms (the
    100 Hz run starts 10 ms before the 50 Hz one, so that both have read piece 0 whole)."""
    mon = Monitor(load_spec_text(text))
    per = rate // 50
    out = []
    for k, (x, y) in enumerate(pieces):
        for _ in range(per):
            v = mon.step({"x": x, "y": y, "p_unsafe": 0.0}).violations
        out.append(v)  # the cycle at 20k ms
    return out


@pytest.mark.slow
@given(w=st.lists(st.integers(1, 12), min_size=4, max_size=4),
       trace=st.lists(st.tuples(st.booleans(), st.booleans(), st.integers(1, 8)), min_size=1, max_size=12))
def test_windows_in_seconds_mean_the_same_at_50_and_100_hz(w, trace):
    pieces = [(x, y) for x, y, steps in trace for _ in range(steps)]  # each 20 ms
    secs = [f"{k * GRID:.2f}" for k in w]
    secs[3] = f"{(w[3] - 1) * GRID:.2f}"  # within_s may be 0
    runs = {rate: _violations(SPEC.format(rate=rate, w1=secs[0], w2=secs[1], w3=secs[2], w4=secs[3]), rate, pieces)
            for rate in (50, 100)}
    assert runs[50] == runs[100]
