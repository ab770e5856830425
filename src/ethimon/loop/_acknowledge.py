"""The acknowledgement gate of a :class:`~ethimon.loop.GovernedLoop`: an operator's acknowledgement
checked (ISO 13849-1 restart conditions, the audit log's health), queued for the loop thread, applied
between two cycles and audited; with a spec ``restart:`` block, the separate start that resumes motion
after it (issue 32 item 4). :class:`AckGate` owns the queue and the restart state."""

from __future__ import annotations

import math
import threading
import time
from collections.abc import Mapping
from typing import Any

from ..audit import bounded
from ..language import Response, Spec
from ..runtime import Acknowledgement, Decision, Monitor
from ._feed import RiskFeed
from ._sink import AuditSink

__all__ = ["AckGate"]

_STOP_2 = Response.STOP_2


class _RestartHold(Decision):
    """A decision the loop holds after an accepted acknowledgement until the spec's start: its
    :attr:`reasons` end with :attr:`hold`, the line a person sees."""

    __slots__ = ("hold",)

    @property
    def reasons(self) -> tuple[str, ...]:
        return super().reasons + (self.hold,)


def _true(v: Any) -> bool:
    """A bool input that reads true (``True`` or a NumPy true scalar); anything else is not."""
    return v is True or (type(v).__name__ == "bool_" and bool(v))


class _Request:
    """An operator's request waiting for the loop thread: its answer is set, then ``done``."""

    __slots__ = ("operator", "reason", "done", "answer", "task", "kind")

    def __init__(self, operator: str, reason: str, task: str | None, kind: str) -> None:
        self.operator, self.reason, self.task, self.kind = operator, reason, task, kind
        self.done = threading.Event()
        self.answer: Acknowledgement | None = None

    def settle(self, a: Acknowledgement) -> None:
        self.answer = a
        self.done.set()


