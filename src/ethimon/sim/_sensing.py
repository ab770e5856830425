"""What :class:`~._arm.ArmSim` reads from the physics state (``Sensors``, handed the ``World``):
joints, the hand, the people, and the monitor's signals (distances, speeds, contact force)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ._cell import ARM_JOINTS, EE_LINK, FINGER_JOINTS, HAND_LINK, _NO_HUMAN_M, _cross3
from ._world import World

__all__ = ["Sensors"]


class Sensors:
    """The state and the signals of the cell (a part of :class:`~._arm.ArmSim`): it reads the
    :class:`~._world.World` it is handed and owns the people's tracks (:meth:`human_speed`)."""

    __slots__ = ("w", "_p", "_track")

    def __init__(self, world: World) -> None:
        self.w = world
        self._p = world.p
        self._track: dict[str, tuple[float, np.ndarray, float]] = {}  # name -> (t, xy, speed)

    # ------------------------------------------------------------ state

    def teleport(self, q: Sequence[float]) -> None:
        """Teleport the arm to ``q`` (zero velocity); fingers open (the physics of ``reset_joints``)."""
        w = self.w
        p, cid, robot = self._p, w.cid, w.robot
        for j, v in zip(ARM_JOINTS, q):
            p.resetJointState(robot, j, float(v), 0.0, physicsClientId=cid)
        for j in FINGER_JOINTS:
            p.resetJointState(robot, j, 0.04, 0.0, physicsClientId=cid)

    def joint_state(self) -> tuple[np.ndarray, np.ndarray]:
        """Measured arm joint positions and velocities (7 each)."""
        q, qd = self.joint_lists()
        return np.array(q), np.array(qd)

    def joint_lists(self) -> tuple[list[float], list[float]]:
        """:meth:`joint_state` as two lists of floats (the same numbers, no arrays built)."""
        w = self.w
        js = w.js_step
        if js is not None:
            return js
        st = self._p.getJointStates(w.robot, ARM_JOINTS, physicsClientId=w.cid)
        return [s[0] for s in st], [s[1] for s in st]

    def grasp_z(self) -> float:
        """Height (m) of the grasp point now."""
        return float(self._p.getLinkState(self.w.robot, EE_LINK, computeForwardKinematics=1,
                                          physicsClientId=self.w.cid)[0][2])

    def applied_torques(self) -> np.ndarray:
        """Motor torques the last physics step applied to the 7 arm joints."""
        st = self._p.getJointStates(self.w.robot, ARM_JOINTS, physicsClientId=self.w.cid)
        return np.array([s[3] for s in st])

    def ee_pose(self) -> tuple[np.ndarray, np.ndarray]:
        """End-effector (grasp target) world position and quaternion."""
        ls = self._p.getLinkState(self.w.robot, EE_LINK, computeForwardKinematics=1,
                                  physicsClientId=self.w.cid)
        return np.array(ls[4]), np.array(ls[5])

    def ee_velocity(self) -> np.ndarray:
        """End-effector linear velocity (m/s, world frame)."""
        ls = self._p.getLinkState(self.w.robot, EE_LINK, computeLinkVelocity=1,
                                  computeForwardKinematics=1, physicsClientId=self.w.cid)
        return np.array(ls[6])

    def human_position(self, name: str) -> np.ndarray:
        """Capsule centre of human ``name``."""
        pos, _ = self._p.getBasePositionAndOrientation(self.w.humans[name].body,
                                                       physicsClientId=self.w.cid)
        return np.array(pos)

    def human_xy(self) -> dict[str, np.ndarray]:
        """Every person's horizontal position now (capsule centre)."""
        return {n: self.human_position(n)[:2] for n in self.w.humans}

    # ------------------------------------------------------------ signals

    def distance(self, body_a: int, body_b: int, max_m: float = _NO_HUMAN_M) -> float:
        """Minimum surface distance between two bodies (0 when touching), via getClosestPoints."""
        pts = self._p.getClosestPoints(body_a, body_b, max_m, physicsClientId=self.w.cid)
        if not pts:
            return max_m
        return max(0.0, min(pt[8] for pt in pts))

    def human_distance(self) -> float:
        """Minimum distance between any human and the arm (or the object it holds)."""
        best = _NO_HUMAN_M
        held = self.w.objects.get(self.w.held) if self.w.held else None
        for hb in self.w.humans.values():
            best = min(best, self.distance(self.w.robot, hb.body, best))
            if held is not None:
                best = min(best, self.distance(held, hb.body, best))
        return best

    def contact_force(self) -> float:
        """Largest contact normal force (N) of the arm against humans/objects.

        Counts arm–human, held-object–human and arm–object contacts; the
        objects the task picks (see :meth:`set_graspable`) and the floor are excluded.
        """
        p, cid = self._p, self.w.cid
        best = 0.0
        held = self.w.objects.get(self.w.held) if self.w.held else None
        others = [hb.body for hb in self.w.humans.values()]
        others += [b for n, b in self.w.objects.items() if n not in self.w.graspable]
        for b in others:
            for c in p.getContactPoints(self.w.robot, b, physicsClientId=cid):
                if c[9] > best:
                    best = c[9]
        if held is not None:
            for hb in self.w.humans.values():
                for c in p.getContactPoints(held, hb.body, physicsClientId=cid):
                    if c[9] > best:
                        best = c[9]
        return float(best)

    def hazard_distance(self) -> float:
        """Minimum distance between any hazard-tagged object and any human (m)."""
        best = _NO_HUMAN_M
        for name, spec in self.w.object_specs.items():
            if spec.hazard:
                for hb in self.w.humans.values():
                    best = min(best, self.distance(self.w.objects[name], hb.body, best))
        return best

    def human_speed(self, name: str) -> float:
        """Horizontal speed (m/s) of person ``name`` as a tracker measures it: the change of
        the measured position since the previous control cycle's reading (0 at the first)."""
        hb = self.w.humans[name]
        pos, _ = self._p.getBasePositionAndOrientation(hb.body, physicsClientId=self.w.cid)
        xy = np.array(pos[:2], dtype=float)
        last = self._track.get(name)
        if last is not None and abs(last[0] - self.w.time_s) < 1e-12:
            return last[2]  # read twice in one cycle: the same measurement
        v = 0.0 if last is None else float(np.linalg.norm(xy - last[1]) / (self.w.time_s - last[0]))
        self._track[name] = (self.w.time_s, xy, v)
        return v

    def closest_approach(self) -> tuple[float, str | None, float]:
        """``(distance, person, speed toward the person)`` of the closest point pair between the
        arm (or the held object) and any person.

        The speed is the velocity of the arm's closest point (its link's linear velocity plus
        ω × r; the hand's rigid motion for a held object) projected on the unit vector from it
        toward the person's closest point, 0 when it moves away (ISO/TS 15066 v_r is the speed
        toward the operator). ``(10, None, 0)`` with nobody in the scene."""
        p, cid = self._p, self.w.cid
        held = self.w.objects.get(self.w.held) if self.w.held else None
        best = (_NO_HUMAN_M, None, None, None)  # (d, person, point record, from the held object)
        for name, hb in self.w.humans.items():
            for body in (self.w.robot, held):
                if body is None:
                    continue
                pts = p.getClosestPoints(body, hb.body, best[0], physicsClientId=cid)
                for pt in pts:
                    d = max(0.0, pt[8])
                    if d < best[0] or best[1] is None and d <= best[0]:
                        best = (d, name, pt, body == held)
        d, name, pt, on_held = best
        if pt is None:
            return _NO_HUMAN_M, None, 0.0
        pa, pb = np.asarray(pt[5]), np.asarray(pt[6])
        link = HAND_LINK if on_held else pt[3]
        if link < 0:
            return float(d), name, 0.0  # the fixed base does not move
        st = p.getLinkState(self.w.robot, link, computeLinkVelocity=1, physicsClientId=cid)
        v = np.asarray(st[6]) + _cross3(st[7], pa - np.asarray(st[0]))
        n = pb - pa
        norm = float(np.linalg.norm(n))
        n = n / norm if norm > 1e-9 else -np.asarray(pt[7])  # touching: the contact normal
        return float(d), name, max(0.0, float(np.dot(v, n)))

    def signals(self) -> dict[str, float]:
        """The monitor's inputs from the current physics state.

        Returns:
            ``human_distance`` (m), ``ee_speed`` (m/s), ``contact_force`` (N),
            ``joint_speed_max`` (rad/s), ``hazard_distance`` (m, hazardous object to nearest
            human; 10 m when there is none), ``human_speed`` (m/s, the person closest to the
            arm, from the tracked position; 0 with nobody) and ``robot_speed_toward_human``
            (m/s, the arm's closest point toward that person, see :meth:`closest_approach`).
        """
        _, qd = self.joint_state()
        dist, who, v_r = self.closest_approach()
        speeds = {n: self.human_speed(n) for n in self.w.humans}  # every track stays current
        return {
            "human_distance": float(dist),
            "ee_speed": float(np.linalg.norm(self.ee_velocity())),
            "contact_force": self.contact_force(),
            "joint_speed_max": float(np.abs(qd).max()),
            "hazard_distance": float(self.hazard_distance()),
            "human_speed": float(speeds[who]) if who is not None else 0.0,
            "robot_speed_toward_human": float(v_r),
        }
