"""The monitor as a node on a ROS 2 robot that runs ``rmw_zenoh``: a zenoh transport (``_channel.py``) under
:class:`ethimon.io.LiveMonitor`, made from the same spec and mapping file as ``ethimon ros2`` over DDS.

Everything that is not the wire comes from ``ethimon.io`` and ``ethimon.loop``: the holds, reductions,
``derive: rate``, staleness and future-stamp rules (as replay), the decision JSON, the acknowledgements
(applied in the loop thread), the loop's deadline, watchdog and audit log. The mapping's ``ros2:`` block
applies as it is (``publishers``, ``allow_unauthenticated_acknowledge``; ``deadline_cycles`` has no zenoh
QoS to offer and is ignored: the override every cycle is the heartbeat).
"""

from __future__ import annotations

import json
import os
import threading
from collections.abc import Callable
from typing import Any

from ..errors import Ros2Error, SpecError
from ..io import ByName, LiveMonitor, Mapping, check_against_spec, load_mapping, parse_field_path
from ..io import mapping_error as _merr
from ..language import Spec
from ..loop import AsyncRiskSource, GovernedLoop, LoopConfig, LoopStats, ProcessEstimator
from ..runtime import Decision, Monitor
from ._channel import Topic, ZenohChannel, zenoh_module

__all__ = ["ZenohMonitor", "run_zenoh", "zenoh_config"]


def zenoh_config(connect: tuple[str, ...] | list[str] = (), listen: tuple[str, ...] | list[str] = (), *,
                 mode: str = "peer", multicast: bool = False, config_file: str | os.PathLike | None = None) -> Any:
    """A ``zenoh.Config``: rmw_zenoh's session defaults (peer, multicast scouting off, connect to the router on
    ``tcp/localhost:7447``) unless ``connect`` / ``listen`` endpoints are given; ``config_file``: a zenoh
    JSON5 configuration instead (``ZENOH_SESSION_CONFIG_URI`` in rmw_zenoh)."""
    zenoh = zenoh_module()
    try:
        if config_file is not None:
            return zenoh.Config.from_file(os.fspath(config_file))
        c = zenoh.Config()
        c.insert_json5("mode", json.dumps(mode))
        c.insert_json5("scouting/multicast/enabled", "true" if multicast else "false")
        c.insert_json5("connect/endpoints", json.dumps(list(connect) if connect or listen
                                                       else ["tcp/localhost:7447"]))
        c.insert_json5("listen/endpoints", json.dumps(list(listen)))
        return c
    except Exception as exc:  # noqa: BLE001 - ZError: a bad endpoint or file
        raise Ros2Error(f"zenoh configuration: {exc}"[:600]) from None


