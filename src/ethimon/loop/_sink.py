"""The audit sink of a :class:`~ethimon.loop.GovernedLoop`: the log, its health, what a cycle records and
whether a release is durable; a log that fails is a fault, never a crash."""

from __future__ import annotations

from typing import Any

from ..runtime import Acknowledgement, Decision
from ._source import RiskReading
from ._stats import LoopStats

__all__ = ["AuditSink"]


class AuditSink:
    """Writes a loop's records to an audit log (any object with ``append(kind, **fields)``, optionally
    ``fault`` and ``flush(timeout=)``), counting them in the loop's :class:`LoopStats`.

    Owns ``failed`` (the last record was refused: the next cycle overrides) and the last logged state
    (a decision is logged when it changes, or every cycle with ``every_cycle``).
    """

    __slots__ = ("log", "every_cycle", "failed", "state_key", "_stats")

    def __init__(self, log: Any, every_cycle: bool, stats: LoopStats) -> None:
        self.log = log
        self.every_cycle = bool(every_cycle)
        #: a record was refused (or a release could not be made durable): the next cycle overrides
        self.failed = False
        #: the last logged decision state (``None``: log the next one)
        self.state_key: tuple | None = None
        self._stats = stats

    def health(self) -> str | None:
        """What the audit log reports as its fault (its ``fault`` text), or ``None`` when healthy or absent."""
        if self.log is None:
            return None
        try:
            afault = getattr(self.log, "fault", None)
        except Exception as exc:  # noqa: BLE001 - a broken log is a fault, not a crash
            return f"audit log health check raised {type(exc).__name__}: {exc}"[:300]
        return afault if isinstance(afault, str) and afault else None

    def refusal(self) -> str | None:
        """Why a release must be refused because it could not be recorded (``None``: it can be)."""
        if self.log is None:
            return None
        afault = self.health()
        if self.failed or afault:
            return afault or "a record was refused"
        return None

    def append(self, kind: str, **fields: Any) -> bool:
        """One record; ``False`` (and :attr:`failed`) when the log refused it or raised."""
        if self.log is None:
            return True
        try:
            ok = bool(self.log.append(kind, **fields))
        except Exception:  # noqa: BLE001 - a broken log is a fault, not a crash
            ok = False
        if ok:
            self._stats.audit_records += 1
            self.failed = False
        else:
            self._stats.audit_drops += 1
            self.failed = True
        return ok

    def decision(self, d: Decision, inputs: dict, reading: RiskReading | None, ids: tuple, spec_sha256: str | None,
                 model_id: str | None) -> None:
        """A cycle's decision, when its state changed (or every cycle)."""
        key = (d.override, d.response, d.violations, tuple((f.kind, f.subject) for f in d.faults) if d.faults else (),
               d.latched_rules)  # a rule released while another holds the override is a change too
        if not self.every_cycle and key == self.state_key:
            return
        prev = self.state_key
        self.state_key = key
        event = "cycle"
        if prev is None or prev[0] != d.override:
            event = "override_on" if d.override else "override_off"
        elif key != prev:
            event = "change"
        ok = self.append("decision", event=event, loop_cycle=self._stats.cycles - 1, cycle=d.cycle,
                         override=d.override, response=d.response.value, violations=list(d.violations),
                         faults=[f.message for f in d.faults], fault_kinds=[f.kind for f in d.faults],
                         latched=d.latched, latched_rules=list(d.latched_rules), risk=d.risk,
                         margins=dict(zip(ids, d.margins)) if d.margins else {},
                         inputs=inputs, risk_age_s=reading.age_s if reading is not None else None,
                         spec_sha256=spec_sha256, model_id=model_id)
        if not ok:
            self.state_key = None  # log the state again once the queue has room

    def durable(self, a: Acknowledgement) -> Acknowledgement:
        """A release reaches the robot only once its ``acknowledge`` record is durable: wait (in the
        thread that applies it, before the next cycle can publish it) until the audit writer has written
        and fsync'd it. If it cannot be made durable (the record was refused, the writer failed or is
        too slow), the loop reports an audit fault, so the next cycle overrides anyway, and the operator
        is told the arm stays stopped."""
        log = self.log
        if log is None:
            return a
        flush = getattr(log, "flush", None)
        why = "the audit log refused the record" if self.failed else ""
        if not why and callable(flush):
            try:
                flush(timeout=float(getattr(log, "max_lag_s", 1.0)))
            except Exception as exc:  # noqa: BLE001 - TimeoutError, OSError: not durable
                why = f"{type(exc).__name__}: {exc}"[:200]
        if not why:
            return a
        self.failed = True  # the next cycle overrides with an audit fault
        return Acknowledgement(False, a.rules, f"refused: the release could not be made durable in the audit log "
                                               f"({why}); the arm stays stopped (audit fault)")
