"""Task planning (motion primitives → joint segments) and the arm's controllers.

Every controller has ``command(sim)``, called once per control cycle before
the physics substeps, and a ``done`` flag. They never import PyBullet
themselves; they only talk to :class:`~ethimon.sim.ArmSim`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ._arm import ArmSim, Segment
from ._model import SimError, HandOver, Pick, Place, Pour, Reach, SimBlock, Wait, Wipe

__all__ = ["plan_task", "TaskController", "SafePoseController", "StopController",
           "SEVERITY"]

#: Responses ordered by severity; the arm never de-escalates while overridden.
SEVERITY = {"none": 0, "safe_pose": 1, "stop_2": 2, "stop_1": 3, "stop_0": 4}

_MIN_SEGMENT_S = 0.25
_IK_TOLERANCE_M = 0.02
_GRIP_S = 0.3
_FF = 0.0  # velocity feed-forward share (PyBullet motors overshoot with it)


def _min_jerk(u: float) -> tuple[float, float]:
    """Position fraction and its derivative (per unit time fraction) of a min-jerk profile."""
    u = min(max(u, 0.0), 1.0)
    s = u * u * u * (10 - 15 * u + 6 * u * u)
    ds = 30 * u * u * (1 - u) * (1 - u)
    return s, ds


def _timed(q_from: np.ndarray, q_to: np.ndarray, duration_s: float | None, v_task: float) -> float:
    # a min-jerk profile peaks at 1.875 × the mean speed
    need = 1.875 * float(np.max(np.abs(q_to - q_from))) / v_task
    return max(duration_s or 0.0, need, _MIN_SEGMENT_S)


def plan_task(sim: ArmSim, block: SimBlock) -> list[Segment]:
    """Turn the block's primitives into joint-space segments (IK solved once, up front).

    Deterministic: IK is seeded by the previous segment's solution.
    """
    v = block.task_joint_speed_rad_s
    q_prev, _ = sim.joint_state()
    grip = sim.gripper_cmd
    segs: list[Segment] = []
    held_half_h = 0.0  # grasp point above the held object's resting centre

    def add(q, dur=None, label="", attach=None, detach=False, gripper=None, hold=False):
        nonlocal q_prev, grip
        q = np.asarray(q, dtype=float)
        if gripper is not None:
            grip = gripper
        d = dur if hold else _timed(q_prev, q, dur, v)
        segs.append(Segment(q=q, duration_s=max(d, 1e-3), gripper_m=grip, attach=attach,
                            detach=detach, label=label))
        q_prev = q

    where = ""

    def ik(xyz, rpy=None):
        q = sim.solve_ik(xyz, rpy, seed=q_prev)
        miss = float(np.linalg.norm(sim.fk(q) - np.asarray(xyz, dtype=float)))
        if miss > _IK_TOLERANCE_M:
            raise SimError(f"sim.task[{where}: the Panda cannot reach {list(xyz)} "
                           f"(inverse kinematics misses by {miss:.3f} m; keep targets within "
                           "about 0.8 m of the shoulder at (0, 0, 0.33))")
        return q

    for i, prim in enumerate(block.task):
        tag = f"{i}:{prim.primitive}"
        where = f"{i}] ({prim.primitive})"
        if isinstance(prim, Reach):
            q = prim.joints_rad if prim.joints_rad is not None else ik(prim.xyz_m, prim.rpy_rad)
            add(q, prim.duration_s, tag)
        elif isinstance(prim, Pick):
            sim.set_graspable(prim.object)
            o = sim.object_specs[prim.object]
            x, y, z = o.xyz_m
            top = _half_height(o)
            grasp_z = z + max(top - 0.02, 0.0)
            held_half_h = grasp_z - z
            add(ik((x, y, grasp_z + prim.approach_height_m)), prim.duration_s, tag + ":approach")
            add(ik((x, y, grasp_z)), prim.duration_s, tag + ":descend")
            width = min(_half_width(o), 0.04)
            add(q_prev, _GRIP_S, tag + ":grasp", attach=prim.object, gripper=width, hold=True)
            add(ik((x, y, grasp_z + prim.approach_height_m)), prim.duration_s, tag + ":lift")
        elif isinstance(prim, Place):
            x, y, z = prim.xyz_m
            gz = z + held_half_h
            add(ik((x, y, gz + prim.approach_height_m)), prim.duration_s, tag + ":carry")
            add(ik((x, y, gz)), prim.duration_s, tag + ":lower")
            add(q_prev, _GRIP_S, tag + ":release", detach=True, gripper=0.04, hold=True)
            add(ik((x, y, gz + prim.approach_height_m)), prim.duration_s, tag + ":retreat")
        elif isinstance(prim, HandOver):
            add(ik(prim.xyz_m), prim.duration_s, tag + ":offer")
            if prim.hold_s > 0:
                add(q_prev, prim.hold_s, tag + ":hold", hold=True)
            if prim.release:
                add(q_prev, _GRIP_S, tag + ":release", detach=True, gripper=0.04, hold=True)
        elif isinstance(prim, Pour):
            x, y, z = prim.xyz_m
            add(ik((x, y, z)), prim.duration_s, tag + ":above")
            tilted = ik((x, y, z), (math.pi, prim.tilt_rad, 0.0))
            add(tilted, prim.duration_s, tag + ":tilt")
            if prim.hold_s > 0:
                add(q_prev, prim.hold_s, tag + ":hold", hold=True)
            add(ik((x, y, z)), prim.duration_s, tag + ":untilt")
        elif isinstance(prim, Wipe):
            x, y, z = prim.xyz_m
            hl, hw = prim.length_m / 2, prim.width_m / 2
            add(ik((x - hl, y - hw, z + 0.1)), prim.duration_s, tag + ":approach")
            ys = np.linspace(y - hw, y + hw, prim.passes)
            for k, yy in enumerate(ys):
                xa, xb = (x - hl, x + hl) if k % 2 == 0 else (x + hl, x - hl)
                add(ik((xa, yy, z)), None, f"{tag}:pass{k}a")
                add(ik((xb, yy, z)), None, f"{tag}:pass{k}b")
            add(ik((x, y, z + 0.1)), prim.duration_s, tag + ":lift")
        elif isinstance(prim, Wait):
            add(q_prev, prim.duration_s, tag, hold=True)
    return segs


def _half_height(o) -> float:
    if o.shape == "box":
        return o.half_extents_m[2]
    if o.shape == "sphere":
        return o.radius_m
    return o.height_m / 2


def _half_width(o) -> float:
    if o.shape == "box":
        return min(o.half_extents_m[0], o.half_extents_m[1])
    return o.radius_m


class TaskController:
    """Plays the planned segments; pauses on override and resumes from where the arm is."""

    name = "task"

    def __init__(self, segments: Sequence[Segment], q_start: np.ndarray, v_task: float) -> None:
        self.segments = list(segments)
        self.v_task = v_task
        self.index = 0
        self.t = 0.0
        self._from = np.asarray(q_start, dtype=float)
        self._dur = self.segments[0].duration_s if self.segments else 0.0
        self.setpoint = self._from.copy()

    @property
    def done(self) -> bool:
        """All segments played."""
        return self.index >= len(self.segments)

    @property
    def label(self) -> str:
        return self.segments[self.index].label if not self.done else "done"

    def resume(self, q_now: np.ndarray) -> None:
        """Restart the current segment from the measured pose ``q_now`` (after a release)."""
        self._from = np.asarray(q_now, dtype=float)
        self.t = 0.0
        if not self.done:
            seg = self.segments[self.index]
            self._dur = _timed(self._from, seg.q, seg.duration_s, self.v_task)

    def command(self, sim: ArmSim) -> None:
        if self.done:
            last = self.segments[-1] if self.segments else None
            sim.command_joints(self.setpoint, None, last.gripper_m if last else None)
            return
        seg = self.segments[self.index]
        s, ds = _min_jerk(self.t / self._dur)
        q = self._from + s * (seg.q - self._from)
        qd = (ds / self._dur) * (seg.q - self._from)
        self.setpoint = q
        sim.command_joints(q, qd * _FF, seg.gripper_m)
        self.t += sim.dt
        if self.t >= self._dur - 1e-9:
            if seg.attach:
                sim.attach(seg.attach)
            if seg.detach:
                sim.detach()
            self._from = seg.q
            self.index += 1
            self.t = 0.0
            if not self.done:
                nxt = self.segments[self.index]
                self._dur = nxt.duration_s


class SafePoseController:
    """Drives every joint to the safe pose on a synchronised, rate-limited path.

    The setpoint moves along the straight joint-space line from the pose at
    the override to ``q_safe``; the path speed has a trapezoidal profile whose
    cruise speed keeps the fastest joint at ``margin × max_joint_speed_rad_s``.
    The motors also clamp their velocity at the limit.
    """

    name = "safe_pose"

    def __init__(self, q_now: np.ndarray, q_safe: Sequence[float], max_joint_speed_rad_s: float,
                 *, margin: float = 0.98, accel_rad_s2: float = 8.0) -> None:
        self.q0 = np.asarray(q_now, dtype=float)
        self.q_safe = np.asarray(q_safe, dtype=float)
        self.v_limit = float(max_joint_speed_rad_s)
        self.v_cruise = margin * self.v_limit
        self.accel = accel_rad_s2
        delta = self.q_safe - self.q0
        self.length = float(np.max(np.abs(delta)))          # path length of the fastest joint
        self.dir = delta / self.length if self.length > 0 else np.zeros(7)
        self.s = 0.0
        self.v = 0.0

    @property
    def done(self) -> bool:
        """The setpoint has arrived (the measured pose may still be settling)."""
        return self.s >= self.length

    def command(self, sim: ArmSim) -> None:
        dt = sim.dt
        remaining = self.length - self.s
        v_brake = math.sqrt(max(2.0 * self.accel * remaining, 0.0))
        self.v = min(self.v_cruise, self.v + self.accel * dt, v_brake)
        self.s = min(self.length, self.s + self.v * dt)
        q = self.q0 + self.s * self.dir
        qd = self.v * self.dir if not self.done else np.zeros(7)
        sim.command_joints(q, qd * _FF, max_velocity=self.v_limit)


class StopController:
    """Stop categories (IEC 60204-1): 0 = power off at once; 1 = controlled stop, then
    power off; 2 = controlled stop, then hold position with power on.

    The controlled stop ramps the commanded joint velocity linearly from the
    measured velocity to zero over ``ramp_s``.
    """

    def __init__(self, category: int, q_now: np.ndarray, qd_now: np.ndarray, ramp_s: float) -> None:
        self.category = category
        self.name = f"stop_{category}"
        self.q = np.asarray(q_now, dtype=float).copy()
        self.qd0 = np.asarray(qd_now, dtype=float).copy()
        self.ramp_s = ramp_s
        self.t = 0.0
        self.powered_off = False

    @property
    def done(self) -> bool:
        return self.category == 0 or self.t >= self.ramp_s

    def command(self, sim: ArmSim) -> None:
        if self.category == 0 or (self.category == 1 and self.t >= self.ramp_s):
            if not self.powered_off:
                sim.command_torque_off()
                self.powered_off = True
            self.t += sim.dt
            return
        k = max(0.0, 1.0 - self.t / self.ramp_s)
        k_next = max(0.0, 1.0 - (self.t + sim.dt) / self.ramp_s)
        self.q = self.q + 0.5 * (k + k_next) * self.qd0 * sim.dt
        sim.command_joints(self.q, k_next * self.qd0)
        self.t += sim.dt
