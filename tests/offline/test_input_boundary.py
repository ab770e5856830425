"""The input boundary, round 2 (issue 25 rows 6 and 7): values whose conversion raises fail closed
offline exactly where ``Monitor.step`` does, and the gym shield judges the action the env gets."""

from __future__ import annotations

import numpy as np
import pytest

import ethimon
from ethimon.offline import check_trace

SPEC = ethimon.load_spec_text("""
ethimon: 1
name: b
signals:
  d: {unit: m, range: [0, 10]}
  lit: {type: bool}
obligations:
  - {id: keep_away, require: "d >= 0.5"}
  - {id: flag, require: "not lit", response: stop_2}
""")


class Raises:
    """A number whose ``__float__`` raises something other than the usual TypeError/ValueError."""

    def __init__(self, exc=RuntimeError):
        self.exc = exc

    def __float__(self):
        raise self.exc("no float for you")

    def __index__(self):
        raise self.exc("no index either")


class RealRaises(Raises):
    pass


import numbers  # noqa: E402

numbers.Real.register(RealRaises)  # claims to be a real number: as_number calls float() on it


class BadIter:
    def __iter__(self):
        raise RuntimeError("cannot iterate")


@pytest.mark.parametrize("method", ["vector", "step"])
def test_offline_fails_closed_where_the_monitor_does_on_a_raising_float(method):
    cols = {
        "d": [2.0, RealRaises(), 3.0, RealRaises(ZeroDivisionError), 0.1, 2.0, 2.0],
        "lit": [False, False, RealRaises(), False, False, False, False],
        "p_unsafe": [0.0, 0.0, 0.0, 0.0, RealRaises(), 0.0, 0.0],
    }
    cols7 = dict(cols, p=[None] * 7)
    cols7["p_unsafe"] = cols["p_unsafe"][:5] + [None, None]
    cols7["p"] = [None] * 5 + [BadIter(), [RealRaises(), 1.0]]
    for columns in (cols, cols7):
        res = check_trace(SPEC, columns, method=method)  # raised RuntimeError before
        m = ethimon.Monitor(SPEC)
        n = len(columns["d"])
        want = [m.step({k: v[t] for k, v in columns.items() if v[t] is not None}) for t in range(n)]
        got = list(res.decisions())
        for t in range(n):
            assert (got[t].override, got[t].response, got[t].violations, [f.kind for f in got[t].faults]) == (
                want[t].override, want[t].response, want[t].violations, [f.kind for f in want[t].faults]), t
        assert want[1].override and [f.kind for f in want[1].faults] == ["invalid"]


# ------------------------------------------------------------------ row 6: the shield judges what the env gets
gymnasium = pytest.importorskip("gymnasium")


class Shifty:
    """An action that reads safe the first time and fast toward the wall every time after."""

    def __init__(self):
        self.reads = 0

    def __array__(self, dtype=None, copy=None):
        self.reads += 1
        return np.array([0.0 if self.reads == 1 else 1.0], dtype=dtype or np.float64)


def test_the_env_gets_the_action_the_shield_judged():
    from tests.gym.test_gym import WALL_SPEC, Wall, predicted
    from ethimon.gym import MonitorWrapper

    env = MonitorWrapper(Wall(start=0.55), ethimon.load_spec_text(WALL_SPEC), signals=predicted,
                         safe_action=np.zeros(1), inputs={"p_unsafe": 0.0})
    env.reset()
    act = Shifty()
    _, _, _, _, info = env.step(act)
    assert not info["decision"]["override"]  # judged as 0.0 m/s: distance stays 0.55 m
    assert env.unwrapped.actions == [0.0], env.unwrapped.actions  # before: the env read 1.0 m/s into the wall
    assert act.reads == 1


def test_an_action_that_cannot_be_read_overrides():
    from tests.gym.test_gym import WALL_SPEC, Wall, predicted
    from ethimon.gym import MonitorWrapper

    class Broken:
        def __array__(self, dtype=None, copy=None):
            raise RuntimeError("sensor bus down")

    env = MonitorWrapper(Wall(start=5.0), ethimon.load_spec_text(WALL_SPEC), signals=predicted,
                         safe_action=np.zeros(1), inputs={"p_unsafe": 0.0})
    env.reset()
    _, _, _, _, info = env.step(Broken())
    assert info["shield"]["replaced"] and env.unwrapped.actions == [0.0]
    assert "cannot be read as an action" in str(info["decision"]["faults"])
