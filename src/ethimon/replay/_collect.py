"""The samples of one mapped signal, gathered message by message into compact arrays and reduced in
batches, then one :class:`Series` (``derive: rate`` included); same-time samples that differ are refused."""

from __future__ import annotations

import math
from array import array
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import BagError
from ..io import ByName, SignalMap
from ._values import _BATCH, _FLOATS, _did_you_mean, _fields, _get, _reduce_rows, _stamp

__all__ = ["Series"]


@dataclass
class Series:
    """Samples of one signal: ``times`` (int64 ns, ascending) and ``values`` (float64, NaN = unusable).

    ``read`` messages were read from the topic (``times`` may hold one fewer with ``derive: rate``);
    ``kind`` is ``"bool"`` when the field holds truth values (a ``std_msgs/Bool``), else ``"number"``;
    ``clock`` is ``"log"`` or ``"header"``; ``offset_ns`` was added to every time (``offset_s``).
    ``visible`` (``clock == "header"`` only, else ``None``): when each sample can first be held, the later of
    its log time and its stamp (the age still counts from its stamp), as live (:func:`ethimon.io.hold`).
    """

    topic: str
    times: np.ndarray
    values: np.ndarray
    bad: int = 0  # samples whose value could not be formed (NaN)
    read: int = 0
    kind: str = "number"
    clock: str = "log"
    msgtype: str = ""
    offset_ns: int = 0
    visible: np.ndarray | None = None


_PAST = object()

_SAME_HINT = ("repeated header stamps (a driver that stamps coarsely or not at all) give same-time samples; "
              "'time: log' uses the bag's receive time")


def _same_time(name: str, topic: str, times: np.ndarray, values: np.ndarray, spath: str, sm: SignalMap) -> None:
    """Two samples at the same time with different values: the monitor could judge only one."""
    if times.size < 2:
        return
    same = np.flatnonzero(times[1:] == times[:-1])
    if not same.size:
        return
    a, b = values[same], values[same + 1]
    differ = ~((a == b) | (np.isnan(a) & np.isnan(b)))
    if differ.any():
        k = int(same[np.argmax(differ)])
        raise BagError(f"signal {name!r}: {int(differ.sum()):,} samples on {topic} share a time with another of "
                       f"a different value (first at bag time {int(times[k])} ns: {values[k]:g} and "
                       f"{values[k + 1]:g}); one cycle cannot judge both", spath, hint=_SAME_HINT)




def task_text(msg: Any, fpath: tuple, topic: str, msgtype: str, field: str, spath: str) -> str:
    """A task message's text, whole (never cut: issue 31 item 4); a field that is not text is a located error."""
    text = _get(msg, fpath, topic, msgtype, field, spath, "task")
    if not isinstance(text, str):
        raise BagError(f"task topic {topic} ({msgtype}): field {field!r} is {type(text).__name__}, not text", spath,
                       hint="the task topic carries std_msgs/String (field 'data')")
    return text


