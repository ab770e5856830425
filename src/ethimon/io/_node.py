"""`LiveNode`: everything a live node is besides its wire, once for every transport: the mapping checked against
the spec and its message types (`plan_topics`, located errors), the risk source of the mapping's task topic (the
spec's estimator in a child process, warmed up), the `GovernedLoop` at the mapping's rate with the watchdog
default, the `LiveMonitor` on the transport's channel, the audit record, and closing on failure and on exit."""

from __future__ import annotations

import os
import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from ..errors import Ros2Error, SpecError
from ..language import Spec
from ..runtime import Decision
from ._channel import TASK_TEXT, Channel, Sample
from ._live import LiveMonitor, mapping_error
from ._mapping import ByName, Mapping, SignalMap, check_against_spec, load_mapping, parse_field_path
from ._values import follow

__all__ = ["LiveNode", "TopicPlan", "plan_topics"]

#: the estimator a live node runs when none is given: the spec's model, loaded in a child process
DEFAULT_ESTIMATOR = "ethimon.risk:load_estimator"


@dataclass
class TopicPlan:
    """One read topic of a live node: its message type and the ``(signal, parsed field path)`` pairs it feeds
    (one ``(TASK_TEXT, path)`` pair for the task topic). A transport keeps its own state beside it."""

    topic: str
    msgtype: str
    fields: list = field(default_factory=list)  # [(signal, path)]
    task: bool = False

    def samples(self, msg: Any, t_log: float) -> list[Sample]:
        """The samples one received message gives, the one way every transport makes them: the task text
        (only if it is text), or each mapped field followed (a field this message lacks: NaN, no usable
        value) with the message's ``header.stamp`` (Unix seconds) when it has one."""
        if self.task:
            try:
                text = follow(msg, self.fields[0][1])
            except Exception:  # noqa: BLE001 - not the field the type check found: no text
                return []
            return [Sample(TASK_TEXT, text, t_log)] if isinstance(text, str) else []
        stamp = None
        st = getattr(getattr(msg, "header", None), "stamp", None)
        if st is not None:
            stamp = st.sec + st.nanosec * 1e-9
        out = []
        for name, path in self.fields:
            try:
                v = follow(msg, path)
            except Exception:  # noqa: BLE001 - a field this sample lacks: no usable value
                v = float("nan")
            out.append(Sample(name, v, t_log, stamp))
        return out

    def unusable(self, t_log: float) -> list[Sample]:
        """A message that could not be read (not this type's payload): no usable value for any of its signals."""
        return [] if self.task else [Sample(name, float("nan"), t_log, None) for name, _ in self.fields]


def _says(kind: str, detail: Any) -> str:
    return {"number": f"a number ({detail})", "text": "text", "array": f"an array of {detail}",
            "vector": f"a vector message ({detail})"}.get(kind, f"a message ({detail})")


