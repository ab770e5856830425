"""``ArmSim``: a Franka Panda cell in PyBullet (humans, objects, signals, controllers).

PyBullet is imported when an ``ArmSim`` is built, never at module import.
Every call passes ``physicsClientId``, so several simulations can live in one
process; with the same inputs a DIRECT simulation is bit-for-bit repeatable.
"""

from __future__ import annotations

import contextlib
import math
import os
import sys
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from ..errors import DependencyNotInstalled
from .._robot import PANDA_HOME_JOINTS_RAD
from ._limits import (BRAKE_DECEL_RAD_S2, BRAKE_ENGAGE_S, BRAKE_TORQUE_N_M, LIMIT_MARGIN_RAD,
                      RATED_DDDQ_MAX,
                      RATED_DDQ_MAX, RATED_DQ_MAX, RATED_Q_MAX, RATED_Q_MIN)
from ._model import PHYSICS_HZ, Gripper, Human, SimBlock, SimObject

__all__ = ["ArmSim", "HOME_JOINTS_RAD", "ARM_JOINTS", "EE_LINK", "BRAKE_TORQUE_N_M", "import_pybullet"]

#: Panda arm joint indices in ``panda.urdf`` (fingers are 9 and 10).
ARM_JOINTS = (0, 1, 2, 3, 4, 5, 6)
FINGER_JOINTS = (9, 10)
HAND_LINK = 8
#: The grasp-target frame between the fingertips.
EE_LINK = 11
#: A comfortable start pose (the Panda "ready" pose; the spec's default safe pose too).
HOME_JOINTS_RAD = PANDA_HOME_JOINTS_RAD
ARM_MAX_FORCE_N_M = (87.0, 87.0, 87.0, 87.0, 12.0, 12.0, 12.0)
_RATED_DQ = np.array(RATED_DQ_MAX)
_RATED_DDQ = np.array(RATED_DDQ_MAX)
_RATED_DDDQ = np.array(RATED_DDDQ_MAX)
_Q_MIN, _Q_MAX = np.array(RATED_Q_MIN), np.array(RATED_Q_MAX)
#: the share of the rated acceleration the servo's limit guard plans with
_LIMIT_SHARE = 0.8
_BRAKE_DECEL = np.array(BRAKE_DECEL_RAD_S2)
#: position feedback of the joint servo (1/s): velocity command = reference velocity
#: + _K_POS × (reference position − measured position), then the rated limits
_K_POS = 30.0
_DOWN_RPY = (math.pi, 0.0, 0.0)
_NO_HUMAN_M = 10.0
#: a held object more than this from where the grasp holds it has slipped out of the fingers
_SLIP_M = 0.02


def import_pybullet():
    """Import PyBullet (and pybullet_data) or raise :class:`DependencyNotInstalled`."""
    try:
        if "pybullet" in sys.modules:
            import pybullet
        else:
            with _quiet_fd(2):  # PyBullet's C code prints its build time to stderr
                import pybullet
        import pybullet_data
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise DependencyNotInstalled(
            'the simulator needs PyBullet: pip install "ethimon[sim]"') from exc
    return pybullet, pybullet_data


@contextlib.contextmanager
def _quiet_fd(fd: int):
    """Silence a file descriptor (C-level prints) for the duration of the block."""
    try:
        (sys.stdout if fd == 1 else sys.stderr).flush()
        saved = os.dup(fd)
    except (OSError, ValueError, AttributeError):  # no real fd 1 (e.g. captured)
        yield
        return
    try:
        with open(os.devnull, "w") as null:
            os.dup2(null.fileno(), fd)
            try:
                yield
            finally:
                os.dup2(saved, fd)
    finally:
        os.close(saved)


@dataclass
class Segment:
    """One task motion: min-jerk from the previous joint target to ``q`` in ``duration_s``."""

    q: np.ndarray
    duration_s: float
    gripper_m: float = 0.04
    attach: str | None = None   # object to attach at the end of this segment
    detach: bool = False        # release the held object at the end
    label: str = ""


