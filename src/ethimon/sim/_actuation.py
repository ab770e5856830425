"""How :class:`~._arm.ArmSim` moves the arm: joint commands within the rated limits, torque off
and the brakes, the unpowered arm, and the grasp (attach, drop, detach)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ._limits import BRAKE_ENGAGE_S, BRAKE_SAFETY_FACTOR, LIMIT_MARGIN_RAD
from ._model import PHYSICS_HZ

from ._cell import (ARM_JOINTS, ARM_MAX_FORCE_N_M, EE_LINK, FINGER_JOINTS, HAND_LINK, _BRAKE_DECEL, _K_POS,
                    _LIMIT_SHARE, _Q_MAX, _Q_MIN, _RATED_DDDQ, _RATED_DDQ, _RATED_DQ)

__all__ = ["_Actuation"]

#: the least speed cap a stop leaves the servo for correcting a position error (rad/s). PyBullet's
#: velocity motor creeps under a heavy load (joint 4 at 0.02 rad/s with 3 kg held out); a stop that
#: capped the servo at the speed at its command (about 0.001 rad/s from rest) let the arm sink, and
#: a stop 2 drifted past its standstill tolerance and fell as a stop 0 (issue 32: 0.24 m with the
#: rated 3 kg at joint 2's worst pose). Below the 0.05 rad/s from which a stop's speed gain counts.
_HOLD_SPEED_RAD_S = 0.05


class _Actuation:
    """Commands, brakes and grasp (a part of :class:`~._arm.ArmSim`)."""

    # ------------------------------------------------------------ commands

    def command_joints(self, q: Sequence[float], qd: Sequence[float] | None = None,
                       gripper_m: float | None = None, *,
                       max_velocity: float | None = None,
                       speed_cap: Sequence[float] | None = None) -> None:
        """Track the joint reference ``q`` (with reference velocity ``qd``) this cycle; powers motors on.

        The joint servo interpolates the reference at the physics rate (cubic Hermite from
        the previous reference when ``qd`` is given, linear otherwise) and commands each
        motor the velocity ``qd_ref + K (q_ref − q)``, clipped to the rated joint speed, to
        ``max_velocity`` (rad/s, all joints) and to ``speed_cap`` (rad/s per joint; a stop
        passes the speed at its command so that nothing can add speed), then rate-limited
        to the rated acceleration and jerk. The reference is clipped to the rated position
        range. So every controller keeps the Panda's rated limits
        (:mod:`ethimon.sim._limits`).
        """
        if not getattr(self, "_holding_refused", False):  # any other command ends a refused power-off's hold
            self.power_off_refused = None
            self._refused_hold = None
        self.max_velocity = max_velocity
        self.speed_cap = None if speed_cap is None else np.abs(np.asarray(speed_cap, dtype=float))
        if not self.powered:  # re-powering: interpolate from where the arm is, as it moves
            self._q_sub, self._v_out = self.joint_state()
            self._qd_sub = self._v_out.copy()
            self._a_out = np.zeros(7)
        self.q_cmd = np.clip(np.asarray(q, dtype=float), _Q_MIN + LIMIT_MARGIN_RAD,
                             _Q_MAX - LIMIT_MARGIN_RAD)
        self._hermite = qd is not None
        self.qd_cmd = np.zeros(7) if qd is None else np.asarray(qd, dtype=float)
        if gripper_m is not None:
            self.gripper_cmd = gripper_m
        self.powered = True

    def command_torque_off(self, *, brakes_already_engaged: bool = False, why: str | None = None) -> None:
        """Stop category 0 style: remove motor power at once, if the brakes can hold the arm.

        First (issue 32) the gravity load of arm + held payload where the arm is
        (:meth:`gravity_load`) is checked against each joint's brake holding torque
        (:attr:`brake_torque`, the cell's or the Panda table's) with the safety factor
        :data:`~ethimon._robot.BRAKE_SAFETY_FACTOR` (:meth:`brake_margin_problem`): when a brake
        cannot hold it with that margin, power is **not** removed: the arm decelerates within its
        rated acceleration and holds powered (a stop 2), :attr:`power_off_refused` says why and
        :attr:`brake_log` has it; later calls keep that hold, and remove power only once the arm
        is at rest (every joint under 0.01 rad/s) where the brakes hold it with the factor (the
        brakes engaged while the motors hold, no coasting). Otherwise the motors apply no torque any more. With ``brakes`` (the default, as
        on a real Panda) the holding brakes engage :data:`~ethimon.sim._limits.BRAKE_ENGAGE_S`
        later (the joints coast meanwhile), then decelerate each joint at
        :data:`~ethimon.sim._limits.BRAKE_DECEL_RAD_S2` with a friction torque of at most its
        holding torque (a larger external torque slips them) and hold it against gravity: the
        timing is assumed, the torques are estimates (see the sim README). Without brakes,
        gravity and contacts act freely and the arm sags (no check: nothing would hold).
        ``brakes_already_engaged``: the brakes were engaged while the motors still held the arm
        (a stop 1 at standstill), so there is no coasting. ``why`` names the stop in the log
        (default: ``stop 1`` with the brakes already engaged, else ``stop 0``).
        """
        why = why or ("stop 1" if brakes_already_engaged else "stop 0")
        after_hold = False
        if self.power_off_refused is not None and self.powered:
            # the powered hold of a refused power-off: power goes off only once the arm is at rest
            # and its brakes hold it there with the safety factor (the brakes engage while the
            # motors still hold, as a stop 1's); otherwise it stays powered
            _, qd = self.joint_state()
            if float(np.max(np.abs(qd))) >= 0.01 or self.brake_margin_problem() is not None:
                self._hold_refused()
                return
            self.power_off_refused = None
            self._refused_hold = None
            brakes_already_engaged = after_hold = True
        if self.powered:
            problem = self.brake_margin_problem() if self.brakes else None
            t = round(self.time_s, 6)
            if problem is not None:
                self.power_off_refused = (f"{why}: power-off refused, the brakes cannot hold the arm "
                                          f"({problem}): held powered (a stop 2)")
                self.brake_log.append((t, self.power_off_refused))
                self._hold_refused()
                return
            if self.brakes:
                load = np.abs(self.gravity_load())
                j = int(np.argmax(load / np.maximum(self.brake_torque, 1e-9)))
                m, _ = self.payload()
                self.brake_log.append((t, f"{why}: power off{' after the powered hold' if after_hold else ''}; "
                                          f"the brakes hold arm + {m:g} kg with the safety factor "
                                          f"{BRAKE_SAFETY_FACTOR:g} (joint {j + 1}: {load[j]:.1f} of "
                                          f"{self.brake_torque[j]:g} N·m)"))
            self.powered = False
            self._off_substeps = 0
            self._brake_hold = None
            self._off_ref = (self.joint_state()[0].copy(), self._grasp_z())
            if self.held is not None and not self.gripper.self_locking:
                self.drop("power_off")  # the unpowered fingers no longer press on the object
            if brakes_already_engaged:  # a stop 1 engaged them at standstill, motors holding
                self._off_substeps = int(math.ceil(BRAKE_ENGAGE_S * PHYSICS_HZ))
        self._apply_unpowered()

    def brake_margin_problem(self) -> str | None:
        """``None`` when every brake holds the gravity load of arm + held payload where the arm is
        with :data:`~ethimon._robot.BRAKE_SAFETY_FACTOR` (holding torque >= factor x load); else one
        sentence per joint short of it: its load, its brake, the margin and the factor."""
        load = np.abs(self.gravity_load())
        hold = np.asarray(self.brake_torque, dtype=float)
        bad = np.flatnonzero(hold < BRAKE_SAFETY_FACTOR * load)
        if bad.size == 0:
            return None
        m, _ = self.payload()
        return "; ".join(f"joint {j + 1} needs {load[j]:.1f} N·m against gravity (arm + {m:g} kg); its brake "
                         f"holds {hold[j]:g} N·m: {hold[j] / max(load[j], 1e-9):.2f} x, under the safety factor "
                         f"{BRAKE_SAFETY_FACTOR:g}" for j in bad)

    def _hold_refused(self) -> None:
        """The powered hold of a refused power-off: from the state it had then, every joint
        decelerates at 80 % of its rated acceleration (never faster than it was) to rest and holds."""
        if self._refused_hold is None:
            q, qd = self.joint_state()
            stop = q + qd * np.abs(qd) / (2.0 * _LIMIT_SHARE * _RATED_DDQ)
            stop = np.clip(stop, _Q_MIN + LIMIT_MARGIN_RAD, _Q_MAX - LIMIT_MARGIN_RAD)
            self._refused_hold = (stop, np.abs(qd) + 1e-3)
        q_hold, cap = self._refused_hold
        self._holding_refused = True
        try:
            self.command_joints(q_hold, np.zeros(7), speed_cap=cap)
        finally:
            self._holding_refused = False

    def _grasp_z(self) -> float:
        return float(self._p.getLinkState(self.robot, EE_LINK, computeForwardKinematics=1,
                                          physicsClientId=self.cid)[0][2])

    def _track_unpowered(self) -> None:
        """After a physics cycle without power: how far every joint and the grasp point have moved
        since the power-off (:attr:`max_travel_unpowered_rad`, :attr:`max_drop_unpowered_m`)."""
        if self._off_ref is None:
            return
        q0, z0 = self._off_ref
        q, _ = self.joint_state()
        self.max_travel_unpowered_rad = max(self.max_travel_unpowered_rad, float(np.max(np.abs(q - q0))))
        self.max_drop_unpowered_m = max(self.max_drop_unpowered_m, z0 - self._grasp_z())

    @property
    def brakes_engaged(self) -> bool:
        """Motor power is off and the brakes have engaged (after their engagement delay)."""
        return (not self.powered and self.brakes
                and self._off_substeps / PHYSICS_HZ >= BRAKE_ENGAGE_S - 1e-9)

    def _apply_unpowered(self) -> None:
        p, cid = self._p, self.cid
        if self.brakes_engaged:
            q, qd = self.joint_state()
            step = _BRAKE_DECEL / PHYSICS_HZ
            target = np.sign(qd) * np.maximum(np.abs(qd) - step, 0.0)
            # a brake that has stopped its joint holds it where it stopped (friction up to its
            # torque), it does not creep: a velocity loop at 0 drifts under gravity (0.55 mrad/s
            # at a stretched elbow), so a stopped joint is held at its latched position
            if self._brake_hold is None:
                self._brake_hold = np.full(7, np.nan)
            # a joint slower than one physics step of braking is stopped by it (issue 32: a
            # 0.01 rad/s threshold left a loaded elbow creeping at 0.02 rad/s under a velocity
            # loop that never latched, 0.05 rad in 2.6 s with 68.6 of 87 N·m at joint 2)
            stopped = np.abs(qd) <= np.maximum(step, 0.01)
            newly = stopped & np.isnan(self._brake_hold)
            self._brake_hold[newly] = q[newly]
            self._brake_hold[~stopped & (np.abs(q - np.nan_to_num(self._brake_hold, nan=0.0)) > 0.02)] = np.nan
            held = ~np.isnan(self._brake_hold)
            for j in range(7):
                if held[j]:
                    p.setJointMotorControl2(self.robot, ARM_JOINTS[j], p.POSITION_CONTROL,
                                            targetPosition=float(self._brake_hold[j]), targetVelocity=0.0,
                                            force=float(self.brake_torque[j]), positionGain=1.0,
                                            velocityGain=1.0, physicsClientId=cid)
                else:
                    p.setJointMotorControl2(self.robot, ARM_JOINTS[j], p.VELOCITY_CONTROL,
                                            targetVelocity=float(target[j]), force=float(self.brake_torque[j]),
                                            physicsClientId=cid)
        else:  # coasting: no motor torque, brakes not (yet) engaged
            self._brake_hold = None
            p.setJointMotorControlArray(self.robot, ARM_JOINTS, p.VELOCITY_CONTROL,
                                        targetVelocities=[0.0] * 7, forces=[0.0] * 7,
                                        physicsClientId=cid)
        if not self.gripper.self_locking:  # unpowered fingers are free (no holding torque)
            p.setJointMotorControlArray(self.robot, FINGER_JOINTS, p.VELOCITY_CONTROL,
                                        targetVelocities=[0.0, 0.0], forces=[0.0, 0.0],
                                        physicsClientId=cid)

    def _servo_velocity(self, q_ref: np.ndarray, qd_ref: np.ndarray, q_meas: np.ndarray) -> np.ndarray:
        """The rated-limited motor velocity command for one physics step."""
        h = 1.0 / PHYSICS_HZ
        v = qd_ref + _K_POS * (q_ref - q_meas)
        cap = _RATED_DQ
        if self.max_velocity is not None:
            cap = np.minimum(cap, self.max_velocity)
        if self.speed_cap is not None:  # never below what holding a loaded joint needs (issue 32)
            cap = np.minimum(cap, np.maximum(self.speed_cap, _HOLD_SPEED_RAD_S))
        v = np.clip(v, -cap, cap)
        # never faster toward a rated position limit than the joint can shed before it (at
        # the planning share of its rated acceleration): no controller carries it past
        up = np.sqrt(2.0 * _LIMIT_SHARE * _RATED_DDQ * np.maximum(_Q_MAX - LIMIT_MARGIN_RAD - q_meas, 0.0))
        dn = np.sqrt(2.0 * _LIMIT_SHARE * _RATED_DDQ * np.maximum(q_meas - _Q_MIN - LIMIT_MARGIN_RAD, 0.0))
        v = np.clip(v, -dn, up)
        a = np.clip((v - self._v_out) / h, -_RATED_DDQ, _RATED_DDQ)
        a = np.clip(a, self._a_out - _RATED_DDDQ * h, self._a_out + _RATED_DDDQ * h)
        self._a_out = a
        self._v_out = self._v_out + a * h
        return self._v_out

    def _apply_command(self, q: np.ndarray | None = None, qd: np.ndarray | None = None) -> None:
        p, cid = self._p, self.cid
        if not self.powered:
            self._apply_unpowered()
            return
        q_ref = self.q_cmd if q is None else q
        qd_ref = self.qd_cmd if qd is None else qd
        q_meas, _ = self.joint_state()
        v = self._servo_velocity(q_ref, qd_ref, q_meas)
        p.setJointMotorControlArray(self.robot, ARM_JOINTS, p.VELOCITY_CONTROL,
                                    targetVelocities=v.tolist(), forces=ARM_MAX_FORCE_N_M,
                                    physicsClientId=cid)
        p.setJointMotorControlArray(self.robot, FINGER_JOINTS, p.POSITION_CONTROL,
                                    targetPositions=[self.gripper_cmd] * 2, forces=[40.0] * 2,
                                    physicsClientId=cid)

    def attach(self, name: str) -> None:
        """Rigidly attach object ``name`` to the hand where it is now (a grasp)."""
        if self.held is not None:
            self.detach()
        p, cid = self._p, self.cid
        body = self.objects[name]
        hs = p.getLinkState(self.robot, HAND_LINK, computeForwardKinematics=1, physicsClientId=cid)
        obj_pos, obj_orn = p.getBasePositionAndOrientation(body, physicsClientId=cid)
        inv_pos, inv_orn = p.invertTransform(hs[0], hs[1])  # constraint frames are COM frames
        rel_pos, rel_orn = p.multiplyTransforms(inv_pos, inv_orn, obj_pos, obj_orn)
        self.set_graspable(name)
        self._held_constraint = p.createConstraint(
            self.robot, HAND_LINK, body, -1, p.JOINT_FIXED, (0, 0, 0), rel_pos, (0, 0, 0),
            parentFrameOrientation=rel_orn, physicsClientId=cid)
        # the fingers hold by friction: 2 mu F_grasp at most (Gripper); more slips the object out
        p.changeConstraint(self._held_constraint, maxForce=self.grip_capacity_n, physicsClientId=cid)
        self._held_rel = (rel_pos, rel_orn)
        self.held = name

    def drop(self, why: str) -> None:
        """The held object leaves the fingers (not a release the task commanded): ``why`` is
        ``"power_off"`` (a gripper that is not self-locking lost power) or ``"slipped"``."""
        if self.held is None:
            return
        self.dropped.append((self.held, round(self.time_s, 6), why))
        self.detach()

    def held_offset_m(self) -> float:
        """How far the held object is from where the grasp holds it (m; 0 when none is held)."""
        pose = self._held_pose_for_hand()
        if pose is None:
            return 0.0
        pos, _ = self._p.getBasePositionAndOrientation(self.objects[self.held], physicsClientId=self.cid)
        return float(np.linalg.norm(np.asarray(pos) - np.asarray(pose[0])))

    def object_z(self) -> dict[str, float]:
        """Height (m) of every object's centre now."""
        return {n: float(self._p.getBasePositionAndOrientation(b, physicsClientId=self.cid)[0][2])
                for n, b in self.objects.items()}

    def set_graspable(self, name: str) -> None:
        """Stop the arm from colliding with object ``name`` (grasps are kinematic).

        The task planner calls this for every object it picks, so fingers that
        close on or let go of an object never kick it; such objects never add
        to ``contact_force`` either.
        """
        p, cid = self._p, self.cid
        body = self.objects[name]
        for link in range(-1, p.getNumJoints(self.robot, physicsClientId=cid)):
            p.setCollisionFilterPair(self.robot, body, link, -1, 0, physicsClientId=cid)
        self.graspable.add(name)

    def detach(self) -> None:
        """Let go of the held object (it falls under gravity)."""
        if self._held_constraint is not None:
            p, cid = self._p, self.cid
            p.removeConstraint(self._held_constraint, physicsClientId=cid)
        self._held_constraint = None
        self._held_rel = None
        self.held = None
