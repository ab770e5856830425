"""`LoopConfig`: the settings of a :class:`~ethimon.loop.GovernedLoop` in one frozen, checked value."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

__all__ = ["LoopConfig"]


def _seconds(name: str, v: Any, *, none_ok: bool, zero_ok: bool = False, finite: bool = False) -> None:
    if v is None and none_ok:
        return
    # inf is allowed where a limit may be off (a deadline no cycle misses); NaN never
    ok = (isinstance(v, (int, float)) and not isinstance(v, bool) and not math.isnan(v)
          and (v >= 0 if zero_ok else v > 0) and (finite is False or math.isfinite(v)))
    if not ok:
        raise ValueError(f"LoopConfig {name}={v!r}; expected a {'positive' if not zero_ok else 'non-negative'} "
                         f"{'finite ' if finite else ''}number of seconds" + (" or None" if none_ok else ""))


@dataclass(frozen=True, slots=True)
class LoopConfig:
    """How a :class:`~ethimon.loop.GovernedLoop` paces and judges its cycles (checked when made).

    Attributes:
        period_s: control period (0.001 = 1 kHz).
        deadline_s: a decision ready later than ``scheduled start + deadline_s`` is a missed deadline,
            which is a fault (``None``: ``period_s``).
        stall_s: a gap longer than this between the end of one cycle and the start of the next (the loop,
            or the whole interpreter, was frozen) is a stall: the resuming cycle overrides and
            ``stats.stalls`` counts it (``None``: ``period_s + deadline_s``).
        max_risk_age_s: oldest usable estimate when the spec has no ``risk.max_age_s`` (and the monitor was
            not built with its own ``max_age_s``): the loop sets it on the monitor, which alone judges the
            age. ``None``: no limit here. Used only with a ``risk`` source.
        watchdog_s: if set, a :class:`~ethimon.loop.Watchdog` thread calls the loop's ``on_stall`` (and logs
            a fault) when no cycle completes for this long.
        audit_every_cycle: log every cycle, not just state changes.
        acknowledge_clear: ``(signal, minimum)``: a manual reset (and a start) is refused while that reading
            was missing or below the minimum on the last cycle (a person inside the protective distance),
            e.g. ``("human_distance", 1.5)``; the signal must be one of the spec's.
        verify: the check a reloaded spec must pass before the swap: a callable ``verify(spec)`` (raising or
            returning ``False`` rejects it), or ``"smt"`` for :func:`ethimon.verify.verify_spec` (z3; any
            refuted or unproved property rejects the spec). ``None``: compile only.
    """

    period_s: float = 0.001
    deadline_s: float | None = None
    stall_s: float | None = None
    max_risk_age_s: float | None = 0.5
    watchdog_s: float | None = None
    audit_every_cycle: bool = False
    acknowledge_clear: tuple[str, float] | None = None
    verify: Callable[[Any], Any] | str | None = None

    def __post_init__(self) -> None:
        _seconds("period_s", self.period_s, none_ok=False, finite=True)
        _seconds("deadline_s", self.deadline_s, none_ok=True)
        _seconds("stall_s", self.stall_s, none_ok=True)
        _seconds("max_risk_age_s", self.max_risk_age_s, none_ok=True, zero_ok=True)
        _seconds("watchdog_s", self.watchdog_s, none_ok=True)
        if not isinstance(self.audit_every_cycle, bool):
            raise ValueError(f"LoopConfig audit_every_cycle={self.audit_every_cycle!r}; expected True or False")
        c = self.acknowledge_clear
        if c is not None:
            ok = (isinstance(c, tuple) and len(c) == 2 and isinstance(c[0], str)
                  and isinstance(c[1], (int, float)) and not isinstance(c[1], bool)
                  and math.isfinite(c[1]) and c[1] >= 0)
            if not ok:
                raise ValueError(f"acknowledge_clear={c!r}; expected (signal of the spec, minimum >= 0), e.g. "
                                 "('human_distance', 1.5): the protective distance a manual reset needs")
        if not (self.verify is None or self.verify == "smt" or callable(self.verify)):
            raise ValueError(f"verify={self.verify!r}; expected None, 'smt' or a callable verify(spec)")

    @property
    def deadline(self) -> float:
        """:attr:`deadline_s` resolved (``period_s`` when unset)."""
        return float(self.deadline_s) if self.deadline_s is not None else float(self.period_s)

    @property
    def stall(self) -> float:
        """:attr:`stall_s` resolved (``period_s + deadline`` when unset)."""
        return float(self.stall_s) if self.stall_s is not None else float(self.period_s) + self.deadline
