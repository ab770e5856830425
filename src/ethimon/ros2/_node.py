"""The monitor as a node on a ROS 2 robot's own DDS wire (Cyclone DDS, no rclpy).

:class:`Ros2Monitor` subscribes to the topics of a replay mapping file (same
fields, reductions and ``max_age_s``; each topic's ``type:``), holds the last
value of every signal (zero-order hold, as replay does), and steps the monitor
with :class:`~ethimon.loop.GovernedLoop` at the mapping's ``rate_hz``
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
naming its writer and participant, and its samples are not used.

Operators acknowledge latched rules on ``/ethimon/acknowledge``
(``std_msgs/msg/String`` holding ``{"operator": ..., "reason": ...}``),
applied through :meth:`GovernedLoop.acknowledge` (audited); the answer is
published on ``/ethimon/acknowledge_result``. Without DDS Security nothing on
the wire is authenticated, so acknowledgements are refused (and audited as
refused) unless the mapping's ``ros2.allow_unauthenticated_acknowledge``
gives a reason to accept them.
"""

from __future__ import annotations

import json
import math
import os
import queue
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from ..errors import DependencyNotInstalled, Ros2Error, SpecError
from ..loop import AsyncRiskSource, GovernedLoop, LoopStats, ProcessEstimator
from ..replay import Mapping, SignalMap, check_against_spec, load_mapping
from ..replay._values import reduce_value
from ..replay._mapping import RISK_INPUTS, parse_field_path
from ..runtime import Decision, Fault, Monitor
from ..language import Spec
from ._config import cyclone_config
from ._names import dds_topic, normalize_type
from ._qos import DEFAULT, SENSOR_DATA, to_cyclone
from ._types import MessageTypes, cyclonedds_modules

__all__ = ["ACK_RESULT_TOPIC", "ACK_TOPIC", "DECISION_TOPIC", "OVERRIDE_TOPIC", "Ros2Monitor", "decision_json",
           "run_ros2"]

OVERRIDE_TOPIC = "/ethimon/override"
DECISION_TOPIC = "/ethimon/decision"
ACK_TOPIC = "/ethimon/acknowledge"
ACK_RESULT_TOPIC = "/ethimon/acknowledge_result"
#: longest task text kept (characters), as replay
MAX_TEXT = 10_000
_U64 = (1 << 64) - 1


class _Frame(dict):
    """One cycle's signals, with the faults the node found in them (read by GovernedLoop)."""

    __slots__ = ("faults",)


class _Slot:
    """One mapped signal: where it comes from and its last value (replaced as one tuple)."""

    __slots__ = ("name", "sm", "path", "limit", "last", "bad")

    def __init__(self, name: str, sm: SignalMap, limit: float | None) -> None:
        self.name, self.sm, self.limit = name, sm, limit
        self.path = parse_field_path(sm.field)
        self.last: tuple[float, float] | None = None  # (value, time: monotonic s, or unix s for time: header)
        self.bad = 0


@dataclass
class _Sub:
    topic: str
    msgtype: str
    slots: list[_Slot]
    task: bool = False
    reader: Any = None
    pinned: tuple = ()          # writer GUIDs accepted on this topic (the first ones seen)
    pinned_handles: frozenset = frozenset()
    foreign: tuple = ()         # Faults naming writers beyond them
    dirty: bool = True
    messages: int = 0


def _finite(x: Any) -> Any:
    if isinstance(x, float) and not math.isfinite(x):
        return None if x != x else ("inf" if x > 0 else "-inf")
    return x


