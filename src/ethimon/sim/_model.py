"""The scenario YAML's ``sim:`` block as pydantic v2 models.

No PyBullet here: the scenario loader validates ``sim:`` blocks even where
the ``sim`` extra is not installed. Every model forbids unknown keys, so a
typo such as ``duraton_s`` is named back to the user.

Example:
    >>> block = SimBlock.model_validate({
    ...     "duration_s": 3.0,
    ...     "task": [{"primitive": "reach", "xyz_m": [0.5, 0.0, 0.3]}],
    ...     "humans": [{"name": "worker", "waypoints": [{"t_s": 0, "xy_m": [1.5, 0]}]}],
    ... })
    >>> block.control_hz, block.task[0].primitive, block.humans[0].radius_m
    (60, 'reach', 0.2)
"""

from __future__ import annotations

import math
from typing import Annotated, Literal, Union

from pydantic import BaseModel, ConfigDict, Field, field_validator, model_validator

from ..errors import SimError

__all__ = [
    "PHYSICS_HZ",
    "SIGNAL_NAMES",
    "SimError",
    "SimBlock",
    "SimExpect",
    "Human",
    "Waypoint",
    "SimObject",
    "Dropout",
    "StuckAt",
    "Sensor",
    "Gripper",
    "InputChange",
    "Primitive",
    "Reach",
    "Pick",
    "Place",
    "HandOver",
    "Pour",
    "Wipe",
    "Wait",
]

#: Physics rate of every simulation (Hz); the control rate must divide it.
PHYSICS_HZ = 240

#: Signals the simulation produces each control cycle.
SIGNAL_NAMES = ("human_distance", "ee_speed", "contact_force", "joint_speed_max", "hazard_distance",
                "human_speed", "robot_speed_toward_human")

Vec3 = tuple[float, float, float]
Vec2 = tuple[float, float]


class _Model(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True)


# ---------------------------------------------------------------- primitives


class _Primitive(_Model):
    duration_s: float | None = Field(
        None, gt=0, description="minimum time for each motion segment; longer if the "
        "joint-speed budget (task_joint_speed_rad_s) needs it")


class _Target(_Primitive):
    xyz_m: Vec3 | None = Field(None, description="Cartesian end-effector target (IK)")
    joints_rad: tuple[float, float, float, float, float, float, float] | None = Field(
        None, description="joint target, instead of xyz_m")
    rpy_rad: Vec3 | None = Field(None, description="end-effector orientation; default points down")

    @model_validator(mode="after")
    def _one_target(self):
        if (self.xyz_m is None) == (self.joints_rad is None):
            raise ValueError("give exactly one of 'xyz_m' or 'joints_rad'")
        return self


class Reach(_Target):
    """Move the end effector to a Cartesian (``xyz_m``) or joint (``joints_rad``) target."""

    primitive: Literal["reach"]


class Pick(_Primitive):
    """Approach an object from above, grasp it, lift it."""

    primitive: Literal["pick"]
    object: str
    approach_height_m: float = Field(0.15, ge=0.0)


class Place(_Primitive):
    """Carry the held object to ``xyz_m`` (its resting point), release it, retreat."""

    primitive: Literal["place"]
    xyz_m: Vec3
    approach_height_m: float = Field(0.15, ge=0.0)


class HandOver(_Primitive):
    """Bring the held object to a hand-over point, hold it out, optionally let go."""

    primitive: Literal["hand_over"]
    xyz_m: Vec3
    human: str | None = Field(None, description="who receives it (documentation)")
    hold_s: float = Field(1.0, ge=0.0)
    release: bool = True


class Pour(_Primitive):
    """Move the held container above ``xyz_m``, tilt by ``tilt_rad``, hold, tilt back."""

    primitive: Literal["pour"]
    xyz_m: Vec3
    tilt_rad: float = Field(1.6, ge=0.0, le=math.pi)
    hold_s: float = Field(1.0, ge=0.0)


class Wipe(_Primitive):
    """Zig-zag over a surface rectangle centred at ``xyz_m``."""

    primitive: Literal["wipe"]
    xyz_m: Vec3
    length_m: float = Field(0.3, gt=0.0)
    width_m: float = Field(0.2, gt=0.0)
    passes: int = Field(3, ge=1, le=20)


