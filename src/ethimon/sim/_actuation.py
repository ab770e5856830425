"""How :class:`~._arm.ArmSim` moves the arm: ``Actuators`` (joint commands within the rated limits,
torque off and the brakes, the unpowered arm) and ``Grasp`` (attach, drop, detach), each handed the
``World``."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ._limits import BRAKE_ENGAGE_S, BRAKE_SAFETY_FACTOR, LIMIT_MARGIN_RAD
from ._model import PHYSICS_HZ

from ._kinematics import Kinematics
from ._sensing import Sensors
from ._world import World
from ._cell import (ARM_JOINTS, ARM_MAX_FORCE_N_M, EE_LINK, FINGER_JOINTS, HAND_LINK, _BRAKE_DECEL, _K_POS,
                    _LIMIT_SHARE, _Q_MAX, _Q_MIN, _RATED_DDDQ, _RATED_DDQ, _RATED_DQ)

__all__ = ["Actuators", "Grasp"]

#: the least speed cap a stop leaves the servo for correcting a position error (rad/s). PyBullet's
#: velocity motor creeps under a heavy load (joint 4 at 0.02 rad/s with 3 kg held out); a stop that
#: capped the servo at the speed at its command (about 0.001 rad/s from rest) let the arm sink, and
#: a stop 2 drifted past its standstill tolerance and fell as a stop 0 (issue 32: 0.24 m with the
#: rated 3 kg at joint 2's worst pose). Below the 0.05 rad/s from which a stop's speed gain counts.
_HOLD_SPEED_RAD_S = 0.05


# ------------------------------------------------------------ per-physics-step math on plain floats
# (issue 32: numpy's call overhead on 7-vectors was most of the servo's time). Each helper computes
# what numpy computed, in the same order, element by element; tests/sim/test_sim_speed_exact.py
# pins them to the numpy code they replaced, bit for bit (NaN and signed zeros included).

def _max(a: float, b: float) -> float:
    """``np.maximum`` of two floats (NaN propagates)."""
    return a if (a != a or a > b) else b


def _min(a: float, b: float) -> float:
    """``np.minimum`` of two floats (NaN propagates)."""
    return a if (a != a or a < b) else b


def _clip(x: float, lo: float, hi: float) -> float:
    """``np.clip`` of one float (numpy's ``min(max(x, lo), hi)``, NaN propagating)."""
    t = x if (x != x or x > lo) else lo
    return t if (t != t or t < hi) else hi


_H = 1.0 / PHYSICS_HZ
_DQ = _RATED_DQ.tolist()
_DDQ = _RATED_DDQ.tolist()
_NEG_DDQ = (-_RATED_DDQ).tolist()
_DDDQ_H = (_RATED_DDDQ * _H).tolist()
_STOP_GAIN = (2.0 * _LIMIT_SHARE * _RATED_DDQ).tolist()   # 2 x share x rated acceleration
_Q_HI = (_Q_MAX - LIMIT_MARGIN_RAD).tolist()
_Q_LO = (_Q_MIN + LIMIT_MARGIN_RAD).tolist()
_BRAKE_STEP = (_BRAKE_DECEL / PHYSICS_HZ).tolist()         # speed one physics step of braking sheds
_BRAKE_STOPPED = [_max(s, 0.01) for s in _BRAKE_STEP]     # a joint at most this fast is stopped
_FLOAT_MAX = float(np.finfo(float).max)


def _servo_step(q_ref: list[float], qd_ref: list[float], q_meas: list[float], v_out, a_out,
                max_velocity: float | None, speed_cap: list[float] | None) -> tuple[list[float], list[float]]:
    """One physics step of the joint servo: ``(velocity command, acceleration)`` from the reference,
    the measured position and the last command ``v_out`` / acceleration ``a_out``.

    The velocity ``qd_ref + K (q_ref - q_meas)`` clipped to the rated speed, ``max_velocity`` and
    ``speed_cap`` (never below :data:`_HOLD_SPEED_RAD_S`), then to what the joint can shed before
    its rated position limit, then rate-limited to the rated acceleration and jerk."""
    if not isinstance(v_out, list):
        v_out = v_out.tolist()
    if not isinstance(a_out, list):
        a_out = a_out.tolist()
    h = _H
    v_new, a_new = [], []
    for j in range(7):
        v = qd_ref[j] + _K_POS * (q_ref[j] - q_meas[j])
        cap = _DQ[j]
        if max_velocity is not None:
            cap = _min(cap, float(max_velocity))
        if speed_cap is not None:  # never below what holding a loaded joint needs (issue 32)
            cap = _min(cap, _max(speed_cap[j], _HOLD_SPEED_RAD_S))
        v = _clip(v, -cap, cap)
        # never faster toward a rated position limit than the joint can shed before it (at
        # the planning share of its rated acceleration): no controller carries it past
        up = math.sqrt(_STOP_GAIN[j] * _max(_Q_HI[j] - q_meas[j], 0.0))
        dn = math.sqrt(_STOP_GAIN[j] * _max(q_meas[j] - _Q_LO[j], 0.0))
        v = _clip(v, -dn, up)
        a = _clip((v - v_out[j]) / h, _NEG_DDQ[j], _DDQ[j])
        a = _clip(a, a_out[j] - _DDDQ_H[j], a_out[j] + _DDDQ_H[j])
        a_new.append(a)
        v_new.append(v_out[j] + a * h)
    return v_new, a_new


def _brake_step(q: list[float], qd: list[float], hold: list[float]) -> list[float]:
    """One physics step of engaged brakes: updates ``hold`` in place (a joint that has stopped is
    held at the position it stopped at, NaN: not held; one moved more than 0.02 rad from its hold
    while not stopped is let go) and returns each joint's velocity target (its speed less one
    step of braking, never reversing)."""
    target = []
    for j in range(7):
        w = qd[j]
        sign = 1.0 if w > 0 else (-1.0 if w < 0 else (w if w != w else 0.0))  # np.sign
        target.append(sign * _max(abs(w) - _BRAKE_STEP[j], 0.0))
        # a joint slower than one physics step of braking is stopped by it (issue 32: a
        # 0.01 rad/s threshold left a loaded elbow creeping at 0.02 rad/s under a velocity
        # loop that never latched, 0.05 rad in 2.6 s with 68.6 of 87 N·m at joint 2)
        stopped = abs(w) <= _BRAKE_STOPPED[j]
        if stopped and hold[j] != hold[j]:
            hold[j] = q[j]
        if not stopped:
            b = hold[j]
            b = 0.0 if b != b else (_FLOAT_MAX if b == math.inf else (-_FLOAT_MAX if b == -math.inf else b))
            if abs(q[j] - b) > 0.02:
                hold[j] = math.nan
    return target


class Actuators:
    """The joint servo, the motor power and the brakes (a part of :class:`~._arm.ArmSim`): handed
    the :class:`~._world.World`, the :class:`~._sensing.Sensors` and :class:`~._kinematics.Kinematics`
    it reads the arm with and the :class:`Grasp` a power-off may drop; owns the servo's reference
    and memory and the power and brake state."""

    __slots__ = ("w", "_p", "_sense", "_kin", "_grasp", "q_cmd", "qd_cmd", "q_sub", "qd_sub", "_v_out", "_a_out",
                 "gripper_cmd", "max_velocity", "speed_cap", "hermite", "powered", "_brake_hold", "_off_substeps",
                 "brake_log", "power_off_refused", "_refused_hold", "_holding_refused",
                 "max_travel_unpowered_rad", "max_drop_unpowered_m", "_off_ref")

    def __init__(self, world: World, sensors: Sensors, kinematics: Kinematics, grasp: Grasp) -> None:
        self.w = world
        self._p = world.p
        self._sense = sensors
        self._kin = kinematics
        self._grasp = grasp
        # the servo: the cycle's reference (q_cmd, qd_cmd), the reference at the last physics step
        # (q_sub, qd_sub), its last command and acceleration (plain floats), caps, interpolation
        self.q_cmd = np.zeros(7)
        self.qd_cmd = np.zeros(7)
        self.q_sub = np.zeros(7)
        self.qd_sub = np.zeros(7)
        self._v_out = [0.0] * 7
        self._a_out = [0.0] * 7
        self.gripper_cmd = 0.04
        self.max_velocity: float | None = None
        self.speed_cap: np.ndarray | None = None
        self.hermite = False
        # power and brakes
        self.powered = True
        self._brake_hold: list[float] | None = None
        self._off_substeps = 0
        #: ``(t_s, what)`` for every power-off the brakes were checked for (issue 32): the gravity
        #: load of arm + payload against each brake; a refused power-off says why
        self.brake_log: list[tuple[float, str]] = []
        #: a stop 0/1 whose power-off was refused (the brakes cannot hold): the powered hold's reason
        self.power_off_refused: str | None = None
        self._refused_hold: tuple[np.ndarray, np.ndarray] | None = None
        self._holding_refused = False
        #: since the last power-off: the furthest any joint travelled (rad) and the grasp point fell (m)
        self.max_travel_unpowered_rad = 0.0
        self.max_drop_unpowered_m = 0.0
        self._off_ref: tuple[np.ndarray, float] | None = None

    # ------------------------------------------------------------ the servo's reference

    def reset(self, q: Sequence[float]) -> None:
        """The servo's state for an arm teleported to ``q`` at rest (``ArmSim.reset_joints``)."""
        self.q_cmd = np.asarray(q, dtype=float).copy()
        self.q_sub = self.q_cmd.copy()
        self.qd_sub = np.zeros(7)
        self.qd_cmd = np.zeros(7)
        self._v_out = [0.0] * 7  # the servo's last command and acceleration (plain floats)
        self._a_out = [0.0] * 7

    def rebase_reference(self) -> None:
        """Restart the joint servo's reference from the measured state (position and velocity).

        Response controllers call it when they take over, so the previous controller's
        reference (which may lead the arm) cannot pull it on."""
        q, qd = self._sense.joint_state()
        self.q_sub, self.qd_sub = q, qd
        self.q_cmd, self.qd_cmd = q.copy(), qd.copy()
        self._v_out = qd.tolist()
        self._a_out = [0.0] * 7

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
        if not self._holding_refused:  # any other command ends a refused power-off's hold
            self.power_off_refused = None
            self._refused_hold = None
        self.max_velocity = max_velocity
        self.speed_cap = None if speed_cap is None else np.abs(np.asarray(speed_cap, dtype=float))
        if not self.powered:  # re-powering: interpolate from where the arm is, as it moves
            self.q_sub, qd_meas = self._sense.joint_state()
            self.qd_sub = qd_meas.copy()
            self._v_out = qd_meas.tolist()
            self._a_out = [0.0] * 7
        self.q_cmd = np.clip(np.asarray(q, dtype=float), _Q_MIN + LIMIT_MARGIN_RAD,
                             _Q_MAX - LIMIT_MARGIN_RAD)
        self.hermite = qd is not None
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
            _, qd = self._sense.joint_state()
            if float(np.max(np.abs(qd))) >= 0.01 or self.brake_margin_problem() is not None:
                self.hold_refused()
                return
            self.power_off_refused = None
            self._refused_hold = None
            brakes_already_engaged = after_hold = True
        if self.powered:
            problem = self.brake_margin_problem() if self.w.brakes else None
            t = round(self.w.time_s, 6)
            if problem is not None:
                self.power_off_refused = (f"{why}: power-off refused, the brakes cannot hold the arm "
                                          f"({problem}): held powered (a stop 2)")
                self.brake_log.append((t, self.power_off_refused))
                self.hold_refused()
                return
            if self.w.brakes:
                load = np.abs(self._kin.gravity_load())
                j = int(np.argmax(load / np.maximum(self.w.brake_torque, 1e-9)))
                m, _ = self._kin.payload()
                self.brake_log.append((t, f"{why}: power off{' after the powered hold' if after_hold else ''}; "
                                          f"the brakes hold arm + {m:g} kg with the safety factor "
                                          f"{BRAKE_SAFETY_FACTOR:g} (joint {j + 1}: {load[j]:.1f} of "
                                          f"{self.w.brake_torque[j]:g} N·m)"))
            self.powered = False
            self._off_substeps = 0
            self._brake_hold = None
            self._off_ref = (self._sense.joint_state()[0].copy(), self._sense.grasp_z())
            if self.w.held is not None and not self.w.gripper.self_locking:
                self._grasp.drop("power_off")  # the unpowered fingers no longer press on the object
            if brakes_already_engaged:  # a stop 1 engaged them at standstill, motors holding
                self._off_substeps = int(math.ceil(BRAKE_ENGAGE_S * PHYSICS_HZ))
        self.apply_unpowered()

    def brake_margin_problem(self) -> str | None:
        """``None`` when every brake holds the gravity load of arm + held payload where the arm is
        with :data:`~ethimon._robot.BRAKE_SAFETY_FACTOR` (holding torque >= factor x load); else one
        sentence per joint short of it: its load, its brake, the margin and the factor."""
        load = np.abs(self._kin.gravity_load())
        hold = np.asarray(self.w.brake_torque, dtype=float)
        bad = np.flatnonzero(hold < BRAKE_SAFETY_FACTOR * load)
        if bad.size == 0:
            return None
        m, _ = self._kin.payload()
        return "; ".join(f"joint {j + 1} needs {load[j]:.1f} N·m against gravity (arm + {m:g} kg); its brake "
                         f"holds {hold[j]:g} N·m: {hold[j] / max(load[j], 1e-9):.2f} x, under the safety factor "
                         f"{BRAKE_SAFETY_FACTOR:g}" for j in bad)

    def hold_refused(self) -> None:
        """The powered hold of a refused power-off: from the state it had then, every joint
        decelerates at 80 % of its rated acceleration (never faster than it was) to rest and holds."""
        if self._refused_hold is None:
            q, qd = self._sense.joint_state()
            stop = q + qd * np.abs(qd) / (2.0 * _LIMIT_SHARE * _RATED_DDQ)
            stop = np.clip(stop, _Q_MIN + LIMIT_MARGIN_RAD, _Q_MAX - LIMIT_MARGIN_RAD)
            self._refused_hold = (stop, np.abs(qd) + 1e-3)
        q_hold, cap = self._refused_hold
        self._holding_refused = True
        try:
            self.command_joints(q_hold, np.zeros(7), speed_cap=cap)
        finally:
            self._holding_refused = False

    def track_unpowered(self) -> None:
        """After a physics cycle without power: how far every joint and the grasp point have moved
        since the power-off (:attr:`max_travel_unpowered_rad`, :attr:`max_drop_unpowered_m`)."""
        if self._off_ref is None:
            return
        q0, z0 = self._off_ref
        q, _ = self._sense.joint_state()
        self.max_travel_unpowered_rad = max(self.max_travel_unpowered_rad, float(np.max(np.abs(q - q0))))
        self.max_drop_unpowered_m = max(self.max_drop_unpowered_m, z0 - self._sense.grasp_z())

    @property
    def brakes_engaged(self) -> bool:
        """Motor power is off and the brakes have engaged (after their engagement delay)."""
        return (not self.powered and self.w.brakes
                and self._off_substeps / PHYSICS_HZ >= BRAKE_ENGAGE_S - 1e-9)

    def apply_unpowered(self) -> None:
        p, cid = self._p, self.w.cid
        if self.brakes_engaged:
            q, qd = self._sense.joint_lists()
            # a brake that has stopped its joint holds it where it stopped (friction up to its
            # torque), it does not creep: a velocity loop at 0 drifts under gravity (0.55 mrad/s
            # at a stretched elbow), so a stopped joint is held at its latched position
            # (:func:`_brake_step`: which joints are held, and the others' velocity targets)
            if self._brake_hold is None:
                self._brake_hold = [math.nan] * 7
            target = _brake_step(q, qd, self._brake_hold)
            hold, torque = self._brake_hold, self.w.brake_torque.tolist()
            for j in range(7):
                if hold[j] == hold[j]:  # held (not NaN)
                    p.setJointMotorControl2(self.w.robot, ARM_JOINTS[j], p.POSITION_CONTROL,
                                            targetPosition=hold[j], targetVelocity=0.0,
                                            force=torque[j], positionGain=1.0,
                                            velocityGain=1.0, physicsClientId=cid)
                else:
                    p.setJointMotorControl2(self.w.robot, ARM_JOINTS[j], p.VELOCITY_CONTROL,
                                            targetVelocity=target[j], force=torque[j],
                                            physicsClientId=cid)
        else:  # coasting: no motor torque, brakes not (yet) engaged
            self._brake_hold = None
            p.setJointMotorControlArray(self.w.robot, ARM_JOINTS, p.VELOCITY_CONTROL,
                                        targetVelocities=[0.0] * 7, forces=[0.0] * 7,
                                        physicsClientId=cid)
        if not self.w.gripper.self_locking:  # unpowered fingers are free (no holding torque)
            p.setJointMotorControlArray(self.w.robot, FINGER_JOINTS, p.VELOCITY_CONTROL,
                                        targetVelocities=[0.0, 0.0], forces=[0.0, 0.0],
                                        physicsClientId=cid)

    def coast_step(self) -> None:
        """One physics step without motor power (the brakes or coasting), counted toward the
        brakes' engagement."""
        self.apply_unpowered()
        self._off_substeps += 1

    def servo_velocity(self, q_ref, qd_ref, q_meas) -> list[float]:
        """The rated-limited motor velocity command for one physics step (:func:`_servo_step`)."""
        if not isinstance(q_ref, list):
            q_ref, qd_ref = q_ref.tolist(), qd_ref.tolist()
        v, self._a_out = _servo_step(q_ref, qd_ref, q_meas, self._v_out, self._a_out, self.max_velocity,
                                     None if self.speed_cap is None else self.speed_cap.tolist())
        self._v_out = v
        return v

    def apply_command(self, q: np.ndarray | None = None, qd: np.ndarray | None = None) -> None:
        """Set the motors for the next physics step: the servo's velocity command toward the reference
        ``(q, qd)`` (default the cycle's), the fingers' position; unpowered: the brakes or coasting."""
        w = self.w
        p, cid = self._p, w.cid
        if not self.powered:
            self.apply_unpowered()
            return
        q_ref = self.q_cmd if q is None else q
        qd_ref = self.qd_cmd if qd is None else qd
        q_meas = w.js_step  # the reading of this physics step, when the step loop has one
        q_meas = q_meas[0] if q_meas is not None else self._sense.joint_lists()[0]
        v = self.servo_velocity(q_ref, qd_ref, q_meas)
        robot = w.robot
        p.setJointMotorControlArray(robot, ARM_JOINTS, p.VELOCITY_CONTROL,
                                    targetVelocities=v, forces=ARM_MAX_FORCE_N_M,
                                    physicsClientId=cid)
        p.setJointMotorControlArray(robot, FINGER_JOINTS, p.POSITION_CONTROL,
                                    targetPositions=[self.gripper_cmd] * 2, forces=[40.0] * 2,
                                    physicsClientId=cid)


class Grasp:
    """The grasp (a part of :class:`~._arm.ArmSim`): attaching, dropping and letting go of objects
    (the held object is the :class:`~._world.World`'s); owns the fingers' capacity and the drops."""

    __slots__ = ("w", "_p", "_kin", "grip_capacity_n", "dropped")

    def __init__(self, world: World, kinematics: Kinematics) -> None:
        self.w = world
        self._p = world.p
        self._kin = kinematics
        #: the most the fingers' friction holds a grasped object with (N)
        self.grip_capacity_n = 2.0 * world.gripper.friction_coefficient * world.gripper.grasp_force_n
        #: objects that left the gripper other than by a release: (name, t_s, "power_off"|"slipped")
        self.dropped: list[tuple[str, float, str]] = []

    def attach(self, name: str) -> None:
        """Rigidly attach object ``name`` to the hand where it is now (a grasp)."""
        if self.w.held is not None:
            self.detach()
        p, cid = self._p, self.w.cid
        body = self.w.objects[name]
        hs = p.getLinkState(self.w.robot, HAND_LINK, computeForwardKinematics=1, physicsClientId=cid)
        obj_pos, obj_orn = p.getBasePositionAndOrientation(body, physicsClientId=cid)
        inv_pos, inv_orn = p.invertTransform(hs[0], hs[1])  # constraint frames are COM frames
        rel_pos, rel_orn = p.multiplyTransforms(inv_pos, inv_orn, obj_pos, obj_orn)
        self.set_graspable(name)
        self.w.held_constraint = p.createConstraint(
            self.w.robot, HAND_LINK, body, -1, p.JOINT_FIXED, (0, 0, 0), rel_pos, (0, 0, 0),
            parentFrameOrientation=rel_orn, physicsClientId=cid)
        # the fingers hold by friction: 2 mu F_grasp at most (Gripper); more slips the object out
        p.changeConstraint(self.w.held_constraint, maxForce=self.grip_capacity_n, physicsClientId=cid)
        self.w.held_rel = (rel_pos, rel_orn)
        self.w.held = name

    def drop(self, why: str) -> None:
        """The held object leaves the fingers (not a release the task commanded): ``why`` is
        ``"power_off"`` (a gripper that is not self-locking lost power) or ``"slipped"``."""
        if self.w.held is None:
            return
        self.dropped.append((self.w.held, round(self.w.time_s, 6), why))
        self.detach()

    def held_offset_m(self) -> float:
        """How far the held object is from where the grasp holds it (m; 0 when none is held)."""
        pose = self._kin.held_pose_for_hand()
        if pose is None:
            return 0.0
        pos, _ = self._p.getBasePositionAndOrientation(self.w.objects[self.w.held], physicsClientId=self.w.cid)
        return float(np.linalg.norm(np.asarray(pos) - np.asarray(pose[0])))

    def object_z(self) -> dict[str, float]:
        """Height (m) of every object's centre now."""
        return {n: float(self._p.getBasePositionAndOrientation(b, physicsClientId=self.w.cid)[0][2])
                for n, b in self.w.objects.items()}

    def set_graspable(self, name: str) -> None:
        """Stop the arm from colliding with object ``name`` (grasps are kinematic).

        The task planner calls this for every object it picks, so fingers that
        close on or let go of an object never kick it; such objects never add
        to ``contact_force`` either.
        """
        p, cid = self._p, self.w.cid
        body = self.w.objects[name]
        for link in range(-1, p.getNumJoints(self.w.robot, physicsClientId=cid)):
            p.setCollisionFilterPair(self.w.robot, body, link, -1, 0, physicsClientId=cid)
        self.w.graspable.add(name)

    def detach(self) -> None:
        """Let go of the held object (it falls under gravity)."""
        if self.w.held_constraint is not None:
            p, cid = self._p, self.w.cid
            p.removeConstraint(self.w.held_constraint, physicsClientId=cid)
        self.w.held_constraint = None
        self.w.held_rel = None
        self.w.held = None
