"""The compiled monitor and the reference interpreter agree cycle by cycle (seeded random traces)."""

import math
import random

import pytest

import ethimon
from ethimon.testing import ReferenceMonitor

ALL_OPS = """ethimon: 1
name: all_ops
signals:
  a: {unit: m, range: [0, 4]}
  b: {unit: m, range: [0, 4]}
  f: {type: bool}
constants:
  k: {value: 1.5, unit: m}
  n3: 3
risk: {threshold: 0.45, release: {hysteresis: 0.05, hold_cycles: 3}}
obligations:
  - {id: cmp, require: "abs(a - b) <= 3.5 and max(a, b, k) >= min(a, b)"}
  - {id: held_, require: "not held(a > 3, 3)", response: stop_2}
  - {id: once_, when: "once(f, 4)", require: "b < 3.5"}
  - {id: since_, require: "not since(a > 1, b < 0.5, n3)", response: stop_1}
  - {id: since_unb, require: "not since(f, a > 3.9) or b > 0.1"}
  - {id: prev_, require: "prev(a, 0) - a < 3 and (prev(f) implies a < 3.95)"}
  - {id: nested, require: "not held(once(a > 2, 2) or prev(b > 3.5), 2)", response: stop_0}
  - {id: resp, when: "a > 2.5", require: "b < 1", within_cycles: 2}
  - {id: resp_always, require: "a < 3.6 or f", within_cycles: 1}
  - {id: divide, require: "a / (b - 2) > -100"}
"""


def random_trace(rng: random.Random, spec, n: int):
    names = [s for s in spec.signals]
    trace = []
    for _ in range(n):
        frame = {}
        for name in names:
            sig = spec.signals[name]
            if sig.type == "bool":
                frame[name] = rng.random() < 0.4
            else:
                lo, hi = sig.range
                frame[name] = round(rng.uniform(lo, hi), 1) if rng.random() < 0.7 else rng.choice([lo, hi, 2.0])
        roll = rng.random()
        if roll < 0.03 and names:
            frame[rng.choice(names)] = math.nan
        elif roll < 0.05 and names:
            frame.pop(rng.choice(names))
        r = rng.random()
        if r < 0.4:
            frame["p_unsafe"] = rng.choice([0.0, 0.05, 0.1, 0.5, 0.7, 0.9, 1.0, rng.random()])
        elif r < 0.7:
            frame["risk"] = rng.choice([0.1, 0.3, 0.39, 0.4, 0.41, 0.45, 0.5, 0.6])
        elif r < 0.98:
            q = rng.random()
            frame["p"] = (1 - q, q)
        trace.append(frame)
    return trace


def assert_same(spec, trace):
    m, ref = ethimon.Monitor(spec), ReferenceMonitor(spec)
    for t, frame in enumerate(trace):
        a, b = m.step(frame), ref.step(frame)
        assert (a.override, a.response, a.violations, a.latched, bool(a.faults), a.cycle) == \
            (b.override, b.response, b.violations, b.latched, bool(b.faults), b.cycle), (t, frame, a, b)
        if a.risk is None or b.risk is None:
            assert a.risk is b.risk
        else:
            assert a.risk == pytest.approx(b.risk, abs=1e-12)


@pytest.mark.parametrize("seed", range(12))
def test_all_operators_spec_agrees(seed):
    spec = ethimon.load_spec_text(ALL_OPS)
    rng = random.Random(seed)
    assert_same(spec, random_trace(rng, spec, 120))


@pytest.mark.slow
@pytest.mark.parametrize("name", ["governor", "cobot_cell"])
def test_shipped_specs_agree(root, name):
    spec = ethimon.load_spec(root / "specs" / f"{name}.yaml")
    rng = random.Random(7)
    for _ in range(5):
        assert_same(spec, random_trace(rng, spec, 150))


def test_reset_replays_identically():
    spec = ethimon.load_spec_text(ALL_OPS)
    trace = random_trace(random.Random(3), spec, 200)
    m = ethimon.Monitor(spec)
    first = [m.step(f) for f in trace]
    m.reset()
    second = [m.step(f) for f in trace]
    assert first == second