class Wait(_Primitive):
    """Hold the current pose for ``duration_s``."""

    primitive: Literal["wait"]
    duration_s: float = Field(1.0, gt=0)


Primitive = Annotated[Union[Reach, Pick, Place, HandOver, Pour, Wipe, Wait],
                      Field(discriminator="primitive")]


# ---------------------------------------------------------------- the world


class Waypoint(_Model):
    """Where a human stands (capsule axis, floor coordinates) at time ``t_s``."""

    t_s: float = Field(ge=0.0)
    xy_m: Vec2


class Human(_Model):
    """A person as an upright capsule on the floor, moving between waypoints.

    Between waypoints the position is interpolated linearly; before the first
    and after the last the person stands still. Kinematic by default (nothing stops
    the person); ``compliant: true`` makes a body that an arm can stop and push.
    """

    name: str
    radius_m: float = Field(0.2, gt=0.0, le=1.0)
    height_m: float = Field(1.7, gt=0.0, le=2.5)
    waypoints: tuple[Waypoint, ...] = Field(min_length=1)
    compliant: bool = Field(False, description="a body that can be stopped and pushed (mass_kg, "
                            "walking with at most max_push_n) instead of a kinematic capsule")
    mass_kg: float = Field(40.0, gt=0.0, le=200.0, description="compliant: body mass (ISO/TS 15066 "
                           "table A.3 gives 40 kg as the effective mass of the chest/abdomen)")
    max_push_n: float = Field(150.0, gt=0.0, le=2000.0, description="compliant: largest force the "
                              "walking drive applies (what the person pushes with)")

    @field_validator("waypoints")
    @classmethod
    def _increasing(cls, v):
        ts = [w.t_s for w in v]
        if any(b <= a for a, b in zip(ts, ts[1:])):
            raise ValueError(f"waypoint times must increase, got {ts}")
        return v


class SimObject(_Model):
    """A rigid object on the floor or in the scene; ``hazard`` tags it (e.g. sharp, hot)."""

    name: str
    shape: Literal["box", "sphere", "cylinder"] = "box"
    xyz_m: Vec3
    half_extents_m: Vec3 = (0.03, 0.03, 0.03)
    radius_m: float = Field(0.03, gt=0.0)
    height_m: float = Field(0.1, gt=0.0)
    mass_kg: float = Field(0.2, ge=0.0)
    hazard: str | None = None
    hazard_axis: Vec3 | None = Field(
        None, description="for a hazard: the direction, in the object's own frame, that must "
        "point away from people (a blade's tip, a spout); while it is held, the safe-pose retreat "
        "turns the wrist (joint 7) so that it does")
    fixed: bool = False
    rgba: tuple[float, float, float, float] | None = None

    @model_validator(mode="after")
    def _axis(self):
        if self.hazard_axis is not None:
            if self.hazard is None:
                raise ValueError(f"object {self.name!r}: hazard_axis needs a hazard (e.g. hazard: sharp)")
            if not all(math.isfinite(c) for c in self.hazard_axis) or \
                    math.hypot(*self.hazard_axis) < 1e-6:
                raise ValueError(f"object {self.name!r}: hazard_axis must be a finite, non-zero "
                                 "direction, e.g. [1, 0, 0] for a blade along the object's x")
        return self


class Dropout(_Model):
    """A sensor fault: ``signal`` is NaN (or absent, ``mode: missing``) in [from_s, to_s)."""

    signal: str
    from_s: float = Field(ge=0.0)
    to_s: float
    mode: Literal["nan", "missing"] = "nan"

    @model_validator(mode="after")
    def _order(self):
        if self.to_s <= self.from_s:
            raise ValueError(f"to_s={self.to_s} must be after from_s={self.from_s}")
        return self


class StuckAt(_Model):
    """A stuck-at sensor fault: from ``from_s`` (until ``to_s``, default the end) ``signal``
    reads ``value``, or, without ``value``, keeps the reading it had at ``from_s`` (frozen)."""

    signal: str
    from_s: float = Field(ge=0.0)
    to_s: float | None = None
    value: float | None = None

    @model_validator(mode="after")
    def _order(self):
        if self.to_s is not None and self.to_s <= self.from_s:
            raise ValueError(f"to_s={self.to_s} must be after from_s={self.from_s}")
        if self.value is not None and not math.isfinite(self.value):
            raise ValueError("value must be a finite number (a NaN reading is a dropout: use dropouts:)")
        return self


