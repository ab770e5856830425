"""``ethimon/PandaCell-v0``: the PyBullet Franka Panda cell as a Gymnasium environment.

Built by composition on :class:`ethimon.sim.ArmSim` (the same cell, arm model,
humans and signals as ``ethimon simulate``). PyBullet is imported when the
environment is built, never at module import.

Observation (``float32``, ``7 + 7 + 3 + 3 + 3·n_humans``)::

    q (rad, 7) | q̇ (rad/s, 7) | end-effector xyz (m) | target xyz (m) | human xyz (m) per human

Action: joint velocity targets (rad/s, 7), a ``Box`` bounded by the Panda's
rated joint speeds (:data:`PANDA_RATED_JOINT_SPEED_RAD_S`); anything outside
is clipped. Each step integrates the target into a joint setpoint
(``q_cmd += a·dt``, kept within the joint limits and 0.25 rad of the measured
pose), which the arm's position motors track at 240 Hz for ``240 / control_hz``
physics substeps.

Reward: ``-‖ee − target‖`` (m) every step; ``terminated`` when the end effector
is within ``reach_tolerance_m`` of the target. Register ``max_episode_steps``
truncates (200 steps = 10 s at 20 Hz).

``info`` (after ``reset`` and every ``step``), measured on the new state:
``human_distance`` (m, closest arm link or held object to any human capsule,
10 with none), ``ee_speed`` (m/s), ``contact_force`` (N), ``joint_speed_max``
(rad/s), ``ee_jacobian`` (3×7, linear velocity Jacobian of the grasp frame at
the current pose), ``distance_to_target`` (m), ``is_success``, ``time_s``.

Humans walk in on a seeded random path each episode: each starts 2.0–2.8 m
from the base, waits, walks in at 0.8–1.6 m/s to 0.45–1.3 m (capsule axis)
from the base, stays, and walks back out.
"""

from __future__ import annotations

import math
from typing import Any

import gymnasium
import numpy as np
from gymnasium import spaces

from ..sim import Human, Waypoint
from ..sim._arm import ARM_JOINTS, EE_LINK, FINGER_JOINTS, HOME_JOINTS_RAD, ArmSim, import_pybullet

__all__ = ["PandaCellEnv", "PANDA_RATED_JOINT_SPEED_RAD_S"]

#: Rated joint speed limits of the Franka Emika Panda (rad/s), from Franka's datasheet.
PANDA_RATED_JOINT_SPEED_RAD_S = (2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61)

_TARGET_LO = np.array([0.30, -0.40, 0.15])
_TARGET_HI = np.array([0.65, 0.40, 0.60])
_MAX_LAG_RAD = 0.25       # the setpoint never runs further than this ahead of the measured pose
_START_NOISE_RAD = 0.1    # start pose: HOME ± this per joint
_Q_BOUND = 2 * math.pi    # observation bounds (values are clipped into them)
_QD_BOUND = 10.0
_XYZ_BOUND = 5.0


