"""Replaying many bags, one record each: :func:`replay_paths` here, one bag after the other, and
:func:`replay_records` on any executor of :func:`ethimon.run` (``fleet.Ray``), each bag one unit
(``_unit.py``), and the :class:`ReplayReport` of a run.
"""

from __future__ import annotations

import functools
import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from ..io import Mapping
from ._unit import bag_error_line, bag_error_record, bag_record, replay_unit

__all__ = ["ReplayReport", "bag_error_line", "bag_error_record", "bag_record", "mcap_path", "replay_paths",
           "replay_records", "replay_unit"]


def mcap_path(out: str | os.PathLike, bag: str, index: int, count: int) -> str:
    """Where ``--mcap OUT`` writes the verdicts of bag ``index`` of ``count``: ``OUT`` itself for one
    bag, else ``OUT/<index>_<bag name>.mcap`` (``OUT`` a folder)."""
    out = os.fspath(out)
    if count == 1:
        return out
    name = os.path.basename(os.path.normpath(bag)) or "bag"
    stem = name[:-5] if name.endswith(".mcap") else name
    return os.path.join(out, f"{index:03d}_{stem}.mcap")


@dataclass
class ReplayReport:
    """The records of a replay run (one per bag, in order) and their counts."""

    results: list[dict[str, Any]]
    seconds: float = 0.0

    @property
    def errors(self) -> int:
        return sum(1 for r in self.results if "error" in r)

    @property
    def passed(self) -> int:
        return sum(1 for r in self.results if "error" not in r and r["passed"])

    @property
    def failed(self) -> int:
        return len(self.results) - self.errors - self.passed

    @property
    def ok(self) -> bool:
        return self.passed == len(self.results)

    def as_dict(self) -> dict[str, Any]:
        return {"results": self.results, "passed": self.passed, "failed": self.failed, "errors": self.errors,
                "seconds": self.seconds}


def replay_paths(bags: Sequence[str | os.PathLike], spec: Any, mapping: Mapping, *, score: Any = None,
                 p: Sequence[float] | None = None, audit: Any = None, mcap: str | os.PathLike | None = None,
                 on_progress: Callable[[int, int, str], None] | None = None,
                 on_messages: Callable[[int, int], None] | None = None, foxglove: Any = None,
                 foxglove_speed: float = 1.0) -> ReplayReport:
    """Replay bags one after the other (the library twin of ``ethimon replay``): one record per bag
    (:func:`bag_record`, one unit of :func:`ethimon.run` each), an unusable bag an error record.
    ``mcap``: a file for one bag, a folder (created) for several (:func:`mcap_path`). ``foxglove``: a live
    view (:class:`~ethimon.view.FoxgloveView`) each bag's verdicts are served to, paced at ``foxglove_speed``.
    ``score`` defaults to one :class:`TaskScorer` for all bags (the model loads once). ``on_progress(done,
    total, bag)``: before each bag and at the end; ``on_messages(read, total)``: while a bag is read.
    For the bags on Ray workers, see :func:`replay_records`."""
    import time

    from .._batch import Unit, run
    from ._scoring import TaskScorer
    t0 = time.perf_counter()
    names = [os.fspath(b) for b in bags]
    if score is None and p is None:
        score = TaskScorer(spec)
    if mcap is not None and len(names) > 1:
        os.makedirs(mcap, exist_ok=True)
    one = functools.partial(bag_record, spec=spec, mapping=mapping, score=score, p=p, audit=audit,
                            on_progress=on_messages, foxglove=foxglove, foxglove_speed=foxglove_speed)
    got = run([Unit(functools.partial(one, mcap=None if mcap is None else mcap_path(mcap, bag, i, len(names))),
                    (bag,), bag) for i, bag in enumerate(names)], None, on_progress)
    return ReplayReport(_records(got), time.perf_counter() - t0)


def _records(report: Any) -> list[dict[str, Any]]:
    """Each unit's record, or the error record of a bag whose unit did not return."""
    return [o.value if o.ok else bag_error_record(o.label, f"{o.label}: {o.error}") for o in report.outcomes]


def replay_records(bags: Sequence[str | os.PathLike], *, spec: str, mapping: str, model_dir: str | None = None,
                   on_progress: Callable[[int, int, str], None] | None = None, executor: Any = None
                   ) -> list[dict[str, Any]]:
    """The JSON record of each bag (``BagReplay.as_dict()``, or an ``"error"`` record), in order, each bag
    a unit (:func:`replay_unit`) of :func:`ethimon.run` on ``executor`` (e.g. ``ethimon.fleet.Ray()``)
    against the spec and mapping files ``spec`` and ``mapping``. The records equal those of
    :func:`replay_paths`; a bag whose unit raised, died or timed out is an ``"error"`` record."""
    import uuid

    from .._batch import Unit, run
    names = [os.fspath(b) for b in bags]
    run_id = uuid.uuid4().hex
    return _records(run([Unit(replay_unit, (run_id, b, spec, mapping, model_dir), b) for b in names],
                        executor, on_progress))
