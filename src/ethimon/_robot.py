"""Robots as data: the robot descriptions that ``language``, ``lint``, ``verify`` and the simulator
read (lowest floor: imports only ``errors``).

A robot description is a YAML file (``src/ethimon/robots/<name>.yaml`` for the shipped ones:
``panda``, ``ur5e``; or a user's file that a spec names by path): its joints, their rated position
range, speed and acceleration (jerk and torque where known), the holding torque of each brake,
the rated payload and reach, and where every number comes from (``source``; ``estimate`` says
where no rated figure exists and why the number was taken). Data, never code: it is read with
the safe YAML loader (``language`` reads a spec's robot with located errors; the Panda's numbers
below are read from ``robots/panda.yaml`` when this module is imported) and checked by
:func:`robot_from_data`. Format: docs/robots.md.

The spec's default robot is the Franka Panda, the simulated arm: its "ready" pose is the spec's
default safe pose and where the simulated arm starts; its rated joint limits bound every
simulated controller; a safe pose outside the robot's rated position range is an error for
``ethimon lint``, a warning of ``ethimon verify`` (lint.safe_pose_range) and an error for
``check --sim``. The module-level names (``RATED_Q_MIN``, ``BRAKE_TABLE``, ...) are the Panda's,
derived from ``panda.yaml``, so that ``language``/``verify`` (which may not import ``sim``) and
``sim`` read the same numbers.

>>> len(PANDA_HOME_JOINTS_RAD)
7
>>> out_of_range(PANDA_HOME_JOINTS_RAD)
[]
>>> out_of_range((0.0, -0.785, 0.0, 0.2, 0.0, 1.571, 0.785))
[(4, 0.2, -3.0718, -0.0698)]
>>> shipped_robot("ur5e").n_joints
6
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .errors import SpecError

__all__ = ["PANDA_HOME_JOINTS_RAD", "RATED_SOURCE", "RATED_Q_MIN", "RATED_Q_MAX", "RATED_DQ_MAX", "TAU_MAX_N_M",
           "BRAKE_TABLE", "BRAKE_HOLDING_N_M", "BRAKE_SAFETY_FACTOR", "RATED_PAYLOAD_KG", "RATED_PAYLOAD_SOURCE",
           "PAYLOAD_OFFSET_M", "GRAVITY_M_S2", "gravity_torque", "gravity_torque_parts", "brake_problem",
           "RATED_DDQ_MAX", "RATED_DDDQ_MAX", "out_of_range", "safe_pose_problem",
           "ROBOTS_DIR", "SHIPPED_ROBOTS", "ROBOT_FORMAT", "Fact", "Robot", "robot_from_data", "shipped_robot",
           "PANDA"]

#: where the shipped robot descriptions live (package data)
ROBOTS_DIR = Path(__file__).resolve().parent / "robots"
#: the robots a spec may name (``robot: NAME``); any other value is the path of a robot YAML file
SHIPPED_ROBOTS: tuple[str, ...] = ("panda", "ur5e")
#: the format version a robot file states (``ethimon_robot: 1``)
ROBOT_FORMAT = 1

#: ``error(message, loc, hint=...)`` -> an exception (``SourceMap.error`` for a located one)
ErrorAt = Callable[..., BaseException]


@dataclass(frozen=True)
class Fact:
    """Numbers of one kind (a column over the joints, or one value) and where they come from."""

    values: tuple[float, ...]
    source: str
    estimate: str | None = None

    @property
    def cited(self) -> str:
        """The source as a reader needs it: ``"ESTIMATE: why"`` first where it is one."""
        return f"ESTIMATE: {self.estimate} (source: {self.source})" if self.estimate else self.source


@dataclass(frozen=True)
class Robot:
    """One robot description (see the module text): rated limits per joint, payload, reach,
    brakes, and :attr:`facts` (``key -> Fact``) citing every number."""

    name: str
    title: str
    joint_names: tuple[str, ...]
    q_min: tuple[float, ...]
    q_max: tuple[float, ...]
    dq_max: tuple[float, ...]
    ddq_max: tuple[float, ...]
    holding_n_m: tuple[float, ...]
    payload_kg: float
    reach_m: float
    home_joints_rad: tuple[float, ...] | None = None
    dddq_max: tuple[float, ...] | None = None
    tau_max_n_m: tuple[float, ...] | None = None
    facts: dict[str, Fact] = field(default_factory=dict, compare=False, repr=False)
    path: str = ""

    @property
    def n_joints(self) -> int:
        return len(self.joint_names)

    def out_of_range(self, joints: Sequence[float], margin_rad: float = 0.0) -> list[tuple[int, float, float, float]]:
        """Joints outside the rated position range: ``(joint number 1..n, value, q_min, q_max)``."""
        bad = []
        for j, (v, lo, hi) in enumerate(zip(joints, self.q_min, self.q_max)):
            if not (lo + margin_rad <= float(v) <= hi - margin_rad):
                bad.append((j + 1, float(v), lo, hi))
        return bad

    def safe_pose_problem(self, joints: Sequence[float]) -> str | None:
        """One sentence naming every safe-pose joint outside the rated range, or ``None`` (a pose
        of another length is checked, and worded, where the pose is used)."""
        if len(joints) != self.n_joints:
            return None
        bad = self.out_of_range(joints)
        if not bad:
            return None
        parts = [f"joint {j} = {v:g} rad (rated {lo:g} .. {hi:g})" for j, v, lo, hi in bad]
        return f"safe_pose.joints_rad is outside the {self.title}'s rated joint range: " + "; ".join(parts)

    def source(self, key: str) -> str:
        """Where the numbers of ``key`` (``position_min_rad``, ``payload_kg``, ...) come from."""
        return self.facts[key].cited


# ------------------------------------------------------------------ reading a description

_TOP = {"ethimon_robot": "the format version (1)", "name": "a short name", "title": "the robot's name in words",
        "payload_kg": "{value, source}", "reach_m": "{value, source}",
        "home_joints_rad": "{values, source} (optional)", "joints": "the joint table"}
_REQUIRED_TOP = ("ethimon_robot", "name", "title", "payload_kg", "reach_m", "joints")
#: joint columns: key -> (required, the check on each value, its words)
_COLUMNS: dict[str, tuple[bool, Callable[[float], bool], str]] = {
    "position_min_rad": (True, lambda v: True, "a number"),
    "position_max_rad": (True, lambda v: True, "a number"),
    "speed_rad_s": (True, lambda v: v > 0, "a number > 0"),
    "acceleration_rad_s2": (True, lambda v: v > 0, "a number > 0"),
    "jerk_rad_s3": (False, lambda v: v > 0, "a number > 0"),
    "torque_n_m": (False, lambda v: v > 0, "a number > 0"),
    "brake_holding_n_m": (True, lambda v: v >= 0, "a number >= 0"),
}
_FACT_KEYS = {"value", "values", "source", "estimate"}
_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_\-]*$")
_FORMAT_HINT = "see docs/robots.md for the format; src/ethimon/robots/ur5e.yaml is an example"


def _default_error(path: str) -> ErrorAt:
    def error(message: str, loc: tuple = (), *, hint: str | None = None) -> BaseException:
        where = ".".join(str(k) for k in loc)
        return SpecError(f"{message}{f' (at {where})' if where else ''}", path=path, hint=hint)
    return error


def _number(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def robot_from_data(data: Any, path: str = "<robot>", error: ErrorAt | None = None) -> Robot:
    """Check a parsed robot description (plain dicts, lists, numbers, strings) and build its
    :class:`Robot`; ``error(message, loc, hint=...)`` makes the exception raised for a problem
    (a located :class:`~ethimon.errors.SpecError` from ``SourceMap.error``)."""
    err = error or _default_error(path)
    if not isinstance(data, dict):
        raise err("a robot description must be a mapping of keys", (), hint=_FORMAT_HINT)
    for k in data:
        if k not in _TOP:
            raise err(f"unknown key {k!r} in a robot description", (k,),
                      hint="known keys: " + ", ".join(f"{n} ({w})" for n, w in _TOP.items()))
    for k in _REQUIRED_TOP:
        if k not in data:
            raise err(f"a robot description needs '{k}:' ({_TOP[k]})", (), hint=_FORMAT_HINT)
    if data["ethimon_robot"] != ROBOT_FORMAT or isinstance(data["ethimon_robot"], bool):
        raise err(f"unsupported robot format version {data['ethimon_robot']!r}", ("ethimon_robot",),
                  hint=f"this ethimon reads 'ethimon_robot: {ROBOT_FORMAT}'")
    for k in ("name", "title"):
        if not isinstance(data[k], str) or not data[k].strip():
            raise err(f"'{k}' must be a non-empty text", (k,))
    if not _NAME.match(data["name"]):
        raise err(f"robot name {data['name']!r} must start with a letter and hold letters, digits, '_' or '-'",
                  ("name",))
    facts: dict[str, Fact] = {}

    def fact(obj: Any, loc: tuple, n: int | None, check: Callable[[float], bool], words: str) -> Fact:
        key = "value" if n is None else "values"
        if not isinstance(obj, dict):
            raise err(f"expected {{{key}: ..., source: ...}}", loc,
                      hint="every number in a robot description says where it comes from (source:)")
        for k in obj:
            if k not in _FACT_KEYS or k == ("values" if n is None else "value"):
                raise err(f"unknown key {k!r}", loc + (k,), hint=f"expected {key}, source and optionally estimate")
        if key not in obj:
            raise err(f"missing '{key}:'", loc)
        src = obj.get("source")
        if not isinstance(src, str) or not src.strip():
            raise err("missing 'source:': where these numbers come from (a data sheet, a manual)", loc,
                      hint="name the document and its section; write 'estimate: why' as well where no "
                           "rated figure exists")
        est = obj.get("estimate")
        if est is not None and (not isinstance(est, str) or not est.strip()):
            raise err("'estimate' must say, in words, why the number was taken", loc + ("estimate",))
        raw = obj[key]
        if n is None:
            raw = [raw]
        elif not isinstance(raw, list) or len(raw) != n:
            got = f"{len(raw)} values" if isinstance(raw, list) else type(raw).__name__
            raise err(f"expected a list of {n} numbers (one per joint), got {got}", loc + (key,))
        for i, v in enumerate(raw):
            at = loc + ((key, i) if n is not None else (key,))
            if not _number(v) or not check(float(v)):
                raise err(f"expected {words}, got {v!r}", at)
        return Fact(tuple(float(v) for v in raw), src.strip(), est.strip() if est else None)

    positive = (lambda v: v > 0, "a number > 0")
    facts["payload_kg"] = fact(data["payload_kg"], ("payload_kg",), None, *positive)
    facts["reach_m"] = fact(data["reach_m"], ("reach_m",), None, *positive)
    joints = data["joints"]
    if not isinstance(joints, dict):
        raise err("'joints' must be a mapping: names and one column per fact", ("joints",), hint=_FORMAT_HINT)
    names = joints.get("names")
    if (not isinstance(names, list) or not 1 <= len(names) <= 16
            or not all(isinstance(x, str) and x.strip() for x in names)):
        raise err("'joints.names' must list the joints' names (1 to 16 texts), base first", ("joints", "names"))
    if len(set(names)) != len(names):
        raise err("'joints.names' names a joint twice", ("joints", "names"))
    n = len(names)
    for k in joints:
        if k != "names" and k not in _COLUMNS:
            raise err(f"unknown joint column {k!r}", ("joints", k),
                      hint="known: names, " + ", ".join(_COLUMNS))
    for k, (required, check, words) in _COLUMNS.items():
        if k in joints:
            facts[k] = fact(joints[k], ("joints", k), n, check, words)
        elif required:
            raise err(f"'joints' needs the column '{k}:'", ("joints",), hint=_FORMAT_HINT)
    q_min, q_max = facts["position_min_rad"].values, facts["position_max_rad"].values
    for j, (lo, hi) in enumerate(zip(q_min, q_max)):
        if not lo < hi:
            raise err(f"joint {j + 1} ({names[j]}): position_min_rad {lo:g} is not below position_max_rad {hi:g}",
                      ("joints", "position_min_rad", "values", j))
    home = None
    if "home_joints_rad" in data:
        facts["home_joints_rad"] = fact(data["home_joints_rad"], ("home_joints_rad",), n, lambda v: True, "a number")
        home = facts["home_joints_rad"].values
        for j, (v, lo, hi) in enumerate(zip(home, q_min, q_max)):
            if not lo <= v <= hi:
                raise err(f"home pose joint {j + 1} = {v:g} rad is outside its rated range {lo:g} .. {hi:g}",
                          ("home_joints_rad", "values", j))
    opt = {k: facts[k].values if k in facts else None for k in ("jerk_rad_s3", "torque_n_m")}
    return Robot(name=data["name"], title=data["title"].strip(), joint_names=tuple(names), q_min=q_min, q_max=q_max,
                 dq_max=facts["speed_rad_s"].values, ddq_max=facts["acceleration_rad_s2"].values,
                 holding_n_m=facts["brake_holding_n_m"].values, payload_kg=facts["payload_kg"].values[0],
                 reach_m=facts["reach_m"].values[0], home_joints_rad=home, dddq_max=opt["jerk_rad_s3"],
                 tau_max_n_m=opt["torque_n_m"], facts=facts, path=path)


_SHIPPED: dict[str, Robot] = {}


def shipped_robot(name: str) -> Robot:
    """A shipped robot description (``panda``, ``ur5e``), read once. The files are the package's
    own: read with PyYAML's safe loader (only plain values are built) and checked as any robot
    file; a spec's robot is read with the located-error loader of ``language``."""
    robot = _SHIPPED.get(name)
    if robot is None:
        if name not in SHIPPED_ROBOTS:
            raise SpecError(f"no shipped robot {name!r}", hint="shipped: " + ", ".join(SHIPPED_ROBOTS))
        import yaml
        path = os.fspath(ROBOTS_DIR / f"{name}.yaml")
        with open(path, encoding="utf-8") as fh:
            data = yaml.load(fh, Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader))  # noqa: S506 - safe loader
        robot = _SHIPPED[name] = robot_from_data(data, path)
    return robot


