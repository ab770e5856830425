"""``World``: the state every part of :class:`~._arm.ArmSim` shares, owned in one ``__slots__``
class: the PyBullet client, the body ids, the arm's limits and brakes, the grasp, the clock, and the
objects and people (placed and walked here)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ._cell import ARM_JOINTS, _HumanBody, physics_only_urdf
from ._model import PHYSICS_HZ, Gripper, Human, SimObject

__all__ = ["World"]


class World:
    """One simulated Panda cell in PyBullet: what the sensors, the kinematics, the actuators and the
    renderer of an :class:`~._arm.ArmSim` all read (and the grasp and the clock, which they move).

    Built by :class:`~._arm.ArmSim`; the parts are handed it and keep no copy of its fields."""

    __slots__ = ("p", "cid", "gui", "control_hz", "substeps", "dt", "plane", "robot", "lower", "upper",
                 "brakes", "brake_torque", "gripper", "objects", "object_specs", "graspable", "humans",
                 "held", "held_constraint", "held_rel", "time_s", "cycle", "js_step")

    p: Any
    cid: int
    #: the arm's joint reading of this physics step (positions, velocities: lists of floats), set by
    #: ``ArmSim.step`` while nothing can move the arm before the next ``stepSimulation`` (``None``: ask
    #: PyBullet)
    js_step: tuple[list[float], list[float]] | None

    def __init__(self, p, pd, *, control_hz: int, gui: bool, visuals: bool, brakes: bool,
                 brake_torque: np.ndarray, gripper: Gripper) -> None:
        self.p = p
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
        self.brakes = brakes
        self.brake_torque = brake_torque
        self.gripper = gripper
        self.objects: dict[str, int] = {}
        self.object_specs: dict[str, SimObject] = {}
        self.graspable: set[str] = set()
        self.humans: dict[str, _HumanBody] = {}
        self.held: str | None = None
        self.held_constraint: int | None = None
        self.held_rel: tuple | None = None
        self.time_s = 0.0
        self.cycle = 0
        self.js_step = None

    # ------------------------------------------------------------ objects and people

    def add_object(self, o: SimObject) -> int:
        """Add a rigid object; returns its body id."""
        p, cid = self.p, self.cid
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
        """Add a person as an upright capsule following its waypoints (see ``ArmSim.add_human``)."""
        p, cid = self.p, self.cid
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
        self.place_human(hb, 0.0)
        return body

    def place_human(self, hb: _HumanBody, t: float) -> None:
        """Put the person where the waypoints say at ``t`` (teleport, zero velocity)."""
        x, y = hb.xy_at(t)
        pos = (float(x), float(y), hb.spec.height_m / 2)
        self.p.resetBasePositionAndOrientation(hb.body, pos, (0, 0, 0, 1), physicsClientId=self.cid)
        if hb.drive is not None:
            self.p.resetBaseVelocity(hb.body, (0, 0, 0), (0, 0, 0), physicsClientId=self.cid)

    def move_human(self, hb: _HumanBody, t: float) -> None:
        """Advance a kinematic person to time ``t`` (placed where the waypoints say); a
        compliant one is walked by :meth:`drive_human` at every physics step instead."""
        if hb.drive is None:
            self.place_human(hb, t)
            return
        p, cid = self.p, self.cid
        pos, _ = p.getBasePositionAndOrientation(hb.body, physicsClientId=cid)
        v, _ = p.getBaseVelocity(hb.body, physicsClientId=cid)
        p.resetBasePositionAndOrientation(hb.body, pos, (0, 0, 0, 1), physicsClientId=cid)
        p.resetBaseVelocity(hb.body, v, (0, 0, 0), physicsClientId=cid)

    def drive_human(self, hb: _HumanBody, t: float) -> None:
        """One physics step of a compliant person's walk: a horizontal force of at most
        ``max_push_n`` toward the velocity the script asks for now.

        The wanted velocity is the script's velocity plus a pull (2 s⁻¹) toward the scripted
        position, never faster than the person walks (:meth:`_HumanBody.walk_speed`, the speed
        of the current segment or, standing, of the last one walked) nor faster than lets
        them stop at the scripted position with half their drive: so a person held up by
        the arm catches up at walking speed, never runs, and stops at the last waypoint."""
        p, cid = self.p, self.cid
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
                self.p.disconnect(physicsClientId=self.cid)
            except Exception:  # already gone
                pass
            self.cid = -1