class AckGate:
    """The acknowledgement gate: the requests waiting for the loop thread and the restart rules.

    Args:
        clear: ``(signal, minimum)`` (:attr:`LoopConfig.acknowledge_clear`): a manual reset and a start are
            refused while that reading was missing or below the minimum on the last cycle.

    A request (kind ``"acknowledge"`` or ``"start"``) waits in :attr:`queue`; the loop thread applies the
    queue between two cycles (``GovernedLoop._ack_now``).
    """

    __slots__ = ("clear", "refused", "queue", "lock", "awaiting_start", "start_prev", "own_decision")

    def __init__(self, clear: tuple[str, float] | None = None) -> None:
        #: (signal, minimum): a manual reset is refused while that reading is missing or below it
        self.clear = clear
        #: why acknowledgements cannot reach this loop's monitor (``None``: they can); a node without
        #: authentication sets it (``holding()`` then says that only a person at the loop can release)
        self.refused: str | None = None
        #: requests waiting for the loop thread
        self.queue: list[_Request] = []
        self.lock = threading.Lock()
        #: the monitor cycle of the accepted acknowledgement whose start is awaited (``None``: none awaited)
        self.awaiting_start: int | None = None
        self.start_prev = True  # the start input's last value (a rising edge starts)
        self.own_decision: Decision | None = None  # the monitor's own decision of the last held cycle

    def check(self, spec: Spec) -> None:
        """Refuse a ``clear`` signal the spec does not have (a located ``ValueError``)."""
        if self.clear is not None and self.clear[0] not in spec.signals:
            raise ValueError(f"acknowledge_clear={self.clear!r}; expected (signal of the spec, minimum >= 0), "
                             f"e.g. ('human_distance', 1.5): {self.clear[0]!r} is not a signal of spec {spec.name!r}")

    # ------------------------------------------------------------------ requests
    @staticmethod
    def request(operator: str, reason: str, task_sha256: str | None, kind: str) -> _Request:
        """A checked request (a ``ValueError`` for a bad operator, reason or task hash)."""
        verb = "acknowledge" if kind == "acknowledge" else "start_motion"
        if not (isinstance(operator, str) and operator.strip()):
            raise ValueError(f"{verb} needs the operator's name or id (a non-empty string)")
        if not isinstance(reason, str):
            raise ValueError(f"reason must be a string, got {type(reason).__name__}")
        if task_sha256 is not None and not isinstance(task_sha256, str):
            raise ValueError(f"task_sha256 must be a hex string, got {type(task_sha256).__name__}")
        return _Request(operator, reason, task_sha256, kind)

    def wait(self, req: _Request, timeout_s: float) -> Acknowledgement:
        """Queue ``req`` for the running loop thread and wait up to ``timeout_s`` for its answer."""
        with self.lock:
            self.queue.append(req)
        if req.done.wait(timeout_s):
            return req.answer
        with self.lock:
            if req in self.queue:
                self.queue.remove(req)
                return Acknowledgement(False, (), f"refused: the loop did not apply it within {timeout_s:g} s")
        req.done.wait()  # the loop took it just now: its answer follows at once
        return req.answer

    def take(self) -> list[_Request]:
        """The queued requests, in order (the queue is emptied)."""
        with self.lock:
            todo, self.queue = self.queue, []
        return todo

    # ------------------------------------------------------------------ the rules
    def restart_refusal(self, spec: Spec, last: Decision | None, inputs: Mapping[str, Any]) -> str:
        """Why a manual reset must be refused now ('' if it may go to the monitor): ISO 13849-1:2015
        5.2.2, the stop condition is kept until safe conditions for restarting exist. Refused while the
        last cycle had a rule firing (the confirm band's hold excepted: acknowledging confirms it) or a
        fault, while the spec's ``restart.standstill`` input was not true (the robot has not reported
        that the stop completed), or, with ``clear``, while that reading was missing or below
        its minimum (a person inside the protective distance). A refusal is not remembered."""
        d = last
        if d is None:
            return ""  # nothing judged yet: the monitor itself has nothing to release
        firing = [v for v in d.violations if v != "confirm"]
        if firing:
            return "rules still fire on the last cycle: " + ", ".join(firing)
        if d.faults:
            return f"a fault on the last cycle: {d.faults[0].kind} ({d.faults[0].subject or d.faults[0].message})"
        ss = spec.restart.standstill
        if ss is not None and not _true(inputs.get(ss)):
            v = inputs.get(ss)
            return (f"the stop has not completed: {ss} is {'missing' if v is None else repr(v)} on the last cycle "
                    "(restart.standstill: the robot reports standstill, brakes engaged, power state settled)")
        return self.clear_refusal(inputs)

    def clear_refusal(self, inputs: Mapping[str, Any]) -> str:
        """Why a person may be inside the protective distance (``clear``), or ''."""
        if self.clear is not None:
            name, least = self.clear
            v = inputs.get(name)
            x = v if type(v) is float else (float(v) if isinstance(v, int) and not isinstance(v, bool) else None)
            if x is None or not math.isfinite(x):
                return f"no usable {name} reading on the last cycle (acknowledge_clear needs it)"
            if x < least:
                return f"{name} {x:g} is inside the protective distance {least:g} (acknowledge_clear)"
        return ""

    # ------------------------------------------------------------------ applied by the loop thread
    def apply(self, req: _Request, m: Monitor, last: Decision | None, inputs: Mapping[str, Any], sink: AuditSink,
              feed: RiskFeed | None, loop_cycle: int, latch_t: dict[int, float]) -> None:
        """Answer ``req`` (its event set): an acknowledgement to the monitor ``m``, or a start."""
        if req.kind == "start":
            self._start_now(req, m, inputs, sink, loop_cycle)
            return
        operator, reason, task = req.operator, req.reason, req.task
        held = sink.refusal()
        why = self.restart_refusal(m.spec, last, inputs)
        if held is not None:
            a = Acknowledgement(False, (), f"refused: the audit log cannot record it ({held})")
        elif why:
            a = Acknowledgement(False, (), "refused: " + why)
        else:
            try:
                a = m.acknowledge() if task is None else m.acknowledge(task_id=task)
            except Exception as exc:  # noqa: BLE001 - never crash the loop on an operator request
                a = Acknowledgement(False, (), f"refused: acknowledge raised {type(exc).__name__}: {exc}"[:300])
        who, why_text = bounded(operator, 200), bounded(reason, 2000)  # sizes an audit record can hold
        if a.released and "confirm" in a.rules and feed is not None:  # what the operator confirmed
            sink.append("confirm", operator=who, reason=why_text, task_text=feed.task_text,
                        task_sha256=feed.task_key, cycle=m.cycle)
        sink.append("acknowledge", operator=who, reason=why_text, released=a.released, rules=list(a.rules),
                    message=a.message, cycle=m.cycle, task_sha256=task, loop_cycle=loop_cycle)
        if a.released:
            a = sink.durable(a)
        if a.released and "restart" in m.spec.model_fields_set and set(a.rules) - {"confirm"}:
            # a reset never starts motion: the loop holds until the spec's start (ISO 13849-1 5.2.2)
            self.awaiting_start = m.cycle
            self.own_decision = None  # judged again by the next cycle
            latch_t[self.awaiting_start] = time.time()  # holding()'s since_t_unix
            self.start_prev = True  # a start input already on does not count: it must rise
            a = Acknowledgement(True, a.rules, f"{a.message}; {self.waiting_text(m.spec)}")
        req.settle(a)

    # ------------------------------------------------------------------ the start after a reset
    @staticmethod
    def waiting_text(spec: Spec) -> str:
        st = spec.restart.start
        how = "GovernedLoop.start_motion()" if st == "command" else f"the rising edge of input {st}"
        return f"acknowledged; waiting for the start ({how})"

    def _start_refusal(self, spec: Spec, inputs: Mapping[str, Any]) -> str:
        if self.awaiting_start is None:
            if "restart" not in spec.model_fields_set:
                return ("no acknowledged stop waits for a start (the spec has no restart block: an accepted "
                        "acknowledgement releases at once)")
            return "no acknowledged stop waits for a start"
        own = self.own_decision
        if own is None:
            return "no cycle judged since the acknowledgement"
        if own.override:
            why = [f"violated: {v}" for v in own.violations] + [f"fault: {f.kind}" for f in own.faults]
            why += [f"latched: {r}" for r in own.latched_rules if r not in own.violations]
            return "the monitor overrides on the last cycle: " + (", ".join(why) or "override")
        return self.clear_refusal(inputs)

    def _start_now(self, req: _Request, m: Monitor, inputs: Mapping[str, Any], sink: AuditSink,
                   loop_cycle: int) -> None:
        operator, reason = req.operator, req.reason
        held = sink.refusal()
        why = self._start_refusal(m.spec, inputs)
        if held is not None:
            a = Acknowledgement(False, (), f"start refused: the audit log cannot record it ({held})")
        elif why:
            a = Acknowledgement(False, (), "start refused: " + why)
        else:
            a = Acknowledgement(True, ("restart",), "started: motion resumes from the next cycle")
        sink.append("start_motion", operator=bounded(operator, 200), reason=bounded(reason, 2000),
                    accepted=a.released, message=a.message, cycle=m.cycle, loop_cycle=loop_cycle)
        if a.released:
            a = sink.durable(a)
            if a.released:
                self.awaiting_start = None
        req.settle(a)

    def hold(self, d: Decision, inputs: Mapping[str, Any], spec: Spec) -> Decision:
        """This cycle's decision while an acknowledged stop waits for its start (called by the loop only
        then): at least stop 2, with the reason a person sees. A rising edge of the spec's start input
        is queued as a start, taken (or refused) at the next cycle like :meth:`GovernedLoop.start_motion`."""
        self.own_decision = d
        st = spec.restart.start
        if st != "command":
            on = _true(inputs.get(st))
            if on and not self.start_prev:
                with self.lock:
                    self.queue.append(_Request(f"start input {st}", "rising edge", None, "start"))
            self.start_prev = on
        resp = d.response if d.response.severity >= _STOP_2.severity else _STOP_2
        h = _RestartHold(True, resp, d.violations, d.margins, d.risk, d.cycle, d.latched, d.faults,
                         d.awaiting_release, d.ids, d.latched_rules + ("restart",))
        h.hold = self.waiting_text(spec)
        return h

    def holding(self, spec: Spec) -> dict:
        """The :meth:`GovernedLoop.holding` entry of an acknowledged stop that waits for its start."""
        return {"rule": "restart", "response": _STOP_2.value, "since_cycle": self.awaiting_start,
                "release": "start", "hold_cycles": 0, "held_cycles": 0, "acknowledge": False,
                "how": "by the start only: " + self.waiting_text(spec)}
