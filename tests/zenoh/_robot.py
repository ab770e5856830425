"""A robot on zenoh for the tests: a second zenoh session on loopback that publishes ROS 2 messages as
rmw_zenoh does (key expression, CDR, attachment), and the node made against it on a fake clock."""

from __future__ import annotations

import os
import socket
import time

import numpy as np

from ethimon.ros2 import MessageTypes, dds_type
from ethimon.zenoh import ZenohMonitor, topic_key, zenoh_config
from ethimon.zenoh._keys import pack_attachment, unpack_attachment

DOMAIN = 7
#: every wait is bounded by this (s)
WAIT_S = 3.0


def free_port() -> int:
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


class Robot:
    """Publishers on the node's zenoh network; ``gid``: the one publisher GID it attaches (one per topic)."""

    def __init__(self, endpoint: str, types: MessageTypes | None = None) -> None:
        import zenoh
        self.session = zenoh.open(zenoh_config(connect=[endpoint]))
        self.types = types if types is not None else MessageTypes()  # building one takes a while: share it
        self.store = self.types.store
        self.pubs: dict[str, object] = {}
        self.gids: dict[str, bytes] = {}
        self.seq = 0

    def key(self, topic: str, msgtype: str, hashed: bool = True) -> str:
        h = self.store.hash_rihs01(msgtype) if hashed else "TypeHashNotSupported"
        return topic_key(DOMAIN, topic, dds_type(msgtype), h)

    def put(self, topic: str, msgtype: str, msg, *, gid: bytes | None = None, attach: bool = True) -> None:
        key = self.key(topic, msgtype)
        if key not in self.pubs:
            pub = self.pubs[key] = self.session.declare_publisher(key)
            self.gids[key] = os.urandom(16)
            end = time.monotonic() + WAIT_S  # the node's subscriber is known here before the first put
            while not pub.matching_status.matching and time.monotonic() < end:
                time.sleep(0.001)
        self.seq += 1
        att = pack_attachment(self.seq, time.time_ns(), gid or self.gids[key]) if attach else None
        self.pubs[key].put(bytes(self.store.serialize_cdr(msg, msgtype)), attachment=att)

    def msg(self, msgtype: str, **kw):
        T = self.store.types
        if msgtype == "sensor_msgs/msg/JointState":
            pos = np.asarray(kw.get("position", [0.0]), dtype=np.float64)
            return T[msgtype](header=self.header(kw.get("stamp", 0.0)), name=["j0"] * len(pos), position=pos,
                              velocity=np.zeros(len(pos)), effort=np.zeros(0))
        if msgtype == "sensor_msgs/msg/Range":
            return T[msgtype](header=self.header(kw["stamp"]), radiation_type=0, field_of_view=0.1, min_range=0.0,
                              max_range=10.0, range=float(kw["range"]))
        return T[msgtype](data=kw["data"])

    def header(self, t: float):
        T = self.store.types
        sec = int(t // 1)
        return T["std_msgs/msg/Header"](stamp=T["builtin_interfaces/msg/Time"](
            sec=sec, nanosec=int(round((t - sec) * 1e9)) % 1_000_000_000), frame_id="base")

    def listen(self, topic: str, msgtype: str):
        import zenoh
        return self.session.declare_subscriber(self.key(topic, msgtype, hashed=False).rsplit("/", 1)[0] + "/*",
                                               zenoh.handlers.FifoChannel(1024))

    def close(self) -> None:
        self.session.close()


def node(spec, mapping, clock, **kw):
    """The node listening on a fresh loopback port, and a robot connected to it (both closed by the caller)."""
    endpoint = f"tcp/127.0.0.1:{free_port()}"
    n = ZenohMonitor(spec, mapping, domain_id=DOMAIN, config=zenoh_config(listen=[endpoint]), clock=clock,
                     deadline_s=1e6, stall_s=1e6, **kw)
    robot = Robot(endpoint, n.types)
    end = time.monotonic() + WAIT_S
    while not n.channel.session.info.peers_zid() and time.monotonic() < end:
        time.sleep(0.002)
    return n, robot


def wait_in(ch, n: int) -> int:
    """Poll the channel until ``n`` samples wait in it (bounded); how many do."""
    end = time.monotonic() + WAIT_S
    got = ch.poll()
    while got < n and time.monotonic() < end:
        time.sleep(0.0005)
        got = ch.poll()
    return got


def recv(sub, pred=lambda s: True):
    """The first sample from ``sub`` that ``pred`` accepts (bounded wait), or ``None``."""
    end = time.monotonic() + WAIT_S
    while time.monotonic() < end:
        s = sub.try_recv()
        if s is None:
            time.sleep(0.001)
        elif pred(s):
            return s
    return None


__all__ = ["DOMAIN", "Robot", "node", "recv", "unpack_attachment", "wait_in"]
