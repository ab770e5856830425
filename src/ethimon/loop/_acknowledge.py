"""An operator's acknowledgement through a :class:`~ethimon.loop.GovernedLoop`: checked (ISO 13849-1
restart conditions, the audit log's health), applied between two cycles, and audited; with a spec
``restart:`` block, the separate start that resumes motion after it (issue 32 item 4)."""

from __future__ import annotations

import math
import threading
import time
from typing import Any

from ..audit import bounded
from ..language import Response
from ..runtime import Acknowledgement, Decision

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


class _Acknowledging:
    """:meth:`acknowledge` and its application by the loop thread (a base of ``GovernedLoop``)."""

    #: the monitor cycle of the accepted acknowledgement whose start is awaited (``None``: none awaited)
    _awaiting_start: int | None = None
    _start_prev = True  # the start input's last value (a rising edge starts)
    _own_decision: Decision | None = None  # the monitor's own decision of the last held cycle

    # ------------------------------------------------------------------ operator release
    def acknowledge(self, operator: str, *, reason: str = "", timeout_s: float = 2.0,
                    task_sha256: str | None = None) -> Acknowledgement:
        """An operator's acknowledgement of the manual latches, checked and audited.

        :meth:`Monitor.acknowledge` through the loop: while :meth:`run` drives the
        monitor in another thread, the request is applied by the loop thread
        between two cycles (never during a step) and this call waits up to
        ``timeout_s`` for it; otherwise it is applied now. The monitor refuses it
        (releases nothing) while a manual rule has not held its release condition
        for its ``hold_cycles``. Every request, accepted or refused, is an
        ``acknowledge`` record in the audit log (operator, reason, result,
        monitor cycle); a request is refused without touching the monitor while
        the audit log reports a fault, so no release goes unrecorded. With a spec ``restart:`` block,
        also refused while its ``standstill`` input was false or missing on the last cycle (the stop has
        not completed), and an accepted one starts nothing: the loop holds until :meth:`start_motion`
        or the spec's start input rises.

        Args:
            operator: who acknowledges (a name or badge id; required).
            reason: why, in the operator's words (kept in the audit log).
            timeout_s: how long to wait for a running loop to apply it.
            task_sha256: the sha256 of the task text the operator was shown (``ethimon.risk.text_sha256``).
                While the confirm band holds, a confirmation naming another text than the one the loop
                holds when it applies the request (the planner replaced it meanwhile) is refused.
                ``None``: the text held then is confirmed (the audit record names it).

        Returns:
            The :class:`~ethimon.runtime.Acknowledgement`; refused if the loop did
            not apply it within ``timeout_s``.
        """
        if not (isinstance(operator, str) and operator.strip()):
            raise ValueError("acknowledge needs the operator's name or id (a non-empty string)")
        if not isinstance(reason, str):
            raise ValueError(f"reason must be a string, got {type(reason).__name__}")
        if task_sha256 is not None and not isinstance(task_sha256, str):
            raise ValueError(f"task_sha256 must be a hex string, got {type(task_sha256).__name__}")
        return self._submit([operator, reason, threading.Event(), None, task_sha256, "acknowledge"], timeout_s)

    def start_motion(self, operator: str, *, reason: str = "", timeout_s: float = 2.0) -> Acknowledgement:
        """The separate start after an accepted acknowledgement (a spec ``restart: {start: command}``).

        With a spec ``restart:`` block an accepted acknowledgement of a manual latch is a reset that
        never starts motion: every cycle after it overrides (at least stop 2; ``"restart"`` among the
        decision's ``latched_rules``, its reason in :meth:`holding` and ``Decision.reasons``) until this
        start, or the rising edge of the spec's start input (``restart: {start: <bool input>}``; the
        edge is taken at the next cycle, as this call is). Refused, and not remembered, while no
        acknowledged stop waits for a start, while the last cycle's monitor decision overrides (a rule
        fires or holds, a fault) or, with ``acknowledge_clear``, a person is inside the protective
        distance, and while the audit log cannot record it. Applied between two cycles like
        :meth:`acknowledge`, audited as a ``start_motion`` record; motion resumes from the next cycle.

        Returns:
            The :class:`~ethimon.runtime.Acknowledgement` (``released``: started; ``message`` says why not).
        """
        if not (isinstance(operator, str) and operator.strip()):
            raise ValueError("start_motion needs the operator's name or id (a non-empty string)")
        if not isinstance(reason, str):
            raise ValueError(f"reason must be a string, got {type(reason).__name__}")
        return self._submit([operator, reason, threading.Event(), None, None, "start"], timeout_s)

    def _submit(self, req: list[Any], timeout_s: float) -> Acknowledgement:
        t = self._thread
        if self._running and t is not None and t is not threading.current_thread():
            with self._acks_lock:
                self._acks.append(req)
            if req[2].wait(timeout_s):
                return req[3]
            with self._acks_lock:
                if req in self._acks:
                    self._acks.remove(req)
                    return Acknowledgement(False, (), f"refused: the loop did not apply it within {timeout_s:g} s")
            req[2].wait()  # the loop took it just now: its answer follows at once
            return req[3]
        self._ack_now(req)
        return req[3]

    def _restart_refusal(self) -> str:
        """Why a manual reset must be refused now ('' if it may go to the monitor): ISO 13849-1:2015
        5.2.2, the stop condition is kept until safe conditions for restarting exist. Refused while the
        last cycle had a rule firing (the confirm band's hold excepted: acknowledging confirms it) or a
        fault, while the spec's ``restart.standstill`` input was not true (the robot has not reported
        that the stop completed), or, with ``acknowledge_clear``, while that reading was missing or below
        its minimum (a person inside the protective distance). A refusal is not remembered."""
        d = self.last_decision
        if d is None:
            return ""  # nothing judged yet: the monitor itself has nothing to release
        firing = [v for v in d.violations if v != "confirm"]
        if firing:
            return "rules still fire on the last cycle: " + ", ".join(firing)
        if d.faults:
            return f"a fault on the last cycle: {d.faults[0].kind} ({d.faults[0].subject or d.faults[0].message})"
        ss = self.monitor.spec.restart.standstill
        if ss is not None and not _true(self._last_inputs.get(ss)):
            v = self._last_inputs.get(ss)
            return (f"the stop has not completed: {ss} is {'missing' if v is None else repr(v)} on the last cycle "
                    "(restart.standstill: the robot reports standstill, brakes engaged, power state settled)")
        return self._clear_refusal()

    def _clear_refusal(self) -> str:
        """Why a person may be inside the protective distance (``acknowledge_clear``), or ''."""
        if self.acknowledge_clear is not None:
            name, least = self.acknowledge_clear
            v = self._last_inputs.get(name)
            x = v if type(v) is float else (float(v) if isinstance(v, int) and not isinstance(v, bool) else None)
            if x is None or not math.isfinite(x):
                return f"no usable {name} reading on the last cycle (acknowledge_clear needs it)"
            if x < least:
                return f"{name} {x:g} is inside the protective distance {least:g} (acknowledge_clear)"
        return ""

    def _apply_acks(self) -> None:
        with self._acks_lock:
            todo, self._acks = self._acks, []
        for req in todo:
            self._ack_now(req)

    def _ack_now(self, req: list[Any]) -> None:
        if req[5] == "start":
            self._start_now(req)
            return
        operator, reason, done, _, task, _kind = req
        afault = self._audit_health()
        why = self._restart_refusal()
        if self.audit is not None and (self._audit_failed or afault):
            a = Acknowledgement(False, (), "refused: the audit log cannot record it "
                                f"({afault or 'a record was refused'})")
        elif why:
            a = Acknowledgement(False, (), "refused: " + why)
        else:
            try:
                a = self.monitor.acknowledge() if task is None else self.monitor.acknowledge(task_id=task)
            except Exception as exc:  # noqa: BLE001 - never crash the loop on an operator request
                a = Acknowledgement(False, (), f"refused: acknowledge raised {type(exc).__name__}: {exc}"[:300])
        who, why_text = bounded(operator, 200), bounded(reason, 2000)  # sizes an audit record can hold
        if a.released and "confirm" in a.rules and self.risk is not None:  # what the operator confirmed
            text = self._task_text
            self._log("confirm", operator=who, reason=why_text, task_text=text, task_sha256=self._task_key,
                      cycle=self.monitor.cycle)
        self._log("acknowledge", operator=who, reason=why_text, released=a.released, rules=list(a.rules),
                  message=a.message, cycle=self.monitor.cycle, task_sha256=task,
                  loop_cycle=self.stats.cycles)
        if a.released:
            a = self._durable(a)
        if a.released and "restart" in self.monitor.spec.model_fields_set and set(a.rules) - {"confirm"}:
            # a reset never starts motion: the loop holds until the spec's start (ISO 13849-1 5.2.2)
            self._awaiting_start = self.monitor.cycle
            self._own_decision = None  # judged again by the next cycle
            self._latch_t[self._awaiting_start] = time.time()  # holding()'s since_t_unix
            self._start_prev = True  # a start input already on does not count: it must rise
            a = Acknowledgement(True, a.rules, f"{a.message}; {self._waiting_text()}")
        req[3] = a
        done.set()

    # ------------------------------------------------------------------ the start after a reset
    def _waiting_text(self) -> str:
        st = self.monitor.spec.restart.start
        how = "GovernedLoop.start_motion()" if st == "command" else f"the rising edge of input {st}"
        return f"acknowledged; waiting for the start ({how})"

    def _start_refusal(self) -> str:
        if self._awaiting_start is None:
            if "restart" not in self.monitor.spec.model_fields_set:
                return ("no acknowledged stop waits for a start (the spec has no restart block: an accepted "
                        "acknowledgement releases at once)")
            return "no acknowledged stop waits for a start"
        own = self._own_decision
        if own is None:
            return "no cycle judged since the acknowledgement"
        if own.override:
            why = [f"violated: {v}" for v in own.violations] + [f"fault: {f.kind}" for f in own.faults]
            why += [f"latched: {r}" for r in own.latched_rules if r not in own.violations]
            return "the monitor overrides on the last cycle: " + (", ".join(why) or "override")
        return self._clear_refusal()

    def _start_now(self, req: list[Any]) -> None:
        operator, reason, done = req[0], req[1], req[2]
        afault = self._audit_health()
        why = self._start_refusal()
        if self.audit is not None and (self._audit_failed or afault):
            a = Acknowledgement(False, (), f"start refused: the audit log cannot record it "
                                f"({afault or 'a record was refused'})")
        elif why:
            a = Acknowledgement(False, (), "start refused: " + why)
        else:
            a = Acknowledgement(True, ("restart",), "started: motion resumes from the next cycle")
        self._log("start_motion", operator=bounded(operator, 200), reason=bounded(reason, 2000), accepted=a.released,
                  message=a.message, cycle=self.monitor.cycle, loop_cycle=self.stats.cycles)
        if a.released:
            a = self._durable(a)
            if a.released:
                self._awaiting_start = None
        req[3] = a
        done.set()

    def _restart_hold(self, d: Decision, inputs: dict) -> Decision:
        """This cycle's decision while an acknowledged stop waits for its start (called by the loop only
        then): at least stop 2, with the reason a person sees. A rising edge of the spec's start input
        is queued as a start, taken (or refused) at the next cycle like :meth:`start_motion`."""
        self._own_decision = d
        st = self.monitor.spec.restart.start
        if st != "command":
            on = _true(inputs.get(st))
            if on and not self._start_prev:
                with self._acks_lock:
                    self._acks.append([f"start input {st}", "rising edge", threading.Event(), None, None, "start"])
            self._start_prev = on
        resp = d.response if d.response.severity >= _STOP_2.severity else _STOP_2
        h = _RestartHold(True, resp, d.violations, d.margins, d.risk, d.cycle, d.latched, d.faults,
                         d.awaiting_release, d.ids, d.latched_rules + ("restart",))
        h.hold = self._waiting_text()
        return h

    def _restart_holding(self) -> dict:
        """The :meth:`holding` entry of an acknowledged stop that waits for its start."""
        return {"rule": "restart", "response": _STOP_2.value, "since_cycle": self._awaiting_start,
                "release": "start", "hold_cycles": 0, "held_cycles": 0, "acknowledge": False,
                "how": "by the start only: " + self._waiting_text()}

    def _durable(self, a: Acknowledgement) -> Acknowledgement:
        """A release reaches the robot only once its ``acknowledge`` record is durable: wait (in the
        thread that applies it, before the next cycle can publish it) until the audit writer has written
        and fsync'd it. If it cannot be made durable (the record was refused, the writer failed or is
        too slow), the loop reports an audit fault, so the next cycle overrides anyway, and the operator
        is told the arm stays stopped."""
        log = self.audit
        if log is None:
            return a
        flush = getattr(log, "flush", None)
        why = "the audit log refused the record" if self._audit_failed else ""
        if not why and callable(flush):
            try:
                flush(timeout=float(getattr(log, "max_lag_s", 1.0)))
            except Exception as exc:  # noqa: BLE001 - TimeoutError, OSError: not durable
                why = f"{type(exc).__name__}: {exc}"[:200]
        if not why:
            return a
        self._audit_failed = True  # the next cycle overrides with an audit fault
        return Acknowledgement(False, a.rules, f"refused: the release could not be made durable in the audit log "
                                               f"({why}); the arm stays stopped (audit fault)")
