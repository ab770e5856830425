"""ethimon.gym: the MonitorWrapper shield (on a toy env, exactly) and the PandaCell-v0 env."""

from __future__ import annotations

import importlib.util
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")

import ethimon  # noqa: E402
from ethimon.gym import MonitorWrapper  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]

WALL_SPEC = """
ethimon: 1
name: wall
signals:
  distance: {unit: m, range: [0, 100], description: distance to the wall after the proposed step}
risk:
  release: {mode: auto, hysteresis: 0.05, hold_cycles: 1}
obligations:
  - {id: keep_off_wall, require: "distance >= 0.5", response: stop_2}
"""


class Wall(gymnasium.Env):
    """A point on a line, ``d`` metres from a wall; the action is a speed toward it (dt = 1/8 s)."""

    DT = 0.125  # a power of two: every position below is exact
    metadata = {"render_modes": []}

    def __init__(self, start: float = 1.0) -> None:
        self.start = start
        self.observation_space = gymnasium.spaces.Box(-100.0, 100.0, (1,), np.float64)
        self.action_space = gymnasium.spaces.Box(-1.0, 1.0, (1,), np.float64)
        self.actions: list[float] = []  # what actually reached the env

    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        self.d = self.start
        self.actions = []
        return np.array([self.d]), {"cost": 0.25}

    def step(self, action):
        a = float(np.asarray(action).reshape(()))
        self.actions.append(a)
        self.d -= a * self.DT
        return np.array([self.d]), 1.0, False, False, {"cost": 0.25}


def predicted(obs, info, action):
    """The distance after the proposed action: the shield judges it before it runs."""
    return {"distance": float(obs[0]) - float(np.asarray(action).reshape(())) * Wall.DT}


def wall(on_override="replace", signals=predicted, safe_action=(0.0,), start=1.0):
    return MonitorWrapper(Wall(start), ethimon.load_spec_text(WALL_SPEC), signals=signals,
                          safe_action=safe_action, on_override=on_override, inputs={"p_unsafe": 0.0})


def test_replace_mode_swaps_exactly_the_unsafe_actions():
    env = wall()
    obs, _ = env.reset(seed=0)
    seen = []
    for _ in range(8):
        obs, reward, term, trunc, info = env.step(np.array([1.0]))
        seen.append((float(obs[0]), info["shield"]["replaced"], info["cost"], info["decision"]["violations"]))
        assert not term and not trunc and reward == 1.0
    # 1.0 -> 0.875 -> 0.75 -> 0.625 -> 0.5 (predicted 0.5 is allowed); the 5th push would reach 0.375
    assert [s[0] for s in seen] == [0.875, 0.75, 0.625, 0.5, 0.5, 0.5, 0.5, 0.5]
    assert [s[1] for s in seen] == [False] * 4 + [True] * 4
    assert [s[2] for s in seen] == [0.0] * 4 + [1.0] * 4
    assert seen[4][3] == ["keep_off_wall"]
    assert env.unwrapped.actions == [1.0] * 4 + [0.0] * 4  # the unsafe push never reached the env
    assert info["shield"]["action"].tolist() == [0.0]
    assert info["decision"]["override"] is True and info["decision"]["response"] == "stop_2"
    assert info["env_cost"] == 0.25  # the env's own cost is kept, ours is the monitor's
    assert info["shield"]["signals"] == {"p_unsafe": 0.0, "distance": 0.375}


def test_backing_off_is_allowed_again_after_the_release_rule():
    env = wall()
    env.reset(seed=0)
    for _ in range(5):
        env.step(np.array([1.0]))
    _, _, _, _, info = env.step(np.array([-1.0]))  # moving away: no violation; latch holds 1 cycle
    assert info["decision"]["latched"] is False and info["decision"]["override"] is False
    assert info["cost"] == 0.0 and not info["shield"]["replaced"]
    assert env.unwrapped.actions[-1] == -1.0


