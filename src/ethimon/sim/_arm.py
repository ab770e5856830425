"""``ArmSim``: a Franka Panda cell in PyBullet (humans, objects, signals, controllers), a ``World``
and the parts that are handed it.

PyBullet is imported when an ``ArmSim`` is built, never at module import.
Every call passes ``physicsClientId``, so several simulations can live in one
process; with the same inputs a DIRECT simulation is bit-for-bit repeatable.

``ArmSim`` holds a ``World`` (``_world``: the client, the bodies, the grasp, the clock) and
composes parts that are handed it, each owning its own state: ``Sensors`` (``_sensing``),
``Kinematics`` (``_kinematics``), ``Actuators`` and ``Grasp`` (``_actuation``), ``Renderer``
(``_render``); this module builds them and steps the physics.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from operator import attrgetter

import numpy as np

from ._limits import BRAKE_TORQUE_N_M
from ._model import PHYSICS_HZ, Gripper, Human, SimBlock, SimObject
from ._cell import (ARM_JOINTS, EE_LINK, FINGER_JOINTS, HAND_LINK, HOME_JOINTS_RAD, Segment, _HumanBody, _Q_MAX,
                    _Q_MIN, _RATED_DDQ, _SLIP_M, _cross3, _half_height, _half_width, import_pybullet)
from ._actuation import Actuators, Grasp
from ._kinematics import Kinematics
from ._render import Renderer
from ._sensing import Sensors
from ._world import World

__all__ = ["ArmSim", "HOME_JOINTS_RAD", "ARM_JOINTS", "FINGER_JOINTS", "EE_LINK", "BRAKE_TORQUE_N_M", "Segment",
           "import_pybullet"]

#: the link frames ``link_speed`` looks at: links 1..7, hand, grasp frame (the fingers' own
#: opening and closing left out)
_LINKS_NOT_FINGERS = tuple(i for i in range(12) if i not in FINGER_JOINTS)


def _world_field(name: str, doc: str, *, settable: bool = False) -> property:
    """``ArmSim.<name>``: the :class:`World`'s field of that name (read by a C-level getter: the
    runner and the controllers read these every cycle)."""
    def put(self, value):
        setattr(self.world, name, value)
    return property(attrgetter(f"world.{name}"), put if settable else None, doc=doc)


def _part_field(part: str, name: str, doc: str) -> property:
    """``ArmSim.<name>``: the field of that name of one of its parts (read only)."""
    return property(attrgetter(f"{part}.{name}"), doc=doc)


class ArmSim:
    """A Panda arm on the floor at the origin, with humans and objects, at 240 Hz.

    One :meth:`step` advances one *control cycle* (``PHYSICS_HZ // control_hz``
    physics steps) using the joint command last given (:meth:`command_joints`,
    :meth:`command_torque_off`). :meth:`signals` reads the monitor's inputs
    from the physics state.

    Args:
        control_hz: control (and monitor) rate; must divide 240.
        gui: open the PyBullet GUI instead of DIRECT (needs a display).
        start_joints_rad: initial arm pose (default :data:`HOME_JOINTS_RAD`).
        humans, objects: :class:`~ethimon.sim.Human` / :class:`~ethimon.sim.SimObject`.
        visuals: load the arm's visual meshes (frames, GUI); ``False`` loads the same physics
            without them, about 5x faster (``run_sim`` does so when it records nothing).

    Example:
        >>> sim = ArmSim(control_hz=60)              # doctest: +SKIP
        >>> sim.step(); sorted(sim.signals())         # doctest: +SKIP
        ['contact_force', 'ee_speed', 'hazard_distance', 'human_distance', 'human_speed', 'joint_speed_max', 'robot_speed_toward_human']
        >>> sim.close()                               # doctest: +SKIP
    """

    def __init__(self, *, control_hz: int = 60, gui: bool = False,
                 start_joints_rad: Sequence[float] | None = None,
                 humans: Sequence[Human] = (), objects: Sequence[SimObject] = (),
                 brakes: bool = True, gripper: Gripper | None = None,
                 brake_torque_n_m: Sequence[float] | None = None, visuals: bool = True) -> None:
        if control_hz <= 0 or PHYSICS_HZ % control_hz:
            raise ValueError(f"control_hz={control_hz} must divide {PHYSICS_HZ}")
        p, pd = import_pybullet()
        #: each joint's brake holding torque (N·m): the cell's, else the Panda table (estimates)
        brake_torque = np.asarray(BRAKE_TORQUE_N_M if brake_torque_n_m is None else brake_torque_n_m,
                                  dtype=float)
        #: the state every part shares (the client, the bodies, the grasp, the clock)
        self.world = w = World(p, pd, control_hz=control_hz, gui=gui, visuals=visuals, brakes=brakes,
                               brake_torque=brake_torque, gripper=gripper if gripper is not None else Gripper())
        self._sense = Sensors(w)
        self._kin = Kinematics(w, self._sense)
        self._grasp = Grasp(w, self._kin)
        self._act = Actuators(w, self._sense, self._kin, self._grasp)
        self._render = Renderer(w)
        self._hermite_coef: dict = {}  # (substeps, dt) -> the Hermite weights of each physics step
        self.max_joint_speed_substep = 0.0  # max |qdot| over the last step's physics substeps
        self.max_joint_accel_substep = 0.0
        self.max_accel_ratio_substep = 0.0
        #: the furthest any joint has been past its rated position limit (rad; every physics step)
        self.max_past_limit_rad = 0.0
        self.link_speed_max = 0.0
        q0 = np.array(start_joints_rad if start_joints_rad is not None else HOME_JOINTS_RAD,
                      dtype=float)
        self.reset_joints(q0)  # also sets the servo's reference
        for o in objects:
            self.add_object(o)
        for h in humans:
            self.add_human(h)
        self._act.apply_command()

    # ------------------------------------------------------------ the world's and the parts' state

    _p = _world_field("p", "The PyBullet module this simulation talks to.")
    cid = _world_field("cid", "The PyBullet client id (-1 once closed).")
    gui = _world_field("gui", "Whether the PyBullet GUI is open.")
    control_hz = _world_field("control_hz", "Control (and monitor) rate (Hz).")
    substeps = _world_field("substeps", "Physics steps per control cycle.")
    dt = _world_field("dt", "One control cycle (s).")
    plane = _world_field("plane", "The floor's body id.")
    robot = _world_field("robot", "The arm's body id.")
    lower = _world_field("lower", "The URDF's lower joint limits (rad).")
    upper = _world_field("upper", "The URDF's upper joint limits (rad).")
    brakes = _world_field("brakes", "Whether the joints have holding brakes.")
    brake_torque = _world_field("brake_torque", "Each joint's brake holding torque (N·m).")
    gripper = _world_field("gripper", "The gripper (:class:`~ethimon.sim.Gripper`).")
    objects = _world_field("objects", "Object name -> body id.")
    object_specs = _world_field("object_specs", "Object name -> its :class:`~ethimon.sim.SimObject`.")
    graspable = _world_field("graspable", "Names of the objects the arm does not collide with (picked).")
    humans = _world_field("humans", "Person name -> their body.")
    held = _world_field("held", "The held object's name (``None``: nothing held).")
    time_s = _world_field("time_s", "Simulated time (s) at the end of the last cycle.", settable=True)
    cycle = _world_field("cycle", "Control cycles stepped.", settable=True)
    q_cmd = _part_field("_act", "q_cmd", "The joint reference of this cycle (rad).")
    qd_cmd = _part_field("_act", "qd_cmd", "The reference velocity of this cycle (rad/s).")
    gripper_cmd = _part_field("_act", "gripper_cmd", "The fingers' commanded opening (m).")
    max_velocity = _part_field("_act", "max_velocity", "The joint speed cap of the last command (rad/s).")
    speed_cap = _part_field("_act", "speed_cap", "The per-joint speed caps of the last command (rad/s).")
    powered = _part_field("_act", "powered", "Whether motor power is on.")
    brake_log = _part_field("_act", "brake_log", "``(t_s, what)`` for every power-off the brakes were checked for.")
    power_off_refused = _part_field("_act", "power_off_refused",
                                    "A stop 0/1 whose power-off was refused: the powered hold's reason.")
    max_travel_unpowered_rad = _part_field("_act", "max_travel_unpowered_rad",
                                           "Since the last power-off: the furthest any joint travelled (rad).")
    max_drop_unpowered_m = _part_field("_act", "max_drop_unpowered_m",
                                       "Since the last power-off: the furthest the grasp point fell (m).")
    brakes_engaged = _part_field("_act", "brakes_engaged",
                                 "Motor power is off and the brakes have engaged (after their engagement delay).")
    grip_capacity_n = _part_field("_grasp", "grip_capacity_n",
                                  "The most the fingers' friction holds a grasped object with (N).")
    dropped = _part_field("_grasp", "dropped",
                          "Objects that left the gripper other than by a release: (name, t_s, why).")

    # ------------------------------------------------------------ sensing (:class:`Sensors`)

    def reset_joints(self, q: Sequence[float]) -> None:
        """Teleport the arm to ``q`` (zero velocity); fingers open; the servo's reference restarts there."""
        self._sense.teleport(q)
        self._act.reset(q)

    def joint_state(self) -> tuple[np.ndarray, np.ndarray]:
        """Measured arm joint positions and velocities (7 each)."""
        return self._sense.joint_state()

    def joint_lists(self) -> tuple[list[float], list[float]]:
        """:meth:`joint_state` as two lists of floats (the same numbers, no arrays built)."""
        return self._sense.joint_lists()

    def applied_torques(self) -> np.ndarray:
        """Motor torques the last physics step applied to the 7 arm joints."""
        return self._sense.applied_torques()

    def ee_pose(self) -> tuple[np.ndarray, np.ndarray]:
        """End-effector (grasp target) world position and quaternion."""
        return self._sense.ee_pose()

    def ee_velocity(self) -> np.ndarray:
        """End-effector linear velocity (m/s, world frame)."""
        return self._sense.ee_velocity()

    def _grasp_z(self) -> float:
        return self._sense.grasp_z()

    def human_position(self, name: str) -> np.ndarray:
        """Capsule centre of human ``name``."""
        return self._sense.human_position(name)

    def human_xy(self) -> dict[str, np.ndarray]:
        """Every person's horizontal position now (capsule centre)."""
        return self._sense.human_xy()

    def distance(self, body_a: int, body_b: int, max_m: float = 10.0) -> float:
        """Minimum surface distance between two bodies (0 when touching), via getClosestPoints."""
        return self._sense.distance(body_a, body_b, max_m)

    def human_distance(self) -> float:
        """Minimum distance between any human and the arm (or the object it holds)."""
        return self._sense.human_distance()

    def contact_force(self) -> float:
        """Largest contact normal force (N) of the arm against humans/objects (:meth:`Sensors.contact_force`)."""
        return self._sense.contact_force()

    def hazard_distance(self) -> float:
        """Minimum distance between any hazard-tagged object and any human (m)."""
        return self._sense.hazard_distance()

    def human_speed(self, name: str) -> float:
        """Horizontal speed (m/s) of person ``name`` as a tracker measures it (:meth:`Sensors.human_speed`)."""
        return self._sense.human_speed(name)

    def closest_approach(self) -> tuple[float, str | None, float]:
        """``(distance, person, speed toward the person)`` (:meth:`Sensors.closest_approach`)."""
        return self._sense.closest_approach()

    def signals(self) -> dict[str, float]:
        """The monitor's inputs from the current physics state (:meth:`Sensors.signals`)."""
        return self._sense.signals()

    # ------------------------------------------------------------ kinematics (:class:`Kinematics`)

    def _set_arm(self, q: Sequence[float], qd: Sequence[float] | None = None) -> None:
        self._kin.set_arm(q, qd)

    def solve_ik(self, xyz: Sequence[float], rpy: Sequence[float] | None = None,
                 seed: Sequence[float] | None = None, iterations: int = 6) -> np.ndarray:
        """Joint angles that put the grasp target at ``xyz`` with orientation ``rpy`` (:meth:`Kinematics.solve_ik`)."""
        return self._kin.solve_ik(xyz, rpy, seed, iterations)

    def fk(self, q: Sequence[float]) -> np.ndarray:
        """Grasp-target position for joint angles ``q`` (state restored afterwards)."""
        return self._kin.fk(q)

    def hazard_axis_angles_deg(self, qs: Sequence[Sequence[float]] | None = None, *,
                               each: bool = False, until=None) -> list | None:
        """The held hazard's axis angle to the people (:meth:`Kinematics.hazard_axis_angles_deg`)."""
        return self._kin.hazard_axis_angles_deg(qs, each=each, until=until)

    def probe(self, qs: Sequence[Sequence[float]], until=None) -> list[dict[str, float]]:
        """Clearances of the arm at each joint configuration in ``qs`` (:meth:`Kinematics.probe`)."""
        return self._kin.probe(qs, until)

    def link_points(self, q: Sequence[float]) -> np.ndarray:
        """World positions of the link frames (and a held object) at ``q`` (state restored afterwards)."""
        return self._kin.link_points(q)

    def link_points_at(self, qs: Sequence[Sequence[float]]) -> list[np.ndarray]:
        """:meth:`link_points` at each configuration in ``qs``, the state read and restored once."""
        return self._kin.link_points_at(qs)

    def away_from_humans(self, xyz: Sequence[float], step_m: float) -> np.ndarray | None:
        """``xyz`` moved ``step_m`` horizontally away from the nearest person and 0.1 m up."""
        return self._kin.away_from_humans(xyz, step_m)

    def payload(self) -> tuple[float, tuple[float, float, float]]:
        """The held object as a payload: ``(mass kg, its centre of mass in the flange frame m)``."""
        return self._kin.payload()

    def gravity_load(self, q: Sequence[float] | None = None) -> np.ndarray:
        """The torque (N·m) each joint must hold against gravity now: arm + held payload."""
        return self._kin.gravity_load(q)

    def brake_problem_now(self) -> str | None:
        """``None`` when every brake holds arm + payload where the arm is; else why not."""
        return self._kin.brake_problem_now()

    # ------------------------------------------------------------ actuation (:class:`Actuators`, :class:`Grasp`)

    def rebase_reference(self) -> None:
        """Restart the joint servo's reference from the measured state (:meth:`Actuators.rebase_reference`)."""
        self._act.rebase_reference()

    def command_joints(self, q: Sequence[float], qd: Sequence[float] | None = None,
                       gripper_m: float | None = None, *,
                       max_velocity: float | None = None,
                       speed_cap: Sequence[float] | None = None) -> None:
        """Track the joint reference ``q`` this cycle; powers motors on (:meth:`Actuators.command_joints`)."""
        self._act.command_joints(q, qd, gripper_m, max_velocity=max_velocity, speed_cap=speed_cap)

    def command_torque_off(self, *, brakes_already_engaged: bool = False, why: str | None = None) -> None:
        """Stop category 0 style: remove motor power, if the brakes can hold the arm
        (:meth:`Actuators.command_torque_off`)."""
        self._act.command_torque_off(brakes_already_engaged=brakes_already_engaged, why=why)

    def brake_margin_problem(self) -> str | None:
        """``None`` when every brake holds arm + payload with the safety factor; else why not."""
        return self._act.brake_margin_problem()

    def _apply_command(self, q: np.ndarray | None = None, qd: np.ndarray | None = None) -> None:
        self._act.apply_command(q, qd)

    def attach(self, name: str) -> None:
        """Rigidly attach object ``name`` to the hand where it is now (a grasp)."""
        self._grasp.attach(name)

    def drop(self, why: str) -> None:
        """The held object leaves the fingers (``"power_off"`` or ``"slipped"``)."""
        self._grasp.drop(why)

    def detach(self) -> None:
        """Let go of the held object (it falls under gravity)."""
        self._grasp.detach()

    def held_offset_m(self) -> float:
        """How far the held object is from where the grasp holds it (m; 0 when none is held)."""
        return self._grasp.held_offset_m()

    def object_z(self) -> dict[str, float]:
        """Height (m) of every object's centre now."""
        return self._grasp.object_z()

    def set_graspable(self, name: str) -> None:
        """Stop the arm from colliding with object ``name`` (grasps are kinematic; :meth:`Grasp.set_graspable`)."""
        self._grasp.set_graspable(name)

    # ------------------------------------------------------------ rendering (:class:`Renderer`)

    def show_status(self, text: str) -> None:
        """GUI only: show ``text`` above the arm (replaces the previous status)."""
        self._render.show_status(text)

    def render(self, width: int = 480, height: int = 360) -> np.ndarray:
        """An RGB frame (H×W×3 uint8) from PyBullet's software TinyRenderer (headless)."""
        return self._render.render(width, height)

    # ------------------------------------------------------------ construction

    @classmethod
    def from_block(cls, block: SimBlock, *, gui: bool = False, visuals: bool = True) -> ArmSim:
        """Build the cell a scenario's ``sim:`` block describes (``visuals``: see :class:`ArmSim`)."""
        sim = cls(control_hz=block.control_hz, gui=gui, start_joints_rad=block.start_joints_rad,
                  humans=block.humans, objects=block.objects, brakes=block.brakes,
                  gripper=block.gripper, brake_torque_n_m=block.brake_torque_n_m, visuals=visuals)
        if block.start_xyz_m is not None:
            q = sim.solve_ik(block.start_xyz_m, seed=HOME_JOINTS_RAD)
            sim.reset_joints(q)
            sim._apply_command()
        if block.start_holding is not None:
            sim.hold_at_start(block.start_holding)
        problem = sim.start_collision()
        if problem is not None:
            key = "start_xyz_m" if block.start_xyz_m is not None else (
                "start_joints_rad" if block.start_joints_rad is not None else "objects")
            sim.close()
            from ..errors import SimError
            err = SimError(f"sim.{key}: {problem}")
            err.loc = ("sim", key)  # where the fix goes: the scenario turns it into file:line:col
            err.hint = ("move the start pose (or the object) so that the arm starts clear: a pose "
                        "inside a fixed object is a contact the scenario never meant")
            raise err
        return sim

    def start_collision(self) -> str | None:
        """What the arm (or the object it holds) penetrates now, more than 5 mm: an object the
        task does not pick (a fixed one, a shelf) or the floor; ``None`` when it starts clear."""
        w = self.world
        p, cid, robot = w.p, w.cid, w.robot
        held = w.objects.get(w.held) if w.held else None
        worst = None
        for name, b in w.objects.items():
            if name in w.graspable or b == held:
                continue
            for body, who in ((robot, "the arm"), (held, f"the held {w.held}")):
                if body is None:
                    continue
                for pt in p.getClosestPoints(body, b, 0.0, physicsClientId=cid):
                    if pt[8] < -0.005 and (worst is None or pt[8] < worst[0]):
                        link = f" (link {pt[3]})" if body == robot else ""
                        worst = (pt[8], f"{who}{link} starts {-pt[8] * 100:.1f} cm inside {name!r}")
        for link in range(2, 12):
            for pt in p.getClosestPoints(robot, w.plane, 0.0, linkIndexA=link, physicsClientId=cid):
                if pt[8] < -0.005 and (worst is None or pt[8] < worst[0]):
                    worst = (pt[8], f"the arm (link {link}) starts {-pt[8] * 100:.1f} cm below the floor")
        return None if worst is None else worst[1]

    def hold_at_start(self, name: str) -> None:
        """Teleport object ``name`` into the closed gripper and attach it."""
        w = self.world
        o = w.object_specs[name]
        pos, _ = self._sense.ee_pose()
        z = pos[2] - max(_half_height(o) - 0.02, 0.0)
        w.p.resetBasePositionAndOrientation(w.objects[name], (pos[0], pos[1], z),
                                            (0, 0, 0, 1), physicsClientId=w.cid)
        self._act.gripper_cmd = min(_half_width(o), 0.04)
        self._grasp.attach(name)

    def add_object(self, o: SimObject) -> int:
        """Add a rigid object; returns its body id."""
        return self.world.add_object(o)

    def add_human(self, h: Human) -> int:
        """Add a person as an upright capsule following its waypoints.

        By default a kinematic (massless, scripted) body: nothing stops it. With
        ``compliant: true`` a body of ``mass_kg`` dragged along its waypoints by a
        constraint of at most ``max_push_n``: an arm (braked or moving) can stop it, it can
        be pushed, and the contact force is limited by what the person can push with
        (plus the impact)."""
        return self.world.add_human(h)

    def _place_human(self, hb: _HumanBody, t: float) -> None:
        """Put the person where the waypoints say at ``t`` (teleport, zero velocity)."""
        self.world.place_human(hb, t)

    def close(self) -> None:
        """Disconnect from PyBullet (idempotent)."""
        self.world.close()

    def __enter__(self) -> ArmSim:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    # ------------------------------------------------------------ stepping

    def step(self) -> None:
        """Advance one control cycle: move humans, run the physics substeps.

        Afterwards :attr:`max_joint_speed_substep` (rad/s), :attr:`max_joint_accel_substep`
        (rad/s², from the velocity change of each physics step), :attr:`max_accel_ratio_substep`
        (the largest |q̈_j| / rated q̈_max,j) and :attr:`link_speed_max` (m/s, the fastest
        link frame or held object at the end of the cycle) describe the cycle.
        """
        w, act = self.world, self._act
        p, cid = w.p, w.cid
        T = w.dt
        t_s = w.time_s = (w.cycle + 1) * T
        for hb in w.humans.values():
            w.move_human(hb, t_s)
        peak = peak_a = ratio_a = 0.0
        n = w.substeps
        q0, v0 = act.q_sub, act.qd_sub
        q1 = act.q_cmd
        v1 = act.qd_cmd if act.hermite else (q1 - q0) / T
        if not act.hermite:
            v0 = v1
        h = 1.0 / PHYSICS_HZ
        get_states, robot = p.getJointStates, w.robot
        st = get_states(robot, ARM_JOINTS, physicsClientId=cid)
        js = ([s[0] for s in st], [s[1] for s in st])  # plain floats: what joint_state() holds
        qms, qds = [], [js[1]]
        refs = None
        compliant = [hb for hb in w.humans.values() if hb.drive is not None]
        drive, apply, step_physics = w.drive_human, act.apply_command, p.stepSimulation
        # the arm's measured state holds until the next physics step (moving people do not
        # change it): the servo reads it from there instead of asking PyBullet again
        w.js_step = js
        try:
            for k in range(1, n + 1):
                for hb in compliant:
                    drive(hb, t_s - T + k * h)
                if act.powered:  # interpolate the reference at the physics rate
                    if refs is None:  # every physics step's reference at once (the same numbers)
                        refs = self._hermite_refs(n, T, q0, v0, q1, v1)
                        ref_lists = (refs[0].tolist(), refs[1].tolist())
                    act.q_sub, act.qd_sub = refs[0][k - 1], refs[1][k - 1]
                    apply(ref_lists[0][k - 1], ref_lists[1][k - 1])
                else:
                    act.coast_step()
                w.js_step = None
                step_physics(physicsClientId=cid)
                st = get_states(robot, ARM_JOINTS, physicsClientId=cid)  # one read per physics step
                js = ([s[0] for s in st], [s[1] for s in st])
                w.js_step = js
                qms.append(js[0])
                qds.append(js[1])
        finally:
            w.js_step = None
        # the cycle's extremes from every physics step's reading at once (same order of
        # comparisons as step by step, so NaN and ties come out as before)
        qm_all, qd_all = np.array(qms), np.array(qds)
        acc = np.abs(qd_all[1:] - qd_all[:-1]) / h
        past_hi = (qm_all - _Q_MAX).max(axis=1).tolist()
        past_lo = (_Q_MIN - qm_all).max(axis=1).tolist()
        speed = np.abs(qd_all[1:]).max(axis=1).tolist()
        acc_max = acc.max(axis=1).tolist()
        ratio = (acc / _RATED_DDQ).max(axis=1).tolist()
        for k in range(n):
            past = max(past_hi[k], past_lo[k])
            if past > self.max_past_limit_rad:
                self.max_past_limit_rad = past
            peak = max(peak, speed[k])
            peak_a = max(peak_a, acc_max[k])
            ratio_a = max(ratio_a, ratio[k])
        if not act.powered:  # a later re-power starts from the measured state
            act.q_sub, act.qd_sub = self._sense.joint_state()
            act.track_unpowered()
        self.max_joint_speed_substep = peak
        self.max_joint_accel_substep = peak_a
        self.max_accel_ratio_substep = ratio_a
        self.link_speed_max = self.link_speed()
        if w.held is not None and self._grasp.held_offset_m() > _SLIP_M:
            self._grasp.drop("slipped")  # pulled out beyond what the fingers' friction holds
        w.cycle += 1

    def _hermite_refs(self, n: int, T: float, q0, v0, q1, v1) -> tuple[np.ndarray, np.ndarray]:
        """The cubic Hermite reference (position, velocity) at each of the ``n`` physics steps
        of a cycle of ``T`` s from ``(q0, v0)`` to ``(q1, v1)``: row ``k - 1`` is step ``k``.
        Computed for all steps in one go with the same operations, in the same order, as one
        step at a time (so bit for bit the same numbers)."""
        c = self._hermite_coef.get((n, T))
        if c is None:
            rows = []
            for k in range(1, n + 1):
                s = k / n
                s2, s3 = s * s, s * s * s
                rows.append((2 * s3 - 3 * s2 + 1, (s3 - 2 * s2 + s) * T, -2 * s3 + 3 * s2, (s3 - s2) * T,
                             6 * s2 - 6 * s, 3 * s2 - 4 * s + 1, -6 * s2 + 6 * s, 3 * s2 - 2 * s))
            c = self._hermite_coef[(n, T)] = [np.array(col, dtype=float)[:, None] for col in zip(*rows)]
        q_ref = c[0] * q0 + c[1] * v0 + c[2] * q1 + c[3] * v1
        qd_ref = c[4] * q0 / T + c[5] * v0 + c[6] * q1 / T + c[7] * v1
        return q_ref, qd_ref

    def link_speed(self) -> float:
        """Largest linear speed (m/s) of any arm link frame (links 1..7, hand, grasp frame;
        the fingers' own opening and closing left out) or of the held object, now."""
        w = self.world
        p, cid = w.p, w.cid
        states = p.getLinkStates(w.robot, list(range(12)), computeLinkVelocity=1,
                                 physicsClientId=cid)
        # the fingers' own opening/closing is left out (their frames ride on the hand)
        best = max([math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])  # = sum(c * c for c in v)
                    for v in [states[i][6] for i in _LINKS_NOT_FINGERS]])
        if w.held is not None:  # rigidly held: the hand's velocity at the object's centre
            hand = states[HAND_LINK]
            pos, _ = p.getBasePositionAndOrientation(w.objects[w.held], physicsClientId=cid)
            r = np.asarray(pos) - np.asarray(hand[0])
            v = np.asarray(hand[6]) + _cross3(hand[7], r)
            best = max(best, float(np.linalg.norm(v)))
        return float(best)
