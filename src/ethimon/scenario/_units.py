"""The unit of ``ethimon check`` on another process (`ethimon.run` with `fleet.Ray`): one file, plain data out

Each worker process keeps what a serial run shares across files (the specs read, the risk model
loaded) for the run it works for (``run_id``), so a model loads once per worker, not once per file.
"""

from __future__ import annotations

from typing import Any

from .._batch import plain

__all__ = ["check_unit", "outcome_as_plain", "outcome_from_plain"]

_STATE: dict[str, Any] = {}  # "check" -> (key, session) of the run this process works for now


def outcome_as_plain(o: Any) -> dict[str, Any]:
    """A :class:`~ethimon.scenario.CheckOutcome` as plain data (its ``result`` object is left out)."""
    return plain({"name": o.name, "path": o.path, "status": o.status, "expected": o.expected, "got": o.got,
                  "first_override_cycle": o.first_override_cycle, "messages": list(o.messages),
                  "record": o.record})


def outcome_from_plain(d: dict[str, Any]) -> Any:
    from ._session import CheckOutcome
    return CheckOutcome(**d)


def check_unit(run_id: str, path: str, sim: bool, model_dir: str | None) -> list[dict[str, Any]]:
    """``ethimon check`` of one scenario file: its outcomes as plain dicts (never raises for a bad file)."""
    from ._session import ScenarioSession
    got = _STATE.get("check")
    if got is None or got[0] != (run_id, model_dir):  # a new run: drop the previous run's specs and models
        got = _STATE["check"] = ((run_id, model_dir), ScenarioSession(model_dir=model_dir))
    return [outcome_as_plain(o) for o in got[1].check_file(path, sim=sim)]
