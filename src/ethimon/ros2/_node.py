"""The monitor as a node on a ROS 2 robot's own DDS wire (Cyclone DDS, no rclpy).

:class:`Ros2Monitor` is a Cyclone DDS transport (``ros2/_channel.py``, an
:class:`ethimon.io.Channel`) under :class:`ethimon.io.LiveMonitor`: the mapping
file replay reads (each topic also names its ``type:``), the same holds,
reductions, ``derive: rate``, staleness and future-stamp rules as replay
(``ethimon.io``), and the monitor stepped by :class:`~ethimon.loop.GovernedLoop`
at the mapping's ``rate_hz``
(deadline, stall detection, watchdog, audit log, async risk scoring of the
task-text topic). Every cycle it publishes

* ``/ethimon/override`` (``std_msgs/msg/Bool``): the decision's override, and
* ``/ethimon/decision`` (``std_msgs/msg/String``): the decision as JSON
  (cycle, override, response, violations, faults, margins, R_e),

both reliable, keep last 10, with an offered *deadline* of
``ros2.deadline_cycles`` cycles: a robot-side reader that requests a deadline
is told by its own DDS stack (requested-deadline-missed) when the node goes
silent, crashed or not; ``/ethimon/override`` arriving every cycle is the
heartbeat. The watchdog publishes ``override: true`` itself when the loop
stalls.

Fail closed: a topic with no message yet is a missing input; one whose last
message is older than its ``max_age_s`` is a ``stale`` fault; a value that
cannot be formed (NaN, an empty array) is invalid; a second publisher on a
monitored topic (or one replacing the first mid-run) is a ``signals`` fault
naming its writer and participant, and its samples are not used; so is any
other writer on ``/ethimon/override``; a header stamp further ahead than
``future_tolerance_s`` is a ``stale`` fault; a sample replaced before a cycle
read it is a ``signals`` fault under ``samples: every`` (replay refuses such a bag).

Operators acknowledge latched rules on ``/ethimon/acknowledge``
(``std_msgs/msg/String`` holding ``{"operator": ..., "reason": ...}``),
queued and applied by the loop thread between two cycles (audited); the answer is
published on ``/ethimon/acknowledge_result``. Without DDS Security nothing on
the wire is authenticated, so acknowledgements are refused (and audited as
refused) unless the mapping's ``ros2.allow_unauthenticated_acknowledge``
gives a reason to accept them.
"""

from __future__ import annotations

import os
import threading
from collections.abc import Callable
from typing import Any

from ..errors import Ros2Error, SpecError
from ..io import LiveMonitor, Mapping, SignalMap, check_against_spec, decision_json, load_mapping
from ..io import mapping_error as _merr
from ..io import parse_field_path
from ..io import ByName
from ..loop import AsyncRiskSource, GovernedLoop, LoopConfig, LoopStats, ProcessEstimator
from ..runtime import Decision, Monitor
from ..language import Spec
from ._channel import (ACK_RESULT_TOPIC, ACK_TOPIC, DECISION_TOPIC, OVERRIDE_TOPIC, DdsChannel, Subscription)
from ._config import cyclone_config
from ._names import normalize_type
from ._types import MessageTypes

__all__ = ["ACK_RESULT_TOPIC", "ACK_TOPIC", "DECISION_TOPIC", "OVERRIDE_TOPIC", "Ros2Monitor", "decision_json",
           "run_ros2"]


