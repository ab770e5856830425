"""The node's Cyclone DDS entities as an :class:`ethimon.io.Channel`: mapped topics taken once per cycle
by the loop thread (each sample's mapped fields, its receive and header times), the task text, the
acknowledgement requests, and the writers it does not accept: a publisher beyond the first ones on a
monitored topic, and any other writer on ``/ethimon/override``; its outlet (:class:`DdsOutlet`) holds the
three writers."""

from __future__ import annotations

import threading
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from ..errors import DependencyNotInstalled, Ros2Error, SpecError
from ..io import AckRequest, Sample, TopicPlan
from ..runtime import Fault
from ._names import dds_topic
from ._qos import DEFAULT, SENSOR_DATA, to_cyclone
from ._types import cyclonedds_modules

__all__ = ["ACK_RESULT_TOPIC", "ACK_TOPIC", "DECISION_TOPIC", "OVERRIDE_TOPIC", "DdsChannel", "DdsOutlet",
           "Subscription"]

OVERRIDE_TOPIC = "/ethimon/override"
DECISION_TOPIC = "/ethimon/decision"
ACK_TOPIC = "/ethimon/acknowledge"
ACK_RESULT_TOPIC = "/ethimon/acknowledge_result"
_U64 = (1 << 64) - 1
#: acknowledgement requests kept between two cycles (more are refused)
_ACK_QUEUE = 64


@dataclass
class Subscription(TopicPlan):
    """One read topic (:class:`ethimon.io.TopicPlan`: its type, the (signal, parsed field path) it feeds, or
    the task text) and its DDS reader and writers."""

    reader: Any = None
    pinned: tuple = ()          # writer GUIDs accepted on this topic (the first ones seen)
    pinned_handles: frozenset = frozenset()
    foreign: tuple = ()         # Faults naming writers beyond them
    dirty: bool = True
    messages: int = 0


class DdsOutlet:
    """The node's three DDS writers (an :class:`ethimon.io.Outlet`): ``/ethimon/override``,
    ``/ethimon/decision``, ``/ethimon/acknowledge_result``. Once closed (the channel closes it before its
    participant leaves) it writes nothing."""

    def __init__(self, w_override: Any, w_decision: Any, w_ack_result: Any, Bool: Any, String: Any) -> None:
        self.w_override, self.w_decision, self.w_ack_result = w_override, w_decision, w_ack_result
        self.Bool, self.String = Bool, String
        self.closed = False

    def write_override(self, value: bool) -> None:
        if not self.closed:
            self.w_override.write(self.Bool(data=bool(value)))

    def write_decision(self, text: str) -> None:
        if not self.closed:
            self.w_decision.write(self.String(data=text))

    def write_ack_result(self, text: str) -> None:
        if not self.closed:
            self.w_ack_result.write(self.String(data=text))


