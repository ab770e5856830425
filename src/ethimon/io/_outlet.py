"""Where a live monitor's answers go: the :class:`Outlet` a transport gives (``channel.out``: the override
every cycle, the decision as JSON, the answer to an acknowledgement), the decision's JSON text
(:func:`decision_json`) and an outlet in memory (:class:`MemoryOutlet`, ``MemoryChannel().out``).

The outlet is a port of its own, not more methods of the :class:`~ethimon.io.Channel`: what comes in
(samples, acknowledgement requests) is read at the start of a cycle, what goes out is written after its
decision, and the two sides keep separate state (readers and queues; writers, their sequence numbers and
whether they are closed). The node's watchdog writes ``override: true`` here from its own thread.
"""

from __future__ import annotations

import json
import math
import threading
import time
from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable

from ..runtime import Decision

__all__ = ["MemoryOutlet", "Outlet", "decision_json"]


def _finite(x: Any) -> Any:
    if isinstance(x, float) and not math.isfinite(x):
        return None if x != x else ("inf" if x > 0 else "-inf")
    return x


def decision_json(d: Decision, ids: tuple[str, ...], *, t_unix: float | None = None,
                  hold: list | None = None) -> str:
    """The JSON text published as the decision of one cycle (strict JSON: no NaN/inf); ``hold``: what
    holds the arm (:meth:`GovernedLoop.holding <ethimon.loop.GovernedLoop.holding>`)."""
    margins = {oid: _finite(float(m)) for oid, m in zip(ids, d.margins)} if d.margins else {}
    return json.dumps({
        "cycle": d.cycle, "t_unix": t_unix if t_unix is not None else time.time(),
        "override": bool(d.override), "response": d.response.value, "violations": list(d.violations),
        "faults": [{"kind": f.kind, "subject": f.subject, "message": f.message} for f in d.faults],
        "margins": margins, "risk": _finite(d.risk) if d.risk is not None else None,
        "latched": bool(d.latched), "latched_rules": list(d.latched_rules), "hold": hold or []},
        separators=(",", ":"), allow_nan=False)


@runtime_checkable
class Outlet(Protocol):
    """What a transport publishes for :class:`~ethimon.io.LiveMonitor` (a channel's ``out``). Called from
    the loop thread after each cycle's decision, and :meth:`write_override` also from the node's watchdog
    thread (so it must be safe to call from two threads); none may block or raise, and a closed outlet
    writes nothing."""

    def write_override(self, value: bool) -> None:
        """Publish the override (every cycle: the heartbeat)."""

    def write_decision(self, text: str) -> None:
        """Publish the decision (JSON, :func:`decision_json`)."""

    def write_ack_result(self, text: str) -> None:
        """Publish the answer to an acknowledgement (JSON)."""


@dataclass
class MemoryOutlet:
    """An :class:`Outlet` in memory: what was written, in order (``overrides``, ``decisions``,
    ``ack_results``)."""

    overrides: list = field(default_factory=list)
    decisions: list = field(default_factory=list)
    ack_results: list = field(default_factory=list)

    def __post_init__(self) -> None:
        self._lock = threading.Lock()  # the watchdog thread writes the override too

    def write_override(self, value: bool) -> None:
        with self._lock:
            self.overrides.append(bool(value))

    def write_decision(self, text: str) -> None:
        self.decisions.append(text)

    def write_ack_result(self, text: str) -> None:
        self.ack_results.append(text)