class Ros2Monitor:
    """A :class:`~ethimon.Monitor` live on a ROS 2 DDS domain (Cyclone DDS; ``pip install 'ethimon[ros2]'``).

    Args:
        spec: the loaded spec (:func:`ethimon.load_spec`).
        mapping: a :class:`~ethimon.replay.Mapping` or the path of a mapping file (the replay format;
            each topic needs ``type:``).
        domain_id: the ROS 2 domain (``ROS_DOMAIN_ID``; default 0).
        estimator: scores the task text: a ``"module:function"`` factory run in a child process
            (the default for a mapping with a task topic: ``"ethimon.risk:load_estimator"`` with the
            spec's ``risk.estimator`` settings), or an object with ``probs(text)`` run in a thread.
        estimator_kwargs: JSON-ready arguments for a factory string.
        audit: an :class:`~ethimon.audit.AuditLog` (decisions on change, acknowledgements, faults).
        interface, peers, multicast, enclave: network and DDS Security settings (see
            :func:`~ethimon.ros2.cyclone_config`); none given: Cyclone's own configuration.
        config: Cyclone DDS XML instead of those four.
        msg_files: ``.msg`` files or folders for types outside the ROS 2 Humble type store.
        watchdog_s: a watchdog publishes ``override: true`` when no cycle completes for this long
            (default: 5 cycles, at least 50 ms).
        loop_kwargs: more :class:`~ethimon.loop.GovernedLoop` arguments (``deadline_s``, ...).

    Raises:
        SpecError: the mapping does not fit the spec or the message types (file, line, column).
        Ros2Error: a DDS entity cannot be made, or DDS Security is asked for but not available.
        DependencyNotInstalled: cyclonedds or rosbags is missing.
    """

    def __init__(self, spec: Spec, mapping: Mapping | str | os.PathLike, *, domain_id: int = 0,
                 estimator: Any = None, estimator_kwargs: dict[str, Any] | None = None, audit: Any = None,
                 interface: str | None = None, peers: tuple[str, ...] | list[str] = (),
                 multicast: bool | None = None, enclave: str | os.PathLike | None = None,
                 config: str | None = None, msg_files: list | tuple = (), watchdog_s: float | None = None,
                 on_decision: Callable[[Decision], None] | None = None, **loop_kwargs: Any) -> None:
        if not isinstance(spec, Spec):
            raise SpecError(f"Ros2Monitor needs a loaded spec (ethimon.load_spec), got {type(spec).__name__}")
        if not isinstance(mapping, Mapping):
            mapping = load_mapping(mapping)
        if not (isinstance(domain_id, int) and 0 <= domain_id <= 232):
            raise ValueError(f"domain_id={domain_id!r}; a ROS 2 domain id is 0..232 (ROS_DOMAIN_ID)")
        if getattr(mapping, "risk", None) == "none":  # replay's `risk: none` (the risk rule NOT CHECKED)
            raise _merr(mapping, "'risk: none' cannot run live: the monitor's risk rule would have no input and "
                        "fail closed on every cycle (replay reports it NOT CHECKED; a live monitor cannot skip it)",
                        ("risk",), hint="map the task text ('task: {topic: /task}') or a 'p_unsafe' topic for "
                        "ethimon ros2")
        check_against_spec(mapping, spec)
        self.spec, self.mapping, self.domain_id = spec, mapping, domain_id
        self.secure = enclave is not None
        self.types = MessageTypes(msg_files)
        self._kinds: dict[str, str] = {}
        self._subs = self._plan_subscriptions()
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
                    # start the child and load its model now, not when the first task text arrives (its
                    # first inference would otherwise be reported hung for the seconds a model load takes)
                    self._child.probs("warm up")
                except Exception as exc:  # noqa: BLE001
                    self._child.close()
                    raise Ros2Error(f"the risk estimator {estimator} did not start: {exc}"[:600]) from None
                risk = AsyncRiskSource(self._child, text=None)
            elif estimator_kwargs is not None:
                raise ValueError("estimator_kwargs need estimator='module:function'")
            else:
                risk = AsyncRiskSource(estimator, text=None)
        elif estimator is not None:
            raise ValueError("an estimator needs a task topic in the mapping ('task: {topic: ...}')")
        if watchdog_s is None:
            watchdog_s = max(0.05, 5 * period)
        try:
            cfg = {k: loop_kwargs.pop(k) for k in LoopConfig.__dataclass_fields__ if k in loop_kwargs}
            self.loop = GovernedLoop(Monitor(spec), risk=risk, audit=audit, on_decision=on_decision,
                                     config=LoopConfig(period_s=period, watchdog_s=watchdog_s, **cfg),
                                     on_stall=self._stalled, **loop_kwargs)
            self._dds = DdsChannel(self._subs, self.types, domain_id, config if config is not None else cyclone_config(
                interface=interface, peers=tuple(peers), multicast=multicast, enclave=enclave),
                period_s=period, deadline_cycles=mapping.ros2.deadline_cycles, publishers=mapping.ros2.publishers,
                secure=self.secure)
            try:
                #: the io seam: holds, frames, publishing and acknowledgements (applied in the loop thread)
                self.live = LiveMonitor(self.loop, mapping, self._dds, kinds=self._kinds)
            except BaseException:
                self._dds.close()
                raise
        except BaseException:
            if getattr(self, "loop", None) is not None:
                self.loop.stop()  # a Foxglove view it started gives its port back
            if risk is not None:
                risk.stop()
            if self._child is not None:
                self._child.close()
            raise
        self._closed = False
        if audit is not None:
            audit.append("ros2", domain_id=domain_id, secure=self.secure, rate_hz=float(mapping.rate_hz),
                         topics={s.topic: s.msgtype for s in self._subs}, mapping=mapping.path,
                         unauthenticated_acknowledge=mapping.ros2.allow_unauthenticated_acknowledge)

    # ------------------------------------------------------------------ set-up
    def _plan_subscriptions(self) -> list[Subscription]:
        m = self.mapping
        by_topic: dict[str, Subscription] = {}
        for name, sm in m.signals.items():
            loc = ("signals", name)
            if sm.type is None:
                raise _merr(m, f"signal {name!r}: live, each topic needs its message type", loc + ("topic",),
                            hint=f"add 'type: sensor_msgs/msg/JointState' (or the type of {sm.topic}) to this entry")
            t = normalize_type(sm.type)
            if not self.types.known(t):
                raise _merr(m, f"signal {name!r}: unknown message type {t}", loc + ("type",),
                            hint="a ROS 2 Humble standard type, or give its .msg file with --msg")
            self._check_field(t, sm, name, loc)
            sub = by_topic.get(sm.topic)
            if sub is None:
                sub = by_topic[sm.topic] = Subscription(sm.topic, t)
            elif sub.msgtype != t:
                raise _merr(m, f"signal {name!r}: topic {sm.topic} is mapped with two types, {sub.msgtype} and {t}",
                            loc + ("type",), hint="a topic has one message type")
            sub.fields.append((name, parse_field_path(sm.field)))
        subs = list(by_topic.values())
        if m.task is not None:
            t = normalize_type(m.task.type or "std_msgs/msg/String")
            if not self.types.known(t):
                raise _merr(m, f"task: unknown message type {t}", ("task", "type"),
                            hint="the task text is usually std_msgs/msg/String")
            try:
                kind, _ = self.types.resolve(t, parse_field_path(m.task.field))
            except KeyError as exc:
                raise _merr(m, f"task: {exc.args[0]}", ("task", "field")) from None
            if kind != "text":
                raise _merr(m, f"task: field {m.task.field!r} of {t} is {kind}, not text", ("task", "field"),
                            hint="the task topic carries text (std_msgs/msg/String, field 'data')")
            if m.task.topic in by_topic:
                raise _merr(m, f"task: topic {m.task.topic} also carries signals", ("task", "topic"))
            subs.append(Subscription(m.task.topic, t, [("task", parse_field_path(m.task.field))], task=True))
        return subs

    def _check_field(self, t: str, sm: SignalMap, name: str, loc: tuple) -> None:
        m = self.mapping
        # a joint by name (position[panda_joint4]) is an element of the array: its type is the array's
        path = tuple(0 if isinstance(p, ByName) else p for p in parse_field_path(sm.field))
        try:
            kind, detail = self.types.resolve(t, path)
        except KeyError as exc:
            raise _merr(m, f"signal {name!r}: {exc.args[0]}", loc + ("field",)) from None
        self._kinds[name] = "bool" if kind == "number" and detail == "bool" else kind
        if sm.reduce == "value" and kind != "number":
            raise _merr(m, f"signal {name!r}: field {sm.field!r} of {t} is {_says(kind, detail)}, not one number",
                        loc + ("field",), hint="pick a reduction: reduce: max | min | max_abs | norm | mean | index"
                        if kind in ("array", "vector") else "map a numeric field")
        if sm.reduce != "value" and kind not in ("array", "vector"):
            raise _merr(m, f"signal {name!r}: reduce {sm.reduce!r} needs an array of numbers or a vector, but "
                        f"field {sm.field!r} of {t} is {_says(kind, detail)}", loc + ("reduce",),
                        hint="use 'reduce: value' for a single number")
        if sm.time == "header":
            try:
                self.types.resolve(t, ("header", "stamp", "sec"))
            except KeyError:
                raise _merr(m, f"signal {name!r}: {t} has no header.stamp, but the mapping sets 'time: header'",
                            loc + ("time",), hint="use 'time: log' (the receive time)") from None

    # ------------------------------------------------------------------ running
    @property
    def stats(self) -> LoopStats:
        return self.loop.stats

    def run(self, duration_s: float | None = None) -> LoopStats:
        """Govern until ``duration_s`` has passed (``None``: until :meth:`stop`), then close the node."""
        try:
            return self.loop.run(duration_s)
        finally:
            self.close()

    def start(self, duration_s: float | None = None) -> threading.Thread:
        """:meth:`GovernedLoop.start`: the loop in a daemon thread (:meth:`stop` ends it)."""
        return self.loop.start(duration_s)

    def stop(self) -> None:
        self.loop.stop()

    def close(self) -> None:
        """Stop the loop, publish a last ``override: true`` and leave the DDS domain."""
        if getattr(self, "_closed", True):
            return
        self._closed = True
        self.loop.stop()
        try:
            self._dds.write_override(True)  # the node leaving is an override, never a silent "all clear"
        except Exception:  # noqa: BLE001
            pass
        if self.loop.risk is not None:
            self.loop.risk.stop()
        if self._child is not None:
            self._child.close()
        self._dds.close()

    def __enter__(self) -> "Ros2Monitor":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # ------------------------------------------------------------------ the watchdog
    def _stalled(self, reason: str) -> None:
        try:
            self._dds.write_override(True)
        except Exception:  # noqa: BLE001 - the watchdog must not die
            pass

    @property
    def acks_refused(self) -> int:
        return self.live.acks_refused


def _says(kind: str, detail: Any) -> str:
    return {"number": f"a number ({detail})", "text": "text", "array": f"an array of {detail}",
            "vector": f"a vector message ({detail})"}.get(kind, f"a message ({detail})")


def run_ros2(spec: Spec | str | os.PathLike, mapping: Mapping | str | os.PathLike, *,
             duration_s: float | None = None, **kwargs: Any) -> LoopStats:
    """Load ``spec`` (a path or a :class:`~ethimon.Spec`) and ``mapping``, govern the domain for
    ``duration_s`` seconds (``None``: until interrupted) and return the loop's statistics.

    Keyword arguments go to :class:`Ros2Monitor`.
    """
    if not isinstance(spec, Spec):
        from .._api import load_spec
        spec = load_spec(spec)
    node = Ros2Monitor(spec, mapping, **kwargs)
    return node.run(duration_s)
