"""One bag, one record: what ``ethimon replay`` reports of a bag, as plain data.

:func:`bag_record` is the unit of work of a replay run, the same in the serial
loop and on a Ray worker (:mod:`ethimon.fleet`): it never raises for a bad bag
(the record then carries ``"error"``), and its result is the JSON record of the
bag (dicts, lists, str, int, float, bool, None), so it travels between processes.
"""

from __future__ import annotations

import functools
import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from ..errors import EthimonError, SpecError
from ._bag import BagError
from ..io import Mapping

__all__ = ["ReplayReport", "bag_error_line", "bag_error_record", "bag_record", "mcap_path", "replay_paths",
           "replay_records", "replay_unit"]


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


_STATE: dict[str, Any] = {}  # "replay" -> (key, (spec, mapping, scorer)) of the run this process works for


def replay_unit(run_id: str, bag: str, spec_path: str, mapping_path: str, model_dir: str | None) -> dict[str, Any]:
    """``ethimon replay`` of one bag from the spec and mapping files: its JSON record as plain data (an
    ``"error"`` record if unusable). A process keeps the spec, mapping and risk model of its run."""
    from .._batch import plain
    key = (run_id, spec_path, mapping_path, model_dir)
    try:
        got = _STATE.get("replay")
        if got is None or got[0] != key:
            got = _STATE["replay"] = (key, _replay_setup(spec_path, mapping_path, model_dir))
    except Exception as exc:  # noqa: BLE001 - the spec or mapping fails here (it loaded on the driver)
        _STATE.pop("replay", None)
        return bag_error_record(bag, bag_error_line(bag, exc))
    spec, mapping, scorer = got[1]
    return plain(bag_record(bag, spec, mapping, score=scorer))


def _replay_setup(spec_path: str, mapping_path: str, model_dir: str | None) -> tuple[Any, Any, Any]:
    from ..compiler import plan_of
    from ..language import parse_spec_file
    from ..io import load_mapping
    from ._scoring import TaskScorer
    spec = parse_spec_file(spec_path)
    plan_of(spec)  # compiled now, as ethimon.load_spec does
    mapping = load_mapping(mapping_path)
    mapping.check(spec)
    return spec, mapping, TaskScorer(spec, model_dir=model_dir)