class PandaCellEnv(gymnasium.Env):
    """A Franka Panda reaching task in a cell with walking people (PyBullet, DIRECT).

    Args:
        control_hz: steps per simulated second; must divide 240 (physics rate).
        n_humans: number of people walking in the cell (0–4).
        reach_tolerance_m: success radius around the target.
        render_mode: ``None`` or ``"rgb_array"`` (PyBullet's software renderer).

    Deterministic with a seed: ``reset(seed=s)`` followed by the same actions
    gives bit-identical observations (the physics state is restored from a
    snapshot taken when the cell was built).

    Example:
        >>> import gymnasium, ethimon.gym                       # doctest: +SKIP
        >>> env = gymnasium.make("ethimon/PandaCell-v0")         # doctest: +SKIP
        >>> obs, info = env.reset(seed=0); info["human_distance"]  # doctest: +SKIP
    """

    metadata = {"render_modes": ["rgb_array"], "render_fps": 20}

    def __init__(self, *, control_hz: int = 20, n_humans: int = 1, reach_tolerance_m: float = 0.05,
                 render_mode: str | None = None) -> None:
        if not 0 <= n_humans <= 4:
            raise ValueError(f"n_humans={n_humans!r}: give 0 to 4 people")
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise ValueError(f"render_mode={render_mode!r}: use None or 'rgb_array'")
        if control_hz <= 0 or 240 % control_hz:
            raise ValueError(f"control_hz={control_hz!r} must divide 240 (the physics rate)")
        self.control_hz = int(control_hz)
        self.n_humans = int(n_humans)
        self.reach_tolerance_m = float(reach_tolerance_m)
        self.render_mode = render_mode
        self.metadata = {**self.metadata, "render_fps": self.control_hz}
        vmax = np.array(PANDA_RATED_JOINT_SPEED_RAD_S, dtype=np.float32)
        self.action_space = spaces.Box(-vmax, vmax, dtype=np.float32)
        n = 7 + 7 + 3 + 3 + 3 * self.n_humans
        hi = np.concatenate([np.full(7, _Q_BOUND), np.full(7, _QD_BOUND), np.full(n - 14, _XYZ_BOUND)])
        self._obs_hi = hi.astype(np.float32)
        self.observation_space = spaces.Box(-self._obs_hi, self._obs_hi, dtype=np.float32)
        self._sim: ArmSim | None = None
        self._p, _ = import_pybullet()  # DependencyNotInstalled (with the pip line) here, not at reset
        self._snapshot: int | None = None
        self._names = tuple(f"human{i}" for i in range(self.n_humans))
        self._target = np.zeros(3)
        self._q_cmd = np.zeros(7)

    # ------------------------------------------------------------ the cell

    def _build(self) -> ArmSim:
        # people start far away; their paths are replaced at every reset
        humans = [Human(name=nm, waypoints=(Waypoint(t_s=0.0, xy_m=(3.0 + i, 0.0)),)) for i, nm in
                  enumerate(self._names)]
        sim = ArmSim(control_hz=self.control_hz, humans=humans)
        self._snapshot = self._p.saveState(physicsClientId=sim.cid)
        return sim

    def _walk_path(self, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
        """A seeded walk-in / stay / walk-out path: (times, xy) arrays."""
        theta = rng.uniform(-0.6 * math.pi, 0.6 * math.pi)
        far = rng.uniform(2.0, 2.8)
        near = rng.uniform(0.45, 1.3)
        side = rng.uniform(-0.3, 0.3)  # the stop point is a little off the line to the base
        speed = rng.uniform(0.8, 1.6)
        t0 = rng.uniform(0.0, 3.0)
        stay = rng.uniform(1.0, 3.0)
        u = np.array([math.cos(theta), math.sin(theta)])
        v = np.array([-u[1], u[0]])
        a = far * u
        b = near * u + side * v
        walk = float(np.linalg.norm(b - a)) / speed
        times = np.array([0.0, t0, t0 + walk, t0 + walk + stay, t0 + 2 * walk + stay])
        xy = np.array([a, a, b, b, a])
        return times, xy

    def _set_human_path(self, name: str, times: np.ndarray, xy: np.ndarray) -> None:
        # ArmSim moves each person along (times, xy) in ``step``; a new path per episode
        # without rebuilding the cell (a rebuild costs ~0.2 s)
        hb = self._sim.humans[name]
        hb.times = times
        hb.xy = xy

    # ------------------------------------------------------------ gymnasium API

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        super().reset(seed=seed)
        if self._sim is None:
            self._sim = self._build()
        sim, p = self._sim, self._p
        p.restoreState(self._snapshot, physicsClientId=sim.cid)
        rng = self.np_random
        q0 = np.clip(np.asarray(HOME_JOINTS_RAD) + rng.uniform(-_START_NOISE_RAD, _START_NOISE_RAD, 7),
                     sim.lower, sim.upper)
        self._target = rng.uniform(_TARGET_LO, _TARGET_HI)
        for name in self._names:
            self._set_human_path(name, *self._walk_path(rng))
        sim.cycle = 0
        sim.time_s = 0.0
        sim.reset_joints(q0)
        sim.command_joints(q0, gripper_m=0.04, max_velocity=None)
        for hb in sim.humans.values():  # where they stand at t = 0
            sim._place_human(hb, 0.0)
        self._q_cmd = q0.copy()
        obs, info = self._observe()
        return obs, info

    def step(self, action):
        if self._sim is None:
            raise gymnasium.error.ResetNeeded("call reset() before step()")
        sim = self._sim
        a = np.asarray(action, dtype=np.float64).reshape(7)
        if not np.all(np.isfinite(a)):
            a = np.zeros(7)  # a NaN velocity target is no motion, never undefined motion
        a = np.clip(a, self.action_space.low, self.action_space.high)
        q, _ = sim.joint_state()
        q_cmd = self._q_cmd + a * sim.dt
        q_cmd = np.clip(q_cmd, q - _MAX_LAG_RAD, q + _MAX_LAG_RAD)
        self._q_cmd = np.clip(q_cmd, sim.lower, sim.upper)
        sim.command_joints(self._q_cmd)
        sim.step()
        obs, info = self._observe()
        d = info["distance_to_target"]
        terminated = bool(info["is_success"])
        return obs, float(-d), terminated, False, info

    def _jacobian(self, q: np.ndarray) -> np.ndarray:
        p, sim = self._p, self._sim
        fingers = [s[0] for s in p.getJointStates(sim.robot, FINGER_JOINTS, physicsClientId=sim.cid)]
        lin, _ = p.calculateJacobian(sim.robot, EE_LINK, [0.0, 0.0, 0.0], q.tolist() + fingers,
                                     [0.0] * 9, [0.0] * 9, physicsClientId=sim.cid)
        return np.asarray(lin, dtype=np.float64)[:, :len(ARM_JOINTS)]

    def _observe(self) -> tuple[np.ndarray, dict[str, Any]]:
        sim = self._sim
        q, qd = sim.joint_state()
        ee, _ = sim.ee_pose()
        humans = [sim.human_position(nm) for nm in self._names]
        obs = np.concatenate([q, qd, ee, self._target, *humans]).astype(np.float32)
        obs = np.clip(obs, -self._obs_hi, self._obs_hi)
        d = float(np.linalg.norm(ee - self._target))
        sig = sim.signals()
        info = {
            "human_distance": sig["human_distance"],
            "ee_speed": sig["ee_speed"],
            "contact_force": sig["contact_force"],
            "joint_speed_max": sig["joint_speed_max"],
            "ee_jacobian": self._jacobian(q),
            "distance_to_target": d,
            "is_success": d < self.reach_tolerance_m,
            "time_s": float(sim.time_s),
        }
        return obs, info

    def render(self):
        if self.render_mode != "rgb_array" or self._sim is None:
            return None
        return self._sim.render(width=320, height=240)

    def close(self) -> None:
        if self._sim is not None:
            self._sim.close()
            self._sim = None
            self._snapshot = None