class Sensor(_Model):
    """How one simulated signal is measured: the monitor sees the value of ``latency_s``
    earlier (rounded to whole control cycles) plus Gaussian noise of standard deviation
    ``noise`` (in the signal's unit, seeded by ``seed``), clipped at 0."""

    latency_s: float = Field(0.0, ge=0.0, le=5.0)
    noise: float = Field(0.0, ge=0.0)
    seed: int = Field(0, ge=0)


class Gripper(_Model):
    """The Franka Hand as the simulation models it: a held object is kept by the fingers'
    friction, at most ``2 × friction_coefficient × grasp_force_n`` (a larger pull slips it
    out); when motor power is removed the fingers hold only if ``self_locking``."""

    grasp_force_n: float = Field(70.0, gt=0.0, le=140.0, description="grasping force (N); 70 N "
                                 "continuous is the figure usually quoted for the Franka Hand (assumed)")
    friction_coefficient: float = Field(0.5, gt=0.0, le=2.0, description="finger pad/object "
                                        "friction (assumed)")
    self_locking: bool = Field(False, description="the fingers keep their grip without power "
                               "(assumed false: no Franka document available here says so)")


class InputChange(_Model):
    """From ``t_s`` on, feed these monitor inputs (e.g. the planner's next instruction
    raised ``p_unsafe``); they replace the run's constant inputs of the same name."""

    t_s: float = Field(ge=0.0)
    inputs: dict[str, float | tuple[float, ...] | bool]


class SimExpect(_Model):
    """What ``check --sim`` verifies about the simulated run (all optional)."""

    safe_pose_within_s: float | None = Field(
        None, gt=0.0, description="safe pose reached (within the spec's tolerance) this "
        "soon after the first override")
    min_separation_m: float | None = Field(
        None, ge=0.0, description="human-robot distance never below this")
    task_completed: bool | None = None
    released: bool | None = Field(None, description="an override was released before the end")
    response: Literal["none", "safe_pose", "stop_2", "stop_1", "stop_0"] | None = Field(
        None, description="most severe response the arm executed")
    max_reaction_cycles: int = Field(0, ge=0, description="cycles from override to controller switch")
    max_stop_speed_gain: float | None = Field(
        None, ge=0.0, description="peak joint speed (per physics step) while a stop controller "
        "runs, over the largest joint speed at its command; 1.0 = a stop never adds speed")
    max_accel_ratio: float | None = Field(
        None, gt=0.0, description="peak |joint acceleration| / the joint's rated acceleration "
        "while a response controller drives the arm (contact cycles left out)")
    standstill_within_s: float | None = Field(
        None, gt=0.0, description="every joint below 0.01 rad/s this soon after the first stop command")
    powered_off: bool | None = Field(None, description="motor power is off at the end of the run")
    near_human_m: float = Field(1.5, gt=0.0, description="'near a person' for "
                                "retreat_max_link_speed_m_s (true distance)")
    retreat_max_link_speed_m_s: float | None = Field(
        None, gt=0.0, description="fastest link frame or held object during the safe-pose "
        "retreat while a person is within near_human_m")
    retreat_min_separation_m: float | None = Field(
        None, ge=0.0, description="closest approach of arm (or held object) to a person during the retreat")
    max_contact_force_n: float | None = Field(None, ge=0.0, description="peak contact force of the run")
    min_hazard_distance_m: float | None = Field(
        None, ge=0.0, description="a hazard-tagged object never nearer a person than this "
        "(simulated hazard_distance) once the monitor has overridden")
    route: Literal["direct", "fold", "lift", "away", "back", "turn", "hold", "none"] | None = Field(
        None, description="the safe-pose route the planner took (hold: none was collision-free)")
    object_dropped: bool | None = Field(
        None, description="a held object left the gripper other than by the task's release "
        "(power removed from a gripper that is not self-locking, or pulled out beyond its friction)")
    min_hazard_axis_angle_deg: float | None = Field(
        None, ge=0.0, le=180.0, description="at the end of the run, the angle between a held "
        "object's hazard_axis and the direction from it to every person (the worst-placed) is at least this "
        "(over 90: pointed away)")
    max_human_speed_ratio: float | None = Field(
        None, gt=0.0, description="every person's measured horizontal speed at most this many "
        "times the fastest speed its waypoints script")
    max_human_overshoot_m: float | None = Field(
        None, ge=0.0, description="no person ends up further than this past its last waypoint "
        "(along the last segment walked)")
    max_past_limit_mrad: float | None = Field(
        None, ge=0.0, description="no joint ever further than this past its rated position "
        "limit (mrad), over the whole run, power-off included")
    acknowledgements: tuple[bool, ...] | None = Field(
        None, description="per acknowledge_at_s, in order: accepted (true) or refused (false)")
    starts: tuple[bool, ...] | None = Field(
        None, description="per start_at_s, in order: accepted (true) or refused (false)")
    reset_started_motion: bool | None = Field(
        None, description="false: the task never resumed after an accepted acknowledgement without "
        "an accepted start since (a reset never starts motion)")
    max_restart_speed_in_zone_m_s: float | None = Field(
        None, gt=0.0, description="after a restart, no link faster than this (+1 %) while a person "
        "is within the near-human zone (true distance)")
    min_response_s: float | None = Field(
        None, ge=0.0, description="every response lasted at least this long before the task "
        "resumed (no chatter)")
    task_stopped_object_missing: bool | None = Field(
        None, description="the task found the object it should carry not in the gripper (dropped) "
        "and stopped: the arm held in a stop 2, the task not resumed")
    object_end_z_m: dict[str, tuple[float, float]] | None = Field(
        None, description="object name -> [lowest, highest] height (m) of its centre at the end")
    max_drop_after_power_off_m: float | None = Field(
        None, ge=0.0, description="the grasp point (and a held payload) never lower than this "
        "below where it was when motor power went off (m; over every unpowered cycle)")
    brakes_escalated: bool | None = Field(
        None, description="a stop 0/1 whose power-off the brakes could not hold was turned into "
        "a powered hold (true), or none was (false)")


