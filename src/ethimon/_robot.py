"""Facts about the robot arm that both the spec language and the simulator need (lowest floor: imports nothing).

The spec's default safe pose is the Franka Panda's "ready" pose, which is also
where the simulated arm starts; it lives here once so that ``spec`` (below
``sim``) and ``sim`` read the same numbers.

>>> len(PANDA_HOME_JOINTS_RAD)
7
"""

from __future__ import annotations

__all__ = ["PANDA_HOME_JOINTS_RAD"]

#: The Franka Panda "ready" pose (rad, joints 1-7): the simulated arm's start pose and the spec's
#: default ``safe_pose.joints_rad``.
PANDA_HOME_JOINTS_RAD: tuple[float, ...] = (0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785)