def test_terminate_mode_ends_the_episode_without_stepping_the_env():
    env = wall("terminate")
    env.reset(seed=0)
    for _ in range(4):
        _, _, term, _, _ = env.step(np.array([1.0]))
        assert not term
    obs, reward, term, trunc, info = env.step(np.array([1.0]))
    assert (term, trunc, reward) == (True, False, 0.0)
    assert float(obs[0]) == 0.5 and len(env.unwrapped.actions) == 4
    assert info["shield"] == {"replaced": False, "terminated": True, "action": None,
                              "signals": {"p_unsafe": 0.0, "distance": 0.375}}
    assert info["cost"] == 1.0


def test_reset_resets_the_monitor():
    env = wall()
    env.reset(seed=0)
    for _ in range(6):
        env.step(np.array([1.0]))
    assert env.monitor.cycle == 6 and env.monitor.latched
    env.reset(seed=0)
    assert env.monitor.cycle == 0 and not env.monitor.latched
    _, _, _, _, info = env.step(np.array([1.0]))
    assert info["decision"]["cycle"] == 0 and info["cost"] == 0.0


def _raises(obs, info, action):
    raise RuntimeError("sensor gone")


@pytest.mark.parametrize("signals, kind, words", [
    (_raises, "external", "signals callable failed: RuntimeError: sensor gone"),
    (lambda obs, info, action: [1.0], "external", "not a mapping"),
    (lambda obs, info, action: {"distance": math.nan}, "invalid", "'distance'"),
    (lambda obs, info: {}, "missing", "'distance' is missing"),  # two-argument form, a missing signal
])
def test_signal_faults_fail_closed_to_the_safe_action(signals, kind, words):
    env = wall(signals=signals, safe_action=lambda obs: np.array([-0.5]))
    env.reset(seed=0)
    obs, _, term, _, info = env.step(np.array([1.0]))
    assert not term and info["shield"]["replaced"] and env.unwrapped.actions == [-0.5]
    assert info["decision"]["override"] and info["cost"] == 1.0
    assert kind in info["decision"]["fault_kinds"]
    assert any(words in f for f in info["decision"]["faults"]), info["decision"]["faults"]


def test_a_fault_holds_the_shield_until_acknowledged_or_reset():
    calls = []

    def glitch_once(obs, info, action):
        calls.append(1)
        if len(calls) == 1:
            raise RuntimeError("glitch")
        return predicted(obs, info, action)

    env = wall(signals=glitch_once)
    env.reset(seed=0)
    for _ in range(3):  # the fault latch is manual by default: good inputs alone do not release it
        _, _, _, _, info = env.step(np.array([0.0]))
        assert info["shield"]["replaced"] and info["cost"] == 1.0
    assert info["decision"]["latched"] and not info["decision"]["faults"]
    assert env.monitor.acknowledge().released
    _, _, _, _, info = env.step(np.array([1.0]))
    assert not info["shield"]["replaced"] and env.unwrapped.actions[-1] == 1.0
    env.step(np.array([math.nan]))  # NaN: a fault again, latched again ...
    env.reset(seed=0)               # ... and a new episode starts unlatched
    _, _, _, _, info = env.step(np.array([1.0]))
    assert info["cost"] == 0.0 and not info["shield"]["replaced"]


def test_a_safe_action_that_fails_ends_the_episode():
    env = wall(safe_action=lambda obs, decision: np.array([5.0]))  # outside the action space
    env.reset(seed=0)
    for _ in range(4):
        env.step(np.array([1.0]))
    obs, reward, term, trunc, info = env.step(np.array([1.0]))
    assert (term, trunc, reward) == (True, False, 0.0) and len(env.unwrapped.actions) == 4
    assert "safe_action" in " ".join(info["decision"]["faults"])


def test_safe_action_gets_the_decision_when_it_takes_two_arguments():
    got = []
    env = wall(safe_action=lambda obs, decision: got.append(decision.violations) or np.array([0.0]))
    env.reset(seed=0)
    for _ in range(5):
        env.step(np.array([1.0]))
    assert got == [("keep_off_wall",)]


