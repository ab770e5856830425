"""One bag, one record: what ``ethimon replay`` reports of a bag, as plain data, the unit of work of a replay run.

:func:`bag_record` is the unit of work of a replay run, the same in the serial
loop and on a Ray worker (:mod:`ethimon.fleet`): it never raises for a bad bag
(the record then carries ``"error"``), and its result is the JSON record of the
bag (dicts, lists, str, int, float, bool, None), so it travels between processes.
:func:`replay_unit` is the same from the spec and mapping files (a worker of a
run keeps them). The runs that call them are ``_record.py``'s.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from typing import Any

from ..errors import EthimonError, SpecError
from ._bag import BagError
from ..io import Mapping

__all__ = ["bag_error_line", "bag_error_record", "bag_record", "replay_unit"]


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