def plan_topics(mapping: Mapping, types: Any, make: Callable[..., Any] = TopicPlan) -> tuple[list, dict[str, str]]:
    """The topics a live node reads, each field checked against its message type: ``(topics, kinds)``.

    Args:
        mapping: the mapping (each topic names its ``type:``).
        types: the message types: ``known(msgtype)``, ``resolve(msgtype, path) -> (kind, detail)`` and
            ``normalize(msgtype)`` (:class:`ethimon.ros2.MessageTypes`).
        make: builds one topic from ``(topic, msgtype, fields, task=)`` (a transport's own topic class).

    Returns the topics (the task topic last) and each signal's kind before any message (``"bool"``,
    ``"number"``, ...; :class:`LiveMonitor` refuses a true/false field on a number input with it).

    Raises:
        SpecError: at the mapping entry (file, line, column): a topic without ``type:``, an unknown type, a
            field the type does not have or of the wrong kind for its reduction, ``time: header`` on a type
            without ``header.stamp``, a topic mapped with two types, a task topic that is not text.
    """
    m = mapping
    by_topic: dict[str, Any] = {}
    kinds: dict[str, str] = {}
    for name, sm in m.signals.items():
        loc = ("signals", name)
        if sm.type is None:
            raise mapping_error(m, f"signal {name!r}: live, each topic needs its message type", loc + ("topic",),
                                hint=f"add 'type: sensor_msgs/msg/JointState' (or the type of {sm.topic}) to this "
                                "entry")
        t = types.normalize(sm.type)
        if not types.known(t):
            raise mapping_error(m, f"signal {name!r}: unknown message type {t}", loc + ("type",),
                                hint="a ROS 2 Humble standard type, or give its .msg file with --msg")
        kinds[name] = _check_field(m, types, t, sm, name, loc)
        sub = by_topic.get(sm.topic)
        if sub is None:
            sub = by_topic[sm.topic] = make(sm.topic, t)
        elif sub.msgtype != t:
            raise mapping_error(m, f"signal {name!r}: topic {sm.topic} is mapped with two types, {sub.msgtype} and "
                                f"{t}", loc + ("type",), hint="a topic has one message type")
        sub.fields.append((name, parse_field_path(sm.field)))
    out = list(by_topic.values())
    if m.task is not None:
        t = types.normalize(m.task.type or "std_msgs/msg/String")
        if not types.known(t):
            raise mapping_error(m, f"task: unknown message type {t}", ("task", "type"),
                                hint="the task text is usually std_msgs/msg/String")
        try:
            kind, _ = types.resolve(t, parse_field_path(m.task.field))
        except KeyError as exc:
            raise mapping_error(m, f"task: {exc.args[0]}", ("task", "field")) from None
        if kind != "text":
            raise mapping_error(m, f"task: field {m.task.field!r} of {t} is {kind}, not text", ("task", "field"),
                                hint="the task topic carries text (std_msgs/msg/String, field 'data')")
        if m.task.topic in by_topic:
            raise mapping_error(m, f"task: topic {m.task.topic} also carries signals", ("task", "topic"))
        out.append(make(m.task.topic, t, [(TASK_TEXT, parse_field_path(m.task.field))], task=True))
    return out, kinds


def _check_field(m: Mapping, types: Any, t: str, sm: SignalMap, name: str, loc: tuple) -> str:
    # a joint by name (position[panda_joint4]) is an element of the array: its type is the array's
    path = tuple(0 if isinstance(p, ByName) else p for p in parse_field_path(sm.field))
    try:
        kind, detail = types.resolve(t, path)
    except KeyError as exc:
        raise mapping_error(m, f"signal {name!r}: {exc.args[0]}", loc + ("field",)) from None
    if sm.reduce == "value" and kind != "number":
        raise mapping_error(m, f"signal {name!r}: field {sm.field!r} of {t} is {_says(kind, detail)}, not one number",
                            loc + ("field",), hint="pick a reduction: reduce: max | min | max_abs | norm | mean | "
                            "index" if kind in ("array", "vector") else "map a numeric field")
    if sm.reduce != "value" and kind not in ("array", "vector"):
        raise mapping_error(m, f"signal {name!r}: reduce {sm.reduce!r} needs an array of numbers or a vector, but "
                            f"field {sm.field!r} of {t} is {_says(kind, detail)}", loc + ("reduce",),
                            hint="use 'reduce: value' for a single number")
    if sm.time == "header":
        try:
            types.resolve(t, ("header", "stamp", "sec"))
        except KeyError:
            raise mapping_error(m, f"signal {name!r}: {t} has no header.stamp, but the mapping sets 'time: header'",
                                loc + ("time",), hint="use 'time: log' (the receive time)") from None
    return "bool" if kind == "number" and detail == "bool" else kind