def test_constructor_errors_are_clear():
    spec = ethimon.load_spec_text(WALL_SPEC)
    with pytest.raises(ValueError, match="not in the action space"):
        MonitorWrapper(Wall(), spec, signals=predicted, safe_action=[3.0])
    with pytest.raises(ValueError, match="'replace' or 'terminate'"):
        MonitorWrapper(Wall(), spec, signals=predicted, safe_action=[0.0], on_override="stop")
    with pytest.raises(TypeError, match="signals must take"):
        MonitorWrapper(Wall(), spec, signals=lambda obs: {}, safe_action=[0.0])
    with pytest.raises(gymnasium.error.ResetNeeded):
        MonitorWrapper(Wall(), spec, signals=predicted, safe_action=[0.0]).step(np.array([0.0]))


def test_no_risk_input_is_a_fault_not_a_silent_default():
    env = MonitorWrapper(Wall(), ethimon.load_spec_text(WALL_SPEC), signals=predicted, safe_action=[0.0])
    env.reset(seed=0)
    _, _, _, _, info = env.step(np.array([0.0]))
    assert info["cost"] == 1.0 and info["decision"]["fault_kinds"] == ["missing"]


@pytest.mark.slow
def test_import_ethimon_stays_light():
    code = ("import sys, ethimon; import ethimon.sim; "
            "assert 'gymnasium' not in sys.modules and 'pybullet' not in sys.modules, 'heavy'; "
            "import ethimon.gym; assert 'pybullet' not in sys.modules, 'pybullet'; "
            "import gymnasium; assert 'ethimon/PandaCell-v0' in gymnasium.registry; print('ok')")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0 and out.stdout.strip() == "ok", out.stderr


# ---------------------------------------------------------------- the Panda cell (PyBullet)

_NO_PYBULLET = importlib.util.find_spec("pybullet") is None
pytestmark_sim = pytest.mark.skipif(_NO_PYBULLET, reason='needs PyBullet: pip install "ethimon[sim]"')


@pytest.fixture
def panda():
    env = gymnasium.make("ethimon/PandaCell-v0")
    yield env
    env.close()


@pytest.mark.slow
@pytest.mark.sim
@pytestmark_sim
def test_panda_cell_passes_check_env():
    import warnings

    from gymnasium.utils.env_checker import check_env

    env = gymnasium.make("ethimon/PandaCell-v0", render_mode="rgb_array").unwrapped
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            check_env(env)  # raises on any API breach
        # its one remaining advice: a [-1, 1] action space (ours is in rad/s, the rated limits)
        left = [str(w.message) for w in caught if "symmetric and normalized" not in str(w.message)]
        assert not left, left
        env.reset(seed=1)
        frame = env.render()
        assert frame.shape == (240, 320, 3) and frame.dtype == np.uint8 and frame.std() > 0
    finally:
        env.close()


@pytest.mark.sim
@pytestmark_sim
def test_panda_cell_spaces_and_info(panda):
    from ethimon.gym import PANDA_RATED_JOINT_SPEED_RAD_S

    assert panda.action_space.high.tolist() == pytest.approx(PANDA_RATED_JOINT_SPEED_RAD_S)
    assert panda.observation_space.shape == (7 + 7 + 3 + 3 + 3,)
    obs, info = panda.reset(seed=3)
    assert obs in panda.observation_space
    assert set(info) >= {"human_distance", "ee_speed", "contact_force", "joint_speed_max", "ee_jacobian",
                         "distance_to_target", "is_success"}
    # the target is in the observation; the reward is minus the distance to it
    obs, reward, *_ , info = panda.step(np.zeros(7, np.float32))
    assert reward == pytest.approx(-float(np.linalg.norm(obs[14:17] - obs[17:20])), abs=1e-5)
    assert reward == -info["distance_to_target"]


def test_action_bounds_are_the_rated_joint_speeds():
    from ethimon.gym import PANDA_RATED_JOINT_SPEED_RAD_S

    assert PANDA_RATED_JOINT_SPEED_RAD_S == (2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61)  # Franka datasheet
    try:
        from ethimon.sim._limits import RATED_DQ_MAX
    except ImportError:  # an older sim without its own table of rated limits
        return
    assert tuple(RATED_DQ_MAX) == PANDA_RATED_JOINT_SPEED_RAD_S


