"""An operator's acknowledgement through a :class:`~ethimon.loop.GovernedLoop`: checked (ISO 13849-1
restart conditions, the audit log's health), applied between two cycles, and audited."""

from __future__ import annotations

import math
import threading
from typing import Any

from ..audit import bounded
from ..runtime import Acknowledgement


class _Acknowledging:
    """:meth:`acknowledge` and its application by the loop thread (a base of ``GovernedLoop``)."""

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
        the audit log reports a fault, so no release goes unrecorded.

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
        req: list[Any] = [operator, reason, threading.Event(), None, task_sha256]
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
        fault, or, with ``acknowledge_clear``, while that reading was missing or below its minimum (a
        person inside the protective distance). A refusal is not remembered."""
        d = self.last_decision
        if d is None:
            return ""  # nothing judged yet: the monitor itself has nothing to release
        firing = [v for v in d.violations if v != "confirm"]
        if firing:
            return "rules still fire on the last cycle: " + ", ".join(firing)
        if d.faults:
            return f"a fault on the last cycle: {d.faults[0].kind} ({d.faults[0].subject or d.faults[0].message})"
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
        operator, reason, done, _, task = req
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
        req[3] = a
        done.set()

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