# ------------------------------------------------------------------ the Panda (the simulated arm)

#: the Franka Panda's description (``robots/panda.yaml``)
PANDA: Robot = shipped_robot("panda")
assert PANDA.home_joints_rad is not None and PANDA.dddq_max is not None and PANDA.tau_max_n_m is not None

#: The Franka Panda "ready" pose (rad, joints 1-7): the simulated arm's start pose and the spec's
#: default ``safe_pose.joints_rad``.
PANDA_HOME_JOINTS_RAD: tuple[float, ...] = PANDA.home_joints_rad

RATED_SOURCE = PANDA.source("position_min_rad")

#: rated joint position range (rad), joints 1..7
RATED_Q_MIN: tuple[float, ...] = PANDA.q_min
RATED_Q_MAX: tuple[float, ...] = PANDA.q_max
#: rated joint speed (rad/s)
RATED_DQ_MAX: tuple[float, ...] = PANDA.dq_max
#: rated joint acceleration (rad/s²)
RATED_DDQ_MAX: tuple[float, ...] = PANDA.ddq_max
#: rated joint jerk (rad/s³)
RATED_DDDQ_MAX: tuple[float, ...] = PANDA.dddq_max


def out_of_range(joints: Sequence[float], margin_rad: float = 0.0) -> list[tuple[int, float, float, float]]:
    """Joints outside the Panda's rated position range: ``(joint number 1..7, value, q_min, q_max)``."""
    return PANDA.out_of_range(joints, margin_rad)


