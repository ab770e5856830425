"""``ArmSim``: a Franka Panda cell in PyBullet (humans, objects, signals, controllers).

PyBullet is imported when an ``ArmSim`` is built, never at module import.
Every call passes ``physicsClientId``, so several simulations can live in one
process; with the same inputs a DIRECT simulation is bit-for-bit repeatable.

This module builds the world (the cell, its objects and people) and steps it; the other
jobs are parts of the class, one module each: ``_sensing`` (state and signals),
``_actuation`` (commands, brakes, grasp), ``_kinematics`` (IK/FK, route probing),
``_render`` (status text, frames); the shared facts are in ``_cell``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ._limits import BRAKE_TORQUE_N_M
from ._model import PHYSICS_HZ, Gripper, Human, SimBlock, SimObject
from ._cell import (ARM_JOINTS, EE_LINK, FINGER_JOINTS, HAND_LINK, HOME_JOINTS_RAD, Segment, _HumanBody, _Q_MAX,
                    _Q_MIN, _RATED_DDQ, _SLIP_M, _cross3, _half_height, _half_width, import_pybullet,
                    physics_only_urdf)
from ._actuation import _Actuation
from ._kinematics import _Kinematics
from ._render import _Rendering
from ._sensing import _Sensing

__all__ = ["ArmSim", "HOME_JOINTS_RAD", "ARM_JOINTS", "FINGER_JOINTS", "EE_LINK", "BRAKE_TORQUE_N_M", "Segment",
           "import_pybullet"]

#: the link frames ``link_speed`` looks at: links 1..7, hand, grasp frame (the fingers' own
#: opening and closing left out)
_LINKS_NOT_FINGERS = tuple(i for i in range(12) if i not in FINGER_JOINTS)


class ArmSim(_Sensing, _Actuation, _Kinematics, _Rendering):
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
        self._p = p
        self.control_hz = control_hz
        self.substeps = PHYSICS_HZ // control_hz
        self.dt = 1.0 / control_hz
        self.gui = gui
        self.cid = p.connect(p.GUI if gui else p.DIRECT)
        if self.cid < 0:
            raise RuntimeError("could not connect to PyBullet")
        cid = self.cid
        p.setAdditionalSearchPath(pd.getDataPath(), physicsClientId=cid)
        p.setGravity(0, 0, -9.81, physicsClientId=cid)
        p.setTimeStep(1.0 / PHYSICS_HZ, physicsClientId=cid)
        p.setPhysicsEngineParameter(deterministicOverlappingPairs=1, physicsClientId=cid)
        if gui:
            p.configureDebugVisualizer(p.COV_ENABLE_GUI, 0, physicsClientId=cid)
        self.plane = p.loadURDF("plane.urdf", physicsClientId=cid)
        # visuals=False: the same arm without its visual meshes (nothing is rendered), 5x faster to load
        urdf = "franka_panda/panda.urdf" if visuals or gui else physics_only_urdf(pd.getDataPath())
        self.robot = p.loadURDF(urdf, useFixedBase=True,
                                flags=p.URDF_USE_SELF_COLLISION_EXCLUDE_PARENT,
                                physicsClientId=cid)
        info = [p.getJointInfo(self.robot, j, physicsClientId=cid) for j in ARM_JOINTS]
        self.lower = np.array([i[8] for i in info])
        self.upper = np.array([i[9] for i in info])
        q0 = np.array(start_joints_rad if start_joints_rad is not None else HOME_JOINTS_RAD,
                      dtype=float)
        self.reset_joints(q0)  # also sets q_cmd and the substep setpoint _q_sub
        self.qd_cmd = np.zeros(7)
        self.gripper_cmd = 0.04
        self.max_velocity: float | None = None
        self.speed_cap: np.ndarray | None = None
        self._hermite = False
        self._hermite_coef: dict = {}  # (substeps, dt) -> the Hermite weights of each physics step
        self.powered = True
        self._brake_hold: np.ndarray | None = None
        self._off_substeps = 0
        self.max_joint_accel_substep = 0.0
        self.max_accel_ratio_substep = 0.0
        #: the furthest any joint has been past its rated position limit (rad; every physics step)
        self.max_past_limit_rad = 0.0
        self.link_speed_max = 0.0
        self.brakes = brakes
        #: each joint's brake holding torque (N·m): the cell's, else the Panda table (estimates)
        self.brake_torque = np.asarray(BRAKE_TORQUE_N_M if brake_torque_n_m is None else brake_torque_n_m,
                                       dtype=float)
        #: ``(t_s, what)`` for every power-off the brakes were checked for (issue 32): the gravity
        #: load of arm + payload against each brake; a refused power-off says why
        self.brake_log: list[tuple[float, str]] = []
        #: a stop 0/1 whose power-off was refused (the brakes cannot hold): the powered hold's reason
        self.power_off_refused: str | None = None
        self._refused_hold: tuple[np.ndarray, np.ndarray] | None = None
        #: since the last power-off: the furthest any joint travelled (rad) and the grasp point fell (m)
        self.max_travel_unpowered_rad = 0.0
        self.max_drop_unpowered_m = 0.0
        self._off_ref: tuple[np.ndarray, float] | None = None
        self.gripper = gripper if gripper is not None else Gripper()
        #: the most the fingers' friction holds a grasped object with (N)
        self.grip_capacity_n = 2.0 * self.gripper.friction_coefficient * self.gripper.grasp_force_n
        #: objects that left the gripper other than by a release: (name, t_s, "power_off"|"slipped")
        self.dropped: list[tuple[str, float, str]] = []
        self._track: dict[str, tuple[float, np.ndarray, float]] = {}  # name -> (t, xy, speed)
        self.graspable: set[str] = set()
        self._status_id: int | None = None
        self.time_s = 0.0
        self.cycle = 0
        self.max_joint_speed_substep = 0.0  # max |qdot| over the last step's physics substeps
        self.held: str | None = None
        self._held_constraint: int | None = None
        self.objects: dict[str, int] = {}
        self.object_specs: dict[str, SimObject] = {}
        for o in objects:
            self.add_object(o)
        self.humans: dict[str, _HumanBody] = {}
        for h in humans:
            self.add_human(h)
        self._apply_command()

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
        p, cid = self._p, self.cid
        held = self.objects.get(self.held) if self.held else None
        worst = None
        for name, b in self.objects.items():
            if name in self.graspable or b == held:
                continue
            for body, who in ((self.robot, "the arm"), (held, f"the held {self.held}")):
                if body is None:
                    continue
                for pt in p.getClosestPoints(body, b, 0.0, physicsClientId=cid):
                    if pt[8] < -0.005 and (worst is None or pt[8] < worst[0]):
                        link = f" (link {pt[3]})" if body == self.robot else ""
                        worst = (pt[8], f"{who}{link} starts {-pt[8] * 100:.1f} cm inside {name!r}")
        for link in range(2, 12):
            for pt in p.getClosestPoints(self.robot, self.plane, 0.0, linkIndexA=link, physicsClientId=cid):
                if pt[8] < -0.005 and (worst is None or pt[8] < worst[0]):
                    worst = (pt[8], f"the arm (link {link}) starts {-pt[8] * 100:.1f} cm below the floor")
        return None if worst is None else worst[1]

    def hold_at_start(self, name: str) -> None:
        """Teleport object ``name`` into the closed gripper and attach it."""
        o = self.object_specs[name]
        pos, _ = self.ee_pose()
        z = pos[2] - max(_half_height(o) - 0.02, 0.0)
        self._p.resetBasePositionAndOrientation(self.objects[name], (pos[0], pos[1], z),
                                                (0, 0, 0, 1), physicsClientId=self.cid)
        self.gripper_cmd = min(_half_width(o), 0.04)
        self.attach(name)

    def add_object(self, o: SimObject) -> int:
        """Add a rigid object; returns its body id."""
        p, cid = self._p, self.cid
        if o.shape == "box":
            col = p.createCollisionShape(p.GEOM_BOX, halfExtents=o.half_extents_m, physicsClientId=cid)
            vis_kw = {"halfExtents": o.half_extents_m}
        elif o.shape == "sphere":
            col = p.createCollisionShape(p.GEOM_SPHERE, radius=o.radius_m, physicsClientId=cid)
            vis_kw = {"radius": o.radius_m}
        else:
            col = p.createCollisionShape(p.GEOM_CYLINDER, radius=o.radius_m, height=o.height_m,
                                         physicsClientId=cid)
            vis_kw = {"radius": o.radius_m, "length": o.height_m}
        shape = {"box": p.GEOM_BOX, "sphere": p.GEOM_SPHERE, "cylinder": p.GEOM_CYLINDER}[o.shape]
        rgba = o.rgba or ((0.9, 0.2, 0.1, 1) if o.hazard else (0.3, 0.5, 0.9, 1))
        vis = p.createVisualShape(shape, rgbaColor=rgba, physicsClientId=cid, **vis_kw)
        body = p.createMultiBody(baseMass=0.0 if o.fixed else o.mass_kg,
                                 baseCollisionShapeIndex=col, baseVisualShapeIndex=vis,
                                 basePosition=o.xyz_m, physicsClientId=cid)
        self.objects[o.name] = body
        self.object_specs[o.name] = o
        return body

    def add_human(self, h: Human) -> int:
        """Add a person as an upright capsule following its waypoints.

        By default a kinematic (massless, scripted) body: nothing stops it. With
        ``compliant: true`` a body of ``mass_kg`` dragged along its waypoints by a
        constraint of at most ``max_push_n``: an arm (braked or moving) can stop it, it can
        be pushed, and the contact force is limited by what the person can push with
        (plus the impact)."""
        p, cid = self._p, self.cid
        # capsule "height" is the cylinder part; total height = cylinder + 2 r
        cyl = max(h.height_m - 2 * h.radius_m, 0.01)
        col = p.createCollisionShape(p.GEOM_CAPSULE, radius=h.radius_m, height=cyl,
                                     physicsClientId=cid)
        vis = p.createVisualShape(p.GEOM_CAPSULE, radius=h.radius_m, length=cyl,
                                  rgbaColor=(0.95, 0.75, 0.55, 1), physicsClientId=cid)
        body = p.createMultiBody(baseMass=h.mass_kg if h.compliant else 0.0,
                                 baseCollisionShapeIndex=col, baseVisualShapeIndex=vis,
                                 basePosition=(0, 0, h.height_m / 2), physicsClientId=cid)
        hb = _HumanBody(h, body, np.array([w.t_s for w in h.waypoints], dtype=float),
                        np.array([w.xy_m for w in h.waypoints], dtype=float))
        if h.compliant:
            # no floor friction (the drive does the walking); upright: a rotational inertia no
            # contact can tip, the orientation reset upright every cycle
            p.changeDynamics(body, -1, lateralFriction=0.0, localInertiaDiagonal=(1e4, 1e4, 1e4),
                             linearDamping=0.0, angularDamping=0.0, physicsClientId=cid)
            hb.drive = 1
        self.humans[h.name] = hb
        self._place_human(hb, 0.0)
        return body

    def _place_human(self, hb: _HumanBody, t: float) -> None:
        """Put the person where the waypoints say at ``t`` (teleport, zero velocity)."""
        x, y = hb.xy_at(t)
        pos = (float(x), float(y), hb.spec.height_m / 2)
        self._p.resetBasePositionAndOrientation(hb.body, pos, (0, 0, 0, 1), physicsClientId=self.cid)
        if hb.drive is not None:
            self._p.resetBaseVelocity(hb.body, (0, 0, 0), (0, 0, 0), physicsClientId=self.cid)

    def _move_human(self, hb: _HumanBody, t: float) -> None:
        """Advance a kinematic person to time ``t`` (placed where the waypoints say); a
        compliant one is walked by :meth:`_drive_human` at every physics step instead."""
        if hb.drive is None:
            self._place_human(hb, t)
            return
        p, cid = self._p, self.cid
        pos, _ = p.getBasePositionAndOrientation(hb.body, physicsClientId=cid)
        v, _ = p.getBaseVelocity(hb.body, physicsClientId=cid)
        p.resetBasePositionAndOrientation(hb.body, pos, (0, 0, 0, 1), physicsClientId=cid)
        p.resetBaseVelocity(hb.body, v, (0, 0, 0), physicsClientId=cid)

    def _drive_human(self, hb: _HumanBody, t: float) -> None:
        """One physics step of a compliant person's walk: a horizontal force of at most
        ``max_push_n`` toward the velocity the script asks for now.

        The wanted velocity is the script's velocity plus a pull (2 s⁻¹) toward the scripted
        position, never faster than the person walks (:meth:`_HumanBody.walk_speed`, the speed
        of the current segment or, standing, of the last one walked) nor faster than lets
        them stop at the scripted position with half their drive: so a person held up by
        the arm catches up at walking speed, never runs, and stops at the last waypoint."""
        p, cid = self._p, self.cid
        pos, _ = p.getBasePositionAndOrientation(hb.body, physicsClientId=cid)
        v, _ = p.getBaseVelocity(hb.body, physicsClientId=cid)
        xy, vxy = np.array(pos[:2]), np.array(v[:2])
        target = hb.xy_at(t)
        want = hb.velocity_at(t) + 2.0 * (target - xy)
        lim = hb.walk_speed(t)
        a_stop = 0.5 * hb.spec.max_push_n / hb.spec.mass_kg
        lim = min(lim, math.sqrt(2.0 * a_stop * float(np.linalg.norm(target - xy))))
        n = float(np.linalg.norm(want))
        if n > lim:
            want = want * (lim / n) if n > 0 else want
        f = hb.spec.mass_kg * (want - vxy) / 0.05  # 50 ms to reach the wanted velocity
        fn = float(np.linalg.norm(f))
        if fn > hb.spec.max_push_n:
            f = f * (hb.spec.max_push_n / fn)
        p.applyExternalForce(hb.body, -1, (float(f[0]), float(f[1]), 0.0), pos, p.WORLD_FRAME,
                             physicsClientId=cid)

    def close(self) -> None:
        """Disconnect from PyBullet (idempotent)."""
        if self.cid is not None and self.cid >= 0:
            try:
                self._p.disconnect(physicsClientId=self.cid)
            except Exception:  # already gone
                pass
            self.cid = -1

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
        p, cid = self._p, self.cid
        self.time_s = (self.cycle + 1) * self.dt
        for hb in self.humans.values():
            self._move_human(hb, self.time_s)
        peak = peak_a = ratio_a = 0.0
        n = self.substeps
        T = self.dt
        q0, v0 = self._q_sub, self._qd_sub
        q1 = self.q_cmd
        v1 = self.qd_cmd if self._hermite else (q1 - q0) / T
        if not self._hermite:
            v0 = v1
        h = 1.0 / PHYSICS_HZ
        get_states, robot = p.getJointStates, self.robot
        st = get_states(robot, ARM_JOINTS, physicsClientId=cid)
        js = ([s[0] for s in st], [s[1] for s in st])  # plain floats: what joint_state() holds
        qms, qds = [], [js[1]]
        refs = None
        compliant = [hb for hb in self.humans.values() if hb.drive is not None]
        # the arm's measured state holds until the next physics step (moving people do not
        # change it): the servo reads it from there instead of asking PyBullet again
        self._js_step = js
        try:
            for k in range(1, n + 1):
                for hb in compliant:
                    self._drive_human(hb, self.time_s - self.dt + k * h)
                if self.powered:  # interpolate the reference at the physics rate
                    if refs is None:  # every physics step's reference at once (the same numbers)
                        refs = self._hermite_refs(n, T, q0, v0, q1, v1)
                        ref_lists = (refs[0].tolist(), refs[1].tolist())
                    self._q_sub, self._qd_sub = refs[0][k - 1], refs[1][k - 1]
                    self._apply_command(ref_lists[0][k - 1], ref_lists[1][k - 1])
                else:
                    self._apply_unpowered()
                    self._off_substeps += 1
                self._js_step = None
                p.stepSimulation(physicsClientId=cid)
                st = get_states(robot, ARM_JOINTS, physicsClientId=cid)  # one read per physics step
                js = ([s[0] for s in st], [s[1] for s in st])
                self._js_step = js
                qms.append(js[0])
                qds.append(js[1])
        finally:
            self._js_step = None
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
        if not self.powered:  # a later re-power starts from the measured state
            self._q_sub, self._qd_sub = self.joint_state()
            self._track_unpowered()
        self.max_joint_speed_substep = peak
        self.max_joint_accel_substep = peak_a
        self.max_accel_ratio_substep = ratio_a
        self.link_speed_max = self.link_speed()
        if self.held is not None and self.held_offset_m() > _SLIP_M:
            self.drop("slipped")  # pulled out beyond what the fingers' friction holds
        self.cycle += 1

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
        p, cid = self._p, self.cid
        states = p.getLinkStates(self.robot, list(range(12)), computeLinkVelocity=1,
                                 physicsClientId=cid)
        # the fingers' own opening/closing is left out (their frames ride on the hand)
        best = max([math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])  # = sum(c * c for c in v)
                    for v in [states[i][6] for i in _LINKS_NOT_FINGERS]])
        if self.held is not None:  # rigidly held: the hand's velocity at the object's centre
            hand = states[HAND_LINK]
            pos, _ = p.getBasePositionAndOrientation(self.objects[self.held], physicsClientId=cid)
            r = np.asarray(pos) - np.asarray(hand[0])
            v = np.asarray(hand[6]) + _cross3(hand[7], r)
            best = max(best, float(np.linalg.norm(v)))
        return float(best)
