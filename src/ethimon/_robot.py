"""Facts about the robot arm that the spec language, ``verify`` and the simulator need (lowest floor:
imports nothing).

The spec's default safe pose is the Franka Panda's "ready" pose, which is also
where the simulated arm starts; the Panda's rated joint limits bound every simulated
controller, and a safe pose outside the rated position range is an error for ``ethimon lint``,
``ethimon verify`` (lint.safe_pose_range) and ``check --sim``. They live here once so that
``language``/``verify`` (which may not import ``sim``) and ``sim`` read the same numbers.

Rated limits: Franka Emika, FCI documentation, "Robot and interface specifications", section
"Limits for Panda" (https://frankaemika.github.io/docs/control_parameters.html).

>>> len(PANDA_HOME_JOINTS_RAD)
7
>>> out_of_range(PANDA_HOME_JOINTS_RAD)
[]
>>> out_of_range((0.0, -0.785, 0.0, 0.2, 0.0, 1.571, 0.785))
[(4, 0.2, -3.0718, -0.0698)]
"""

from __future__ import annotations

from collections.abc import Sequence

__all__ = ["PANDA_HOME_JOINTS_RAD", "RATED_SOURCE", "RATED_Q_MIN", "RATED_Q_MAX", "RATED_DQ_MAX", "TAU_MAX_N_M",
           "BRAKE_TABLE", "BRAKE_HOLDING_N_M", "RATED_PAYLOAD_KG", "RATED_PAYLOAD_SOURCE",
           "PAYLOAD_OFFSET_M", "GRAVITY_M_S2", "gravity_torque", "gravity_torque_parts", "brake_problem",
           "RATED_DDQ_MAX", "RATED_DDDQ_MAX", "out_of_range", "safe_pose_problem"]

#: The Franka Panda "ready" pose (rad, joints 1-7): the simulated arm's start pose and the spec's
#: default ``safe_pose.joints_rad``.
PANDA_HOME_JOINTS_RAD: tuple[float, ...] = (0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785)

RATED_SOURCE = ("Franka Emika FCI documentation, 'Robot and interface specifications', Limits for "
                "Panda (https://frankaemika.github.io/docs/control_parameters.html)")

#: rated joint position range (rad), joints 1..7
RATED_Q_MIN: tuple[float, ...] = (-2.8973, -1.7628, -2.8973, -3.0718, -2.8973, -0.0175, -2.8973)
RATED_Q_MAX: tuple[float, ...] = (2.8973, 1.7628, 2.8973, -0.0698, 2.8973, 3.7525, 2.8973)
#: rated joint speed (rad/s)
RATED_DQ_MAX: tuple[float, ...] = (2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61)
#: rated joint acceleration (rad/s²)
RATED_DDQ_MAX: tuple[float, ...] = (15.0, 7.5, 10.0, 12.5, 15.0, 20.0, 20.0)
#: rated joint jerk (rad/s³)
RATED_DDDQ_MAX: tuple[float, ...] = (7500.0, 3750.0, 5000.0, 6250.0, 7500.0, 10000.0, 10000.0)


def out_of_range(joints: Sequence[float], margin_rad: float = 0.0) -> list[tuple[int, float, float, float]]:
    """Joints outside the rated position range: ``(joint number 1..7, value, q_min, q_max)``."""
    bad = []
    for j, (v, lo, hi) in enumerate(zip(joints, RATED_Q_MIN, RATED_Q_MAX)):
        if not (lo + margin_rad <= float(v) <= hi - margin_rad):
            bad.append((j + 1, float(v), lo, hi))
    return bad


def safe_pose_problem(joints: Sequence[float]) -> str | None:
    """One sentence naming every safe-pose joint outside the Panda's rated range, or ``None``."""
    if len(joints) != 7:
        return None  # the joint count is checked (and worded) where the pose is used
    bad = out_of_range(joints)
    if not bad:
        return None
    parts = [f"joint {j} = {v:g} rad (rated {lo:g} .. {hi:g})" for j, v, lo, hi in bad]
    return ("safe_pose.joints_rad is outside the Franka Panda's rated joint range: "
            + "; ".join(parts))



# ------------------------------------------------------------------ brakes, payload, gravity
#
# One data table per fact, each number with where it comes from, so that a robot-description
# format (issue 34) can take them over as they are.

#: the Panda's joint torque limits τ_max (N·m), joints 1..7: FCI "Limits for Panda" (RATED_SOURCE)
TAU_MAX_N_M: tuple[float, ...] = (87.0, 87.0, 87.0, 87.0, 12.0, 12.0, 12.0)

#: The holding brake of every joint: ``(joint, holding torque N·m, source)``. Franka publishes no
#: holding torque for the Panda's brakes (not in the FCI documents, not in the product data
#: sheet): every number here is an ESTIMATE. Why this estimate: a Panda is sold to hold its
#: rated payload at any pose when its brakes engage; the largest gravity load of arm + 3 kg
#: (:data:`RATED_PAYLOAD_KG` at the grasp point) over the rated range is 79.3 N·m at joint 2
#: (shoulder forward, elbow nearly straight, the hand reaching out; 47.9 N·m at joint 3, 39.1 at
#: joint 4, 9.0 at joints 5 and 6: :func:`gravity_torque`, maximised from 30 starts per joint),
#: so a brake that holds the rated payload must hold at least that; we take the joint's own torque limit τ_max (87 N·m joints 1-4,
#: 12 N·m joints 5-7), the most the drive can hold powered, as the brake's holding torque. A
#: cell whose brakes are weaker states its own (``sim.brake_torque_n_m``).
BRAKE_TABLE: tuple[tuple[int, float, str], ...] = tuple(
    (j + 1, t, "ESTIMATE: no Franka figure published; taken as the joint's torque limit tau_max "
     "(FCI 'Limits for Panda'), above the largest rated-payload gravity load (79.3 N·m, joint 2)")
    for j, t in enumerate(TAU_MAX_N_M))
#: holding torque per joint (N·m), joints 1..7 (the numbers of :data:`BRAKE_TABLE`)
BRAKE_HOLDING_N_M: tuple[float, ...] = tuple(t for _, t, _ in BRAKE_TABLE)

#: rated payload (kg): Franka Emika, "Panda" product data sheet, "Payload 3 kg"
RATED_PAYLOAD_KG = 3.0
RATED_PAYLOAD_SOURCE = "Franka Emika Panda data sheet: payload 3 kg"
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