def safe_pose_problem(joints: Sequence[float]) -> str | None:
    """One sentence naming every safe-pose joint outside the Panda's rated range, or ``None``."""
    return PANDA.safe_pose_problem(joints)


# ------------------------------------------------------------------ brakes, payload, gravity
#
# The Panda's, from panda.yaml; each number with where it comes from.

#: the Panda's joint torque limits τ_max (N·m), joints 1..7: FCI "Limits for Panda" (RATED_SOURCE)
TAU_MAX_N_M: tuple[float, ...] = PANDA.tau_max_n_m

#: The holding brake of every joint: ``(joint, holding torque N·m, source)``. Franka publishes no
#: holding torque for the Panda's brakes (not in the FCI documents, not in the product data
#: sheet): every number here is an ESTIMATE (``panda.yaml`` says so, and why). Why this estimate:
#: a Panda is sold to hold its rated payload at any pose when its brakes engage; the largest
#: gravity load of arm + 3 kg (:data:`RATED_PAYLOAD_KG` at the grasp point) over the rated range
#: is 79.3 N·m at joint 2 (shoulder forward, elbow nearly straight, the hand reaching out; 47.9 N·m
#: at joint 3, 39.1 at joint 4, 9.0 at joints 5 and 6: :func:`gravity_torque`, maximised from 30
#: starts per joint), so a brake that holds the rated payload must hold at least that; we take the
#: joint's own torque limit τ_max (87 N·m joints 1-4, 12 N·m joints 5-7), the most the drive can
#: hold powered, as the brake's holding torque. A cell whose brakes are weaker states its own
#: (``sim.brake_torque_n_m``).
BRAKE_TABLE: tuple[tuple[int, float, str], ...] = tuple(
    (j + 1, t, PANDA.source("brake_holding_n_m")) for j, t in enumerate(PANDA.holding_n_m))
