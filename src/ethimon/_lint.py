"""``ethimon lint`` as a library: load and compile spec files, report errors and warnings (no z3,
no proofs: ``ethimon verify`` proves). The CLI only prints the lines of :func:`lint_paths`."""

from __future__ import annotations

import os
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field

from . import _api
from ._batch import Unit
from ._files import scan_yaml_files
from .scenario import error_line
from .language import Spec
from .verify._policy import release_policy_warnings  # no z3

__all__ = ["LintLine", "LintReport", "iter_lint", "lint_paths", "lint_safe_pose", "lint_unit", "lint_units"]

#: the kinds of :class:`LintLine`; an ``"error"`` line makes the exit code 2
LINE_KINDS = ("ok", "skipped", "warning", "error")


@dataclass(frozen=True)
class LintLine:
    """One line of ``ethimon lint``.

    Attributes:
        path: the file it is about (the spec; the mapping for a mapping's warnings).
        kind: one of :data:`LINE_KINDS`.
        text: the line as printed (``path: ok (...)``, ``path:line:col: message (hint)``, ...).
    """

    path: str
    kind: str
    text: str


@dataclass
class LintReport:
    """Every line of one lint run, in order; :attr:`exit_code` 0 if no error, else 2."""

    lines: list[LintLine] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return not any(ln.kind == "error" for ln in self.lines)

    @property
    def exit_code(self) -> int:
        return 0 if self.ok else 2


def lint_safe_pose(spec: Spec) -> None:
    """A safe pose outside the rated range of the spec's robot (``robot:``, the Franka Panda by
    default) is a lint error naming each joint, as it is a SpecError for ``check --sim``."""
    from .language._robots import robot_of
    robot = robot_of(spec)
    joints = tuple(spec.safe_pose.joints_rad)
    problem = robot.safe_pose_problem(joints)
    if problem is not None:
        raise spec.source.error(problem, ("safe_pose", "joints_rad", robot.out_of_range(joints)[0][0] - 1),
                                hint=f"keep every joint inside the {robot.title}'s rated range "
                                     f"({robot.source('position_min_rad')}; robot: {spec.robot}, docs/robots.md)")


def lint_unit(path: str, skipped: str | None = None, mapping: str | None = None) -> list[LintLine]:
    """The unit of ``ethimon lint`` (one unit of :func:`ethimon.run`): the lines of one spec file (``skipped``:
    why a file found in a folder is passed over). Never raises for a bad spec: it is an ``"error"`` line."""
    if skipped is not None:  # a FIFO, socket or device in a folder: never opened
        return [LintLine(path, "skipped", f"{path}: skipped: {skipped}")]
    out: list[LintLine] = []
    try:
        spec = _api.load_spec(path)
        lint_safe_pose(spec)
        out.append(LintLine(path, "ok", f"{path}: ok ({spec.name}, {len(spec.obligations)} obligations)"))
        for w in release_policy_warnings(spec):
            out.append(LintLine(path, "warning", f"{path}: warning: {w}"))
        from .risk._estimator import model_tau_warnings  # no torch
        for w in model_tau_warnings(spec):
            out.append(LintLine(path, "warning", f"{path}: warning: {w}"))
        if mapping:
            from .io import check_against_spec, lint_mapping, load_mapping
            m = load_mapping(mapping)
            check_against_spec(m, spec)
            for w in lint_mapping(m, spec):
                out.append(LintLine(mapping, "warning", f"{mapping}: warning: {w}"))
    except Exception as exc:  # noqa: BLE001 - one bad file is one line; the others are still linted
        out.append(LintLine(path, "error", error_line(path, exc)))
    return out


def lint_units(paths: Iterable[str | os.PathLike], *, mapping: str | None = None) -> list[Unit]:
    """One :func:`lint_unit` per spec file under ``paths`` (folders scanned now).

    Raises:
        SpecError: a path that does not exist or is not a regular file or folder, or a folder
            with no spec files.
    """
    return [Unit(lint_unit, (path, skipped, mapping), path)
            for path, skipped in scan_yaml_files([os.fspath(p) for p in paths], what="spec", command="ethimon lint")]


def iter_lint(paths: Iterable[str | os.PathLike], *, mapping: str | None = None) -> Iterator[LintLine]:
    """The lines of :func:`lint_paths`, one spec at a time (a CLI prints each as it comes).

    Raises:
        SpecError: a path that does not exist or is not a regular file or folder, or a folder
            with no spec files (before any line); a problem with one spec file is an
            ``"error"`` line, and the others are still linted.
    """
    for unit in lint_units(paths, mapping=mapping):
        yield from unit.fn(*unit.args)


def lint_paths(paths: Iterable[str | os.PathLike], *, mapping: str | None = None) -> LintReport:
    """Load and compile every spec file (files or folders of ``*.yaml``/``*.yml``).

    Args:
        paths: spec files or folders.
        mapping: also lint this replay mapping against each spec (``prev()`` of a
            zero-order-held input, unmapped signals).

    Returns:
        One ``ok`` line per spec, its release-policy warnings, the mapping's warnings, or
        the spec's error as ``path:line:column: message (hint)``; passed-over files
        (FIFOs, sockets, devices in a folder) as ``skipped``.
    """
    return LintReport(list(iter_lint(paths, mapping=mapping)))