class DdsChannel:
    """The transport of ``ethimon ros2`` (see the module doc). Made by :class:`~ethimon.ros2.Ros2Monitor`."""

    def __init__(self, subs: list[Subscription], types: Any, domain_id: int, config: str | None, *,
                 period_s: float, deadline_cycles: int, publishers: int, secure: bool) -> None:
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
        self.subs, self.types, self.secure, self.publishers = subs, types, secure, publishers
        self._lock = threading.Lock()
        self._closed = False
        self._acks: deque = deque()
        self.acks_dropped = 0
        self._own_dirty = True
        self._own_foreign: tuple = ()
        self.domain = None
        self.out: DdsOutlet | None = None
        try:
            if config is not None:
                try:
                    self.domain = Domain(domain_id, config)
                except Exception as exc:  # noqa: BLE001
                    # this process has the domain already (another participant of it): that configuration holds
                    if "PRECONDITION_NOT_MET" not in str(exc):
                        raise
            self.dp = DomainParticipant(domain_id)
        except Exception as exc:  # noqa: BLE001 - DDSException and friends
            raise Ros2Error(f"cannot join DDS domain {domain_id}: {exc}"[:600]) from None
        try:
            self.Bool = types.idl("std_msgs/msg/Bool")
            self.String = types.idl("std_msgs/msg/String")
            out_qos = to_cyclone(DEFAULT, deadline_s=deadline_cycles * period_s, lease_s=max(1.0, 10 * period_s))
            t_override = Topic(self.dp, dds_topic(OVERRIDE_TOPIC), self.Bool)
            self.w_override = DataWriter(self.dp, t_override, out_qos)
            self.out = DdsOutlet(
                self.w_override, DataWriter(self.dp, Topic(self.dp, dds_topic(DECISION_TOPIC), self.String), out_qos),
                DataWriter(self.dp, Topic(self.dp, dds_topic(ACK_RESULT_TOPIC), self.String), to_cyclone(DEFAULT)),
                self.Bool, self.String)
            self._listeners = []
            # who else writes /ethimon/override: a reader of our own topic lists every matched writer
            own_l = Listener(on_subscription_matched=self._own_matched)
            self._listeners.append(own_l)
            self.r_override = DataReader(self.dp, t_override, to_cyclone(SENSOR_DATA), listener=own_l)
            for sub in subs:
                cls = types.idl(sub.msgtype)
                # every read topic is taken by the loop thread at the start of each cycle (no Python callback
                # per sample in Cyclone's receive thread: under load those queue up behind the GIL)
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

    # the Channel protocol ------------------------------------------------------------
    def now(self, clock: str) -> float:
        return time.time() if clock == "header" else time.monotonic()

    def take(self) -> list[Sample]:
        out: list[Sample] = []
        for sub in self.subs:
            if sub.reader is None:
                continue
            if sub.dirty:
                self.check_publishers(sub)
            mono = time.monotonic()
            for smp, info in self._take(sub.reader, 64):
                h = info.publication_handle & _U64 if info is not None else None
                if h is not None and h not in sub.pinned_handles:
                    if sub.pinned and not sub.dirty:
                        continue  # a foreign writer's sample is never used (its presence is a fault)
                    self.check_publishers(sub)  # a writer that matched just now
                    if h not in sub.pinned_handles:
                        continue
                sub.messages += 1
                out.extend(sub.samples(smp, mono))
        return out

    def faults(self) -> tuple[Fault, ...]:
        out: list[Fault] = []
        for sub in self.subs:
            if sub.dirty:
                self.check_publishers(sub)
            out.extend(sub.foreign)
        if self._own_dirty:
            self._check_override_writers()
        out.extend(self._own_foreign)
        return tuple(out)

    def acks(self) -> list[AckRequest]:
        out = []
        while self._acks:
            out.append(self._acks.popleft())
        return out

    # readers ---------------------------------------------------------------------------
    @staticmethod
    def _take(reader: Any, n: int) -> list[tuple[Any, Any]]:
        """Up to ``n`` valid samples and their infos. Never raises: a take that fails takes nothing, so the
        held values age and go stale."""
        try:
            samples = reader.take(N=n)
        except Exception:  # noqa: BLE001
            return []
        out = []
        for smp in samples:
            info = getattr(smp, "sample_info", None)
            if info is not None and not info.valid_data:
                continue
            out.append((smp, info))
        return out

    def _matched_cb(self, sub: Subscription) -> Callable:
        def on_matched(reader: Any, status: Any) -> None:
            sub.dirty = True
        return on_matched

    def _own_matched(self, reader: Any, status: Any) -> None:
        self._own_dirty = True

    def _ack_cb(self, reader: Any) -> None:
        for smp, info in self._take(reader, 16):
            sender = self.writer_of(info)
            if len(self._acks) >= _ACK_QUEUE:
                self.acks_dropped += 1  # more than a cycle's worth: dropped unread (no answer, no record)
                continue
            self._acks.append(self._parse_ack(smp, sender))

    def _parse_ack(self, msg: Any, sender: str) -> AckRequest:
        return AckRequest.from_json(getattr(msg, "data", None), sender=f"{sender} via {ACK_TOPIC}",
                                    authenticated=self.secure)

    def writer_of(self, info: Any) -> str:
        """``writer <guid> of participant <guid>`` for a sample's publication, as far as it is known."""
        try:
            ep = self.r_ack.get_matched_publication_data(info.publication_handle)
            return f"writer {ep.key} of participant {ep.participant_key}"
        except Exception:  # noqa: BLE001
            return "an unknown writer"

    def check_publishers(self, sub: Subscription) -> None:
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
            allowed = self.publishers
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

    def _check_override_writers(self) -> None:
        """Every writer on /ethimon/override but this node's own is a fault: a robot reading the topic would
        take its values for this node's (and a dead node's silence would be covered by it)."""
        with self._lock:
            if self._closed:
                return
            self._own_dirty = False
            try:
                mine = str(self.w_override.guid)
                eps = [self.r_override.get_matched_publication_data(h)
                       for h in self.r_override.get_matched_publications()]
            except Exception as exc:  # noqa: BLE001
                self._own_foreign = (Fault("signals", f"cannot list the writers of {OVERRIDE_TOPIC}: {exc}"[:300],
                                           OVERRIDE_TOPIC),)
                self._own_dirty = True
                return
            self._own_foreign = tuple(
                Fault("signals", f"another writer on {OVERRIDE_TOPIC}: writer {ep.key} of participant "
                      f"{ep.participant_key}; a robot reading the override could take its values for this node's",
                      OVERRIDE_TOPIC) for ep in eps if ep is not None and str(ep.key) != mine)

    def close(self) -> None:
        with self._lock:
            if self._closed:
                return
            self._closed = True
            if self.out is not None:
                self.out.closed = True  # nothing written once the participant is leaving
        for sub in self.subs:
            sub.reader = None
        for ent in (getattr(self, "dp", None), self.domain):
            if ent is not None:
                try:
                    ent.__del__()  # dds_delete: the participant and everything in it leave the domain now
                except Exception:  # noqa: BLE001
                    pass
        self.dp = self.domain = None
