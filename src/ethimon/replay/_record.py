"""One bag, one record: what ``ethimon replay`` reports of a bag, as plain data.

:func:`bag_record` is the unit of work of a replay run, the same in the serial
loop and on a Ray worker (:mod:`ethimon.fleet`): it never raises for a bad bag
(the record then carries ``"error"``), and its result is the JSON record of the
bag (dicts, lists, str, int, float, bool, None), so it travels between processes.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import Any

from ..errors import EthimonError, SpecError
from ._bag import BagError
from ._mapping import Mapping

__all__ = ["bag_error_line", "bag_error_record", "bag_record"]


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
               p: Sequence[float] | None = None, audit: Any = None) -> dict[str, Any]:
    """:func:`~ethimon.replay.replay_bag` of one bag as its JSON record (``BagReplay.as_dict()``), or
    :func:`bag_error_record` when the bag cannot be checked (never raises for a bad bag)."""
    from ._replay import replay_bag  # the module's name, looked up per call
    bag = os.fspath(bag)
    try:
        return replay_bag(bag, spec, mapping, score=score, p=p, audit=audit).as_dict()
    except Exception as exc:  # noqa: BLE001 - one unusable bag is one ERROR row; the others still run
        return bag_error_record(bag, bag_error_line(bag, exc))