class ZenohMonitor:
    """A :class:`~ethimon.Monitor` live on a ROS 2 system over zenoh (``rmw_zenoh``; ``pip install
    'ethimon[zenoh]'``).

    Args:
        spec: the loaded spec.
        mapping: a :class:`~ethimon.io.Mapping` or a mapping file's path (each topic names its ``type:``).
        domain_id: the ROS 2 domain (``ROS_DOMAIN_ID``).
        config: a ``zenoh.Config`` (:func:`zenoh_config`; default: connect to ``tcp/localhost:7447``).
        type_hash: ``"rihs01"`` (Jazzy and later) or ``"none"`` (Humble): the hash chunk of the keys written.
        estimator, estimator_kwargs, audit, msg_files, watchdog_s, on_decision, loop_kwargs: as
            :class:`~ethimon.ros2.Ros2Monitor`.
        clock: one clock for the loop and the channel (tests).

    Raises:
        SpecError: the mapping does not fit the spec or the message types (file, line, column).
        Ros2Error: the zenoh session or its publishers and subscribers cannot be made.
        DependencyNotInstalled: eclipse-zenoh or rosbags is missing.
    """

    def __init__(self, spec: Spec, mapping: Mapping | str | os.PathLike, *, domain_id: int = 0,
                 config: Any = None, type_hash: str = "rihs01", estimator: Any = None,
                 estimator_kwargs: dict[str, Any] | None = None, audit: Any = None, msg_files: list | tuple = (),
                 watchdog_s: float | None = None, on_decision: Callable[[Decision], None] | None = None,
                 clock: Callable[[], float] | None = None, record: bool = False, **loop_kwargs: Any) -> None:
        from ..ros2 import MessageTypes
        if not isinstance(spec, Spec):
            raise SpecError(f"ZenohMonitor needs a loaded spec (ethimon.load_spec), got {type(spec).__name__}")
        if not isinstance(mapping, Mapping):
            mapping = load_mapping(mapping)
        if not (isinstance(domain_id, int) and 0 <= domain_id <= 232):
            raise ValueError(f"domain_id={domain_id!r}; a ROS 2 domain id is 0..232 (ROS_DOMAIN_ID)")
        check_against_spec(mapping, spec)
        self.spec, self.mapping, self.domain_id = spec, mapping, domain_id
        self.types = MessageTypes(msg_files)
        self._kinds: dict[str, str] = {}
        self.topics = self._plan()
        period = 1.0 / float(mapping.rate_hz)
        risk: Any = None
        self._child: ProcessEstimator | None = None
        if mapping.task is not None:
            if estimator is None:
                from ..risk import estimator_kwargs as _ekw
                estimator = "ethimon.risk:load_estimator"
                if estimator_kwargs is None:
                    estimator_kwargs = {k: v for k, v in _ekw(spec).items() if v is not None}
            if isinstance(estimator, str):
                self._child = ProcessEstimator(estimator, estimator_kwargs)
                try:
                    self._child.probs("warm up")  # the model loads now, not at the first task text
                except Exception as exc:  # noqa: BLE001
                    self._child.close()
                    raise Ros2Error(f"the risk estimator {estimator} did not start: {exc}"[:600]) from None
                risk = AsyncRiskSource(self._child, text=None)
            else:
                risk = AsyncRiskSource(estimator, text=None)
        elif estimator is not None:
            raise ValueError("an estimator needs a task topic in the mapping ('task: {topic: ...}')")
        if watchdog_s is None:
            watchdog_s = max(0.05, 5 * period)
        if clock is not None:
            loop_kwargs.setdefault("clock", clock)
        self.channel: ZenohChannel | None = None
        try:
            cfg = {k: loop_kwargs.pop(k) for k in LoopConfig.__dataclass_fields__ if k in loop_kwargs}
            self.loop = GovernedLoop(Monitor(spec), risk=risk, audit=audit, on_decision=on_decision,
                                     config=LoopConfig(period_s=period, watchdog_s=watchdog_s, **cfg),
                                     on_stall=self._stalled, **loop_kwargs)
            self.channel = ZenohChannel(self.topics, self.types, domain_id,
                                        config if config is not None else zenoh_config(),
                                        publishers=mapping.ros2.publishers, period_s=period, type_hash=type_hash,
                                        clock=clock)
            #: the io seam: holds, frames, publishing and acknowledgements (applied in the loop thread)
            self.live = LiveMonitor(self.loop, mapping, self.channel, kinds=self._kinds, record=record)
        except BaseException:
            if self.channel is not None:
                self.channel.close()
            if getattr(self, "loop", None) is not None:
                self.loop.stop()
            if risk is not None:
                risk.stop()
            if self._child is not None:
                self._child.close()
            raise
        self._closed = False
        if audit is not None:
            audit.append("ros2", transport="zenoh", domain_id=domain_id, secure=False,
                         rate_hz=float(mapping.rate_hz), topics={t.topic: t.msgtype for t in self.topics},
                         mapping=mapping.path, unauthenticated_acknowledge=mapping.ros2.allow_unauthenticated_acknowledge)

    # ------------------------------------------------------------------ set-up
    def _plan(self) -> list[Topic]:
        """One :class:`Topic` per mapped topic, each field checked against its message type (located errors)."""
        from ..ros2 import normalize_type
        m, types = self.mapping, self.types
        by_topic: dict[str, Topic] = {}
        for name, sm in m.signals.items():
            loc = ("signals", name)
            if sm.type is None:
                raise _merr(m, f"signal {name!r}: live, each topic needs its message type", loc + ("topic",),
                            hint=f"add 'type: sensor_msgs/msg/JointState' (or the type of {sm.topic}) to this entry")
            t = normalize_type(sm.type)
            if not types.known(t):
                raise _merr(m, f"signal {name!r}: unknown message type {t}", loc + ("type",),
                            hint="a ROS 2 Humble standard type, or give its .msg file with --msg")
            path = tuple(0 if isinstance(p, ByName) else p for p in parse_field_path(sm.field))
            try:
                kind, detail = types.resolve(t, path)
            except KeyError as exc:
                raise _merr(m, f"signal {name!r}: {exc.args[0]}", loc + ("field",)) from None
            self._kinds[name] = "bool" if kind == "number" and detail == "bool" else kind
            if sm.reduce == "value" and kind != "number":
                raise _merr(m, f"signal {name!r}: field {sm.field!r} of {t} is not one number ({kind})",
                            loc + ("field",), hint="pick a reduction (reduce: max | min | max_abs | norm | mean | "
                            "index) or map a numeric field")
            if sm.reduce != "value" and kind not in ("array", "vector"):
                raise _merr(m, f"signal {name!r}: reduce {sm.reduce!r} needs an array of numbers or a vector, but "
                            f"field {sm.field!r} of {t} is {kind}", loc + ("reduce",),
                            hint="use 'reduce: value' for a single number")
            if sm.time == "header":
                try:
                    types.resolve(t, ("header", "stamp", "sec"))
                except KeyError:
                    raise _merr(m, f"signal {name!r}: {t} has no header.stamp, but the mapping sets 'time: header'",
                                loc + ("time",), hint="use 'time: log' (the receive time)") from None
            topic = by_topic.setdefault(sm.topic, Topic(sm.topic, t))
            if topic.msgtype != t:
                raise _merr(m, f"signal {name!r}: topic {sm.topic} is mapped with two types, {topic.msgtype} and {t}",
                            loc + ("type",), hint="a topic has one message type")
            topic.fields.append((name, parse_field_path(sm.field)))
        out = list(by_topic.values())
        if m.task is not None:
            t = normalize_type(m.task.type or "std_msgs/msg/String")
            if not types.known(t):
                raise _merr(m, f"task: unknown message type {t}", ("task", "type"),
                            hint="the task text is usually std_msgs/msg/String")
            try:
                kind, _ = types.resolve(t, parse_field_path(m.task.field))
            except KeyError as exc:
                raise _merr(m, f"task: {exc.args[0]}", ("task", "field")) from None
            if kind != "text":
                raise _merr(m, f"task: field {m.task.field!r} of {t} is {kind}, not text", ("task", "field"),
                            hint="the task topic carries text (std_msgs/msg/String, field 'data')")
            if m.task.topic in by_topic:
                raise _merr(m, f"task: topic {m.task.topic} also carries signals", ("task", "topic"))
            out.append(Topic(m.task.topic, t, [("task", parse_field_path(m.task.field))], task=True))
        return out

    # ------------------------------------------------------------------ running
    @property
    def stats(self) -> LoopStats:
        return self.loop.stats

    @property
    def acks_refused(self) -> int:
        return self.live.acks_refused

    def run(self, duration_s: float | None = None) -> LoopStats:
        """Govern until ``duration_s`` has passed (``None``: until :meth:`stop`), then close the node."""
        try:
            return self.loop.run(duration_s)
        finally:
            self.close()

    def start(self, duration_s: float | None = None) -> threading.Thread:
        return self.loop.start(duration_s)

    def stop(self) -> None:
        self.loop.stop()

    def close(self) -> None:
        """Stop the loop, publish a last ``override: true`` and close the zenoh session."""
        if getattr(self, "_closed", True):
            return
        self._closed = True
        self.loop.stop()
        try:
            self.channel.write_override(True)  # the node leaving is an override, never a silent "all clear"
        except Exception:  # noqa: BLE001
            pass
        if self.loop.risk is not None:
            self.loop.risk.stop()
        if self._child is not None:
            self._child.close()
        self.channel.close()

    def __enter__(self) -> "ZenohMonitor":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def _stalled(self, reason: str) -> None:
        try:
            self.channel.write_override(True)
        except Exception:  # noqa: BLE001 - the watchdog must not die
            pass


def run_zenoh(spec: Spec | str | os.PathLike, mapping: Mapping | str | os.PathLike, *,
              duration_s: float | None = None, **kwargs: Any) -> LoopStats:
    """Load ``spec`` and ``mapping``, govern over zenoh for ``duration_s`` seconds (``None``: until
    interrupted) and return the loop's statistics. Keyword arguments go to :class:`ZenohMonitor`."""
    if not isinstance(spec, Spec):
        from .._api import load_spec
        spec = load_spec(spec)
    return ZenohMonitor(spec, mapping, **kwargs).run(duration_s)
