"""The tiers (confirm band, judge) on random specs: Monitor ≡ ReferenceMonitor ≡ offline check_trace,
and the tier rules hold on every cycle of random traces (issue 26, issue 19 item 5).

Specs come from the suite's generator with a confirm band and/or a judge added; traces add the
``judge`` input (a valid p, no judgement, or an unusable value) and ``task_id`` (which confirmations
are bound to), with random ``acknowledge()`` calls.
"""

from __future__ import annotations

import math

import numpy as np
import yaml
import pytest
from hypothesis import given, note
from hypothesis import strategies as st

import ethimon
from ethimon.offline import check_trace
from ethimon.testing import ReferenceMonitor
from ethimon_strategies import decision_key, ops, spec_doc

JUDGE_VALUES = (0.0, 0.1, 0.19, 0.2, 0.5, 0.79, 0.8, 0.95, 1.0)


@st.composite
def tier_specs(draw):
    doc = spec_doc(draw, max_obligations=2, depth=2)
    tau = doc["risk"]["threshold"]
    band, judge = draw(st.sampled_from(((True, True), (True, False), (False, True))))
    if band:
        doc["risk"]["confirm_threshold"] = draw(st.sampled_from((0.0, round(tau / 2, 3), round(tau - 0.05, 3))))
    if judge:
        lo = draw(st.sampled_from((0.0, 0.2, 0.5)))
        doc["risk"]["judge"] = {"url": "http://127.0.0.1:9/v1", "model": "m", "safe_below": lo,
                                "unsafe_from": draw(st.sampled_from(tuple(x for x in (0.5, 0.8, 1.0) if x >= lo)))}
    text = yaml.safe_dump(doc, sort_keys=False)
    return text, ethimon.load_spec_text(text, "<generated>")


@st.composite
def tier_ops(draw, spec):
    out = []
    for op in draw(ops(spec, max_size=20)):
        if op[0] == "step":
            f = dict(op[1])
            r = draw(st.integers(0, 9))
            if r < 6:
                f["judge"] = draw(st.sampled_from(JUDGE_VALUES))
            elif r == 6:
                f["judge"] = draw(st.sampled_from((math.nan, -0.1, 1.5, "0.1", True)))
            if draw(st.booleans()):
                f["task_id"] = draw(st.sampled_from(("a", "b")))
            op = ("step", f)
        out.append(op)
    return out


@pytest.mark.slow
@given(st.data())
def test_monitor_equals_reference_with_tiers(data):
    text, spec = data.draw(tier_specs())
    note(text)
    m, ref = ethimon.Monitor(spec), ReferenceMonitor(spec)
    for op in data.draw(tier_ops(spec)):
        if op[0] == "acknowledge":
            assert m.acknowledge() == ref.acknowledge()
        elif op[0] == "reset":
            m.reset()
            ref.reset()
        elif op[0] == "release":
            m.release()
            ref.release()
        else:
            a, b = m.step(op[1]), ref.step(op[1])
            note(f"frame={op[1]!r}\n  monitor  ={a!r}\n  reference={b!r}")
            assert decision_key(a) == decision_key(b)


@pytest.mark.slow
@given(st.data())
def test_tier_rules_hold_on_every_valid_cycle(data):
    """R_e >= tau overrides; in the band without a safe verdict or a confirmation it overrides at
    stop 2 or more; an unsafe verdict overrides; a missing judgement never executes in the band."""
    text, spec = data.draw(tier_specs())
    note(text)
    r = spec.risk
    m = ethimon.Monitor(spec)
    confirmed_task = None
    for op in data.draw(tier_ops(spec)):
        if op[0] != "step":
            continue  # no acknowledge: nothing is ever confirmed here
        d = m.step(op[1])
        if d.faults or d.risk is None:
            assert d.override
            continue
        jp = op[1].get("judge") if r.judge is not None else None
        if d.risk >= r.threshold:
            assert d.override and "risk" in d.violations
        if r.judge is not None and jp is not None and jp >= r.judge.unsafe_from:
            assert d.override and "judge" in d.violations
        safe = r.judge is not None and jp is not None and jp < r.judge.safe_below
        if r.confirm_threshold is not None and r.confirm_threshold <= d.risk < r.threshold and not safe:
            assert d.override and d.response.severity >= min(2, ethimon.Response(r.response).severity) \
                and confirmed_task is None


@pytest.mark.slow
@given(st.data())
def test_offline_equals_monitor_with_tiers(data):
    text, spec = data.draw(tier_specs())
    note(text)
    frames = [op[1] for op in data.draw(tier_ops(spec)) if op[0] == "step"]
    frames = [{k: v for k, v in f.items() if k != "judge" or (isinstance(v, float) and 0 <= v <= 1)} for f in frames]
    m = ethimon.Monitor(spec)
    want = [m.step(f) for f in frames]
    n = len(frames)
    cols = {}
    for name in spec.signals:
        vals = [f.get(name) for f in frames]
        cols[name] = np.array(vals, dtype=object)
    for key in ("risk", "p_unsafe", "p", "risk_age_s"):
        if any(key in f for f in frames):
            cols[key] = np.array([f.get(key) for f in frames], dtype=object) if key != "p" else None
    if "p" in cols:  # p as a 2-d column is awkward with gaps; drop those traces
        return
    cols["judge"] = np.array([f.get("judge", math.nan) for f in frames], dtype=float)
    cols["task_id"] = np.array([f.get("task_id") for f in frames], dtype=object)
    try:
        off = check_trace(spec, cols, length=n)
    except ValueError:
        return  # an object column the offline reader refuses as a whole (not the tiers' business)
    assert off.override.tolist() == [d.override for d in want]
    assert off.response.tolist() == [d.response.severity for d in want]
    assert off.tier_violated["confirm"].tolist() == ["confirm" in d.violations for d in want]
