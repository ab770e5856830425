"""The spec's robot (``robot:``): a shipped description named (``panda``, ``ur5e``) or a robot YAML
file by path (data, never code), read with the safe loader (located errors) and checked against
the spec's safe pose."""

from __future__ import annotations

import os
import re
from pathlib import Path
from typing import Any

from .._robot import ROBOTS_DIR, SHIPPED_ROBOTS, Robot, robot_from_data
from ..errors import SpecError
from ._yaml import SourceMap, read_yaml

__all__ = ["attach_robot", "load_robot", "robot_of"]

_NAMED = re.compile(r"^[A-Za-z][A-Za-z0-9_\-]*$")
_HINT = ("name a shipped robot (" + ", ".join(SHIPPED_ROBOTS) + ") or the path of a robot YAML file, "
         "relative to the spec (docs/robots.md)")
_shipped: dict[str, Robot] = {}


def _read(path: str) -> Robot:
    data, smap = read_yaml(path, what="robot description")
    return robot_from_data(data, path, smap.error)


def load_robot(ref: str, base_dir: str | os.PathLike | None = None) -> Robot:
    """The robot a spec names: a shipped one by name, else a robot YAML file (relative paths from
    ``base_dir``, the spec's folder). Raises :class:`SpecError`: an unknown name (unlocated: the
    caller places it), or any problem of the file, located in the file."""
    if _NAMED.match(ref) and not ref.endswith((".yaml", ".yml")):
        if ref not in SHIPPED_ROBOTS:
            raise SpecError(f"unknown robot {ref!r}", hint=_HINT)
        robot = _shipped.get(ref)
        if robot is None:
            robot = _shipped[ref] = _read(os.fspath(ROBOTS_DIR / f"{ref}.yaml"))
        return robot
    path = Path(ref).expanduser()
    if not path.is_absolute() and base_dir is not None:
        path = Path(base_dir) / path
    return _read(os.fspath(path))


def attach_robot(spec: Any, data: Any, smap: SourceMap) -> Any:
    """Resolve the spec's robot and check the safe pose against it (located errors); returns the
    spec with its robot attached (its safe pose the robot's home pose where the spec states none).

    A spec that names its robot must give a safe pose of that robot's joint count; one that names
    none is a Panda spec, whose other joint counts stay a warning of ``verify`` (as before)."""
    base = os.path.dirname(os.path.abspath(smap.path)) if smap.path and not smap.path.startswith("<") else None
    stated = isinstance(data, dict) and "robot" in data
    try:
        robot = load_robot(spec.robot, base)
    except SpecError as exc:
        if exc.line is None:  # an unknown name, or a file that cannot be read: point at the spec's robot:
            where = f" ({exc.path})" if exc.path else ""
            raise smap.error(f"{exc.message}{where}", ("robot",), hint=exc.hint or _HINT) from None
        raise
    sp = data.get("safe_pose") if isinstance(data, dict) else None
    pose_stated = isinstance(sp, dict) and "joints_rad" in sp
    joints = tuple(spec.safe_pose.joints_rad)
    if stated and not pose_stated:
        if robot.home_joints_rad is None:
            raise smap.error(f"robot {spec.robot!r} ({robot.title}) has no default safe pose, and the spec "
                             f"states none", ("robot",), key=True,
                             hint=f"state safe_pose.joints_rad: {robot.n_joints} joint angles (rad), in the "
                                  f"order {', '.join(robot.joint_names)}")
        if robot.home_joints_rad != joints:
            spec = _with_pose(spec, robot.home_joints_rad, smap)
    elif stated and len(joints) != robot.n_joints:
        raise smap.error(f"safe_pose.joints_rad has {len(joints)} values; the {robot.title} (robot: {spec.robot}) "
                         f"has {robot.n_joints} joints", ("safe_pose", "joints_rad"),
                         hint=f"give {robot.n_joints} joint angles (rad), in the order {', '.join(robot.joint_names)}")
    spec._robot = robot
    return spec


def _with_pose(spec: Any, joints: tuple[float, ...], smap: SourceMap) -> Any:
    new = spec.model_copy(update={"safe_pose": spec.safe_pose.model_copy(update={"joints_rad": joints})})
    new._source = smap
    return new


def robot_of(spec: Any) -> Robot:
    """The spec's robot description (attached when the spec was read; else resolved now, relative
    paths from the spec file's folder)."""
    robot = getattr(spec, "_robot", None)
    if robot is not None:
        return robot
    src = getattr(spec, "_source", None)
    path = getattr(src, "path", None)
    base = os.path.dirname(os.path.abspath(path)) if path and not path.startswith("<") else None
    return load_robot(getattr(spec, "robot", "panda") or "panda", base)
