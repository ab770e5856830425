"""What a transport must provide to run the monitor live (:class:`Channel`: what comes in, and its
:class:`~ethimon.io.Outlet` for what goes out), the values it carries (:class:`Sample`, :class:`AckRequest`),
one cycle's inputs (:class:`Frame`) and an in-memory channel (:class:`MemoryChannel`) that drives
:class:`~ethimon.io.LiveMonitor` without any middleware (tests, simulators, a recording played back)."""

from __future__ import annotations

import json
import threading
from collections import deque
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable

from ..runtime import Fault
from ._outlet import MemoryOutlet, Outlet

__all__ = ["TASK_TEXT", "AckRequest", "Channel", "Frame", "MemoryChannel", "Sample"]

#: the ``signal`` of a :class:`Sample` that carries the task text (not a name a spec signal can have)
TASK_TEXT = "<task>"


class Frame(dict):
    """One cycle's inputs (signal → value) and ``faults``: what the live side found wrong with them
    (stale, stamped in the future, replaced unjudged, a foreign writer); ``GovernedLoop`` fails closed on each."""

    __slots__ = ("faults",)

    def __init__(self, values: dict[str, Any] | None = None, faults: tuple[Fault, ...] = ()) -> None:
        super().__init__(values or {})
        self.faults = faults


@dataclass(frozen=True)
class Sample:
    """One mapped field of one message: the monitor input ``signal`` it feeds (:data:`TASK_TEXT` for the task
    text), ``value`` (the field as the message holds it, before any reduction: the mapping's ``field`` path
    followed, :func:`~ethimon.io.follow`), ``t_log`` (its receive time on the channel's ``now("log")`` clock)
    and ``t_header`` (its ``header.stamp`` in Unix seconds, ``None`` without one)."""

    signal: str
    value: Any
    t_log: float
    t_header: float | None = None

    @property
    def is_task(self) -> bool:
        """Whether this sample is the task text (not a monitor input)."""
        return self.signal == TASK_TEXT


@dataclass(frozen=True)
class AckRequest:
    """An operator's acknowledgement as it came off the transport. ``error``: why it is malformed (refused);
    ``authenticated``: the transport authenticated the sender (e.g. DDS Security)."""

    operator: str | None
    reason: str = ""
    task_sha256: str | None = None
    sender: str = "an unknown sender"
    authenticated: bool = False
    error: str | None = None

    @classmethod
    def from_json(cls, text: str | bytes, *, sender: str = "an unknown sender",
                  authenticated: bool = False) -> "AckRequest":
        """The one parser of an acknowledgement's JSON text (every transport's ``/ethimon/acknowledge``):
        ``{"operator": "<name>", "reason": "<text>"[, "task_sha256": "<hex>"]}``. Never raises: a request
        that is not that shape is an ``AckRequest`` with ``error`` saying what is wrong (refused, audited);
        the operator is cut to 200 characters, the reason to 2000, the task hash to 128."""
        try:
            if isinstance(text, (bytes, bytearray)):
                try:
                    text = bytes(text).decode("utf-8")
                except UnicodeDecodeError:
                    return cls.refused("not UTF-8 text", sender, authenticated)
            try:
                req = json.loads(text)
            except ValueError as exc:
                where = f" (line {exc.lineno}, column {exc.colno}: {exc.msg})" if hasattr(exc, "lineno") else ""
                return cls.refused(f"not JSON{where}", sender, authenticated)
            if not isinstance(req, dict):
                return cls.refused(f"a JSON object expected, got {_kind(req)}", sender, authenticated)
            unknown = sorted(set(req) - set(_ACK_KEYS))
            if unknown:
                import difflib
                near = difflib.get_close_matches(str(unknown[0]), _ACK_KEYS, n=1)
                return cls.refused(f"unknown key {unknown[0]!r}" + (f" (did you mean {near[0]!r}?)" if near else ""),
                                    sender, authenticated)
            if "operator" not in req:
                return cls.refused("'operator' is missing", sender, authenticated)
            for key in _ACK_KEYS:
                v = req.get(key)
                if key in req and not (isinstance(v, str) or (key == "task_sha256" and v is None)):
                    return cls.refused(f"{key!r} is {_kind(v)}, not text", sender, authenticated)
            operator, reason, task = req["operator"], req.get("reason", ""), req.get("task_sha256")
            if not operator.strip():
                return cls.refused("'operator' is empty", sender, authenticated)
            if task is not None and not task.strip():  # an empty hash is not "no task named": refused
                return cls.refused("'task_sha256' is empty", sender, authenticated)
        except Exception as exc:  # noqa: BLE001 - never raise on a sender's bytes
            return cls.refused(f"unreadable ({type(exc).__name__})", sender, authenticated)
        return cls(operator[:200], reason[:2000], task[:128] if task is not None else None, sender,
                   authenticated=authenticated)

    @classmethod
    def refused(cls, why: str, sender: str = "an unknown sender", authenticated: bool = False) -> "AckRequest":
        """A request refused for ``why`` (a transport that cannot even read the text says so this way)."""
        return cls(None, sender=sender, authenticated=authenticated, error=f"refused: {why}; {_ACK_SHAPE}")


