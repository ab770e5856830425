"""The risk feed of a :class:`~ethimon.loop.GovernedLoop`: the async risk source, the judge tier and the
task text both read, turned into a cycle's ``p``/``risk_age_s``/``pending_s``/``judge``/``task_id`` inputs."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Mapping
from typing import Any

from ..runtime import Fault, Monitor
from ._process import ProcessEstimator
from ._sink import AuditSink
from ._source import AsyncJudgeSource, AsyncRiskSource, RiskReading

__all__ = ["RiskFeed"]


class RiskFeed:
    """A risk source and its judge, read once per cycle without waiting.

    Args:
        risk: an :class:`AsyncRiskSource`, a :class:`ProcessEstimator`, a ``"module:function"`` estimator
            factory (run in a child process; its task text starts as ``None``: fail closed), or an
            estimator in any form :func:`ethimon.risk.as_estimator` takes (run in a thread).
        judge: ``"spec"`` (the spec's ``risk.judge``), a :class:`~ethimon.risk.Judge`, an
            :class:`AsyncJudgeSource` or ``None``.
        monitor: the running monitor (its spec names the judge; its age limit is set here).
        max_risk_age_s: the loop's age limit, used when neither the spec nor the monitor has one.
    """

    __slots__ = ("risk", "judge", "judge_from_spec", "task_text", "task_key", "age_fallback", "isolation")

    def __init__(self, risk: AsyncRiskSource | ProcessEstimator | str, judge: Any, monitor: Monitor,
                 max_risk_age_s: float | None) -> None:
        if isinstance(risk, str):
            risk = ProcessEstimator(risk)  # a loop's string names a factory run in a child process
        if not callable(getattr(risk, "snapshot", None)):
            try:  # an estimator in any form ethimon.risk.as_estimator takes, run in its own thread
                risk = AsyncRiskSource(risk, text=None)
            except TypeError:
                raise TypeError(f"risk must be an AsyncRiskSource, a ProcessEstimator, 'module:function' or an "
                                f"estimator (ethimon.risk.as_estimator), got {type(risk).__name__}") from None
        #: the risk source (:class:`AsyncRiskSource`)
        self.risk = risk
        self.judge_from_spec = isinstance(judge, str)
        if isinstance(judge, str):
            if judge != "spec":
                raise ValueError(f"judge={judge!r}; expected 'spec', None, a Judge or an AsyncJudgeSource")
            judge = None
            if monitor.plan.tiers.judges:  # risk.judge or risk.judges
                from ..risk import load_judge_for
                judge = load_judge_for(monitor.spec)
        if judge is not None and not isinstance(judge, AsyncJudgeSource):
            judge = AsyncJudgeSource(judge)
        #: the judge tier's source (:class:`AsyncJudgeSource`), or ``None``
        self.judge: AsyncJudgeSource | None = judge
        #: the task text the last cycle's inputs are for, and its sha256 (``task_id``)
        self.task_text: str | None = None
        self.task_key: str | None = None
        # staleness is judged by the monitor alone, with one limit: the spec's risk.max_age_s, else
        # the monitor's own max_age_s, else this loop's max_risk_age_s
        own = monitor.max_age_s if monitor.plan.risk_plan.max_age_s is None else None
        self.age_fallback: float | None = own if own is not None else max_risk_age_s
        if monitor.max_age_s is None and self.age_fallback is not None:
            monitor.set_max_age(self.age_fallback)
        self.isolation = "process" if getattr(risk, "isolated", False) else "thread"

    @property
    def model_id(self) -> str | None:
        return self.risk.model_id

    def read(self, inputs: dict, m: Monitor, reasons: list, gone: Callable[[dict], bool], sink: AuditSink,
             loop_cycle: int) -> RiskReading:
        """Put this cycle's risk inputs into ``inputs`` (dropping any the signals carried) and return the
        reading; a reading that faulted adds a fault to ``reasons`` unless it is awaited (``pending_s``)."""
        risk = self.risk
        text = None
        try:
            # the text read before and after the estimate: a set_text() in between (the planner's
            # thread) would pair one text's R_e with another text's judge verdict and task_id
            text = risk.text
            reading = risk.snapshot()
            if reading.fault is None and risk.text is not text:
                reading = RiskReading(None, math.inf, "the task text changed while its estimate was read",
                                      reading.count)
        except Exception as exc:  # noqa: BLE001
            reading = RiskReading(None, math.inf, f"risk source failed: {type(exc).__name__}: {exc}", 0)
        inputs.pop("risk", None)
        inputs.pop("p_unsafe", None)
        inputs.pop("pending_s", None)  # the loop owns it: what it awaits
        if reading.fault is None:
            inputs["p"] = reading.probs  # judged by the monitor (one rule for every risk input)
            inputs["risk_age_s"] = reading.age_s  # judged by the monitor (one age limit)
        else:
            inputs.pop("p", None)
            inputs.pop("risk_age_s", None)
            if reading.pending_s is not None and not gone(inputs):
                inputs["pending_s"] = reading.pending_s  # awaited: the monitor holds (stop 2) or fails closed
            else:
                reasons.append(Fault("estimator", reading.fault))
        if self.judge is not None or m.plan.tiers.confirm_threshold is not None:
            self._tier_inputs(inputs, text, sink, loop_cycle)
        return reading

    def _tier_inputs(self, inputs: dict, text: str | None, sink: AuditSink, loop_cycle: int) -> None:
        """``task_id`` (the hash of ``text``, the task text this cycle's estimate is for) and the judge's
        answer for it (asked once per text)."""
        if text is not self.task_text:
            self.task_text = text
            self.task_key = None if text is None else AsyncJudgeSource.key(text)
            if self.judge is not None:
                self.judge.ask(text, self.task_key)
        inputs["task_id"] = self.task_key  # the loop owns these two inputs
        j = self.judge
        if j is None:
            inputs.pop("judge", None)
            return
        jr = j.result(text, self.task_key) if text is not None else None
        inputs["judge"] = jr.p_unsafe if jr is not None else None
        if j._log:  # unlocked peek; drain() takes the lock
            for res in j.drain():
                sink.append("judge", loop_cycle=loop_cycle, **res.audit_fields())

    def swap(self, old: Monitor, new: Monitor) -> None:
        """A reloaded spec: the judge the new spec names (or none) when the judge came from the spec and
        the new spec names another; its texts are asked again."""
        if self.judge_from_spec and _clients(new.plan.tiers) != _clients(old.plan.tiers):
            if self.judge is not None:
                self.judge.stop(timeout=0.0)
            from ..risk import load_judge_for
            j = load_judge_for(new.spec)
            self.judge = AsyncJudgeSource(j) if j is not None else None
            self.task_text = self.task_key = None


def _clients(tiers: Any) -> tuple:
    """The judges' settings a reload compares (where each is written left out: the same judge moved from
    ``risk.judge`` to a one-judge ``risk.judges`` is the same client)."""
    return tuple(dataclasses.replace(j, where="") for j in tiers.judges)
