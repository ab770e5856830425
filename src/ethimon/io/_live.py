"""``LiveMonitor(loop, mapping, channel)``: a :class:`~ethimon.loop.GovernedLoop` fed from a transport.

Each cycle, in the loop thread: the samples that arrived are put into one :class:`~ethimon.io.Hold` per
mapped signal (the same reduction, ``derive: rate``, staleness and future-stamp rules as replay), the
task text goes to the loop's risk source, the cycle's :class:`~ethimon.io.Frame` (values and faults, the
channel's own faults included) is stepped, and the decision is published on the channel's outlet
(``channel.out``). The acknowledgement requests that arrived are taken with the samples and applied by the
loop thread after that cycle's decision is published, before the next cycle (never during a step). With
``record=True`` every sample and every cycle's time is kept in :attr:`LiveMonitor.recording`, which replay
reads back (:func:`ethimon.replay.recorded_data`).
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from ..audit import bounded
from ..errors import SpecError
from ..runtime import Decision, Fault
from ._channel import TASK_TEXT, AckRequest, Channel, Frame, Sample
from ._hold import Hold
from ._mapping import RISK_INPUTS, Mapping, bool_mismatch, check_against_spec
from ._outlet import decision_json

__all__ = ["LiveMonitor", "Recording", "mapping_error"]


def mapping_error(mapping: Mapping, message: str, loc: tuple, *, hint: str | None = None) -> SpecError:
    """A :class:`SpecError` pointing at ``loc`` in the mapping file (the nearest key it has)."""
    src = mapping._source
    if src is not None:
        try:
            return src.error(message, loc, hint=hint)
        except Exception:  # noqa: BLE001 - a location the file does not have: the nearest one
            return src.error(message, loc[:-1], hint=hint, key=True)
    return SpecError(message, hint=hint)


@dataclass
class Recording:
    """What a live run received and when it judged: every sample (arrival order), the cycle that took each
    (``taken``: an index into ``cycles``) and each cycle's time on both clocks ``(log, header)``; replay reads
    it back (:func:`ethimon.replay.recorded_data`)."""

    samples: list[Sample] = field(default_factory=list)
    cycles: list[tuple[float, float | None]] = field(default_factory=list)
    taken: list[int] = field(default_factory=list)


#: acknowledgement requests kept from one cycle's samples to its decision (more are refused, each answered)
_ACK_PENDING = 64
_OUTLET_METHODS = ("write_override", "write_decision", "write_ack_result")


class LiveMonitor:
    """A :class:`~ethimon.loop.GovernedLoop` (built without ``signals=``) fed from a :class:`Channel`.

    Args:
        loop: the loop; this object becomes its signal source and its decision callback (an
            ``on_decision`` it had is still called, after publishing).
        mapping: the mapping (its ``signals`` and ``task``; ``ros2.allow_unauthenticated_acknowledge``).
        channel: the transport.
        kinds: what the transport knows of each mapped field before any message (``"bool"``,
            ``"number"``, ...): a true/false field on a number input is refused here, with the message
            replay gives.
        record: keep a :class:`Recording` in :attr:`recording`.

    Raises:
        SpecError: the mapping does not fit the spec, cannot run live (``risk: none``, a signal that can
            never go stale) or maps a bool field to a number (located in the mapping file).
    """

    def __init__(self, loop: Any, mapping: Mapping, channel: Channel, *, kinds: dict[str, str] | None = None,
                 record: bool = False) -> None:
        spec = loop.spec
        if mapping.risk == "none":
            raise mapping_error(mapping, "'risk: none' cannot run live: the monitor's risk rule would have no input "
                                "and fail closed on every cycle (replay reports it NOT CHECKED; a live monitor "
                                "cannot skip it)", ("risk",), hint="map the task text ('task: {topic: /task}') or a "
                                "'p_unsafe' topic")
        check_against_spec(mapping, spec, risk_given=loop.risk is not None and mapping.task is None)
        if getattr(loop, "_signals", None) is not None:
            raise ValueError("LiveMonitor is the loop's signal source: build the GovernedLoop without signals=")
        self.loop, self.mapping, self.channel = loop, mapping, channel
        out = getattr(channel, "out", None)
        if out is None or not all(callable(getattr(out, m, None)) for m in _OUTLET_METHODS):
            raise TypeError(f"{type(channel).__name__} has no outlet: a Channel's 'out' is an ethimon.io.Outlet "
                            f"({', '.join(_OUTLET_METHODS)}); what goes out is not written by the channel itself")
        self.out = out  # where the decisions and the answers to acknowledgements go
        self._acks: list[AckRequest] = []  # taken with this cycle's samples, applied after its decision
        self.holds: dict[str, Hold] = {}
        for name, sm in mapping.signals.items():
            limit = mapping.limit_s(name)
            if limit is None and sm.stale:  # never stale by default, not by choice: a dead topic held forever
                raise mapping_error(mapping, f"signal {name!r}: live, every topic needs a staleness limit, and the "
                                    "mapping's max_age_s is null: a publisher that dies would leave its last value "
                                    "in force forever (override off)", ("max_age_s",),
                                    hint=f"set 'max_age_s: <s>' at the top or on this signal; 'stale: false' on "
                                    f"{name!r} if its topic is latched (published once) on purpose")
            kind = (kinds or {}).get(name)
            msg = bool_mismatch(name, spec, sm.topic, sm.type or "?")
            if kind == "bool" and msg is not None:
                raise mapping_error(mapping, msg, ("signals", name, "field"),
                                    hint=f"declare {name!r} with 'type: bool' in the spec, or map a numeric field")
            sig = spec.signals.get(name)
            h = Hold(name, sm, limit, every=mapping.samples_of(name) == "every",
                     tolerance_s=mapping.future_tolerance_s, truth=sig is not None and sig.type == "bool",
                     bool_message=msg)
            self.holds[name] = h
        self._risk_hold = next((h for n, h in self.holds.items() if n in RISK_INPUTS), None)
        self._header = any(sm.time == "header" for sm in mapping.signals.values())
        self._ids = loop.monitor.obligation_ids
        self.recording: Recording | None = Recording() if record else None
        self.acks_refused = 0
        self.acks_dropped = 0
        self._user_on_decision: Callable[[Decision], None] | None = getattr(loop, "_on_decision", None)
        loop._signals = self.frame  # the loop calls these from its own thread, every cycle
        loop._on_decision = self._after

    # ------------------------------------------------------------------ each cycle (the loop thread)
    def frame(self) -> Frame:
        """This cycle's inputs: the samples that arrived, put into their holds, read at the channel's now."""
        ch = self.channel
        faults: list[Fault] = []
        try:
            samples = ch.take()
        except Exception as exc:  # noqa: BLE001 - a transport that fails: nothing new, the holds age
            faults.append(Fault("signals", f"the channel failed to deliver samples: {type(exc).__name__}: {exc}"[:300]))
            samples = ()
        rec = self.recording
        now = ch.now("log")
        wall = ch.now("header") if self._header else None
        try:  # the channel's own faults (listed after the holds'), asked now: one visit to the channel a cycle
            own = tuple(ch.faults())
        except Exception as exc:  # noqa: BLE001
            own = (Fault("signals", f"the channel cannot say what it found: {type(exc).__name__}: {exc}"[:300]),)
        self._take_acks(ch)
        frame = Frame()
        for s in samples:
            if rec is not None:
                rec.samples.append(s)
                rec.taken.append(len(rec.cycles))
            if s.signal == TASK_TEXT:
                self._text(s.value)
                continue
            h = self.holds.get(s.signal)
            if h is None:
                continue
            if h.sm.time == "header":
                if s.t_header is None:
                    faults.append(Fault("invalid", f"{h.name}: {h.sm.topic} has no header.stamp, but the mapping "
                                        "sets 'time: header'", h.name))
                    continue
                h.put(s.value, s.t_header, h.sm.topic, now=wall)
            else:
                h.put(s.value, s.t_log, h.sm.topic)
        if rec is not None:
            rec.cycles.append((now, wall))
        for name, h in self.holds.items():
            at = wall if h.sm.time == "header" else now
            v = h.read(at, faults)
            if v is None:
                continue
            frame[name] = v
            if h is self._risk_hold and self.loop.monitor.max_age_s is not None:
                frame["risk_age_s"] = h.age(at)
        faults.extend(own)
        frame.faults = tuple(faults)
        return frame

    def _text(self, value: Any) -> None:
        risk = self.loop.risk
        if isinstance(value, str) and risk is not None:
            text = value  # never cut: the estimator reads it all or refuses it (fail closed)
            if text != risk.text:
                risk.set_text(text)

    def _take_acks(self, ch: Channel) -> None:
        """The acknowledgement requests that arrived, kept until this cycle's decision is published (at most
        :data:`_ACK_PENDING`; as many again beyond them are refused, each with an answer; more are dropped and
        counted in ``acks_dropped``)."""
        try:
            reqs = list(ch.acks())
        except Exception:  # noqa: BLE001 - a channel that fails here: no requests this cycle
            return
        pending = self._acks
        for req in reqs:
            if len(pending) < _ACK_PENDING:
                pending.append(req)
            elif len(pending) < 2 * _ACK_PENDING:  # answered: refused
                pending.append(AckRequest.refused("too many acknowledgement requests in one cycle",
                                                  sender=req.sender, authenticated=req.authenticated))
            else:  # not even answered (as a transport's full queue drops them), counted
                self.acks_dropped += 1

    def _after(self, d: Decision) -> None:
        """After each cycle's decision: publish it on the outlet, then apply the acknowledgements taken with
        this cycle's samples (the next cycle is the first to see a release)."""
        out = self.out
        try:
            out.write_override(d.override)
            try:
                hold = self.loop.holding() if d.override else []
            except Exception:  # noqa: BLE001 - the description is best effort; the decision is published anyway
                hold = []
            out.write_decision(decision_json(d, self._ids, hold=hold))
        finally:
            try:
                if self._user_on_decision is not None:
                    self._user_on_decision(d)
            finally:  # a callback that raises (a fault the loop records) leaves no request unanswered
                self._apply_acks()

    def _apply_acks(self) -> None:
        reqs, self._acks = self._acks, []
        for req in reqs:
            out = self._ack(req)
            try:
                self.out.write_ack_result(json.dumps(out))
            except Exception:  # noqa: BLE001
                pass

    def _ack(self, req: AckRequest) -> dict[str, Any]:
        operator = req.operator[:200] if isinstance(req.operator, str) else None
        reason = req.reason[:2000] if isinstance(req.reason, str) else ""
        if req.error is not None or not (operator and operator.strip()):
            return self._refuse(None, "", req.sender, req.error or "refused: no operator named")
        allow = self.mapping.ros2.allow_unauthenticated_acknowledge
        if not req.authenticated and allow is None:
            return self._refuse(operator, reason, req.sender,
                                "refused: unauthenticated (no authentication on this transport); the mapping's "
                                "ros2.allow_unauthenticated_acknowledge is not set")
        how = "authenticated" if req.authenticated else f"unauthenticated, allowed by the mapping: {allow}"
        task = req.task_sha256[:128] if isinstance(req.task_sha256, str) else None
        try:
            # in the loop thread, between two cycles: applied now (GovernedLoop.acknowledge)
            a = self.loop.acknowledge(operator, reason=f"{reason} [from {req.sender[:300]} ({how})]", task_sha256=task)
            return {"operator": operator, "released": a.released, "rules": list(a.rules), "message": a.message}
        except Exception as exc:  # noqa: BLE001
            return {"operator": operator, "released": False, "rules": [], "message": f"refused: {exc}"[:300]}

    def _refuse(self, operator: str | None, reason: str, sender: str, message: str) -> dict[str, Any]:
        self.acks_refused += 1
        audit = self.loop.audit
        operator, reason = bounded(operator, 200), bounded(reason, 256)  # a sender's payload (issue 31)
        if audit is not None:
            try:
                audit.append("acknowledge", operator=operator, reason=reason, released=False, rules=[],
                             message=message[:300], sender=sender[:300], cycle=self.loop.monitor.cycle)
            except Exception:  # noqa: BLE001
                pass
        return {"operator": operator if not isinstance(operator, dict) else operator["head"], "released": False,
                "rules": [], "message": message}

    @property
    def skipped(self) -> dict[str, int]:
        """Samples per signal replaced before a cycle read them (after the first cycle)."""
        return {n: h.skipped for n, h in self.holds.items()}