#: holding torque per joint (N·m), joints 1..7 (the numbers of :data:`BRAKE_TABLE`)
BRAKE_HOLDING_N_M: tuple[float, ...] = tuple(t for _, t, _ in BRAKE_TABLE)
#: DECISION (the project's lead, issue 32): a brake must hold the gravity load of arm + payload with
#: this safety factor (holding torque >= factor x load) before a stop 0/1 may leave the arm to it; a
#: smaller margin lets the joints coast and sink while the brakes engage. The project's choice, in
#: the spirit of the brake-test margins of ISO 10218-1 / IEC 60204-1 practice (no standard gives
#: this number). The simulator escalates a stop 0/1 below it to a powered stop 2; lint.brakes uses it.
BRAKE_SAFETY_FACTOR = 1.5

#: rated payload (kg): Franka Emika, "Panda" product data sheet, "Payload 3 kg"
RATED_PAYLOAD_KG = PANDA.payload_kg
RATED_PAYLOAD_SOURCE = PANDA.source("payload_kg")
#: where a payload sits when none is stated (m, in the flange frame): the grasp point between
#: the fingertips, 0.105 m from the flange (panda.urdf, panda_grasptarget_hand)
PAYLOAD_OFFSET_M: tuple[float, float, float] = (0.0, 0.0, 0.105)