def decision_json(d: Decision, ids: tuple[str, ...], *, t_unix: float | None = None,
                  hold: list | None = None) -> str:
    """The JSON text published on ``/ethimon/decision`` for one decision (strict JSON: no NaN/inf);
    ``hold``: what holds the arm (:meth:`GovernedLoop.holding <ethimon.loop.GovernedLoop.holding>`)."""
    margins = {oid: _finite(float(m)) for oid, m in zip(ids, d.margins)} if d.margins else {}
    return json.dumps({
        "cycle": d.cycle, "t_unix": t_unix if t_unix is not None else time.time(),
        "override": bool(d.override), "response": d.response.value, "violations": list(d.violations),
        "faults": [{"kind": f.kind, "subject": f.subject, "message": f.message} for f in d.faults],
        "margins": margins, "risk": _finite(d.risk) if d.risk is not None else None,
        "latched": bool(d.latched), "latched_rules": list(d.latched_rules), "hold": hold or []},
        separators=(",", ":"), allow_nan=False)


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
        self._subs = self._plan_subscriptions()
        self._user_on_decision = on_decision
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
        self._risk_slot = next((s for sub in self._subs for s in sub.slots if s.name in RISK_INPUTS), None)
        if watchdog_s is None:
            watchdog_s = max(0.05, 5 * period)
        self.acks_refused = 0
        self._ack_q: queue.Queue = queue.Queue(maxsize=64)
        self._ack_thread = threading.Thread(target=self._ack_worker, name="ethimon-ros2-ack", daemon=True)
        self._ack_thread.start()
        try:
            # the loop first: the DDS listeners (task text, acknowledgements) may fire as soon as they exist
            self.loop = GovernedLoop(Monitor(spec), signals=self._frame, risk=risk, period_s=period, audit=audit,
                                     on_decision=self._publish, watchdog_s=watchdog_s, on_stall=self._stalled,
                                     **loop_kwargs)
            self._dds = _Dds(self, config if config is not None else cyclone_config(
                interface=interface, peers=tuple(peers), multicast=multicast, enclave=enclave))
        except BaseException:
            if getattr(self, "loop", None) is not None:
                self.loop.stop()  # a Foxglove view it started gives its port back
            self._ack_q.put(None)
            if risk is not None:
                risk.stop()
            if self._child is not None:
                self._child.close()
            raise
        self._ids = self.loop.monitor.obligation_ids
        self._closed = False
        if audit is not None:
            audit.append("ros2", domain_id=domain_id, secure=self.secure, rate_hz=float(mapping.rate_hz),
                         topics={s.topic: s.msgtype for s in self._subs}, mapping=mapping.path,
                         unauthenticated_acknowledge=mapping.ros2.allow_unauthenticated_acknowledge)

    # ------------------------------------------------------------------ set-up
    def _plan_subscriptions(self) -> list[_Sub]:
        m = self.mapping
        by_topic: dict[str, _Sub] = {}
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
                sub = by_topic[sm.topic] = _Sub(sm.topic, t, [])
            elif sub.msgtype != t:
                raise _merr(m, f"signal {name!r}: topic {sm.topic} is mapped with two types, {sub.msgtype} and {t}",
                            loc + ("type",), hint="a topic has one message type")
            limit = m.limit_s(name)
            if limit is None and sm.stale:  # never stale by default, not by choice: a dead topic held forever
                raise _merr(m, f"signal {name!r}: live, every topic needs a staleness limit, and the mapping's "
                            "max_age_s is null: a publisher that dies would leave its last value in force "
                            "forever (override off)", ("max_age_s",),
                            hint=f"set 'max_age_s: <s>' at the top or on this signal; 'stale: false' on "
                            f"{name!r} if its topic is latched (published once) on purpose")
            sub.slots.append(_Slot(name, sm, limit))
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
            subs.append(_Sub(m.task.topic, t, [], task=True))
        return subs

    def _check_field(self, t: str, sm: SignalMap, name: str, loc: tuple) -> None:
        m = self.mapping
        try:
            kind, detail = self.types.resolve(t, parse_field_path(sm.field))
        except KeyError as exc:
            raise _merr(m, f"signal {name!r}: {exc.args[0]}", loc + ("field",)) from None
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
        self._ack_q.put(None)
        if self.loop.risk is not None:
            self.loop.risk.stop()
        if self._child is not None:
            self._child.close()
        self._dds.close()

    def __enter__(self) -> "Ros2Monitor":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # ------------------------------------------------------------------ per cycle
    def _frame(self) -> _Frame:
        frame = _Frame()
        faults: list[Fault] = []
        mono = time.monotonic()
        wall = None
        for sub in self._subs:
            if not sub.task:
                self._dds.drain(sub)
            if sub.dirty:
                self._dds.check_publishers(sub)
            if sub.foreign:
                faults.extend(sub.foreign)
            for s in sub.slots:
                last = s.last
                if last is None:
                    continue  # the monitor reports it missing
                value, t = last
                if s.sm.time == "header":
                    wall = time.time() if wall is None else wall
                    age = wall - t
                else:
                    age = mono - t
                if s.limit is not None and age > s.limit:
                    faults.append(Fault("stale", f"{s.name}: stale (last {sub.topic} message {age:.3f} s old, "
                                        f"max_age_s {s.limit:g})", s.name))
                    continue
                if s.limit is not None and -age > s.limit:  # a header stamp ahead of this clock never ages
                    faults.append(Fault("stale", f"{s.name}: the last {sub.topic} message is stamped {-age:.3f} s "
                                        f"in the future (more than max_age_s {s.limit:g}): its age cannot be "
                                        "judged (the robot's clock runs ahead of this one, or the stamp is forged)",
                                        s.name))
                    continue
                frame[s.name] = value
                if s is self._risk_slot:
                    frame["risk_age_s"] = max(0.0, age)
        frame.faults = tuple(faults)
        return frame

    def _publish(self, d: Decision) -> None:
        self._dds.write_override(d.override)
        self._dds.write_decision(decision_json(d, self._ids, hold=self.loop.holding(
            None if self.secure or self.mapping.ros2.allow_unauthenticated_acknowledge is not None else
            "unauthenticated: no DDS Security, the mapping's ros2.allow_unauthenticated_acknowledge is not set")
            if d.override else None))
        if self._user_on_decision is not None:
            self._user_on_decision(d)

    def _stalled(self, reason: str) -> None:
        try:
            self._dds.write_override(True)
        except Exception:  # noqa: BLE001 - the watchdog must not die
            pass

    # ------------------------------------------------------------------ from the wire (DDS threads)
    def _on_sample(self, sub: _Sub, msg: Any, info: Any) -> None:
        h = info.publication_handle & _U64 if info is not None else None
        if h is not None and h not in sub.pinned_handles:
            if sub.pinned and not sub.dirty:
                return  # a foreign writer's sample is never used (its presence is a fault)
            self._dds.check_publishers(sub)  # a writer that matched just now
            if h not in sub.pinned_handles:
                return
        sub.messages += 1
        if sub.task:
            text = _follow(msg, parse_field_path(self.mapping.task.field))
            if isinstance(text, str) and self.loop.risk is not None:
                text = text[:MAX_TEXT]
                if text != self.loop.risk.text:
                    self.loop.risk.set_text(text)
            return
        mono = time.monotonic()
        for s in sub.slots:
            try:
                v = reduce_value(_follow(msg, s.path), s.sm)
            except Exception:  # noqa: BLE001 - a value that cannot be formed is NaN: invalid, fails closed
                v = math.nan
            if v != v:
                s.bad += 1
            if s.sm.time == "header":
                st = msg.header.stamp
                s.last = (v, st.sec + st.nanosec * 1e-9)
            else:
                s.last = (v, mono)

    def _on_ack(self, msg: Any, info: Any) -> None:
        sender = self._dds.writer_of(info)
        try:
            req = json.loads(msg.data)
            operator, reason = req.get("operator"), req.get("reason", "")
            task = req.get("task_sha256")  # the text the operator was shown: a confirmation binds to it
            if not (isinstance(operator, str) and operator.strip() and isinstance(reason, str)
                    and (task is None or isinstance(task, str))):
                raise ValueError
        except Exception:  # noqa: BLE001 - any malformed request is refused
            self._refuse_ack(None, "", sender, 'refused: expected {"operator": "<name>", "reason": "<text>"'
                             '[, "task_sha256": "<hex>"]}')
            return
        allow = self.mapping.ros2.allow_unauthenticated_acknowledge
        if not self.secure and allow is None:
            self._refuse_ack(operator, reason, sender, "refused: unauthenticated (no DDS Security on this node); "
                             "the mapping's ros2.allow_unauthenticated_acknowledge is not set")
            return
        how = "DDS Security" if self.secure else f"unauthenticated, allowed by the mapping: {allow}"
        try:
            self._ack_q.put_nowait((operator[:200], reason[:2000], f"{sender} ({how})", task and task[:128]))
        except queue.Full:
            self._refuse_ack(operator, reason, sender, "refused: too many acknowledgements queued")

    def _refuse_ack(self, operator: str | None, reason: str, sender: str, message: str) -> None:
        self.acks_refused += 1
        audit = self.loop.audit
        if audit is not None:
            try:
                audit.append("acknowledge", operator=operator, reason=reason, released=False, rules=[],
                             message=message, via=ACK_TOPIC, sender=sender, cycle=self.loop.monitor.cycle)
            except Exception:  # noqa: BLE001
                pass
        self._dds.write_ack_result(json.dumps({"operator": operator, "released": False, "rules": [],
                                               "message": message}))

    def _ack_worker(self) -> None:
        while True:
            item = self._ack_q.get()
            if item is None:
                return
            operator, reason, via, task = item
            try:
                a = self.loop.acknowledge(operator, reason=f"{reason} [via {ACK_TOPIC} from {via}]",
                                          task_sha256=task)
                out = {"operator": operator, "released": a.released, "rules": list(a.rules), "message": a.message}
            except Exception as exc:  # noqa: BLE001
                out = {"operator": operator, "released": False, "rules": [], "message": f"refused: {exc}"[:300]}
            try:
                self._dds.write_ack_result(json.dumps(out))
            except Exception:  # noqa: BLE001
                pass