class _Collector:
    """The samples of one mapped signal, gathered message by message (compact arrays, not lists)."""

    __slots__ = ("name", "sm", "fpath", "spath", "times", "values", "raw", "bad", "past_end", "read", "bools",
                 "zero", "header", "logs", "off", "where", "names_key", "names_idx", "names_last", "fast", "named",
                 "pending")

    def __init__(self, name: str, sm: SignalMap, spath: str) -> None:
        self.name, self.sm, self.spath = name, sm, spath
        self.fpath = sm.field_path
        self.times, self.values = array("q"), array("d")
        self.raw: list[np.ndarray] | None = [] if sm.derive == "rate" else None
        self.bad = self.past_end = self.read = self.bools = self.zero = 0
        self.header = sm.time == "header"
        self.logs = array("q")  # with 'time: header': each message's log time too
        self.off = int(round(sm.offset_s * 1e9))
        self.where = ""
        self.names_key: Any = None
        self.names_idx: dict[str, int] = {}
        self.names_last: list[str] = []
        self.pending: list[Any] = []
        # the common case: one plain field name, no index
        self.fast = self.fpath[0] if len(self.fpath) == 1 and isinstance(self.fpath[0], str) else None
        self.named = (self.fpath if len(self.fpath) == 2 and not isinstance(self.fpath[0], ByName)
                      and isinstance(self.fpath[1], ByName) else None)  # e.g. position[panda_joint4]

    def add(self, msg: Any, t_log: int, topic: str, msgtype: str) -> None:
        """One message: its field value is kept as is (reduced in batches by :meth:`_flush`)."""
        fast = self.fast
        named = self.named
        if fast is not None and fast in msg.__dataclass_fields__:
            v = getattr(msg, fast)
        elif named is not None and named[0] in msg.__dataclass_fields__ and "name" in msg.__dataclass_fields__:
            idx = self._by_name(msg, named[1], named[:1], topic, msgtype)
            arr = getattr(msg, named[0])
            try:
                v = _PAST if idx is None else arr[idx]
            except (IndexError, TypeError, KeyError):
                v = _PAST
        else:
            if not self.where:
                self.where = f"signal {self.name!r}: {topic} ({msgtype}) field {self.sm.field!r}"
            v = self._get(msg, topic, msgtype)
        if self.header:
            t = _stamp(msg, topic, msgtype, self.spath, self.name)
            if t == 0:
                self.zero += 1
            self.logs.append(t_log)
        else:
            t = t_log
        self.times.append(t + self.off)
        pending = self.pending
        pending.append(v)
        if len(pending) >= _BATCH:
            self._flush(topic, msgtype)

    def _flush(self, topic: str, msgtype: str) -> None:
        """Reduce the pending field values: whole batches of same-shape numeric arrays at once, else one
        by one (:meth:`SignalMap.number <ethimon.io.SignalMap.number>`, which refuses text, messages and other
        kinds with a located error)."""
        vals = self.pending
        if not vals:
            return
        self.pending = []
        self.read += len(vals)
        if not self.where:
            self.where = f"signal {self.name!r}: {topic} ({msgtype}) field {self.sm.field!r}"
        sm = self.sm
        first = vals[0]
        if self.raw is None and sm.reduce != "value" and type(first) is np.ndarray and first.ndim == 1 \
                and first.dtype.kind in "iuf":
            shape, kind = first.shape, first.dtype
            if all(type(v) is np.ndarray and v.shape == shape and v.dtype == kind for v in vals):
                x = _reduce_rows(np.stack(vals).astype(np.float64, copy=False), sm)
                if sm.reduce == "index" and sm.index is not None and sm.index >= shape[0]:
                    self.past_end += len(vals)
                self.bad += int(np.isnan(x).sum())
                self.values.frombytes(x.tobytes())
                return
        if self.raw is None and sm.reduce == "value" and type(first) in _FLOATS:
            if all(type(v) in _FLOATS for v in vals):
                x = np.asarray(vals, dtype=np.float64) * sm.scale + sm.offset
                self.bad += int(np.isnan(x).sum())
                self.values.frombytes(x.tobytes())
                return
        for v in vals:
            if v is _PAST:
                self.past_end += 1
                v = math.nan
            elif sm.reduce == "index":
                try:
                    if len(v) <= sm.index:  # type: ignore[operator]
                        self.past_end += 1
                except TypeError:
                    pass
            if isinstance(v, (bool, np.bool_)) or (isinstance(v, np.ndarray) and v.dtype.kind == "b"):
                self.bools += 1
            if self.raw is not None:
                self.raw.append(sm.numbers(v, where=self.where, path=self.spath))
                continue
            x = sm.number(v, where=self.where, path=self.spath)
            if x != x:
                self.bad += 1
            self.values.append(x)

    def _get(self, msg: Any, topic: str, msgtype: str) -> Any:
        cur, parent = msg, None
        fpath = self.fpath
        for i, part in enumerate(fpath):
            if isinstance(part, ByName):
                idx = self._by_name(parent, part, fpath[:i], topic, msgtype)
                if idx is None:
                    return _PAST
                part = idx
            if isinstance(part, int):
                try:
                    cur = cur[part]
                except (IndexError, TypeError, KeyError):
                    return _PAST  # an element this message does not have: no usable value
                continue
            if not hasattr(cur, "__dataclass_fields__") or part not in _fields(cur):
                have = _fields(cur)
                hint = _did_you_mean(part, have) or (
                    f"fields here: {', '.join(have)}" if have else "this part of the message has no fields")
                at = "" if i == 0 else f" (in {'.'.join(str(x) for x in fpath[:i])})"
                raise BagError(f"{self.name}: {topic} ({msgtype}) has no field {part!r}{at} for field path "
                               f"{self.sm.field!r}", self.spath, hint=hint)
            parent, cur = cur, getattr(cur, part)
        return cur

    def _by_name(self, parent: Any, key: str, before: tuple, topic: str, msgtype: str) -> int | None:
        names = getattr(parent, "name", None) if parent is not None else None
        if not isinstance(names, (list, tuple)):
            raise BagError(f"{self.name}: field path {self.sm.field!r} selects {key!r} by name, but "
                           f"{topic} ({msgtype}) has no 'name' list beside "
                           f"{'.'.join(str(x) for x in before)!r}", self.spath,
                           hint="select by name in a sensor_msgs/JointState (position[panda_joint4]); "
                           "elsewhere use a number: position[3]")
        if names is not self.names_key and names != self.names_key:
            self.names_key = names
            self.names_idx = {str(n): i for i, n in enumerate(names)}
        got = self.names_idx.get(key)
        if got is None:
            self.names_last = list(self.names_idx)  # for the error, if no message has the name
        return got

    def series(self, topic: str, msgtype: str) -> Series:
        sm = self.sm
        self._flush(topic, msgtype)
        if self.header and self.zero:
            raise BagError(f"signal {self.name!r}: {self.zero:,} of {self.read:,} header stamps on {topic} are unset "
                           "(0), but the mapping sets 'time: header'", self.spath,
                           hint="the driver does not stamp its messages: map this signal with 'time: log' (the "
                           "bag's receive time)")
        if self.read and self.past_end == self.read:
            raise BagError(f"{self.where}: {self._past_what()} on every one of its {self.read:,} messages",
                           self.spath, hint=self._past_hint())
        times = np.frombuffer(self.times, dtype=np.int64).copy() if self.times else np.zeros(0, np.int64)
        kind = "bool" if self.bools and self.bools == self.read else "number"
        if self.raw is not None:
            return self._rate(times, topic, msgtype, kind)
        values = np.frombuffer(self.values, dtype=np.float64).copy() if self.values else np.zeros(0)
        visible = self._visible(times)
        if times.size and np.any(np.diff(times) < 0):  # header stamps (or offsets) out of order
            order = np.argsort(times, kind="stable")
            times, values = times[order], values[order]
            visible = None if visible is None else visible[order]
        _same_time(self.name, topic, times, values, self.spath, sm)
        return Series(sm.topic, times, values, self.bad, self.read, kind, sm.time, msgtype, self.off, visible)

    def _visible(self, times: np.ndarray) -> np.ndarray | None:
        """With ``time: header``: the later of each message's log time and its stamp (``None`` when that is
        the stamp throughout, as in a bag whose stamps are at or after its log times)."""
        if not self.header or len(self.logs) != times.size:
            return None
        logs = np.frombuffer(self.logs, dtype=np.int64)
        return np.maximum(logs, times) if np.any(logs > times) else None

    def _rate(self, times: np.ndarray, topic: str, msgtype: str, kind: str) -> Series:
        sm, raw = self.sm, self.raw
        assert raw is not None
        if kind == "bool":
            raise BagError(f"{self.where}: 'derive: rate' of a bool field", self.spath,
                           hint="a rate needs numbers")
        visible = self._visible(times)
        order = np.argsort(times, kind="stable")
        times = times[order]
        visible = None if visible is None else visible[order][1:]
        dup = np.flatnonzero(np.diff(times) == 0)
        if dup.size:
            raise BagError(f"signal {self.name!r}: {dup.size:,} messages on {topic} share a time with the one "
                           f"before (first at bag time {int(times[dup[0]])} ns): 'derive: rate' cannot divide by "
                           "0 s", self.spath, hint=_SAME_HINT)
        out = np.full(max(times.size - 1, 0), np.nan)
        bad = 0
        for j in range(1, times.size):
            # the one derivation, live and replay (ethimon.io's SignalMap.rate)
            x = sm.rate(raw[order[j - 1]], raw[order[j]], float(times[j] - times[j - 1]) / 1e9)
            if x != x:
                bad += 1
            out[j - 1] = x
        self.raw = None
        return Series(sm.topic, times[1:], out, bad, self.read, "number", sm.time, msgtype, self.off, visible)

    def _past_what(self) -> str:
        sm = self.sm
        if any(isinstance(x, ByName) for x in self.fpath):
            return "the named entry is not in the message's 'name' list"
        if sm.reduce == "index":
            return f"index {sm.index} is past the end of the array"
        return "an index of the field path is past the end of its array"

    def _past_hint(self) -> str:
        names = self.names_last
        key = next((x for x in self.fpath if isinstance(x, ByName)), None)
        if key is not None and names:
            return (_did_you_mean(key, names) or "") + f" names in the message: {', '.join(names)[:300]}"
        return "count from 0: an array of 7 entries has indices 0 to 6"


#: a field the reader could not reach: an index past the end, a name not in the message's list

