"""One batch runner: units of work through an executor (`Serial`, `fleet.Ray`), typed outcomes in a `Report`

Every "run over many files" of ethimon (``check``, ``simulate``, ``replay``, ``verify``, ``lint``) is
:func:`run` over :class:`Unit` s: one file, one unit. A unit function returns its file's result and
reports a bad file in that result (an ERROR row, an error record); the runner turns anything it still
raises into an error :class:`Outcome` for that unit, so one unit never stops the others (but
:class:`~ethimon.errors.DependencyNotInstalled`, which no unit could get past, and a ``BrokenPipeError``,
stdout closed, stop the run).

The executor decides where units run: :class:`Serial` here, one after the other (a unit's function
may then be any callable); ``ethimon.fleet.Ray`` on a Ray cluster (then a module-level function of
plain data in, plain data out). Both call ``on_progress(done, total, label)``, the one progress
callback: ``done`` units have finished, ``label`` names the unit now starting (serial) or just
finished (parallel), and once at the end ``(total, total, "")``.
"""

from __future__ import annotations

import enum
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import Any, Protocol

from .errors import DependencyNotInstalled

__all__ = ["Executor", "Outcome", "ProgressCallback", "Report", "Serial", "Unit", "plain", "run"]

#: ``on_progress(done, total, label)``: see the module's docstring
ProgressCallback = Callable[[int, int, str], None]


@dataclass(frozen=True, slots=True)
class Unit:
    """One unit of work: ``fn(*args)``, named ``label`` (a file's path) in progress and errors."""

    fn: Callable[..., Any]
    args: tuple = ()
    label: str = ""


@dataclass(frozen=True, slots=True)
class Outcome:
    """What one unit gave: its ``value``, or the ``error`` (one line) that kept it from giving one."""

    label: str
    value: Any = None
    error: str | None = None

    @property
    def ok(self) -> bool:
        return self.error is None

    def to_json(self) -> dict[str, Any]:
        """``{"label", "ok", "value"|"error"}``; a value with its own ``to_json()``/``as_dict()`` gives that."""
        if self.error is not None:
            return {"label": self.label, "ok": False, "error": self.error}
        v = self.value
        for attr in ("to_json", "as_dict"):
            if callable(getattr(v, attr, None)):
                v = getattr(v, attr)()
                break
        return {"label": self.label, "ok": True, "value": v}

    def lines(self) -> list[str]:
        """One line per finding: the error as ``label: error``, or the value's own ``lines()``."""
        if self.error is not None:
            return [f"{self.label}: {self.error}"]
        own = getattr(self.value, "lines", None)
        return list(own()) if callable(own) else [f"{self.label}: ok"]


@dataclass(frozen=True, slots=True)
class Report:
    """Every unit's :class:`Outcome`, in the order the units were given, and the run's wall time."""

    outcomes: tuple[Outcome, ...] = ()
    seconds: float = 0.0

    @property
    def errors(self) -> int:
        return sum(1 for o in self.outcomes if not o.ok)

    def values(self) -> list[Any]:
        """The units' values in order (``None`` for a unit that failed)."""
        return [o.value for o in self.outcomes]

    def to_json(self) -> dict[str, Any]:
        return {"outcomes": [o.to_json() for o in self.outcomes], "errors": self.errors, "seconds": self.seconds}

    def lines(self) -> list[str]:
        return [line for o in self.outcomes for line in o.lines()]


class Executor(Protocol):
    """Where units run: ``map`` gives one :class:`Outcome` per unit, in order."""

    def map(self, units: Sequence[Unit], on_progress: ProgressCallback | None) -> list[Outcome]: ...


def internal_error(exc: BaseException) -> str:
    """One line for an exception a unit's function raised: ``internal error: Type: text``."""
    text = str(exc)
    text = text if len(text) <= 300 else text[:297] + "..."
    return f"internal error: {type(exc).__name__}: {text}" if text else f"internal error: {type(exc).__name__}"


def plain(obj: Any) -> Any:
    """``obj`` as plain data, the way the CLI's JSON writer (``json.dumps(..., default=str)``) sees it:
    dicts, lists (tuples too), str, int, float, bool and None are kept (subclasses such as numpy
    floats or enums become the base type's value); anything else becomes ``str(obj)``."""
    if obj is None or type(obj) in (str, int, float, bool):
        return obj
    if isinstance(obj, dict):
        return {(k if k is None or type(k) in (str, int, float, bool) else _plain_key(k)): plain(v)
                for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [plain(v) for v in obj]
    if isinstance(obj, bool):
        return bool(obj)
    if isinstance(obj, str):
        return str.__str__(obj)
    if isinstance(obj, int) and not isinstance(obj, enum.Flag):
        return int(obj)
    if isinstance(obj, float):
        return float(obj)
    return str(obj)


def _plain_key(k: Any) -> Any:
    if isinstance(k, str):
        return str.__str__(k)
    if isinstance(k, (int, float)):
        return int(k) if isinstance(k, int) else float(k)
    return str(k)


class Serial:
    """Run the units here, one after the other (``on_progress`` before each, and at the end)."""

    __slots__ = ()

    def map(self, units: Sequence[Unit], on_progress: ProgressCallback | None = None) -> list[Outcome]:
        out: list[Outcome] = []
        total = len(units)
        for i, u in enumerate(units):
            if on_progress is not None:
                on_progress(i, total, u.label)
            try:
                out.append(Outcome(u.label, u.fn(*u.args)))
            except (DependencyNotInstalled, BrokenPipeError):
                raise  # a missing extra: no unit can run; stdout closed: no one reads the rest
            except Exception as exc:  # noqa: BLE001 - one unit's failure; the others still run
                out.append(Outcome(u.label, error=internal_error(exc)))
        if on_progress is not None:
            on_progress(total, total, "")
        return out

    def __repr__(self) -> str:
        return "Serial()"


def run(units: Iterable[Unit], executor: Executor | None = None,
        on_progress: ProgressCallback | None = None) -> Report:
    """Run every unit through ``executor`` (default :class:`Serial`); a :class:`Report` in unit order.

    Example:
        >>> from ethimon import Unit, run
        >>> report = run([Unit(len, ("ab",), "a"), Unit(int, ("x",), "b")])
        >>> [o.value for o in report.outcomes], report.errors
        ([2, None], 1)
    """
    units = list(units)
    t0 = time.perf_counter()
    outcomes = (executor if executor is not None else Serial()).map(units, on_progress)
    return Report(tuple(outcomes), time.perf_counter() - t0)
