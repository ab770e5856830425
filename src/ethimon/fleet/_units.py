"""The units of work a Ray worker runs: one scenario file, one bag. Plain data in, plain data out.

Each worker process keeps what a serial run shares across files (the specs read,
the risk model loaded) for the run it is working for (``run_id``), so a model
loads once per worker, not once per file. Paths are opened relative to the
driver's working directory (``cwd``), as the serial run opens them, so every
path and message in a result reads exactly as in the serial run.
"""

from __future__ import annotations

import os
from typing import Any

from ._ray import plain

__all__ = ["check_unit", "outcome_as_plain", "replay_unit"]

_STATE: dict[str, Any] = {}  # kind -> (key, state) of the run this worker works for now


def _enter(cwd: str) -> None:
    """Work in the driver's folder (where it exists on this node: a cluster with a shared file system)."""
    if os.getcwd() != cwd and os.path.isdir(cwd):
        os.chdir(cwd)


def _cached(kind: str, key: tuple, make) -> Any:
    got = _STATE.get(kind)
    if got is None or got[0] != key:  # a new run: drop the previous run's specs and models
        got = _STATE[kind] = (key, make())
    return got[1]


def outcome_as_plain(o: Any) -> dict[str, Any]:
    """A :class:`~ethimon.scenario.CheckOutcome` as plain data (its ``result`` object is left out)."""
    return plain({"name": o.name, "path": o.path, "status": o.status, "expected": o.expected, "got": o.got,
                  "first_override_cycle": o.first_override_cycle, "messages": list(o.messages),
                  "record": o.record})


def check_unit(run_id: str, cwd: str, path: str, sim: bool, model_dir: str | None) -> list[dict[str, Any]]:
    """``ethimon check`` of one scenario file on a worker: its outcomes as plain dicts."""
    from ..scenario import ScenarioSession
    _enter(cwd)
    session = _cached("check", (run_id, model_dir), lambda: ScenarioSession(model_dir=model_dir))
    return [outcome_as_plain(o) for o in session.check_file(path, sim=sim)]


def replay_unit(run_id: str, cwd: str, bag: str, spec_path: str, mapping_path: str,
                model_dir: str | None) -> dict[str, Any]:
    """``ethimon replay`` of one bag on a worker: its JSON record (an ``"error"`` record if unusable)."""
    from ..replay._record import bag_error_line, bag_error_record, bag_record
    _enter(cwd)
    try:
        spec, mapping, scorer = _cached("replay", (run_id, spec_path, mapping_path, model_dir),
                                        lambda: _replay_setup(spec_path, mapping_path, model_dir))
    except Exception as exc:  # noqa: BLE001 - the spec or mapping fails here (it loaded on the driver)
        _STATE.pop("replay", None)
        return bag_error_record(bag, bag_error_line(bag, exc))
    return plain(bag_record(bag, spec, mapping, score=scorer))


def _replay_setup(spec_path: str, mapping_path: str, model_dir: str | None) -> tuple[Any, Any, Any]:
    from .. import _api
    from ..replay import TaskScorer, check_against_spec, load_mapping
    spec = _api.load_spec(spec_path)
    mapping = load_mapping(mapping_path)
    check_against_spec(mapping, spec)
    return spec, mapping, TaskScorer(spec, model_dir=model_dir)
