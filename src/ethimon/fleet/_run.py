"""The drivers: ``ethimon check --ray`` and ``ethimon replay --ray`` over many files."""

from __future__ import annotations

import os
import time
import uuid
from collections.abc import Iterable, Sequence
from typing import Any

from ._ray import Failure, ProgressCallback, map_files
from ._units import check_unit, replay_unit

__all__ = ["check_paths", "replay_records"]


def _failed_line(path: str, failure: Failure) -> str:
    return f"{path}: {failure.what} (this file could not be checked; the other files were)"


def check_paths(paths: Iterable[str], *, sim: bool = False, model_dir: str | None = None,
                on_file: ProgressCallback | None = None, address: str | None = None,
                num_cpus: int | None = None, max_retries: int = 1, file_timeout: float | None = None) -> Any:
    """:func:`ethimon.scenario.check_paths` with the scenario files spread over Ray workers.

    The report has the same outcomes in the same order as the serial run (its ``seconds`` is
    this run's wall time); each outcome's ``result`` is ``None`` (workers return plain data). A file
    whose worker raised, died or ran past ``file_timeout`` seconds (its task is then cancelled) is one
    ERROR outcome. ``address``, ``num_cpus``, ``max_retries``, ``file_timeout``: see
    :func:`ethimon.fleet.map_files`; ``on_file(done, total, path)`` after each finished file.

    Raises:
        SpecError: a bad path, or a folder without YAML files (as the serial run).
        DependencyNotInstalled: Ray is not installed.
        EthimonError: Ray cannot start, the cluster cannot be reached, or a bad ``file_timeout``.
    """
    from .._files import scan_yaml_files
    from ..scenario import CheckOutcome, CheckReport
    from ..scenario._session import _skipped

    files = scan_yaml_files(paths, what="scenario", command="ethimon check")
    todo = [path for path, reason in files if reason is None]
    skipped = len(files) - len(todo)
    report = CheckReport()
    t0 = time.perf_counter()

    def progress(done: int, total: int, label: str) -> None:
        if on_file is not None:
            on_file(done + skipped if done else 0, len(files), label)

    run_id, cwd = uuid.uuid4().hex, os.getcwd()
    got = iter(map_files(check_unit, [(run_id, cwd, p, sim, model_dir) for p in todo], todo, address=address,
                         num_cpus=num_cpus, on_done=progress, max_retries=max_retries,
                         file_timeout=file_timeout))
    for path, reason in files:
        if reason is not None:  # a FIFO, socket or device in a folder: never opened
            report.outcomes.append(_skipped(path, reason))
            continue
        res = next(got)
        if isinstance(res, Failure):
            msg = _failed_line(path, res)
            report.outcomes.append(CheckOutcome(path, path, "ERROR", "-", "bad input", messages=[msg],
                                                record={"name": path, "path": path, "passed": False,
                                                        "error": msg}))
        else:
            report.outcomes.extend(CheckOutcome(**o) for o in res)
    if on_file is not None:
        on_file(len(files), len(files), "")
    report.seconds = time.perf_counter() - t0
    return report


def replay_records(bags: Sequence[str], *, spec: str, mapping: str, model_dir: str | None = None,
                   on_bag: ProgressCallback | None = None, address: str | None = None,
                   num_cpus: int | None = None, max_retries: int = 1,
                   file_timeout: float | None = None) -> list[dict[str, Any]]:
    """The JSON record of each bag (``BagReplay.as_dict()``, or an ``"error"`` record), in order,
    each bag replayed on a Ray worker against the spec and mapping files ``spec`` and ``mapping``.

    The records equal those of the serial run (:func:`ethimon.replay._record.bag_record`); a bag
    whose worker raised, died or timed out is an ``"error"`` record. See :func:`check_paths` for the rest.
    """
    from ..replay._record import bag_error_record

    bags = [os.fspath(b) for b in bags]
    run_id, cwd = uuid.uuid4().hex, os.getcwd()
    got = map_files(replay_unit, [(run_id, cwd, b, spec, mapping, model_dir) for b in bags], bags,
                    address=address, num_cpus=num_cpus, on_done=on_bag, max_retries=max_retries,
                    file_timeout=file_timeout)
    return [bag_error_record(b, _failed_line(b, r)) if isinstance(r, Failure) else r for b, r in zip(bags, got)]
