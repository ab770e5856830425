"""`Ray`: the executor of `ethimon.run` that spreads units over a Ray cluster (a local instance by default)"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from typing import Any

from .._batch import Outcome, ProgressCallback, Unit
from ._ray import Failure, check_address, check_file_timeout, map_files

__all__ = ["Ray"]


def _enter(cwd: str) -> None:
    """Work in the driver's folder (where it exists on this node: a cluster with a shared file system)."""
    if os.getcwd() != cwd and os.path.isdir(cwd):
        os.chdir(cwd)


def _call(cwd: str, fn: Callable[..., Any], *args: Any) -> Any:
    """A worker's task: ``fn(*args)`` in the driver's working folder, so every path reads as it does there."""
    _enter(cwd)
    return fn(*args)


class Ray:
    """Run each unit as one Ray task; the outcomes in unit order, as :class:`~ethimon.Serial` gives them.

    A unit's function must be a module-level function (workers import it by name) taking and returning
    plain data. A unit whose task raised, whose worker died (after ``max_retries``) or that ran past
    ``file_timeout`` seconds (its task is cancelled) is an error :class:`~ethimon.Outcome`. Ray is
    imported when :meth:`map` runs, never before.

    Args:
        address: ``None``/``"local"`` a new local instance of ``num_cpus`` CPUs; ``"auto"``,
            ``"ray://HOST:10001"`` or ``HOST:PORT`` an existing cluster (see :func:`map_files`).
        num_cpus: the CPUs of a local instance (default: up to ``DEFAULT_LOCAL_CPUS``).
        max_retries: how often Ray re-runs a unit whose worker process died.
        file_timeout: seconds a unit's task may take (``None``: no limit).

    Raises:
        EthimonError: a bad ``address`` or ``file_timeout`` (at construction).
    """

    __slots__ = ("address", "num_cpus", "max_retries", "file_timeout")

    def __init__(self, address: str | None = None, *, num_cpus: int | None = None, max_retries: int = 1,
                 file_timeout: float | None = None) -> None:
        self.address = check_address(address)
        self.num_cpus = num_cpus
        self.max_retries = max_retries
        self.file_timeout = check_file_timeout(file_timeout)

    def map(self, units: Sequence[Unit], on_progress: ProgressCallback | None = None) -> list[Outcome]:
        cwd = os.getcwd()
        labels = [u.label for u in units]
        got = map_files(_call, [(cwd, u.fn, *u.args) for u in units], labels, address=self.address,
                        num_cpus=self.num_cpus, on_done=on_progress, max_retries=self.max_retries,
                        file_timeout=self.file_timeout)
        if on_progress is not None:
            on_progress(len(units), len(units), "")
        return [Outcome(label, error=f"{r.what} (this file could not be checked; the other files were)")
                if isinstance(r, Failure) else Outcome(label, r) for label, r in zip(labels, got)]

    def __repr__(self) -> str:
        return (f"Ray({self.address!r}, num_cpus={self.num_cpus!r}, max_retries={self.max_retries!r}, "
                f"file_timeout={self.file_timeout!r})")