#: the keys of an acknowledgement's JSON, and its shape as a refusal states it
_ACK_KEYS = ("operator", "reason", "task_sha256")
_ACK_SHAPE = 'expected {"operator": "<name>", "reason": "<text>"[, "task_sha256": "<hex>"]}'


def _kind(v: Any) -> str:
    return {bool: "true/false", int: "a number", float: "a number", list: "a list", dict: "an object",
            type(None): "null"}.get(type(v), type(v).__name__)


@runtime_checkable
class Channel(Protocol):
    """A transport under :class:`~ethimon.io.LiveMonitor`: what comes in, read once at the start of each
    cycle by the loop thread (:meth:`take`, :meth:`now`, :meth:`faults`, :meth:`acks`, in that order), and
    ``out``, the :class:`~ethimon.io.Outlet` the cycle's decision and the answers to acknowledgements are
    written to after the decision. None may block or raise (a failure is a fault in :meth:`faults`)."""

    #: where the monitor's answers go (override, decision, acknowledgement results)
    out: Outlet

    def now(self, clock: str) -> float:
        """The time on ``"log"`` (the receive times' clock) or ``"header"`` (Unix seconds) now."""

    def take(self) -> Iterable[Sample]:
        """The samples that arrived since the last call, in arrival order (one per mapped signal a message
        feeds, and the task text)."""

    def faults(self) -> tuple[Fault, ...]:
        """What the transport finds wrong now: a foreign writer on a read topic or on the override topic."""

    def acks(self) -> Iterable[AckRequest]:
        """Acknowledgement requests that arrived since the last call (applied after this cycle's decision)."""


@dataclass
class MemoryChannel:
    """A :class:`Channel` in memory: :meth:`publish` a sample, :meth:`request_ack`; what the monitor wrote
    is in ``out`` (a :class:`~ethimon.io.MemoryOutlet`; ``overrides``, ``decisions``, ``ack_results`` read
    it). ``clock`` gives both clocks (a fake clock in tests)."""

    clock: Any = None
    extra_faults: tuple = ()
    out: MemoryOutlet = field(default_factory=MemoryOutlet)

    def __post_init__(self) -> None:
        self._q: deque = deque()
        self._acks: deque = deque()
        self._lock = threading.Lock()

    @property
    def overrides(self) -> list:
        """The overrides written, in order (``out.overrides``)."""
        return self.out.overrides

    @property
    def decisions(self) -> list:
        """The decisions written (JSON texts), in order (``out.decisions``)."""
        return self.out.decisions

    @property
    def ack_results(self) -> list:
        """The answers to acknowledgements written (JSON texts), in order (``out.ack_results``)."""
        return self.out.ack_results

    def now(self, clock: str) -> float:
        import time
        if self.clock is not None:
            return float(self.clock())
        return time.time() if clock == "header" else time.monotonic()

    def publish(self, signal: str, value: Any, t_log: float | None = None, t_header: float | None = None) -> None:
        """A value for ``signal`` (:data:`TASK_TEXT`: a task text) received at ``t_log`` (default: now)."""
        with self._lock:
            self._q.append(Sample(signal, value, self.now("log") if t_log is None else t_log, t_header))

    def request_ack(self, req: AckRequest) -> None:
        with self._lock:
            self._acks.append(req)

    def take(self) -> list[Sample]:
        with self._lock:
            out = list(self._q)
            self._q.clear()
        return out

    def faults(self) -> tuple[Fault, ...]:
        return tuple(self.extra_faults)

    def acks(self) -> list[AckRequest]:
        with self._lock:
            out = list(self._acks)
            self._acks.clear()
        return out