@pytest.mark.slow
@pytest.mark.sim
@pytestmark_sim
def test_panda_cell_tracks_joint_velocity_targets(panda):
    panda.reset(seed=0)
    a = np.array([0.3, -0.2, 0.3, 0.3, 0.5, -0.5, 0.5], np.float32)
    for _ in range(10):
        obs, *_ = panda.step(a)
    assert np.abs(obs[7:14] - a).max() < 0.05  # measured joint speeds follow the targets
    # a target above the rated limit is clipped to it
    panda.reset(seed=0)
    for _ in range(20):
        obs, *_ = panda.step(np.full(7, 50.0, np.float32))
    assert np.all(np.abs(obs[7:14]) <= np.array(panda.action_space.high) * 1.02)


@pytest.mark.sim
@pytestmark_sim
@pytest.mark.parametrize("n_humans", [0, 2])
def test_panda_cell_with_no_or_several_people(n_humans):
    env = gymnasium.make("ethimon/PandaCell-v0", n_humans=n_humans)
    try:
        obs, info = env.reset(seed=2)
        assert obs.shape == (20 + 3 * n_humans,) and obs in env.observation_space
        obs, *_, info = env.step(env.action_space.sample())
        assert obs in env.observation_space
        assert (info["human_distance"] == 10.0) == (n_humans == 0)  # 10 m: nobody in the cell
    finally:
        env.close()
    with pytest.raises(ValueError, match="0 to 4 people"):
        gymnasium.make("ethimon/PandaCell-v0", n_humans=5)


@pytest.mark.slow
@pytest.mark.sim
@pytestmark_sim
def test_panda_cell_is_deterministic_with_a_seed(panda):
    def rollout(env, seed):
        obs, _ = env.reset(seed=seed)
        rng = np.random.default_rng(7)
        out = [obs]
        for _ in range(25):
            obs, reward, *_ = env.step(rng.uniform(-2, 2, 7).astype(np.float32))
            out.append(np.append(obs, reward))
        return np.concatenate(out)

    first = rollout(panda, 5)
    rollout(panda, 6)  # another episode in between: the next reset restores the physics
    again = rollout(panda, 5)
    other = gymnasium.make("ethimon/PandaCell-v0")
    try:
        fresh = rollout(other, 5)
    finally:
        other.close()
    assert np.array_equal(first, again) and np.array_equal(first, fresh)
    assert not np.array_equal(first[:23], rollout(panda, 6)[:23])  # the seed matters (start pose, target, human)


@pytest.mark.sim
@pytestmark_sim
def test_panda_shield_replaces_fast_commands_near_the_limits(panda):
    from ethimon.gym import panda_signals, panda_spec

    env = MonitorWrapper(panda, panda_spec(), signals=panda_signals, safe_action=np.zeros(7, np.float32),
                         inputs={"p_unsafe": 0.0})
    env.reset(seed=0)
    fast = np.array([0, 0, 0, 0, 2.6, 0, 0], np.float32)  # a wrist joint above w_max = 2.5 rad/s
    _, _, _, _, info = env.step(fast)
    assert info["shield"]["replaced"] and "joint_speed" in info["decision"]["violations"]
    assert info["shield"]["signals"]["joint_speed_max"] == pytest.approx(2.6)
    assert np.abs(env.unwrapped._sim.joint_state()[1]).max() < 0.05  # the fast command never ran
    # a NaN command is a fault: overridden, and the env never sees it
    _, _, _, _, info = env.step(np.full(7, np.nan, np.float32))
    assert info["shield"]["replaced"] and "invalid" in info["decision"]["fault_kinds"]


@pytest.mark.slow
@pytest.mark.sim
@pytestmark_sim
def test_gym_shield_example_runs(capsys):
    import runpy

    mod = runpy.run_path(str(ROOT / "examples" / "gym_shield.py"), run_name="gym_shield")
    assert mod["main"](["--episodes", "1", "--steps", "15", "--seed", "4"]) == 0
    out = capsys.readouterr().out
    assert "shielded (ethimon)" in out and "unsafe steps by rule" in out
    row = next(line for line in out.splitlines() if line.strip().startswith("4 |"))
    bare, shield = row.split("|")[1].split(), row.split("|")[2].split()
    assert bare[0] == shield[0] == "15"  # both runs took all 15 steps
    assert int(shield[2]) >= 1  # the shield stepped in at least once (seed 4 proposes a too-fast step first)
