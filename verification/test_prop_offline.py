"""Vectorised offline checker ≡ ``Monitor.step`` on random specs and random traces.

``ethimon.offline.check_trace`` evaluates a whole trace column by column; these
properties step a :class:`~ethimon.Monitor` over the same cycles and require
the same :class:`~ethimon.Decision` at every cycle (override, response,
violations, R_e, latched flag, fault reasons) and the same margins, bit for bit
(NaN where the monitor has NaN). Three kinds of trace:

* the equivalence suite's frames (every bad-input type: NaN, wrong types,
  objects that lie about their class, bad ``p``), as object columns;
* numeric columns as recorded logs have them (float and bool arrays with NaN,
  infinities, out-of-range values and masked entries; ``p`` as a 2-d array);
* long traces through long windows and long bounded responses (up to 60
  cycles), where the scans and the window maxima are exercised well past the
  window length.
"""

from __future__ import annotations

import numpy as np
import yaml
import pytest
from hypothesis import given, note
from hypothesis import strategies as st

import ethimon
from ethimon.offline import check_trace, iter_rows
from ethimon.language._expr import to_source
from ethimon_strategies import BOOL_SIGNALS, NUM_SIGNALS, RESPONSES, bool_expr, frame, specs


def object_columns(frames: list[dict]) -> dict[str, np.ndarray]:
    """The frames as object columns: each value kept as it is, ``None`` where a key is absent."""
    keys = sorted({k for f in frames for k in f})
    cols = {}
    for k in keys:
        col = np.empty(len(frames), dtype=object)
        for i, f in enumerate(frames):
            col[i] = f.get(k)
        cols[k] = col
    return cols


def _same(x: float, y: float) -> bool:
    return (x != x and y != y) or x == y


def assert_equal_to_monitor(spec, columns, frames, *, margins: bool = True) -> None:
    res = check_trace(spec, columns, length=len(frames), margins=margins)
    m = ethimon.Monitor(spec, margins=margins)
    for t, f in enumerate(frames):
        a, b = m.step(f), res.decision(t)
        note(f"cycle {t}: inputs={f!r}\n  monitor={a!r} {a.margins}\n  offline={b!r} {b.margins}")
        assert a == b
        assert res.fault[t] == bool(a.faults)
        assert len(a.margins) == len(b.margins)
        assert all(_same(x, y) for x, y in zip(a.margins, b.margins))
    assert res.fallback_cycles == 0 or res.fallback_reason
    summary = res.summary()
    for k, oid in enumerate(res.obligation_ids):
        hits = np.flatnonzero(res.violated[:, k])
        assert summary[oid]["cycles_violated"] == len(hits)
        assert summary[oid]["first_violation"] == (int(hits[0]) if len(hits) else None)


@pytest.mark.slow
@given(st.data())
def test_offline_equals_monitor_on_random_specs(data):
    gen = data.draw(specs())
    note(gen.text)
    p_bad = data.draw(st.sampled_from((0.0, 0.05, 0.3)))
    frames = data.draw(st.lists(frame(gen.spec, p_bad=p_bad), min_size=1, max_size=30))
    assert_equal_to_monitor(gen.spec, object_columns(frames), frames, margins=data.draw(st.booleans()))


# -- numeric columns ---------------------------------------------------------------------------