class LiveNode:
    """A :class:`~ethimon.Monitor` live on a transport: what every transport's node shares, so that a
    transport is only its :class:`Channel` and its own settings (:class:`ethimon.ros2.Ros2Monitor`,
    :class:`ethimon.zenoh.ZenohMonitor`).

    Args:
        spec: the loaded spec (:func:`ethimon.load_spec`).
        mapping: a :class:`Mapping` or a mapping file's path.
        open_channel: ``(topics, period_s) -> Channel``: the transport, opened once the loop exists
            (``topics``: :func:`plan_topics`' list); a ``close()`` it has is called when the node closes.
        types: the message types the mapping is checked against (:func:`plan_topics`); ``None``: none
            (every mapped topic is planned as it is, e.g. for a :class:`MemoryChannel`).
        topic: the transport's topic class (``make`` of :func:`plan_topics`).
        estimator: scores the task text: ``None`` (the spec's ``risk.estimator``), a ``"module:function"``
            factory run in a child process (:class:`~ethimon.loop.ProcessEstimator`, started and its model
            loaded now), or anything :func:`ethimon.risk.as_estimator` takes, run in a thread.
        estimator_kwargs: JSON-ready arguments for a factory string (only for one).
        audit: an :class:`~ethimon.audit.AuditLog`: decisions, acknowledgements, faults and one record of the
            node (``audit_fields`` first, then rate, topics, mapping and the acknowledgement policy).
        watchdog_s: the watchdog's limit (default: 5 cycles, at least 50 ms); when it fires, and when the
            node closes, the override is published as ``True``.
        on_decision: called after each cycle's decision is published.
        record: keep every sample in :attr:`live`'s ``recording`` (replay reads it back).
        loop_kwargs: :class:`~ethimon.loop.LoopConfig` fields (``deadline_s``, ...) and more
            :class:`~ethimon.loop.GovernedLoop` arguments (``clock``, ...).

    Raises:
        SpecError: the mapping does not fit the spec or the message types, or cannot run live (located).
        Ros2Error: the risk estimator's child process did not start; whatever ``open_channel`` raises.
    """

    def __init__(self, spec: Spec, mapping: Mapping | str | os.PathLike, open_channel: Callable[[list, float], Any],
                 *, types: Any = None, topic: Callable[..., Any] = TopicPlan, estimator: Any = None,
                 estimator_kwargs: dict[str, Any] | None = None, audit: Any = None, watchdog_s: float | None = None,
                 on_decision: Callable[[Decision], None] | None = None, record: bool = False,
                 audit_fields: dict[str, Any] | None = None, **loop_kwargs: Any) -> None:
        from ..loop import AsyncRiskSource, GovernedLoop, LoopConfig, ProcessEstimator
        from ..runtime import Monitor
        if not isinstance(spec, Spec):
            raise SpecError(f"{type(self).__name__} needs a loaded spec (ethimon.load_spec), got {type(spec).__name__}")
        if not isinstance(mapping, Mapping):
            mapping = load_mapping(mapping)
        if mapping.risk == "none":  # replay's `risk: none` (the risk rule NOT CHECKED)
            raise mapping_error(mapping, "'risk: none' cannot run live: the monitor's risk rule would have no input "
                                "and fail closed on every cycle (replay reports it NOT CHECKED; a live monitor "
                                "cannot skip it)", ("risk",), hint="map the task text ('task: {topic: /task}') or a "
                                "'p_unsafe' topic")
        check_against_spec(mapping, spec)
        self.spec, self.mapping, self.types = spec, mapping, types
        if types is not None:
            self.topics, self._kinds = plan_topics(mapping, types, topic)
        else:
            self.topics, self._kinds = _untyped(mapping, topic), {}
        period = 1.0 / float(mapping.rate_hz)
        risk: Any = None
        self._child: Any = None
        self.channel: Any = None
        self._closed = True
        if mapping.task is None and estimator is not None:
            raise ValueError("an estimator needs a task topic in the mapping ('task: {topic: ...}')")
        if estimator_kwargs is not None and not (estimator is None or isinstance(estimator, str)):
            raise ValueError("estimator_kwargs need estimator='module:function'")
        if mapping.task is not None:
            if estimator is None:
                from ..risk import estimator_kwargs as _ekw
                estimator = DEFAULT_ESTIMATOR
                if estimator_kwargs is None:
                    estimator_kwargs = {k: v for k, v in _ekw(spec).items() if v is not None}
            if isinstance(estimator, str):
                self._child = ProcessEstimator(estimator, estimator_kwargs)
                try:
                    # start the child and load its model now, not when the first task text arrives (its
                    # first inference would otherwise be reported hung for the seconds a model load takes)
                    self._child.probs("warm up")
                except Exception as exc:  # noqa: BLE001
                    self._child.close()
                    raise Ros2Error(f"the risk estimator {estimator} did not start: {exc}"[:600]) from None
                estimator = self._child
            else:
                from ..risk import as_estimator
                estimator = as_estimator(estimator)  # the one hand-over: an estimator, a factory, a function
            risk = AsyncRiskSource(estimator, text=None)
        if watchdog_s is None:
            watchdog_s = max(0.05, 5 * period)
        try:
            cfg = {k: loop_kwargs.pop(k) for k in LoopConfig.__dataclass_fields__ if k in loop_kwargs}
            self.loop = GovernedLoop(Monitor(spec), risk=risk, audit=audit, on_decision=on_decision,
                                     config=LoopConfig(period_s=period, watchdog_s=watchdog_s, **cfg),
                                     on_stall=self._stalled, **loop_kwargs)
            self.channel = open_channel(self.topics, period)
            #: the io seam: holds, frames, publishing and acknowledgements (applied in the loop thread)
            self.live = LiveMonitor(self.loop, mapping, self.channel, kinds=self._kinds, record=record)
        except BaseException:
            if self.channel is not None:
                _close(self.channel)
            if getattr(self, "loop", None) is not None:
                self.loop.stop()  # a Foxglove view it started gives its port back
            if risk is not None:
                risk.stop()
            if self._child is not None:
                self._child.close()
            raise
        self._closed = False
        if audit is not None:
            audit.append("ros2", **(audit_fields or {}), rate_hz=float(mapping.rate_hz),
                         topics={t.topic: t.msgtype for t in self.topics}, mapping=mapping.path,
                         unauthenticated_acknowledge=mapping.ros2.allow_unauthenticated_acknowledge)

    # ------------------------------------------------------------------ running
    @property
    def stats(self) -> Any:
        """The loop's :class:`~ethimon.loop.LoopStats`."""
        return self.loop.stats

    @property
    def acks_refused(self) -> int:
        return self.live.acks_refused

    def run(self, duration_s: float | None = None) -> Any:
        """Govern until ``duration_s`` has passed (``None``: until :meth:`stop`), then close the node."""
        try:
            return self.loop.run(duration_s)
        finally:
            self.close()

    def start(self, duration_s: float | None = None) -> threading.Thread:
        """:meth:`GovernedLoop.start <ethimon.loop.GovernedLoop.start>`: the loop in a daemon thread."""
        return self.loop.start(duration_s)

    def stop(self) -> None:
        self.loop.stop()

    def close(self) -> None:
        """Stop the loop, publish a last ``override: true`` and close the channel."""
        if self._closed:
            return
        self._closed = True
        self.loop.stop()
        try:
            self.channel.out.write_override(True)  # the node leaving is an override, never a silent "all clear"
        except Exception:  # noqa: BLE001
            pass
        if self.loop.risk is not None:
            self.loop.risk.stop()
        if self._child is not None:
            self._child.close()
        _close(self.channel)

    def __enter__(self) -> "LiveNode":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def _stalled(self, reason: str) -> None:
        try:
            self.channel.out.write_override(True)
        except Exception:  # noqa: BLE001 - the watchdog must not die
            pass


def _untyped(mapping: Mapping, make: Callable[..., Any]) -> list:
    by_topic: dict[str, Any] = {}
    for name, sm in mapping.signals.items():
        by_topic.setdefault(sm.topic, make(sm.topic, sm.type or "?")).fields.append((name, parse_field_path(sm.field)))
    out = list(by_topic.values())
    if mapping.task is not None:
        out.append(make(mapping.task.topic, mapping.task.type or "?",
                        [(TASK_TEXT, parse_field_path(mapping.task.field))], task=True))
    return out


def _close(channel: Channel) -> None:
    close = getattr(channel, "close", None)
    if callable(close):
        close()