class SimBlock(_Model):
    """The ``sim:`` block of a scenario: what the simulated cell does."""

    control_hz: int = Field(60, gt=0, le=PHYSICS_HZ)
    duration_s: float = Field(6.0, gt=0.0, le=120.0)
    start_joints_rad: tuple[float, float, float, float, float, float, float] | None = None
    start_xyz_m: Vec3 | None = Field(None, description="start with the end effector here (IK), "
                                     "instead of start_joints_rad")
    start_holding: str | None = Field(None, description="object already in the gripper at t = 0")
    task_joint_speed_rad_s: float = Field(
        0.8, gt=0.0, description="peak joint speed of task motions (auto-timing)")
    stop_ramp_s: float = Field(0.25, gt=0.0, description="shortest deceleration time of "
                               "stop_1/stop_2 (longer when the rated acceleration or jerk needs it)")
    standstill_tolerance_rad: float = Field(
        0.02, gt=0.0, le=0.5, description="stop_2 standstill monitoring: a drift of any joint "
        "beyond this from the held pose escalates to stop_0")
    brakes: bool = Field(True, description="holding brakes engage when motor power is removed "
                                           "(stop_0 at once, stop_1 after its ramp)")
    brake_torque_n_m: tuple[float, float, float, float, float, float, float] | None = Field(
        None, description="holding torque of each joint's brake (N·m), as the cell's data sheet "
        "states it; default the Panda table (ethimon._robot.BRAKE_TABLE, estimates). Before any "
        "power-off the gravity load of arm + held object is checked against it: a stop 0/1 the "
        "brakes cannot hold keeps power on and holds (a powered stop 2), with the reason recorded")
    gripper: Gripper = Gripper()
    task: tuple[Primitive, ...] = ()
    humans: tuple[Human, ...] = ()
    objects: tuple[SimObject, ...] = ()
    dropouts: tuple[Dropout, ...] = ()
    sensors: dict[str, Sensor] = Field(
        default_factory=dict, description="per simulated signal: latency_s, noise (sd), seed")
    stuck_at: tuple[StuckAt, ...] = ()
    inputs_at: tuple[InputChange, ...] = ()
    acknowledge_at_s: tuple[float, ...] = Field(
        (), description="an operator acknowledges (GovernedArm.acknowledge) at these simulated "
        "times: refused while a rule fires, a fault is reported or a person is within the "
        "protective distance; otherwise Monitor.acknowledge releases the manual latches whose "
        "condition has held. A refused acknowledgement is not remembered")
    start_at_s: tuple[float, ...] = Field(
        (), description="an operator's start command (GovernedArm.start) at these simulated times: "
        "after an accepted acknowledgement motion resumes only on it (spec restart.start: command); "
        "refused while the monitor overrides or a person is within the protective distance")
    release_dwell_s: float = Field(
        1.0, ge=0.0, le=60.0, description="after an automatic release the task resumes only once "
        "the monitor has stayed released this long (the response carries on meanwhile), so task "
        "and response cannot chatter; an accepted acknowledgement resumes at once")
    record_at_s: tuple[float, ...] = Field(
        (), description="extra PNG frames at these simulated times (with --record); start, "
        "override, safe pose reached, release and end are always recorded")
    expect: SimExpect = SimExpect()

    @field_validator("control_hz")
    @classmethod
    def _divides(cls, v):
        if PHYSICS_HZ % v:
            ok = [h for h in range(1, PHYSICS_HZ + 1) if PHYSICS_HZ % h == 0 and h >= 10]
            raise ValueError(f"control_hz={v} must divide the physics rate {PHYSICS_HZ} Hz "
                             f"(one of {ok})")
        return v

    @field_validator("brake_torque_n_m")
    @classmethod
    def _brakes_finite(cls, v):
        if v is not None and not all(math.isfinite(t) and t >= 0.0 for t in v):
            raise ValueError(f"brake_torque_n_m must be 7 finite holding torques >= 0 N·m, got {list(v)}")
        return v

    @model_validator(mode="after")
    def _names(self):
        if self.start_joints_rad is not None and self.start_xyz_m is not None:
            raise ValueError("give at most one of 'start_joints_rad' or 'start_xyz_m'")
        seen: set[str] = set()
        for thing in (*self.humans, *self.objects):
            if thing.name in seen:
                raise ValueError(f"duplicate name {thing.name!r} among humans/objects")
            seen.add(thing.name)
        objs = {o.name for o in self.objects}
        if self.start_holding is not None and self.start_holding not in objs:
            raise ValueError(f"start_holding names unknown object {self.start_holding!r} "
                             f"(objects: {sorted(objs)})")
        for where, names in (("sensors", list(self.sensors)),
                             ("stuck_at", [f.signal for f in self.stuck_at])):
            bad = [n for n in names if n not in SIGNAL_NAMES]
            if bad:
                raise ValueError(f"{where} names {bad[0]!r}, which the simulation does not measure "
                                 f"(simulated signals: {', '.join(SIGNAL_NAMES)})")
        if self.expect.object_end_z_m:
            for name, (lo, hi) in self.expect.object_end_z_m.items():
                if name not in objs:
                    raise ValueError(f"expect.object_end_z_m names unknown object {name!r} "
                                     f"(objects: {sorted(objs)})")
                if hi < lo:
                    raise ValueError(f"expect.object_end_z_m[{name!r}] is [{lo:g}, {hi:g}]: lowest first")
        for i, ch in enumerate(self.inputs_at):
            sim_set = sorted(set(ch.inputs) & set(SIGNAL_NAMES))
            if sim_set:  # the simulation measures these; a scenario value would hide the physics
                raise ValueError(f"inputs_at[{i}] sets {sim_set}, which the simulation measures "
                                 "(a scenario value would hide what the physics says, e.g. a person "
                                 "at 0.04 m); use dropouts: for sensor faults")
        humans = {h.name for h in self.humans}
        for i, prim in enumerate(self.task):
            if isinstance(prim, Pick) and prim.object not in objs:
                raise ValueError(f"task[{i}] picks unknown object {prim.object!r} "
                                 f"(objects: {sorted(objs)})")
            if isinstance(prim, HandOver) and prim.human is not None and prim.human not in humans:
                raise ValueError(f"task[{i}] hands over to unknown human {prim.human!r} "
                                 f"(humans: {sorted(humans)})")
        return self
