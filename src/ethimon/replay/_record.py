"""One bag, one record: what ``ethimon replay`` reports of a bag, as plain data.

:func:`bag_record` is the unit of work of a replay run, the same in the serial
loop and on a Ray worker (:mod:`ethimon.fleet`): it never raises for a bad bag
(the record then carries ``"error"``), and its result is the JSON record of the
bag (dicts, lists, str, int, float, bool, None), so it travels between processes.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from ..errors import EthimonError, SpecError
from ._bag import BagError
from ._mapping import Mapping

__all__ = ["ReplayReport", "bag_error_line", "bag_error_record", "bag_record", "mcap_path", "replay_paths"]


def bag_error_line(bag: str, exc: BaseException) -> str:
    """The one line that reports ``exc`` raised while replaying ``bag``."""
    if isinstance(exc, (SpecError, BagError)):
        return str(exc)
    if isinstance(exc, (EthimonError, OSError)):
        return f"{bag}: {exc}"
    text = str(exc)
    text = text if len(text) <= 300 else text[:297] + "..."
    return f"{bag}: internal error: {type(exc).__name__}: {text} (this bag could not be checked; please report this)"


def bag_error_record(bag: str, msg: str) -> dict[str, Any]:
    """The record of a bag that could not be checked (an ERROR row)."""
    return {"name": bag, "path": bag, "passed": False, "error": msg}


def bag_record(bag: str | os.PathLike, spec: Any, mapping: Mapping, *, score: Any = None,
               p: Sequence[float] | None = None, audit: Any = None, mcap: str | os.PathLike | None = None,
               on_progress: Callable[[int, int], None] | None = None, foxglove: Any = None,
               foxglove_speed: float = 1.0) -> dict[str, Any]:
    """:func:`~ethimon.replay.replay_bag` of one bag as its JSON record (``BagReplay.as_dict()``), or
    :func:`bag_error_record` when the bag cannot be checked (never raises for a bad bag). ``mcap``:
    also write the cycles' verdicts to this MCAP file (:func:`~ethimon.replay._mcap.write_mcap`);
    ``foxglove``: also serve them to this live view at ``foxglove_speed`` (``_mcap.serve_verdicts``)."""
    from ._replay import replay_bag  # the module's name, looked up per call
    bag = os.fspath(bag)
    try:
        res = replay_bag(bag, spec, mapping, score=score, p=p, audit=audit,
                         keep_trace=mcap is not None or foxglove is not None, on_progress=on_progress)
        rec = res.as_dict()
        if mcap is not None:
            from ._mcap import write_mcap
            rec["mcap"] = {"path": os.fspath(mcap), "messages": write_mcap(res, mcap, spec)}
        if foxglove is not None:
            from ._mcap import serve_verdicts
            rec["foxglove"] = {"url": getattr(foxglove, "url", None),
                               "cycles": serve_verdicts(res, foxglove, spec, speed=foxglove_speed)}
        return rec
    except Exception as exc:  # noqa: BLE001 - one unusable bag is one ERROR row; the others still run
        return bag_error_record(bag, bag_error_line(bag, exc))


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
                 on_bag: Callable[[int, int, str], None] | None = None,
                 on_progress: Callable[[int, int], None] | None = None, foxglove: Any = None,
                 foxglove_speed: float = 1.0) -> ReplayReport:
    """Replay bags one after the other (the library twin of ``ethimon replay``): one record per bag
    (:func:`bag_record`), an unusable bag an error record. ``mcap``: a file for one bag, a folder
    (created) for several (:func:`mcap_path`). ``foxglove``: a live view (:class:`~ethimon.view.FoxgloveView`)
    each bag's verdicts are served to, paced at ``foxglove_speed``. ``score`` defaults to one :class:`TaskScorer` for
    all bags (the model loads once)."""
    import time

    from ._scoring import TaskScorer
    t0 = time.perf_counter()
    names = [os.fspath(b) for b in bags]
    if score is None and p is None:
        score = TaskScorer(spec)
    if mcap is not None and len(names) > 1:
        os.makedirs(mcap, exist_ok=True)
    out = []
    for i, bag in enumerate(names):
        if on_bag is not None:
            on_bag(i, len(names), bag)
        where = None if mcap is None else mcap_path(mcap, bag, i, len(names))
        out.append(bag_record(bag, spec, mapping, score=score, p=p, audit=audit, mcap=where,
                              on_progress=on_progress, foxglove=foxglove, foxglove_speed=foxglove_speed))
    if on_bag is not None:
        on_bag(len(names), len(names), "")
    return ReplayReport(out, time.perf_counter() - t0)