def numeric_columns(spec, n: int, seed: int, p_bad: float, risk_kind: str) -> dict[str, np.ndarray]:
    """Columns as a recorded log has them: held values with changes, some NaN/inf/out-of-range/masked."""
    rng = np.random.default_rng(seed)
    hold = rng.random(n) < 0.6  # keep the previous value: conditions persist across windows

    def held(x: np.ndarray) -> np.ndarray:
        keep = np.where(hold, -1, np.arange(n))
        keep[0] = 0
        return x[np.maximum.accumulate(keep)]

    def spoil(x: np.ndarray, bad_values) -> np.ndarray:
        x = x.astype(np.float64)
        bad = rng.random(n) < p_bad
        x[bad] = rng.choice(bad_values, bad.sum())
        return x

    def maybe_mask(x: np.ndarray) -> np.ndarray:
        if rng.random() < 0.3:
            mask = rng.random(len(x)) < p_bad
            return np.ma.masked_array(x, np.broadcast_to(mask.reshape((-1,) + (1,) * (x.ndim - 1)), x.shape))
        return x

    cols = {}
    for name, sig in spec.signals.items():
        if sig.type == "bool":
            b = held(rng.random(n) < 0.5)
            if rng.random() < 0.5:
                cols[name] = maybe_mask(b)
            else:
                cols[name] = maybe_mask(spoil(b, [0.5, np.nan, 2.0]))
        else:
            lo, hi = sig.range
            special = np.array([lo, hi, 0.0 if lo <= 0 <= hi else lo, (lo + hi) / 2, 1.0 if lo <= 1 <= hi else hi])
            x = np.where(rng.random(n) < 0.5, rng.choice(special, n), rng.uniform(lo, hi, n))
            cols[name] = maybe_mask(spoil(held(x), [np.nan, np.inf, -np.inf, hi + 1.0, lo - 1.0]))
    q = held(np.where(rng.random(n) < 0.5, rng.choice([0.0, 0.5, 1.0, 0.55, 0.7, 0.9], n), rng.random(n)))
    if risk_kind == "p":
        cols["p"] = maybe_mask(np.stack([1.0 - q, spoil(q, [np.nan, 1.5, -0.1])], axis=1))
    elif risk_kind == "risk":
        cols["risk"] = maybe_mask(spoil(q, [np.nan, -0.5, 1.5]))
        if rng.random() < 0.5:  # where risk is missing, p_unsafe is read
            cols["p_unsafe"] = q[::-1].copy()
    else:
        cols["p_unsafe"] = maybe_mask(spoil(q, [np.nan, 1.5, -0.1]))
    if spec.risk.max_age_s is not None:
        cols["risk_age_s"] = maybe_mask(spoil(rng.uniform(0, spec.risk.max_age_s, n), [np.nan, 1.0, -1.0]))
    return cols


@pytest.mark.slow
@given(st.data())
def test_offline_equals_monitor_on_numeric_columns(data):
    gen = data.draw(specs())
    note(gen.text)
    n = data.draw(st.integers(1, 120))
    cols = numeric_columns(gen.spec, n, data.draw(st.integers(0, 2 ** 32 - 1)),
                           data.draw(st.sampled_from((0.0, 0.02, 0.2))),
                           data.draw(st.sampled_from(("p_unsafe", "risk", "p"))))
    frames = list(iter_rows(gen.spec, cols))
    assert len(frames) == n
    assert_equal_to_monitor(gen.spec, cols, frames)


# -- long windows --------------------------------------------------------------------------------

BIG_WINDOWS = (1, 2, 5, 13, 30, 60)


@st.composite
def long_window_specs(draw):
    """Specs whose temporal operators and bounded responses span up to 60 cycles."""
    atom = bool_expr(1)
    obligations = []
    for i in range(draw(st.integers(1, 4))):
        a, b = to_source(draw(atom)), to_source(draw(atom))
        n = draw(st.sampled_from(BIG_WINDOWS))
        form = draw(st.sampled_from(("held", "once", "since", "since_unbounded", "within", "nested")))
        ob = {"id": f"ob{i}", "response": draw(st.sampled_from(RESPONSES))}
        if form == "held":
            ob["require"] = f"not held({a}, {n})"
        elif form == "once":
            ob["require"] = f"once({a}, {n}) implies {b}"
        elif form == "since":
            ob["require"] = f"since({a}, {b}, {n}) or {to_source(draw(atom))}"
        elif form == "since_unbounded":
            ob["require"] = f"not since({a}, {b})"
        elif form == "nested":
            m = draw(st.sampled_from(BIG_WINDOWS))
            ob["require"] = f"not held(once({a}, {n}) or prev({b}), {m})"
        else:
            ob["when"] = a
            ob["require"] = b
            ob["within_cycles"] = n
        if form != "within" and draw(st.booleans()):
            ob["when"] = to_source(draw(atom))
        obligations.append(ob)
    signals = {k: {"range": [lo, hi]} for k, (lo, hi) in NUM_SIGNALS.items()}
    signals.update({k: {"type": "bool"} for k in BOOL_SIGNALS})
    doc = {"ethimon": 1, "name": "long_windows", "signals": signals,
           "risk": {"threshold": draw(st.sampled_from((0.4, 0.6))),
                    "release": {"mode": "auto", "hold_cycles": draw(st.sampled_from((1, 3, 20)))}},
           "on_fault": draw(st.sampled_from(RESPONSES)), "obligations": obligations}
    text = yaml.safe_dump(doc, sort_keys=False)
    return text, ethimon.load_spec_text(text, "<long_windows>")