@dataclass
class _HumanBody:
    spec: Human
    body: int
    times: np.ndarray = field(default_factory=lambda: np.zeros(0))
    xy: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    drive: int | None = None  # the constraint that walks a compliant person

    def xy_at(self, t: float) -> np.ndarray:
        ts = self.times
        return np.array([np.interp(t, ts, self.xy[:, 0]), np.interp(t, ts, self.xy[:, 1])])

    def _segment(self, t: float) -> int:
        """Index ``k`` of the segment ``times[k] <= t < times[k+1]`` (-1 before, n-1 after)."""
        return int(np.searchsorted(self.times, t, side="right")) - 1

    def velocity_at(self, t: float) -> np.ndarray:
        """The scripted horizontal velocity at ``t`` (0 standing, before and after the script)."""
        k = self._segment(t)
        if k < 0 or k >= len(self.times) - 1:
            return np.zeros(2)
        return (self.xy[k + 1] - self.xy[k]) / (self.times[k + 1] - self.times[k])

    def speeds(self) -> np.ndarray:
        """The scripted speed of every segment (m/s)."""
        if len(self.times) < 2:
            return np.zeros(0)
        return (np.linalg.norm(np.diff(self.xy, axis=0), axis=1) / np.diff(self.times))

    def walk_speed(self, t: float) -> float:
        """How fast the person walks at ``t``: the current segment's scripted speed; standing,
        the last segment walked (else the next one to walk): a person held up catches up at
        the speed the script gives them, never faster."""
        sp = self.speeds()
        if sp.size == 0:
            return 0.0
        k = self._segment(t)
        if 0 <= k < sp.size and sp[k] > 0:
            return float(sp[k])
        before = [v for v in sp[:max(k, 0)] if v > 0]
        if before:
            return float(before[-1])
        after = [v for v in sp[max(k, 0):] if v > 0]
        return float(after[0]) if after else 0.0


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

    Example:
        >>> sim = ArmSim(control_hz=60)              # doctest: +SKIP
        >>> sim.step(); sorted(sim.signals())         # doctest: +SKIP
        ['contact_force', 'ee_speed', 'hazard_distance', 'human_distance', 'human_speed', 'joint_speed_max', 'robot_speed_toward_human']
        >>> sim.close()                               # doctest: +SKIP
    """

    def __init__(self, *, control_hz: int = 60, gui: bool = False,
                 start_joints_rad: Sequence[float] | None = None,
                 humans: Sequence[Human] = (), objects: Sequence[SimObject] = (),
                 brakes: bool = True, gripper: Gripper | None = None) -> None:
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
        self.robot = p.loadURDF("franka_panda/panda.urdf", useFixedBase=True,
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
        self.powered = True
        self._brake_hold: np.ndarray | None = None
        self._off_substeps = 0
        self.max_joint_accel_substep = 0.0
        self.max_accel_ratio_substep = 0.0
        #: the furthest any joint has been past its rated position limit (rad; every physics step)
        self.max_past_limit_rad = 0.0
        self.link_speed_max = 0.0
        self.brakes = brakes
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
    def from_block(cls, block: SimBlock, *, gui: bool = False) -> ArmSim:
        """Build the cell a scenario's ``sim:`` block describes."""
        sim = cls(control_hz=block.control_hz, gui=gui, start_joints_rad=block.start_joints_rad,
                  humans=block.humans, objects=block.objects, brakes=block.brakes,
                  gripper=block.gripper)
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
        from ._control import _half_height, _half_width  # no cycle at import time
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

    # ------------------------------------------------------------ state

    def reset_joints(self, q: Sequence[float]) -> None:
        """Teleport the arm to ``q`` (zero velocity); fingers open."""
        p, cid = self._p, self.cid
        for j, v in zip(ARM_JOINTS, q):
            p.resetJointState(self.robot, j, float(v), 0.0, physicsClientId=cid)
        for j in FINGER_JOINTS:
            p.resetJointState(self.robot, j, 0.04, 0.0, physicsClientId=cid)
        self.q_cmd = np.asarray(q, dtype=float).copy()
        self._q_sub = self.q_cmd.copy()
        self._qd_sub = np.zeros(7)
        self.qd_cmd = np.zeros(7)
        self._v_out = np.zeros(7)
        self._a_out = np.zeros(7)

    def joint_state(self) -> tuple[np.ndarray, np.ndarray]:
        """Measured arm joint positions and velocities (7 each)."""
        st = self._p.getJointStates(self.robot, ARM_JOINTS, physicsClientId=self.cid)
        return np.array([s[0] for s in st]), np.array([s[1] for s in st])

    def applied_torques(self) -> np.ndarray:
        """Motor torques the last physics step applied to the 7 arm joints."""
        st = self._p.getJointStates(self.robot, ARM_JOINTS, physicsClientId=self.cid)
        return np.array([s[3] for s in st])

    def ee_pose(self) -> tuple[np.ndarray, np.ndarray]:
        """End-effector (grasp target) world position and quaternion."""
        ls = self._p.getLinkState(self.robot, EE_LINK, computeForwardKinematics=1,
                                  physicsClientId=self.cid)
        return np.array(ls[4]), np.array(ls[5])

    def ee_velocity(self) -> np.ndarray:
        """End-effector linear velocity (m/s, world frame)."""
        ls = self._p.getLinkState(self.robot, EE_LINK, computeLinkVelocity=1,
                                  computeForwardKinematics=1, physicsClientId=self.cid)
        return np.array(ls[6])

    def human_position(self, name: str) -> np.ndarray:
        """Capsule centre of human ``name``."""
        pos, _ = self._p.getBasePositionAndOrientation(self.humans[name].body,
                                                       physicsClientId=self.cid)
        return np.array(pos)

    def human_xy(self) -> dict[str, np.ndarray]:
        """Every person's horizontal position now (capsule centre)."""
        return {n: self.human_position(n)[:2] for n in self.humans}

    # ------------------------------------------------------------ signals

    def distance(self, body_a: int, body_b: int, max_m: float = _NO_HUMAN_M) -> float:
        """Minimum surface distance between two bodies (0 when touching), via getClosestPoints."""
        pts = self._p.getClosestPoints(body_a, body_b, max_m, physicsClientId=self.cid)
        if not pts:
            return max_m
        return max(0.0, min(pt[8] for pt in pts))

    def human_distance(self) -> float:
        """Minimum distance between any human and the arm (or the object it holds)."""
        best = _NO_HUMAN_M
        held = self.objects.get(self.held) if self.held else None
        for hb in self.humans.values():
            best = min(best, self.distance(self.robot, hb.body, best))
            if held is not None:
                best = min(best, self.distance(held, hb.body, best))
        return best

    def contact_force(self) -> float:
        """Largest contact normal force (N) of the arm against humans/objects.

        Counts arm–human, held-object–human and arm–object contacts; the
        objects the task picks (see :meth:`set_graspable`) and the floor are excluded.
        """
        p, cid = self._p, self.cid
        best = 0.0
        held = self.objects.get(self.held) if self.held else None
        others = [hb.body for hb in self.humans.values()]
        others += [b for n, b in self.objects.items() if n not in self.graspable]
        for b in others:
            for c in p.getContactPoints(self.robot, b, physicsClientId=cid):
                if c[9] > best:
                    best = c[9]
        if held is not None:
            for hb in self.humans.values():
                for c in p.getContactPoints(held, hb.body, physicsClientId=cid):
                    if c[9] > best:
                        best = c[9]
        return float(best)

    def hazard_distance(self) -> float:
        """Minimum distance between any hazard-tagged object and any human (m)."""
        best = _NO_HUMAN_M
        for name, spec in self.object_specs.items():
            if spec.hazard:
                for hb in self.humans.values():
                    best = min(best, self.distance(self.objects[name], hb.body, best))
        return best

    def human_speed(self, name: str) -> float:
        """Horizontal speed (m/s) of person ``name`` as a tracker measures it: the change of
        the measured position since the previous control cycle's reading (0 at the first)."""
        hb = self.humans[name]
        pos, _ = self._p.getBasePositionAndOrientation(hb.body, physicsClientId=self.cid)
        xy = np.array(pos[:2], dtype=float)
        last = self._track.get(name)
        if last is not None and abs(last[0] - self.time_s) < 1e-12:
            return last[2]  # read twice in one cycle: the same measurement
        v = 0.0 if last is None else float(np.linalg.norm(xy - last[1]) / (self.time_s - last[0]))
        self._track[name] = (self.time_s, xy, v)
        return v

    def closest_approach(self) -> tuple[float, str | None, float]:
        """``(distance, person, speed toward the person)`` of the closest point pair between the
        arm (or the held object) and any person.

        The speed is the velocity of the arm's closest point (its link's linear velocity plus
        ω × r; the hand's rigid motion for a held object) projected on the unit vector from it
        toward the person's closest point, 0 when it moves away (ISO/TS 15066 v_r is the speed
        toward the operator). ``(10, None, 0)`` with nobody in the scene."""
        p, cid = self._p, self.cid
        held = self.objects.get(self.held) if self.held else None
        best = (_NO_HUMAN_M, None, None, None)  # (d, person, point record, from the held object)
        for name, hb in self.humans.items():
            for body in (self.robot, held):
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
        st = p.getLinkState(self.robot, link, computeLinkVelocity=1, physicsClientId=cid)
        v = np.asarray(st[6]) + np.cross(np.asarray(st[7]), pa - np.asarray(st[0]))
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
        speeds = {n: self.human_speed(n) for n in self.humans}  # every track stays current
        return {
            "human_distance": float(dist),
            "ee_speed": float(np.linalg.norm(self.ee_velocity())),
            "contact_force": self.contact_force(),
            "joint_speed_max": float(np.max(np.abs(qd))),
            "hazard_distance": float(self.hazard_distance()),
            "human_speed": float(speeds[who]) if who is not None else 0.0,
            "robot_speed_toward_human": float(v_r),
        }

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

    def command_torque_off(self, *, brakes_already_engaged: bool = False) -> None:
        """Stop category 0 style: remove motor power at once.

        The motors apply no torque any more. With ``brakes`` (the default, as on a real
        Panda) the holding brakes engage :data:`~ethimon.sim._limits.BRAKE_ENGAGE_S` later
        (the joints coast meanwhile), then decelerate each joint at
        :data:`~ethimon.sim._limits.BRAKE_DECEL_RAD_S2` with a friction torque of at most
        :data:`BRAKE_TORQUE_N_M` (a larger external torque slips them) and hold it against
        gravity: both values are assumed (see the sim README). Without brakes, gravity and
        contacts act freely and the arm sags. ``brakes_already_engaged``: the brakes were
        engaged while the motors still held the arm (a stop 1 at standstill), so there is
        no coasting.
        """
        if self.powered:
            self.powered = False
            self._off_substeps = 0
            self._brake_hold = None
            if self.held is not None and not self.gripper.self_locking:
                self.drop("power_off")  # the unpowered fingers no longer press on the object
            if brakes_already_engaged:  # a stop 1 engaged them at standstill, motors holding
                self._off_substeps = int(math.ceil(BRAKE_ENGAGE_S * PHYSICS_HZ))
        self._apply_unpowered()

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
            stopped = np.abs(qd) < 0.01
            newly = stopped & np.isnan(self._brake_hold)
            self._brake_hold[newly] = q[newly]
            self._brake_hold[~stopped & (np.abs(q - np.nan_to_num(self._brake_hold, nan=0.0)) > 0.02)] = np.nan
            held = ~np.isnan(self._brake_hold)
            for j in range(7):
                if held[j]:
                    p.setJointMotorControl2(self.robot, ARM_JOINTS[j], p.POSITION_CONTROL,
                                            targetPosition=float(self._brake_hold[j]), targetVelocity=0.0,
                                            force=BRAKE_TORQUE_N_M[j], positionGain=1.0,
                                            velocityGain=1.0, physicsClientId=cid)
                else:
                    p.setJointMotorControl2(self.robot, ARM_JOINTS[j], p.VELOCITY_CONTROL,
                                            targetVelocity=float(target[j]), force=BRAKE_TORQUE_N_M[j],
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
        if self.speed_cap is not None:
            cap = np.minimum(cap, self.speed_cap)
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
        _, qd_prev = self.joint_state()
        compliant = [hb for hb in self.humans.values() if hb.drive is not None]
        for k in range(1, n + 1):
            for hb in compliant:
                self._drive_human(hb, self.time_s - self.dt + k * h)
            if self.powered:  # interpolate the reference at the physics rate
                s = k / n
                s2, s3 = s * s, s * s * s
                q_ref = ((2 * s3 - 3 * s2 + 1) * q0 + (s3 - 2 * s2 + s) * T * v0
                         + (-2 * s3 + 3 * s2) * q1 + (s3 - s2) * T * v1)
                qd_ref = ((6 * s2 - 6 * s) * q0 / T + (3 * s2 - 4 * s + 1) * v0
                          + (-6 * s2 + 6 * s) * q1 / T + (3 * s2 - 2 * s) * v1)
                self._q_sub, self._qd_sub = q_ref, qd_ref
                self._apply_command(q_ref, qd_ref)
            else:
                self._apply_unpowered()
                self._off_substeps += 1
            p.stepSimulation(physicsClientId=cid)
            _, qd = self.joint_state()
            acc = np.abs(qd - qd_prev) / h
            qd_prev = qd
            qm, _ = self.joint_state()
            past = max(float(np.max(qm - _Q_MAX)), float(np.max(_Q_MIN - qm)))
            if past > self.max_past_limit_rad:
                self.max_past_limit_rad = past
            peak = max(peak, float(np.max(np.abs(qd))))
            peak_a = max(peak_a, float(np.max(acc)))
            ratio_a = max(ratio_a, float(np.max(acc / _RATED_DDQ)))
        if not self.powered:  # a later re-power starts from the measured state
            self._q_sub, self._qd_sub = self.joint_state()
        self.max_joint_speed_substep = peak
        self.max_joint_accel_substep = peak_a
        self.max_accel_ratio_substep = ratio_a
        self.link_speed_max = self.link_speed()
        if self.held is not None and self.held_offset_m() > _SLIP_M:
            self.drop("slipped")  # pulled out beyond what the fingers' friction holds
        self.cycle += 1

    def link_speed(self) -> float:
        """Largest linear speed (m/s) of any arm link frame (links 1..7, hand, grasp frame;
        the fingers' own opening and closing left out) or of the held object, now."""
        p, cid = self._p, self.cid
        states = p.getLinkStates(self.robot, list(range(12)), computeLinkVelocity=1,
                                 physicsClientId=cid)
        # the fingers' own opening/closing is left out (their frames ride on the hand)
        best = max(math.sqrt(sum(c * c for c in st[6])) for i, st in enumerate(states)
                   if i not in FINGER_JOINTS)
        if self.held is not None:  # rigidly held: the hand's velocity at the object's centre
            hand = states[HAND_LINK]
            pos, _ = p.getBasePositionAndOrientation(self.objects[self.held], physicsClientId=cid)
            r = np.asarray(pos) - np.asarray(hand[0])
            v = np.asarray(hand[6]) + np.cross(np.asarray(hand[7]), r)
            best = max(best, float(np.linalg.norm(v)))
        return float(best)

    # ------------------------------------------------------------ kinematics

    def solve_ik(self, xyz: Sequence[float], rpy: Sequence[float] | None = None,
                 seed: Sequence[float] | None = None, iterations: int = 6) -> np.ndarray:
        """Joint angles that put the grasp target at ``xyz`` with orientation ``rpy``.

        Deterministic: seeds from ``seed`` (default the current pose), refines a
        few times, and restores the arm's state afterwards.
        """
        p, cid = self._p, self.cid
        q_now, qd_now = self.joint_state()
        seed_q = np.asarray(seed if seed is not None else q_now, dtype=float)
        orn = p.getQuaternionFromEuler(tuple(rpy) if rpy is not None else _DOWN_RPY)
        ranges = (self.upper - self.lower).tolist()
        q = seed_q.copy()
        for _ in range(iterations):
            for j, v in zip(ARM_JOINTS, q):
                p.resetJointState(self.robot, j, float(v), physicsClientId=cid)
            sol = p.calculateInverseKinematics(
                self.robot, EE_LINK, list(xyz), orn,
                lowerLimits=self.lower.tolist() + [0.0, 0.0],
                upperLimits=self.upper.tolist() + [0.04, 0.04],
                jointRanges=ranges + [0.04, 0.04],
                restPoses=list(HOME_JOINTS_RAD) + [0.04, 0.04],
                maxNumIterations=200, residualThreshold=1e-5, physicsClientId=cid)
            q = np.clip(np.array(sol[:7]), self.lower, self.upper)
        for j, v, w in zip(ARM_JOINTS, q_now, qd_now):
            p.resetJointState(self.robot, j, float(v), float(w), physicsClientId=cid)
        return q

    def fk(self, q: Sequence[float]) -> np.ndarray:
        """Grasp-target position for joint angles ``q`` (state restored afterwards)."""
        p, cid = self._p, self.cid
        q_now, qd_now = self.joint_state()
        for j, v in zip(ARM_JOINTS, q):
            p.resetJointState(self.robot, j, float(v), physicsClientId=cid)
        pos, _ = self.ee_pose()
        for j, v, w in zip(ARM_JOINTS, q_now, qd_now):
            p.resetJointState(self.robot, j, float(v), float(w), physicsClientId=cid)
        return pos

    # ------------------------------------------------------------ planning probes

    def rebase_reference(self) -> None:
        """Restart the joint servo's reference from the measured state (position and velocity).

        Response controllers call it when they take over, so the previous controller's
        reference (which may lead the arm) cannot pull it on."""
        q, qd = self.joint_state()
        self._q_sub, self._qd_sub = q, qd
        self.q_cmd, self.qd_cmd = q.copy(), qd.copy()
        self._v_out = qd.copy()
        self._a_out = np.zeros(7)

    def _held_pose_for_hand(self) -> tuple | None:
        if self.held is None or getattr(self, "_held_rel", None) is None:
            return None
        p, cid = self._p, self.cid
        hs = p.getLinkState(self.robot, HAND_LINK, computeForwardKinematics=1, physicsClientId=cid)
        return p.multiplyTransforms(hs[0], hs[1], *self._held_rel)

    def hazard_axis_angles_deg(self, qs: Sequence[Sequence[float]] | None = None) -> list[float] | None:
        """Angle (deg) between the held object's declared ``hazard_axis`` and the direction from
        the object's centre to the nearest person (the nearest point of their capsule axis), at
        each configuration in ``qs`` (default: now; state restored afterwards). 180 = pointed
        straight away. ``None`` when no object with a ``hazard_axis`` is held or there is nobody.
        """
        if self.held is None or not self.humans:
            return None
        axis = self.object_specs[self.held].hazard_axis
        if axis is None or getattr(self, "_held_rel", None) is None:
            return None
        p, cid = self._p, self.cid
        a_obj = np.asarray(axis, dtype=float) / float(np.linalg.norm(axis))
        people = []
        for hb in self.humans.values():
            c = self.human_position(hb.spec.name)
            r, h = hb.spec.radius_m, hb.spec.height_m
            people.append((c, max(h / 2 - r, 0.0)))

        def angle() -> float:
            pos, orn = self._held_pose_for_hand()
            pos = np.asarray(pos)
            rot = np.asarray(p.getMatrixFromQuaternion(orn)).reshape(3, 3)
            a = rot @ a_obj
            best, to = math.inf, None
            for c, half in people:
                z = min(max(pos[2], c[2] - half), c[2] + half)
                v = np.array([c[0], c[1], z]) - pos
                d = float(np.linalg.norm(v))
                if d < best:
                    best, to = d, v
            if to is None or best < 1e-9:
                return 0.0
            cos = float(np.dot(a, to) / best)
            return math.degrees(math.acos(min(1.0, max(-1.0, cos))))

        if qs is None:
            return [angle()]
        q_now, qd_now = self.joint_state()
        out = []
        try:
            for q in qs:
                for j, v in zip(ARM_JOINTS, q):
                    p.resetJointState(self.robot, j, float(v), physicsClientId=cid)
                out.append(angle())
        finally:
            for j, v, w in zip(ARM_JOINTS, q_now, qd_now):
                p.resetJointState(self.robot, j, float(v), float(w), physicsClientId=cid)
        return out

    def probe(self, qs: Sequence[Sequence[float]]) -> list[dict[str, float]]:
        """Clearances of the arm at each joint configuration in ``qs`` (state restored after).

        Each result: ``human`` (m, arm or held object to the nearest person), ``obstacle``
        (m, arm or held object to any object the task does not pick, and arm links 3..8 to
        the floor) and ``hazard`` (m, a held hazard-tagged object to the nearest person;
        10 when none). People stand where they are now.
        """
        p, cid = self._p, self.cid
        q_now, qd_now = self.joint_state()
        held = self.objects.get(self.held) if self.held else None
        held_pose = p.getBasePositionAndOrientation(held, physicsClientId=cid) if held is not None else None
        # resetting a body's pose zeroes its velocity: keep it, or the grasp constraint has to
        # re-accelerate the held object from rest in one physics step (issue 23: a 3 kg pot
        # yanked joint 5 at 16.9 x its rated acceleration at every re-plan)
        held_vel = p.getBaseVelocity(held, physicsClientId=cid) if held is not None else None
        hazardous = held is not None and bool(self.object_specs[self.held].hazard)
        obstacles = [b for n, b in self.objects.items() if n not in self.graspable and b != held]
        out = []
        try:
            for q in qs:
                for j, v in zip(ARM_JOINTS, q):
                    p.resetJointState(self.robot, j, float(v), physicsClientId=cid)
                if held is not None:
                    pose = self._held_pose_for_hand()
                    if pose is not None:
                        p.resetBasePositionAndOrientation(held, pose[0], pose[1], physicsClientId=cid)
                bodies = [self.robot] + ([held] if held is not None else [])
                h = hz = _NO_HUMAN_M
                for hb in self.humans.values():
                    for b in bodies:
                        h = min(h, self.distance(b, hb.body, h))
                    if hazardous:
                        hz = min(hz, self.distance(held, hb.body, hz))
                ob = 1.0
                for o in obstacles:
                    for b in bodies:
                        ob = min(ob, self.distance(b, o, ob))
                for link in range(2, 12):
                    pts = p.getClosestPoints(self.robot, self.plane, ob, linkIndexA=link,
                                             physicsClientId=cid)
                    if pts:
                        ob = min(ob, max(0.0, min(pt[8] for pt in pts)))
                if held is not None:
                    pts = p.getClosestPoints(held, self.plane, ob, physicsClientId=cid)
                    if pts:
                        ob = min(ob, max(0.0, min(pt[8] for pt in pts)))
                out.append({"human": float(h), "obstacle": float(ob), "hazard": float(hz)})
        finally:
            for j, v, w in zip(ARM_JOINTS, q_now, qd_now):
                p.resetJointState(self.robot, j, float(v), float(w), physicsClientId=cid)
            if held is not None:
                p.resetBasePositionAndOrientation(held, held_pose[0], held_pose[1], physicsClientId=cid)
                p.resetBaseVelocity(held, held_vel[0], held_vel[1], physicsClientId=cid)
        return out

    def link_points(self, q: Sequence[float]) -> np.ndarray:
        """World positions of the link frames (links 1..7, hand, fingers, grasp frame) at ``q``
        (state restored afterwards); with a held object, its position too."""
        p, cid = self._p, self.cid
        q_now, qd_now = self.joint_state()
        for j, v in zip(ARM_JOINTS, q):
            p.resetJointState(self.robot, j, float(v), physicsClientId=cid)
        states = p.getLinkStates(self.robot, list(range(12)), computeForwardKinematics=1,
                                 physicsClientId=cid)
        pts = [st[4] for st in states]
        pose = self._held_pose_for_hand()
        if pose is not None:
            pts.append(pose[0])
        for j, v, w in zip(ARM_JOINTS, q_now, qd_now):
            p.resetJointState(self.robot, j, float(v), float(w), physicsClientId=cid)
        return np.array(pts, dtype=float)

    def away_from_humans(self, xyz: Sequence[float], step_m: float) -> np.ndarray | None:
        """``xyz`` moved ``step_m`` horizontally away from the nearest person and 0.1 m up
        (``None`` with nobody in the scene)."""
        if not self.humans:
            return None
        x = np.asarray(xyz, dtype=float)
        best = min(self.humans.values(), key=lambda hb: float(np.linalg.norm(hb.xy_at(self.time_s) - x[:2])))
        d = x[:2] - best.xy_at(self.time_s)
        n = float(np.linalg.norm(d))
        if n < 1e-6:
            return None
        return np.array([x[0] + step_m * d[0] / n, x[1] + step_m * d[1] / n, x[2] + 0.1])

    # ------------------------------------------------------------ rendering

    def show_status(self, text: str) -> None:
        """GUI only: show ``text`` above the arm (replaces the previous status)."""
        if not self.gui:
            return
        p = self._p
        kw = {"replaceItemUniqueId": self._status_id} if self._status_id is not None else {}
        self._status_id = p.addUserDebugText(text, (0.0, 0.0, 1.2), textColorRGB=(0.8, 0.1, 0.1),
                                             textSize=1.6, physicsClientId=self.cid, **kw)

    def render(self, width: int = 480, height: int = 360) -> np.ndarray:
        """An RGB frame (H×W×3 uint8) from PyBullet's software TinyRenderer (headless)."""
        p, cid = self._p, self.cid
        view = p.computeViewMatrixFromYawPitchRoll((0.6, 0.3, 0.35), 2.7, -40, -25, 0, 2,
                                                   physicsClientId=cid)
        proj = p.computeProjectionMatrixFOV(50, width / height, 0.05, 10, physicsClientId=cid)
        _, _, rgba, _, _ = p.getCameraImage(width, height, view, proj, lightDirection=(1, 1, 2),
                                            renderer=p.ER_TINY_RENDERER, physicsClientId=cid)
        return np.asarray(rgba, dtype=np.uint8).reshape(height, width, 4)[:, :, :3]