GRAVITY_M_S2 = 9.81

# The arm's gravity model: the kinematic and inertial data of panda.urdf as shipped in
# pybullet_data (franka_panda/panda.urdf; the simulated arm), per joint: origin xyz, origin
# roll about x (every Panda joint origin is a rotation about x only), then the child link's
# mass (kg) and centre of mass (m, in the link frame). The hand (0.81 kg, z 0.04 m after the
# flange) and both fingers (0.1 kg each, z 0.0784 m) ride on the flange.
_HALF_PI = 1.57079632679
_JOINTS = (((0.0, 0.0, 0.333), 0.0, 2.7, (0.0, -0.04, -0.05)),
           ((0.0, 0.0, 0.0), -_HALF_PI, 2.73, (0.0, -0.04, 0.06)),
           ((0.0, -0.316, 0.0), _HALF_PI, 2.04, (0.01, 0.01, -0.05)),
           ((0.0825, 0.0, 0.0), _HALF_PI, 2.08, (-0.03, 0.03, 0.02)),
           ((-0.0825, 0.384, 0.0), -_HALF_PI, 3.0, (0.0, 0.04, -0.12)),
           ((0.0, 0.0, 0.0), _HALF_PI, 1.3, (0.04, 0.0, 0.0)),
           ((0.088, 0.0, 0.0), _HALF_PI, 0.2, (0.0, 0.0, 0.08)))
_FLANGE_Z = 0.107
_FLANGE_MASSES = ((0.81, (0.0, 0.0, 0.04)), (0.2, (0.0, 0.0, 0.0784)))


def gravity_torque(joints: Sequence[float], payload_kg: float = 0.0,
                   payload_offset_m: Sequence[float] = PAYLOAD_OFFSET_M) -> tuple[float, ...]:
    """The torque (N·m) each joint must hold against gravity at ``joints`` (rad), arm + payload.

    ``payload_offset_m``: the payload's centre of mass in the flange frame. Signed as a motor
    or brake must apply it (what an inverse-dynamics model gives at rest). Pure Python (no
    numpy): ``lint`` uses it without importing the simulator.

    >>> round(abs(gravity_torque((0, 1.2, 0, -0.3, 0, 1.5, 0.785), 2.9)[1]), 1)
    71.6
    """
    arm, per_kg = gravity_torque_parts(joints, payload_offset_m)
    return tuple(a + payload_kg * b for a, b in zip(arm, per_kg))


