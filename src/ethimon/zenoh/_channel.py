"""A zenoh session as an :class:`ethimon.io.Channel`, speaking what ``rmw_zenoh`` speaks (``_keys.py``): the
mapped topics taken once per cycle by the loop thread (CDR decoded with rosbags' type store, each sample's
mapped fields, its receive and header times), the task text, the acknowledgement requests, its outlet
(:class:`ZenohOutlet`: the three writers, each sample with rmw_zenoh's attachment; each writer and reader
has its liveliness token), and the writers it does not accept: a publisher beyond the first ones on a
monitored topic (by the GID in its samples' attachments, and by its liveliness token), a sample whose
publisher cannot be told, and any other writer on ``/ethimon/override``."""

from __future__ import annotations

import os
import threading
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from ..errors import DependencyNotInstalled, Ros2Error
from ..io import AckRequest, Sample, TopicPlan
from ..runtime import Fault
from ._keys import ADMIN_SPACE, HASH_NOT_SUPPORTED, liveliness_token, pack_attachment, parse_token, topic_key, \
    unpack_attachment

__all__ = ["ACK_RESULT_TOPIC", "ACK_TOPIC", "DECISION_TOPIC", "OVERRIDE_TOPIC", "Topic", "ZenohChannel",
           "ZenohOutlet", "zenoh_module"]

OVERRIDE_TOPIC = "/ethimon/override"
DECISION_TOPIC = "/ethimon/decision"
ACK_TOPIC = "/ethimon/acknowledge"
ACK_RESULT_TOPIC = "/ethimon/acknowledge_result"
NODE_NAME = "ethimon"
#: samples taken from one topic in one cycle (more wait for the next cycle)
_TAKE = 256
#: samples a subscriber queues between two cycles; a full queue makes zenoh wait (never drops one unseen)
_QUEUE = 4096
_ACK_QUEUE = 64


def zenoh_module() -> Any:
    """``zenoh`` (eclipse-zenoh), or :class:`DependencyNotInstalled` naming the extra."""
    try:
        import zenoh
    except ImportError as exc:
        raise DependencyNotInstalled(f"ethimon's zenoh transport needs eclipse-zenoh, which is not installed "
                                     f"({exc}); pip install 'ethimon[zenoh]'") from None
    return zenoh


@dataclass
class Topic(TopicPlan):
    """One read topic (:class:`ethimon.io.TopicPlan`: its type, the (signal, parsed field path) it feeds, or
    the task text) and its zenoh subscriber's state."""

    sub: Any = None
    hashes: frozenset = frozenset()  # the type hashes accepted in a sample's key
    pinned: tuple = ()               # publisher GIDs (hex) accepted (the first ones seen)
    strangers: dict = field(default_factory=dict)  # who -> (last seen, Fault)
    messages: int = 0


class ZenohOutlet:
    """The node's three zenoh publishers (an :class:`ethimon.io.Outlet`): every sample carries rmw_zenoh's
    attachment (a sequence number, the time, this node's GID). Safe from two threads (the loop and the
    watchdog both write the override); once closed it writes nothing."""

    def __init__(self, w_override: Any, w_decision: Any, w_ack_result: Any, types: Any, gid: bytes) -> None:
        self.w_override, self.w_decision, self.w_ack_result = w_override, w_decision, w_ack_result
        self.store, self.gid = types.store, gid
        self._string_t = self.store.types["std_msgs/msg/String"]
        bool_t = self.store.types["std_msgs/msg/Bool"]
        self._true = bytes(self.store.serialize_cdr(bool_t(data=True), "std_msgs/msg/Bool"))
        self._false = bytes(self.store.serialize_cdr(bool_t(data=False), "std_msgs/msg/Bool"))
        self._lock = threading.Lock()
        self._seq = 0
        self.closed = False

    def write_override(self, value: bool) -> None:
        self._put(self.w_override, self._true if value else self._false)

    def write_decision(self, text: str) -> None:
        self.write_text(self.w_decision, text)

    def write_ack_result(self, text: str) -> None:
        self.write_text(self.w_ack_result, text)

    def write_text(self, pub: Any, text: str) -> None:
        self._put(pub, bytes(self.store.serialize_cdr(self._string_t(data=text), "std_msgs/msg/String")))

    def close(self) -> None:
        with self._lock:
            self.closed = True

    def _put(self, pub: Any, payload: bytes) -> None:
        with self._lock:
            if self.closed:
                return
            self._seq += 1
            pub.put(payload, attachment=pack_attachment(self._seq, time.time_ns(), self.gid))