@given(long_window_specs(), st.integers(100, 400), st.integers(0, 2 ** 32 - 1),
       st.sampled_from((0.0, 0.003, 0.02)))
@pytest.mark.slow
def test_offline_equals_monitor_on_long_windows(spec_and_text, n, seed, p_bad):
    text, spec = spec_and_text
    note(text)
    cols = numeric_columns(spec, n, seed, p_bad, "p_unsafe")
    assert_equal_to_monitor(spec, cols, list(iter_rows(spec, cols)))


# -- expressions that raise ----------------------------------------------------------------------

RAISING = ("x / y", "sqrt(x)", "x / prev(y, 1)", "1 / (y - prev(y))", "sqrt(x - prev(x))", "z / min(y, x)")


@st.composite
def raising_specs(draw):
    """Specs whose expressions divide by zero or take the root of a negative number on some cycles.

    The monitor turns such a cycle into a fault and clears its history; some of these raise only
    with some history (``prev``), so the offline checker's re-evaluation after a fault, and its
    fallback to ``Monitor.step``, are both exercised.
    """
    atom = bool_expr(1)
    obligations = []
    for i in range(draw(st.integers(1, 3))):
        num = draw(st.sampled_from(RAISING))
        cmp = f"{num} {draw(st.sampled_from(('<', '>=', '!=')))} {draw(st.sampled_from(('0.5', '2', 'x')))}"
        guard = to_source(draw(atom))
        form = draw(st.sampled_from(("plain", "guarded", "held", "once", "since", "within", "prev")))
        n = draw(st.sampled_from((1, 2, 3, 7)))
        ob = {"id": f"ob{i}", "response": draw(st.sampled_from(RESPONSES))}
        if form == "plain":
            ob["require"] = cmp
        elif form == "guarded":  # the division is skipped where the guard decides
            ob["require"] = f"{guard} {draw(st.sampled_from(('or', 'and', 'implies')))} {cmp}"
        elif form == "held":
            ob["require"] = f"not held({cmp}, {n})"
        elif form == "once":
            ob["require"] = f"once({cmp}, {n}) implies {guard}"
        elif form == "since":
            ob["require"] = f"not since({guard}, {cmp}, {n})"
        elif form == "prev":
            ob["require"] = f"prev({cmp}) or {guard}"
        else:
            ob["when"] = guard
            ob["require"] = cmp
            ob["within_cycles"] = n
        obligations.append(ob)
    signals = {k: {"range": [lo, hi]} for k, (lo, hi) in NUM_SIGNALS.items()}
    signals.update({k: {"type": "bool"} for k in BOOL_SIGNALS})
    doc = {"ethimon": 1, "name": "raising", "signals": signals,
           "risk": {"release": {"mode": "auto", "hold_cycles": draw(st.sampled_from((1, 2, 5)))}},
           "on_fault": draw(st.sampled_from(RESPONSES)), "obligations": obligations}
    text = yaml.safe_dump(doc, sort_keys=False)
    return text, ethimon.load_spec_text(text, "<raising>")


@pytest.mark.slow
@given(raising_specs(), st.integers(1, 150), st.integers(0, 2 ** 32 - 1), st.sampled_from((0.0, 0.02)))
def test_offline_equals_monitor_where_expressions_raise(spec_and_text, n, seed, p_bad):
    text, spec = spec_and_text
    note(text)
    cols = numeric_columns(spec, n, seed, p_bad, "p_unsafe")
    assert_equal_to_monitor(spec, cols, list(iter_rows(spec, cols)))


@pytest.mark.slow
@given(st.data())
def test_offline_step_method_equals_vector(data):
    gen = data.draw(specs(max_obligations=2, depth=2))
    cols = numeric_columns(gen.spec, data.draw(st.integers(1, 60)), data.draw(st.integers(0, 2 ** 32 - 1)), 0.05,
                           "p_unsafe")
    a = check_trace(gen.spec, cols)
    b = check_trace(gen.spec, cols, method="step")
    for name in ("override", "response", "latched", "fault", "internal_error", "violated", "risk_violated"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
    assert np.array_equal(a.margins, b.margins, equal_nan=True)
    assert np.array_equal(a.risk, b.risk, equal_nan=True)