def gravity_torque_parts(joints: Sequence[float], payload_offset_m: Sequence[float] = PAYLOAD_OFFSET_M
                         ) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """``(arm, per kg)``: the arm's own holding torque and that of 1 kg at ``payload_offset_m`` (the
    load is linear in the payload's mass)."""
    from math import cos, sin
    # R: the current frame's rotation (rows), o: its origin
    r00, r01, r02, r10, r11, r12, r20, r21, r22 = 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0
    ox = oy = oz = 0.0
    axes, origins, moments = [], [], []  # per joint: axis, origin, (mass, m x, m y) of its link
    for j in range(7):
        (x, y, z), roll, m, (cx, cy, cz) = _JOINTS[j]
        ox, oy, oz = ox + r00 * x + r01 * y + r02 * z, oy + r10 * x + r11 * y + r12 * z, oz + r20 * x + r21 * y + r22 * z
        c, s_ = cos(roll), sin(roll)  # R = R Rx(roll)
        r01, r02 = r01 * c + r02 * s_, -r01 * s_ + r02 * c
        r11, r12 = r11 * c + r12 * s_, -r11 * s_ + r12 * c
        r21, r22 = r21 * c + r22 * s_, -r21 * s_ + r22 * c
        c, s_ = cos(float(joints[j])), sin(float(joints[j]))  # R = R Rz(q)
        r00, r01 = r00 * c + r01 * s_, -r00 * s_ + r01 * c
        r10, r11 = r10 * c + r11 * s_, -r10 * s_ + r11 * c
        r20, r21 = r20 * c + r21 * s_, -r20 * s_ + r21 * c
        axes.append((r02, r12))
        origins.append((ox, oy))
        moments.append((m, m * (ox + r00 * cx + r01 * cy + r02 * cz), m * (oy + r10 * cx + r11 * cy + r12 * cz)))
    fx, fy = ox + r02 * _FLANGE_Z, oy + r12 * _FLANGE_Z
    m7, mx7, my7 = moments[6]
    for m, (cx, cy, cz) in _FLANGE_MASSES:  # the hand and fingers ride on link 7
        m7, mx7, my7 = m7 + m, mx7 + m * (fx + r00 * cx + r01 * cy + r02 * cz), my7 + m * (fy + r10 * cx + r11 * cy + r12 * cz)
    moments[6] = (m7, mx7, my7)
    px, py, pz = payload_offset_m
    ppx, ppy = fx + r00 * px + r01 * py + r02 * pz, fy + r10 * px + r11 * py + r12 * pz
    arm, per_kg = [0.0] * 7, [0.0] * 7
    M = MX = MY = 0.0
    g = GRAVITY_M_S2
    for i in range(6, -1, -1):  # suffix sums: everything the joint carries
        m, mx, my = moments[i]
        M, MX, MY = M + m, MX + mx, MY + my
        (ax, ay), (oxi, oyi) = axes[i], origins[i]
        # holding torque = g · (a_x Σm(p_y − o_y) − a_y Σm(p_x − o_x))
        arm[i] = g * (ax * (MY - M * oyi) - ay * (MX - M * oxi))
        per_kg[i] = g * (ax * (ppy - oyi) - ay * (ppx - oxi))
    return tuple(arm), tuple(per_kg)


def brake_problem(joints: Sequence[float], payload_kg: float = 0.0,
                  payload_offset_m: Sequence[float] = PAYLOAD_OFFSET_M,
                  holding_n_m: Sequence[float] = BRAKE_HOLDING_N_M) -> str | None:
    """``None`` when every brake holds arm + payload at ``joints``; else one sentence naming each
    joint whose gravity load exceeds its brake's holding torque (its load and its brake).

    >>> brake_problem((0, 1.2, 0, -0.3, 0, 1.5, 0.785), 2.9, holding_n_m=(60.0,) * 4 + (10.0,) * 3)
    'joint 2 needs 71.6 N·m against gravity (arm + 2.9 kg); its brake holds 60 N·m'
    """
    tau = gravity_torque(joints, payload_kg, payload_offset_m)
    bad = [(j + 1, abs(t), h) for j, (t, h) in enumerate(zip(tau, holding_n_m)) if abs(t) > h]
    if not bad:
        return None
    return "; ".join(f"joint {j} needs {t:.1f} N·m against gravity (arm + {payload_kg:g} kg); its "
                     f"brake holds {h:g} N·m" for j, t, h in bad)
