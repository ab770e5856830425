"""The kinematics of :class:`~._arm.ArmSim` (``Kinematics``, handed the ``World``) and the probes the controllers plan with: IK/FK, the
hazard axis, a route's clearances, link points, a step away from the people; the gravity load of
arm + payload that the brakes must hold."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from .._robot import PAYLOAD_OFFSET_M, brake_problem, gravity_torque
from ._cell import (ARM_JOINTS, EE_LINK, FLANGE_LINK, HAND_LINK, HOME_JOINTS_RAD, _DOWN_RPY, _NO_HUMAN_M)
from ._sensing import Sensors
from ._world import World

__all__ = ["Kinematics"]

_ARM_JOINT_LIST = list(ARM_JOINTS)
_ZERO_VEL = [[0.0]] * len(ARM_JOINTS)
_ALL_LINKS = list(range(12))


class Kinematics:
    """IK/FK and route probing (a part of :class:`~._arm.ArmSim`): handed the
    :class:`~._world.World` and the :class:`~._sensing.Sensors` it reads the arm's state with; it
    owns no state of its own (every probe restores the arm)."""

    __slots__ = ("w", "_p", "_sense")

    def __init__(self, world: World, sensors: Sensors) -> None:
        self.w = world
        self._p = world.p
        self._sense = sensors

    # ------------------------------------------------------------ kinematics

    def set_arm(self, q: Sequence[float], qd: Sequence[float] | None = None) -> None:
        """Teleport the 7 arm joints to ``q`` (velocities ``qd``, default 0) in one PyBullet
        call: the same state as seven ``resetJointState`` calls (checked bit for bit by
        ``bench.sim.sim_check diff``), with one forward-kinematics update instead of seven."""
        self._p.resetJointStatesMultiDof(
            self.w.robot, _ARM_JOINT_LIST, [[v] for v in np.asarray(q, dtype=float).tolist()],
            _ZERO_VEL if qd is None else [[w] for w in np.asarray(qd, dtype=float).tolist()],
            physicsClientId=self.w.cid)

    def solve_ik(self, xyz: Sequence[float], rpy: Sequence[float] | None = None,
                 seed: Sequence[float] | None = None, iterations: int = 6) -> np.ndarray:
        """Joint angles that put the grasp target at ``xyz`` with orientation ``rpy``.

        Deterministic: seeds from ``seed`` (default the current pose), refines a
        few times, and restores the arm's state afterwards.
        """
        p, cid = self._p, self.w.cid
        q_now, qd_now = self._sense.joint_state()
        seed_q = np.asarray(seed if seed is not None else q_now, dtype=float)
        orn = p.getQuaternionFromEuler(tuple(rpy) if rpy is not None else _DOWN_RPY)
        ranges = (self.w.upper - self.w.lower).tolist()
        q = seed_q.copy()
        for _ in range(iterations):
            self.set_arm(q)
            sol = p.calculateInverseKinematics(
                self.w.robot, EE_LINK, list(xyz), orn,
                lowerLimits=self.w.lower.tolist() + [0.0, 0.0],
                upperLimits=self.w.upper.tolist() + [0.04, 0.04],
                jointRanges=ranges + [0.04, 0.04],
                restPoses=list(HOME_JOINTS_RAD) + [0.04, 0.04],
                maxNumIterations=200, residualThreshold=1e-5, physicsClientId=cid)
            q = np.clip(np.array(sol[:7]), self.w.lower, self.w.upper)
        self.set_arm(q_now, qd_now)
        return q

    def fk(self, q: Sequence[float]) -> np.ndarray:
        """Grasp-target position for joint angles ``q`` (state restored afterwards)."""
        q_now, qd_now = self._sense.joint_state()
        self.set_arm(q)
        pos, _ = self._sense.ee_pose()
        self.set_arm(q_now, qd_now)
        return pos

    # ------------------------------------------------------------ planning probes

    def held_pose_for_hand(self) -> tuple | None:
        """The held object's pose where the grasp holds it (``None`` when nothing is held)."""
        if self.w.held is None or self.w.held_rel is None:
            return None
        p, cid = self._p, self.w.cid
        hs = p.getLinkState(self.w.robot, HAND_LINK, computeForwardKinematics=1, physicsClientId=cid)
        return p.multiplyTransforms(hs[0], hs[1], *self.w.held_rel)

    def hazard_axis_angles_deg(self, qs: Sequence[Sequence[float]] | None = None, *,
                               each: bool = False, until=None) -> list | None:
        """Angle (deg) between the held object's declared ``hazard_axis`` and the direction from
        the object's centre to each person (the nearest point of their capsule axis), the worst
        (smallest) over every person present (issue 32: every person counts, not only the
        nearest), at each configuration in ``qs`` (default: now; state restored afterwards).
        180 = pointed straight away. ``each=True``: per configuration a dict person -> angle.
        ``until``: a test of each result; the configurations after the first result it passes
        are not evaluated (that result is the last in the list).
        ``None`` when no object with a ``hazard_axis`` is held or there is nobody.
        """
        if self.w.held is None or not self.w.humans:
            return None
        axis = self.w.object_specs[self.w.held].hazard_axis
        rel = self.w.held_rel
        if axis is None or rel is None:
            return None
        p, cid, robot = self._p, self.w.cid, self.w.robot
        a_obj = np.asarray(axis, dtype=float) / float(np.linalg.norm(axis))
        people = []  # (name, x, y, lowest, highest point of the capsule's axis)
        for hb in self.w.humans.values():
            c = self._sense.human_position(hb.spec.name)
            r, h = hb.spec.radius_m, hb.spec.height_m
            half = max(h / 2 - r, 0.0)
            people.append((hb.spec.name, c[0], c[1], c[2] - half, c[2] + half))
        get_link, mul, to_matrix = p.getLinkState, p.multiplyTransforms, p.getMatrixFromQuaternion
        acos, degrees, sqrt = math.acos, math.degrees, math.sqrt

        def angle():
            hs = get_link(robot, HAND_LINK, computeForwardKinematics=1, physicsClientId=cid)
            pos, orn = mul(hs[0], hs[1], *rel)  # the held object's pose (_held_pose_for_hand)
            z_obj = pos[2]
            pos = np.asarray(pos)
            a = np.asarray(to_matrix(orn)).reshape(3, 3) @ a_obj
            per = {}
            for name, cx, cy, lo, hi in people:
                v = np.array([cx, cy, min(max(z_obj, lo), hi)]) - pos
                d = sqrt(float(v.dot(v)))  # = np.linalg.norm(v)
                cos = float(np.dot(a, v) / d) if d > 1e-9 else 1.0
                per[name] = degrees(acos(min(1.0, max(-1.0, cos))))
            return per if each else min(per.values())

        if qs is None:
            return [angle()]
        q_now, qd_now = self._sense.joint_state()
        out = []
        try:
            for q in qs:
                self.set_arm(q)
                out.append(angle())
                if until is not None and until(out[-1]):
                    break
        finally:
            self.set_arm(q_now, qd_now)
        return out

    def probe(self, qs: Sequence[Sequence[float]], until=None) -> list[dict[str, float]]:
        """Clearances of the arm at each joint configuration in ``qs`` (state restored after).

        Each result: ``human`` (m, arm or held object to the nearest person), ``obstacle``
        (m, arm or held object to any object the task does not pick, and arm links 3..8 to
        the floor) and ``hazard`` (m, a held hazard-tagged object to the nearest person;
        10 when none). People stand where they are now. ``until``: a test of each result; the
        configurations after the first result it passes are not probed.
        """
        p, cid = self._p, self.w.cid
        q_now, qd_now = self._sense.joint_state()
        held = self.w.objects.get(self.w.held) if self.w.held else None
        held_pose = p.getBasePositionAndOrientation(held, physicsClientId=cid) if held is not None else None
        # resetting a body's pose zeroes its velocity: keep it, or the grasp constraint has to
        # re-accelerate the held object from rest in one physics step (issue 23: a 3 kg pot
        # yanked joint 5 at 16.9 x its rated acceleration at every re-plan)
        held_vel = p.getBaseVelocity(held, physicsClientId=cid) if held is not None else None
        hazardous = held is not None and bool(self.w.object_specs[self.w.held].hazard)
        obstacles = [b for n, b in self.w.objects.items() if n not in self.w.graspable and b != held]
        distance = self._sense.distance
        out = []
        try:
            for q in qs:
                self.set_arm(q)
                if held is not None:
                    pose = self.held_pose_for_hand()
                    if pose is not None:
                        p.resetBasePositionAndOrientation(held, pose[0], pose[1], physicsClientId=cid)
                bodies = [self.w.robot] + ([held] if held is not None else [])
                h = hz = _NO_HUMAN_M
                for hb in self.w.humans.values():
                    for b in bodies:
                        h = min(h, distance(b, hb.body, h))
                    if hazardous:
                        hz = min(hz, distance(held, hb.body, hz))
                ob = 1.0
                for o in obstacles:
                    for b in bodies:
                        ob = min(ob, distance(b, o, ob))
                # links 2..11 to the floor in one query (the base and links 0-1 stand on it)
                pts = [pt[8] for pt in p.getClosestPoints(self.w.robot, self.w.plane, ob, physicsClientId=cid)
                       if pt[3] >= 2]
                if pts:
                    ob = min(ob, max(0.0, min(pts)))
                if held is not None:
                    pts = p.getClosestPoints(held, self.w.plane, ob, physicsClientId=cid)
                    if pts:
                        ob = min(ob, max(0.0, min(pt[8] for pt in pts)))
                out.append({"human": float(h), "obstacle": float(ob), "hazard": float(hz)})
                if until is not None and until(out[-1]):
                    break
        finally:
            self.set_arm(q_now, qd_now)
            if held is not None:
                p.resetBasePositionAndOrientation(held, held_pose[0], held_pose[1], physicsClientId=cid)
                p.resetBaseVelocity(held, held_vel[0], held_vel[1], physicsClientId=cid)
        return out

    def link_points(self, q: Sequence[float]) -> np.ndarray:
        """World positions of the link frames (links 1..7, hand, fingers, grasp frame) at ``q``
        (state restored afterwards); with a held object, its position too."""
        return self.link_points_at([q])[0]

    def link_points_at(self, qs: Sequence[Sequence[float]]) -> list[np.ndarray]:
        """:meth:`link_points` at each configuration in ``qs``, the state read and restored once."""
        p, cid = self._p, self.w.cid
        q_now, qd_now = self._sense.joint_state()
        out = []
        try:
            for q in qs:
                self.set_arm(q)
                states = p.getLinkStates(self.w.robot, _ALL_LINKS, computeForwardKinematics=1,
                                         physicsClientId=cid)
                pts = [st[4] for st in states]
                pose = self.held_pose_for_hand()
                if pose is not None:
                    pts.append(pose[0])
                out.append(np.array(pts, dtype=float))
        finally:
            self.set_arm(q_now, qd_now)
        return out

    def away_from_humans(self, xyz: Sequence[float], step_m: float) -> np.ndarray | None:
        """``xyz`` moved ``step_m`` horizontally away from the nearest person and 0.1 m up
        (``None`` with nobody in the scene)."""
        if not self.w.humans:
            return None
        x = np.asarray(xyz, dtype=float)
        best = min(self.w.humans.values(), key=lambda hb: float(np.linalg.norm(hb.xy_at(self.w.time_s) - x[:2])))
        d = x[:2] - best.xy_at(self.w.time_s)
        n = float(np.linalg.norm(d))
        if n < 1e-6:
            return None
        return np.array([x[0] + step_m * d[0] / n, x[1] + step_m * d[1] / n, x[2] + 0.1])

    # ------------------------------------------------------------ gravity (issue 32)

    def payload(self) -> tuple[float, tuple[float, float, float]]:
        """The held object as a payload: ``(mass kg, its centre of mass in the flange frame m)``;
        ``(0, grasp point)`` when nothing is held."""
        if self.w.held is None:
            return 0.0, PAYLOAD_OFFSET_M
        p, cid = self._p, self.w.cid
        st = p.getLinkState(self.w.robot, FLANGE_LINK, computeForwardKinematics=1, physicsClientId=cid)
        inv_pos, inv_orn = p.invertTransform(st[4], st[5])  # the flange's URDF frame
        pos, _ = p.getBasePositionAndOrientation(self.w.objects[self.w.held], physicsClientId=cid)
        rel, _ = p.multiplyTransforms(inv_pos, inv_orn, pos, (0.0, 0.0, 0.0, 1.0))
        return float(self.w.object_specs[self.w.held].mass_kg), (float(rel[0]), float(rel[1]), float(rel[2]))

    def gravity_load(self, q: Sequence[float] | None = None) -> np.ndarray:
        """The torque (N·m) each joint must hold against gravity now: arm + held payload
        (:func:`ethimon._robot.gravity_torque`, the URDF's masses; equal to PyBullet's inverse
        dynamics at rest)."""
        q = self._sense.joint_state()[0] if q is None else q
        m, off = self.payload()
        return np.asarray(gravity_torque(q, m, off))

    def brake_problem_now(self) -> str | None:
        """``None`` when every brake holds arm + payload where the arm is; else why not."""
        q, _ = self._sense.joint_state()
        m, off = self.payload()
        return brake_problem(q, m, off, holding_n_m=tuple(self.w.brake_torque))
