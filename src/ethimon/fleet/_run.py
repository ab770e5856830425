"""The Ray-side drivers the docs teach: `check_paths` and `replay_records` with `executor=Ray(...)`"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any

from .._batch import ProgressCallback
from ._executor import Ray

__all__ = ["check_paths", "replay_records"]


def check_paths(paths: Iterable[str], *, sim: bool = False, model_dir: str | None = None,
                on_progress: ProgressCallback | None = None, address: str | None = None,
                num_cpus: int | None = None, max_retries: int = 1, file_timeout: float | None = None) -> Any:
    """:func:`ethimon.scenario.check_paths` with ``executor=Ray(address, num_cpus=..., max_retries=...,
    file_timeout=...)``: the serial run's outcomes in its order, each scenario file a Ray task.

    Raises:
        SpecError: a bad path, or a folder without YAML files (as the serial run).
        DependencyNotInstalled: Ray is not installed.
        EthimonError: Ray cannot start, the cluster cannot be reached, or a bad ``file_timeout``.
    """
    from ..scenario import check_paths as check
    ray = Ray(address, num_cpus=num_cpus, max_retries=max_retries, file_timeout=file_timeout)
    return check(paths, sim=sim, model_dir=model_dir, on_progress=on_progress, executor=ray)


def replay_records(bags: Sequence[str], *, spec: str, mapping: str, model_dir: str | None = None,
                   on_progress: ProgressCallback | None = None, address: str | None = None,
                   num_cpus: int | None = None, max_retries: int = 1,
                   file_timeout: float | None = None) -> list[dict[str, Any]]:
    """``ethimon.replay``'s records of ``bags`` (spec and mapping given as files), each bag a Ray task:
    the serial run's records, a bag whose task raised, died or timed out an ``"error"`` record."""
    from ..replay._record import replay_records as records
    ray = Ray(address, num_cpus=num_cpus, max_retries=max_retries, file_timeout=file_timeout)
    return records(bags, spec=spec, mapping=mapping, model_dir=model_dir, on_progress=on_progress, executor=ray)
