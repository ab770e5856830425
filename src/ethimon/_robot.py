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

__all__ = ["PANDA_HOME_JOINTS_RAD", "RATED_SOURCE", "RATED_Q_MIN", "RATED_Q_MAX", "RATED_DQ_MAX",
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

