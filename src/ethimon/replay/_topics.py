"""``ethimon replay BAG --topics``: every topic of a bag with its type, count, rate, time spans, fields
and joint names (to write a mapping from)."""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from ..errors import BagError
from ._bag import _Open, _storage, _why
from ._values import _fields

__all__ = ["TopicInfo", "list_topics"]



@dataclass
class TopicInfo:
    """One topic of a bag as ``ethimon replay BAG --topics`` lists it (times in ns; ``None``: no message,
    or, for the header span, no ``header.stamp`` in the type or every stamp unset)."""

    topic: str
    type: str
    count: int
    log_first: int | None = None
    log_last: int | None = None
    header_first: int | None = None
    header_last: int | None = None
    header_zero: int = 0  # messages whose header stamp is unset (0)
    fields: tuple[str, ...] = ()
    names: tuple[str, ...] = ()  # the 'name' list of the first message (JointState: the joints)
    error: str | None = None  # this topic could not be deserialised

    @property
    def rate_hz(self) -> float | None:
        if self.count < 2 or self.log_first is None or self.log_last is None or self.log_last <= self.log_first:
            return None
        return (self.count - 1) / ((self.log_last - self.log_first) / 1e9)

    def as_dict(self) -> dict[str, Any]:
        return {"topic": self.topic, "type": self.type, "count": self.count, "rate_hz": self.rate_hz,
                "log_first_ns": self.log_first, "log_last_ns": self.log_last, "header_first_ns": self.header_first,
                "header_last_ns": self.header_last, "header_unset": self.header_zero, "fields": list(self.fields),
                "names": list(self.names), "error": self.error}


def list_topics(path: str | os.PathLike, *, on_progress: Callable[[int, int], None] | None = None
                ) -> tuple[str, list[TopicInfo]]:
    """``(storage, topics)`` of one bag: each topic's type, message count, rate, log-time span, and the
    span of its header stamps (every message is read once, streamed); the fields of its messages and,
    for a ``name`` list (JointState), the names, to write a mapping from.

    Raises:
        BagError: a missing, unreadable or corrupt bag.
        DependencyNotInstalled: rosbags is not installed.
    """
    with _Open(path) as op:
        reader = op.reader
        try:
            infos: dict[str, TopicInfo] = {}
            for c in reader.connections:
                if c.topic not in infos:
                    infos[c.topic] = TopicInfo(c.topic, c.msgtype, 0)
            total = sum(int(getattr(c, "msgcount", 0) or 0) for c in reader.connections)
            n = 0
            for conn, t_log, raw in reader.messages():
                n += 1
                if on_progress is not None and not n & 0x1FFF:
                    on_progress(n, total)
                ti = infos[conn.topic]
                ti.count += 1
                t = int(t_log)
                ti.log_first = t if ti.log_first is None else min(ti.log_first, t)
                ti.log_last = t if ti.log_last is None else max(ti.log_last, t)
                if ti.error is not None:
                    continue
                try:
                    msg = reader.deserialize(raw, conn.msgtype)
                except Exception as exc:  # noqa: BLE001 - listed as unreadable, the others still listed
                    ti.error = _why(exc)
                    continue
                if ti.count == 1:
                    ti.fields = tuple(f for f in _fields(msg) if not f.isupper())  # not the constants
                    names = getattr(msg, "name", None)
                    if isinstance(names, list) and all(isinstance(x, str) for x in names):
                        ti.names = tuple(names[:64])
                stamp = getattr(getattr(msg, "header", None), "stamp", None)
                if stamp is not None and hasattr(stamp, "sec"):
                    h = int(stamp.sec) * 1_000_000_000 + int(getattr(stamp, "nanosec", getattr(stamp, "nsec", 0)))
                    if h == 0:
                        ti.header_zero += 1
                    else:
                        ti.header_first = h if ti.header_first is None else min(ti.header_first, h)
                        ti.header_last = h if ti.header_last is None else max(ti.header_last, h)
            if on_progress is not None:
                on_progress(n, max(n, total))
            return _storage(reader, op.p, op.ros1), sorted(infos.values(), key=lambda x: x.topic)
        except BagError:
            raise
        except Exception as exc:  # noqa: BLE001
            raise BagError(f"cannot read the bag: {_why(exc)}", op.spath) from None
