"""The facts of the simulated Panda cell that every part of :class:`~._arm.ArmSim` shares: joint
and link indices, force and rate limits, the control gain, how PyBullet is imported (lazily,
quietly), the planned :class:`Segment` and a walking person's body; object half sizes."""

from __future__ import annotations

import contextlib
import math
import os
import sys
from dataclasses import dataclass, field

import numpy as np

from ..errors import DependencyNotInstalled
from .._robot import PANDA_HOME_JOINTS_RAD
from ._limits import (BRAKE_DECEL_RAD_S2, BRAKE_TORQUE_N_M, RATED_DDDQ_MAX, RATED_DDQ_MAX, RATED_DQ_MAX,
                      RATED_Q_MAX, RATED_Q_MIN)
from ._model import Human

__all__ = ["ARM_JOINTS", "FINGER_JOINTS", "HAND_LINK", "FLANGE_LINK", "EE_LINK", "HOME_JOINTS_RAD", "ARM_MAX_FORCE_N_M",
           "BRAKE_TORQUE_N_M", "Segment", "import_pybullet", "physics_only_urdf"]


#: Panda arm joint indices in ``panda.urdf`` (fingers are 9 and 10).
ARM_JOINTS = (0, 1, 2, 3, 4, 5, 6)
FINGER_JOINTS = (9, 10)
HAND_LINK = 8
#: The flange (panda_link8): payload offsets are stated in its frame.
FLANGE_LINK = 7
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


_PHYSICS_URDF: dict[str, str] = {}


def physics_only_urdf(data_path: str, name: str = "franka_panda/panda.urdf") -> str:
    """The path of a copy of ``name`` without its ``<visual>`` meshes (written once per process to a
    temporary folder, removed at exit): the same links, joints, masses, inertias and collision
    meshes, so the same physics, but loaded about 5 times faster (0.12 s instead of 0.63 s for the
    Panda on a busy 2-core machine: parsing the visual meshes was most of a scenario's setup).
    Used when nothing is rendered (no ``--record``, no GUI)."""
    import re
    got = _PHYSICS_URDF.get(name)
    if got is not None and os.path.exists(got):
        return got
    import atexit
    import shutil
    import tempfile
    src = os.path.join(data_path, name)
    with open(src, encoding="utf-8") as f:
        text = f.read()
    text = re.sub(r"<visual>.*?</visual>", "", text, flags=re.S)
    # mesh paths resolve against the original folder, wherever the copy lies
    text = text.replace('filename="package://', f'filename="{os.path.dirname(src)}/')
    folder = tempfile.mkdtemp(prefix="ethimon-urdf-")
    atexit.register(shutil.rmtree, folder, ignore_errors=True)
    path = os.path.join(folder, os.path.basename(name))
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)
    _PHYSICS_URDF[name] = path
    return path


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
        cols = self.__dict__.get("_cols")
        if cols is None or cols[0] is not self.xy:  # x and y as contiguous columns, once (same values)
            cols = self.__dict__["_cols"] = (self.xy, np.ascontiguousarray(self.xy[:, 0]),
                                             np.ascontiguousarray(self.xy[:, 1]))
        ts = self.times
        return np.array([np.interp(t, ts, cols[1]), np.interp(t, ts, cols[2])])

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


def _half_height(o) -> float:
    if o.shape == "box":
        return o.half_extents_m[2]
    if o.shape == "sphere":
        return o.radius_m
    return o.height_m / 2


def _half_width(o) -> float:
    if o.shape == "box":
        return min(o.half_extents_m[0], o.half_extents_m[1])
    return o.radius_m


def _cross3(a, b) -> np.ndarray:
    """``np.cross(a, b)`` of two 3-vectors, without its axis bookkeeping (about 20 x faster per
    call): the same products and differences in the same order, so the same numbers bit for bit."""
    a0, a1, a2 = float(a[0]), float(a[1]), float(a[2])
    b0, b1, b2 = float(b[0]), float(b[1]), float(b[2])
    return np.array([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0])