class _Dds:
    """The node's DDS entities (participant, readers with listeners, writers)."""

    def __init__(self, node: Ros2Monitor, config: str | None) -> None:
        try:
            from cyclonedds.core import Listener
            from cyclonedds.domain import Domain, DomainParticipant
            from cyclonedds.pub import DataWriter
            from cyclonedds.sub import DataReader
            from cyclonedds.topic import Topic
        except ImportError as exc:
            raise DependencyNotInstalled(f"ethimon ros2 talks DDS with cyclonedds, which is not installed "
                                         f"({exc}); pip install 'ethimon[ros2]'") from None
        cyclonedds_modules()
        self.node = node
        self._lock = threading.Lock()
        self._closed = False
        self.domain = None
        try:
            if config is not None:
                try:
                    self.domain = Domain(node.domain_id, config)
                except Exception as exc:  # noqa: BLE001
                    # this process has the domain already (another participant of it): that configuration holds
                    if "PRECONDITION_NOT_MET" not in str(exc):
                        raise
            self.dp = DomainParticipant(node.domain_id)
        except Exception as exc:  # noqa: BLE001 - DDSException and friends
            raise Ros2Error(f"cannot join DDS domain {node.domain_id}: {exc}"[:600]) from None
        try:
            types = node.types
            self.Bool = types.idl("std_msgs/msg/Bool")
            self.String = types.idl("std_msgs/msg/String")
            m = node.mapping
            period = 1.0 / float(m.rate_hz)
            out_qos = to_cyclone(DEFAULT, deadline_s=m.ros2.deadline_cycles * period, lease_s=max(1.0, 10 * period))
            self.w_override = DataWriter(self.dp, Topic(self.dp, dds_topic(OVERRIDE_TOPIC), self.Bool), out_qos)
            self.w_decision = DataWriter(self.dp, Topic(self.dp, dds_topic(DECISION_TOPIC), self.String), out_qos)
            self.w_ack_result = DataWriter(self.dp, Topic(self.dp, dds_topic(ACK_RESULT_TOPIC), self.String),
                                           to_cyclone(DEFAULT))
            self._listeners = []
            for sub in node._subs:
                cls = types.idl(sub.msgtype)
                # signal topics are taken by the loop thread at the start of each cycle (no Python callback
                # per sample in Cyclone's receive thread: under load those queue up behind the GIL); the
                # task text, rare and needed at once by the estimator thread, comes through a listener
                if sub.task:
                    lst = Listener(on_data_available=self._data_cb(sub),
                                   on_subscription_matched=self._matched_cb(sub))
                else:
                    lst = Listener(on_subscription_matched=self._matched_cb(sub))
                self._listeners.append(lst)
                qos = to_cyclone(DEFAULT if sub.task else SENSOR_DATA)
                sub.reader = DataReader(self.dp, Topic(self.dp, dds_topic(sub.topic), cls), qos, listener=lst)
            ack_l = Listener(on_data_available=self._ack_cb)
            self._listeners.append(ack_l)
            self.r_ack = DataReader(self.dp, Topic(self.dp, dds_topic(ACK_TOPIC), self.String), to_cyclone(DEFAULT),
                                    listener=ack_l)
        except Exception as exc:  # noqa: BLE001
            self.close()
            if isinstance(exc, (Ros2Error, SpecError)):
                raise
            raise Ros2Error(f"cannot create the node's DDS readers and writers: {exc}"[:600]) from None

    # writers -----------------------------------------------------------------
    def write_override(self, value: bool) -> None:
        if not self._closed:
            self.w_override.write(self.Bool(data=bool(value)))

    def write_decision(self, text: str) -> None:
        if not self._closed:
            self.w_decision.write(self.String(data=text))

    def write_ack_result(self, text: str) -> None:
        if not self._closed:
            self.w_ack_result.write(self.String(data=text))

    # readers -----------------------------------------------------------------
    @staticmethod
    def _take(reader: Any, n: int, handle: Callable[[Any, Any], None]) -> None:
        """Take up to ``n`` samples from ``reader`` and hand each valid one to ``handle(sample, info)``.
        Never raises (it runs in Cyclone's thread too): a take that fails takes nothing, so the held
        values age and go stale; a sample that ``handle`` cannot use is dropped."""
        try:
            samples = reader.take(N=n)
        except Exception:  # noqa: BLE001
            return
        for smp in samples:
            info = getattr(smp, "sample_info", None)
            if info is not None and not info.valid_data:
                continue
            try:
                handle(smp, info)
            except Exception:  # noqa: BLE001
                pass

    def _data_cb(self, sub: _Sub) -> Callable:
        node = self.node

        def on_data(reader: Any) -> None:
            self._take(reader, 64, lambda smp, info: node._on_sample(sub, smp, info))
        return on_data

    def drain(self, sub: _Sub) -> None:
        """Take the samples waiting on ``sub``'s reader (the loop thread, once per cycle)."""
        if sub.reader is not None:
            node = self.node
            self._take(sub.reader, 64, lambda smp, info: node._on_sample(sub, smp, info))

    def _matched_cb(self, sub: _Sub) -> Callable:
        def on_matched(reader: Any, status: Any) -> None:
            sub.dirty = True
        return on_matched

    def _ack_cb(self, reader: Any) -> None:
        self._take(reader, 16, self.node._on_ack)

    def writer_of(self, info: Any) -> str:
        """``writer <guid> of participant <guid>`` for a sample's publication, as far as it is known."""
        try:
            ep = self.r_ack.get_matched_publication_data(info.publication_handle)
            return f"writer {ep.key} of participant {ep.participant_key}"
        except Exception:  # noqa: BLE001
            return "an unknown writer"

    def check_publishers(self, sub: _Sub) -> None:
        """Pin the first publishers of ``sub``'s topic; name every other one in ``sub.foreign``."""
        with self._lock:
            if self._closed or sub.reader is None:
                return
            sub.dirty = False
            try:
                handles = sub.reader.get_matched_publications()
                eps = [(h, sub.reader.get_matched_publication_data(h)) for h in handles]
            except Exception as exc:  # noqa: BLE001 - cannot tell who publishes: fail closed
                sub.foreign = (Fault("signals", f"cannot list the publishers of {sub.topic}: {exc}"[:300],
                                     sub.topic),)
                sub.dirty = True
                return
            allowed = self.node.mapping.ros2.publishers
            eps = [(h, ep) for h, ep in eps if ep is not None]
            if not sub.pinned and eps:
                sub.pinned = tuple(str(ep.key) for _, ep in eps[:allowed])
            pinned = set(sub.pinned)
            # instance handles are uint64; the matched-publications list gives them as signed int64
            sub.pinned_handles = frozenset(h & _U64 for h, ep in eps if str(ep.key) in pinned)
            foreign = [ep for _, ep in eps if str(ep.key) not in pinned]
            sub.foreign = tuple(
                Fault("signals", f"another publisher on {sub.topic}: writer {ep.key} of participant "
                      f"{ep.participant_key} (the mapping allows {allowed}; accepted: {', '.join(sub.pinned)})",
                      sub.topic) for ep in foreign)

    def close(self) -> None:
        with self._lock:
            if self._closed:
                return
            self._closed = True
        for sub in self.node._subs:
            sub.reader = None
        for ent in (getattr(self, "dp", None), self.domain):
            if ent is not None:
                try:
                    ent.__del__()  # dds_delete: the participant and everything in it leave the domain now
                except Exception:  # noqa: BLE001
                    pass
        self.dp = self.domain = None


def _follow(msg: Any, path: tuple) -> Any:
    cur = msg
    for part in path:
        if isinstance(part, int):
            try:
                cur = cur[part]
            except (IndexError, TypeError):
                return math.nan
        else:
            cur = getattr(cur, part)
    return cur


def _says(kind: str, detail: Any) -> str:
    return {"number": f"a number ({detail})", "text": "text", "array": f"an array of {detail}",
            "vector": f"a vector message ({detail})"}.get(kind, f"a message ({detail})")


def _merr(mapping: Mapping, message: str, loc: tuple, *, hint: str | None = None) -> SpecError:
    src = mapping._source
    if src is not None:
        try:
            return src.error(message, loc, hint=hint)
        except Exception:  # noqa: BLE001 - a location the file does not have: the nearest one
            return src.error(message, loc[:-1], hint=hint, key=True)
    return SpecError(message, hint=hint)


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