class ZenohChannel:
    """The transport of ``ethimon ros2 --transport zenoh``, made by :class:`~ethimon.zenoh.ZenohMonitor`.

    Args:
        topics: the read topics.
        types: a :class:`~ethimon.ros2.MessageTypes` (the CDR definitions).
        domain_id: the ROS 2 domain (the first chunk of every key expression).
        config: a ``zenoh.Config``.
        publishers: how many publishers each read topic may have (the mapping's ``ros2.publishers``).
        period_s: the cycle period (a foreign writer's fault lasts ``max(1 s, 10 cycles)`` after its last sample).
        type_hash: the hash chunk of the keys written: ``"rihs01"`` (REP-2016, rmw_zenoh from Jazzy on) or
            ``"none"`` (``TypeHashNotSupported``: rmw_zenoh on Humble). Read keys accept either.
        clock: one clock for both ``now("log")`` and ``now("header")`` (tests); default monotonic / Unix time.
    """

    def __init__(self, topics: list[Topic], types: Any, domain_id: int, config: Any, *, publishers: int = 1,
                 period_s: float = 0.01, type_hash: str = "rihs01", clock: Callable[[], float] | None = None) -> None:
        zenoh = zenoh_module()
        if type_hash not in ("rihs01", "none"):
            raise ValueError(f"type_hash={type_hash!r}: 'rihs01' (Jazzy and later) or 'none' (Humble)")
        self.topics, self.types, self.domain_id, self.publishers = topics, types, int(domain_id), int(publishers)
        self.clock, self._hash_mode = clock, type_hash
        self._window = max(1.0, 10 * float(period_s))
        self._lock = threading.Lock()
        self._closed = False
        self.acks_dropped = 0
        #: samples taken off the read topics (used or not); of them, payloads that were not their type's CDR
        self.received = self.undecodable = 0
        self.gid = os.urandom(16)
        self.out: ZenohOutlet | None = None
        self._tokens: list = []
        self._endpoints: dict[str, dict[str, Any]] = {}  # live MP tokens per topic: key -> TokenInfo
        self._own_foreign: dict[str, tuple[float, Fault]] = {}
        self.session = None
        try:
            self.session = zenoh.open(config)
        except Exception as exc:  # noqa: BLE001 - ZError and friends
            raise Ros2Error(f"cannot open a zenoh session: {exc}"[:600]) from None
        try:
            self.zid = str(self.session.zid())
            self._eid = 0
            self._tokens.append(self.session.liveliness().declare_token(
                liveliness_token(self.domain_id, self.zid, 0, 0, "NN", NODE_NAME)))
            self.out = ZenohOutlet(self._publisher(OVERRIDE_TOPIC, "std_msgs/msg/Bool"),
                                   self._publisher(DECISION_TOPIC, "std_msgs/msg/String"),
                                   self._publisher(ACK_RESULT_TOPIC, "std_msgs/msg/String"), types, self.gid)
            fifo = zenoh.handlers.FifoChannel
            # another writer on our own override key: its samples reach us (ours do not: remote origin only)
            self.r_override = self.session.declare_subscriber(
                self._key(OVERRIDE_TOPIC, "std_msgs/msg/Bool", "*"), fifo(_QUEUE),
                allowed_origin=zenoh.Locality.REMOTE)
            for t in topics:
                t.hashes = frozenset({self._hash(t.msgtype), HASH_NOT_SUPPORTED})
                # taken by the loop thread each cycle (no Python callback per sample in zenoh's threads)
                t.sub = self.session.declare_subscriber(self._key(t.topic, t.msgtype, "*"), fifo(_QUEUE))
                self._token("MS", t.topic, t.msgtype)
            self.r_ack = self.session.declare_subscriber(self._key(ACK_TOPIC, "std_msgs/msg/String", "*"),
                                                         fifo(_ACK_QUEUE))
            self._token("MS", ACK_TOPIC, "std_msgs/msg/String")
            # who publishes what: every endpoint token of the domain, those alive now first (history)
            self.r_graph = self.session.liveliness().declare_subscriber(f"{ADMIN_SPACE}/{self.domain_id}/**",
                                                                        fifo(_QUEUE), history=True)
        except Exception as exc:  # noqa: BLE001
            self.close()
            raise Ros2Error(f"cannot declare the node's zenoh publishers and subscribers: {exc}"[:600]) from None
        self._pending: deque = deque()

    # names -------------------------------------------------------------------------------
    def _hash(self, msgtype: str) -> str:
        if self._hash_mode == "none":
            return HASH_NOT_SUPPORTED
        return self.types.store.hash_rihs01(msgtype)

    def _key(self, topic: str, msgtype: str, type_hash: str | None = None) -> str:
        return topic_key(self.domain_id, topic, self.types.dds_name(msgtype),
                         self._hash(msgtype) if type_hash is None else type_hash)

    def _token(self, kind: str, topic: str, msgtype: str) -> None:
        self._eid += 1
        self._tokens.append(self.session.liveliness().declare_token(liveliness_token(
            self.domain_id, self.zid, 0, self._eid, kind, NODE_NAME, topic, self.types.dds_name(msgtype),
            self._hash(msgtype))))

    def _publisher(self, topic: str, msgtype: str) -> Any:
        pub = self.session.declare_publisher(self._key(topic, msgtype))
        self._token("MP", topic, msgtype)
        return pub

    # the Channel protocol ------------------------------------------------------------
    def now(self, clock: str) -> float:
        if self.clock is not None:
            return float(self.clock())
        return time.time() if clock == "header" else time.monotonic()

    def poll(self) -> int:
        """Move what arrived into this channel (received now, on the ``log`` clock); how many samples wait to
        be taken. :meth:`take` polls first; a test may poll to know a sample is in."""
        if self._closed:
            return len(self._pending)
        t_log = self.now("log")
        for t in self.topics:
            for _ in range(_TAKE):
                try:
                    smp = t.sub.try_recv()
                except Exception:  # noqa: BLE001 - a subscriber that fails gives nothing: the holds age
                    break
                if smp is None:
                    break
                self.received += 1
                self._sample(t, smp, t_log)
        return len(self._pending)

    def take(self) -> list[Sample]:
        self.poll()
        out = list(self._pending)
        self._pending.clear()
        return out

    def faults(self) -> tuple[Fault, ...]:
        out: list[Fault] = []
        self._graph()
        now = self.now("log")
        for t in self.topics:
            mp = self._endpoints.get(t.topic, {})
            if len(mp) > self.publishers:  # declared publishers beyond those allowed (even before a sample)
                out.append(Fault("signals", f"{len(mp)} publishers declared on {t.topic} (the mapping allows "
                                 f"{self.publishers}): " + "; ".join(i.who for i in mp.values())[:240], t.topic))
            for who, (seen, f) in list(t.strangers.items()):
                if now - seen > self._window:
                    del t.strangers[who]
                else:
                    out.append(f)
        self._check_override(now)
        for key, info in self._endpoints.get(OVERRIDE_TOPIC, {}).items():
            if info.session_id != self.zid:
                out.append(Fault("signals", f"another writer on {OVERRIDE_TOPIC}: {info.who}; a robot reading the "
                                 "override could take its values for this node's", OVERRIDE_TOPIC))
        out.extend(f for _, f in self._own_foreign.values())
        return tuple(out)

    def acks(self) -> list[AckRequest]:
        out: list[AckRequest] = []
        if self._closed:
            return out
        for _ in range(_ACK_QUEUE):
            try:
                smp = self.r_ack.try_recv()
            except Exception:  # noqa: BLE001
                break
            if smp is None:
                break
            att = unpack_attachment(_bytes(smp.attachment))
            sender = f"publisher {att.gid_hex}" if att is not None else "a publisher without an rmw_zenoh attachment"
            out.append(self._parse_ack(_bytes(smp.payload), sender))
        return out

    # inside ----------------------------------------------------------------------------
    def _sample(self, t: Topic, smp: Any, t_log: float) -> None:
        key = str(smp.key_expr)
        att = unpack_attachment(_bytes(smp.attachment))
        who = f"publisher {att.gid_hex}" if att is not None else "a publisher that attaches no rmw_zenoh GID"
        if att is None or (att.gid_hex not in t.pinned and len(t.pinned) >= self.publishers):
            t.strangers[who] = (t_log, Fault("signals", f"another publisher on {t.topic}: {who} (the mapping "
                                             f"allows {self.publishers}; accepted: {', '.join(t.pinned) or 'none'}); "
                                             "its samples are not used", t.topic))
            return
        if att.gid_hex not in t.pinned:
            t.pinned = t.pinned + (att.gid_hex,)
        h = key.rsplit("/", 1)[-1]
        if h not in t.hashes:
            t.strangers[f"type {h}"] = (t_log, Fault("invalid", f"{t.topic}: a {t.msgtype} sample with type hash "
                                                     f"{h[:80]}, not this definition's; it is not used", t.topic))
            return
        t.messages += 1
        try:
            msg = self.types.store.deserialize_cdr(_bytes(smp.payload), t.msgtype)
        except Exception:  # noqa: BLE001 - a payload that is not this type's CDR: no usable value
            self.undecodable += 1
            self._pending.extend(t.unusable(t_log))
            return
        self._pending.extend(t.samples(msg, t_log))

    def _graph(self) -> None:
        """Read the liveliness tokens that came and went: the publishers declared on each topic."""
        if self._closed:
            return
        for _ in range(_QUEUE):
            try:
                smp = self.r_graph.try_recv()
            except Exception:  # noqa: BLE001
                return
            if smp is None:
                return
            key = str(smp.key_expr)
            info = parse_token(key)
            if info is None or info.kind != "MP":
                continue
            eps = self._endpoints.setdefault(info.topic, {})
            if str(smp.kind).endswith("DELETE"):
                eps.pop(key, None)
            else:
                eps[key] = info

    def _check_override(self, now: float) -> None:
        for who, (seen, _) in list(self._own_foreign.items()):
            if now - seen > self._window:
                del self._own_foreign[who]
        if self._closed:
            return
        for _ in range(_TAKE):
            try:
                smp = self.r_override.try_recv()
            except Exception:  # noqa: BLE001
                return
            if smp is None:
                return
            att = unpack_attachment(_bytes(smp.attachment))
            if att is not None and att.gid == self.gid:
                continue
            who = f"publisher {att.gid_hex}" if att is not None else "a publisher that attaches no rmw_zenoh GID"
            self._own_foreign[who] = (now, Fault("signals", f"another writer on {OVERRIDE_TOPIC}: {who}; a robot "
                                                 "reading the override could take its values for this node's",
                                                 OVERRIDE_TOPIC))

    def _parse_ack(self, payload: bytes, sender: str) -> AckRequest:
        # zenoh authenticates a session (TLS, user/password), never a sample's writer: never authenticated here
        sender = f"{sender} via {ACK_TOPIC} (zenoh)"
        try:
            text = self.types.store.deserialize_cdr(payload, "std_msgs/msg/String").data
        except Exception:  # noqa: BLE001 - not a std_msgs/String: refused as any malformed request is
            return AckRequest.refused("not a std_msgs/msg/String", sender=sender)
        return AckRequest.from_json(text, sender=sender)

    def close(self) -> None:
        if self.out is not None:
            self.out.close()  # nothing written once the session is leaving
        with self._lock:
            if self._closed:
                return
            self._closed = True
        s, self.session = self.session, None
        if s is not None:
            try:
                s.close()  # every publisher, subscriber and token of the session leaves with it
            except Exception:  # noqa: BLE001
                pass


def _bytes(z: Any) -> bytes | None:
    if z is None:
        return None
    try:
        return z.to_bytes()
    except AttributeError:
        return bytes(z)
