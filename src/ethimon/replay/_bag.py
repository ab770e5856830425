"""Reading the mapped topics of one ROS bag with ``rosbags`` (imported lazily).

ROS 2 bags (a directory with ``metadata.yaml`` and sqlite3 or MCAP storage, or a
bare ``.db3``/``.mcap`` file) and ROS 1 bags (``.bag`` files) are opened with
``rosbags.highlevel.AnyReader``; type definitions come from the bag itself,
else from the ROS 2 Humble / ROS 1 Noetic typestore. Only the mapped topics
are deserialised. Each mapped signal becomes a :class:`Series` (sample times
in ns and the reduced, scaled value; NaN where a message had no usable value);
the task topic becomes a list of ``(time_ns, text)``.
"""

from __future__ import annotations

import math
import os
from array import array
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .._files import file_kind
from ..errors import BagError, DependencyNotInstalled
from ._mapping import ByName, Mapping, SignalMap, msgtype_key, parse_field_path

__all__ = ["MAX_MESSAGES", "BagData", "BagError", "Series", "TopicInfo", "list_topics", "read_bag", "reduce_value"]

#: most messages read from one bag (all mapped topics together)
MAX_MESSAGES = 50_000_000
#: longest task text kept (characters)
MAX_TEXT = 10_000


@dataclass
class Series:
    """Samples of one signal: ``times`` (int64 ns, ascending) and ``values`` (float64, NaN = unusable).

    ``read`` messages were read from the topic (``times`` may hold one fewer with ``derive: rate``);
    ``kind`` is ``"bool"`` when the field holds truth values (a ``std_msgs/Bool``), else ``"number"``;
    ``clock`` is ``"log"`` or ``"header"``; ``offset_ns`` was added to every time (``offset_s``).
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


@dataclass
class BagData:
    """What one bag holds for a mapping."""

    path: str
    storage: str
    series: dict[str, Series]
    texts: list[tuple[int, str]]
    topics: dict[str, tuple[str, int]] = field(default_factory=dict)  # every topic in the bag: (type, count)


def _rosbags():
    try:
        from rosbags.highlevel import AnyReader
        from rosbags.typesys import Stores, get_typestore
    except ImportError as exc:
        raise DependencyNotInstalled(
            f"ethimon replay reads bags with rosbags, which is not installed ({exc}); "
            f"pip install 'ethimon[ros]'") from None
    return AnyReader, Stores, get_typestore


#: deepest folder level looked at inside a bag folder, and most entries
_SCAN_DEPTH, _SCAN_MAX = 4, 10_000


def _scan_folder(p: Path, path: str) -> list[Path]:
    """Every entry of a bag folder must be a regular file or a folder (a FIFO would block the reader
    forever); returns the folder's ``.mcap`` files (read as files: the folder then reads as the file does)."""
    mcaps: list[Path] = []
    todo, seen = [(p, 0)], 0
    while todo:
        d, depth = todo.pop()
        try:
            entries = sorted(os.scandir(d), key=lambda e: e.name)
        except OSError as exc:
            raise BagError(f"cannot read the bag folder {d}: {exc.strerror or exc}", path) from None
        for e in entries:
            seen += 1
            if seen > _SCAN_MAX:
                raise BagError(f"more than {_SCAN_MAX:,} entries in the bag folder", path,
                               hint="a ROS 2 bag folder holds metadata.yaml and its storage files")
            try:
                kind = file_kind(e.path)
            except OSError as exc:  # a dangling link, no permission
                raise BagError(f"cannot read {e.path} in the bag folder: {exc.strerror or exc}", path) from None
            if kind == "a directory":
                if depth + 1 < _SCAN_DEPTH:
                    todo.append((Path(e.path), depth + 1))
                continue
            if kind is not None:
                raise BagError(f"{e.path} in the bag folder is {kind}, not a regular file", path,
                               hint="ethimon reads bag files only, not pipes or devices (a reader would wait "
                               "on it forever); remove it or copy the bag")
            if depth == 0 and e.name.endswith(".mcap"):
                mcaps.append(Path(e.path))
    return mcaps


def _check_path(path: str) -> list[Path]:
    """The paths rosbags opens for one bag: the folder, or (MCAP storage) its .mcap files, or the file."""
    p = Path(path)
    try:
        kind = file_kind(p)
    except FileNotFoundError:
        raise BagError("no such file or folder", path) from None
    except OSError as exc:
        raise BagError(f"cannot read this bag: {exc.strerror or exc}", path) from None
    if kind == "a directory":
        if p.suffix == ".bag":
            raise BagError("a ROS 2 bag folder whose name ends in '.bag' is read as a ROS 1 bag by rosbags", path,
                           hint="rename the folder (e.g. without '.bag'), or pass its .mcap/.db3 file")
        mcaps = _scan_folder(p, path)
        if mcaps and not any(p.glob("*.db3")):
            return mcaps  # MCAP storage: each .mcap file holds its own schemas; the folder reads as the file
        if not (p / "metadata.yaml").is_file():
            raise BagError("this folder is not a ROS 2 bag: it has no metadata.yaml", path,
                           hint="a ROS 2 bag is the folder 'ros2 bag record' writes; a ROS 1 bag is a .bag file")
        return [p]
    if kind is not None:
        raise BagError(f"expected a bag, found {kind}, not a regular file", path,
                       hint="ethimon reads bag files and folders only, not pipes or devices")
    if p.suffix not in (".bag", ".mcap", ".db3"):
        raise BagError(f"unknown bag file type {p.suffix or '(no suffix)'!r}", path,
                       hint="ROS 1 bags end in .bag; ROS 2 bags are folders (or one .mcap / .db3 file)")
    return [p]


class _Open:
    """An open ``AnyReader`` over one bag (closed on exit; errors become :class:`BagError`)."""

    def __init__(self, path: str | os.PathLike) -> None:
        self.spath = os.fspath(path)
        self.paths = _check_path(self.spath)
        self.p = Path(self.spath)
        AnyReader, Stores, get_typestore = _rosbags()
        self.ros1 = self.paths[0].suffix == ".bag"
        default = get_typestore(Stores.ROS1_NOETIC if self.ros1 else Stores.ROS2_HUMBLE)
        try:
            self.reader = AnyReader(self.paths, default_typestore=default)
            self.reader.open()
        except BagError:
            raise
        except Exception as exc:  # noqa: BLE001 - rosbags raises many kinds on corrupt input
            raise BagError(f"cannot open the bag: {_why(exc)}", self.spath) from None

    def __enter__(self) -> "_Open":
        return self

    def __exit__(self, *exc: Any) -> None:
        try:
            self.reader.close()
        except Exception:  # noqa: BLE001
            pass


def read_bag(path: str | os.PathLike, mapping: Mapping, *,
             on_progress: Callable[[int, int], None] | None = None) -> BagData:
    """Read the mapped topics of one bag (streamed: one message at a time, never the whole bag).

    ``on_progress(done, total)`` is called every few thousand messages.

    Raises:
        BagError: missing or unreadable bag, corrupt storage, a mapped topic or field the bag lacks
            (with "did you mean"), a topic of another type than the mapping's ``type``, unset header stamps,
            an index past the end of every message's array, two same-time samples that differ.
        DependencyNotInstalled: rosbags is not installed.
    """
    with _Open(path) as op:
        try:
            return _read(op.reader, op.spath, op.p, op.ros1, mapping, on_progress)
        except (BagError, DependencyNotInstalled):
            raise
        except Exception as exc:  # noqa: BLE001
            raise BagError(f"cannot read the bag: {_why(exc)}", op.spath) from None


def _why(exc: BaseException) -> str:
    text = " ".join(str(a) for a in exc.args) if exc.args else str(exc)
    text = text.strip() or type(exc).__name__
    if len(text) > 300:
        text = text[:297] + "..."
    return f"{type(exc).__name__}: {text}" if type(exc).__name__ not in text else text


def _storage(reader: Any, p: Path, ros1: bool) -> str:
    if ros1:
        return "ROS 1"
    if p.is_dir():
        ids = {f.suffix for f in p.iterdir()}
        return "ROS 2 MCAP" if ".mcap" in ids else "ROS 2 sqlite3" if ".db3" in ids else "ROS 2"
    return "ROS 2 MCAP" if p.suffix == ".mcap" else "ROS 2 sqlite3"


def _topics(reader: Any) -> dict[str, tuple[str, int]]:
    topics: dict[str, tuple[str, int]] = {}  # every topic in the bag: (type, message count)
    for c in reader.connections:
        _, cnt = topics.get(c.topic, (c.msgtype, 0))
        topics[c.topic] = (c.msgtype, cnt + int(getattr(c, "msgcount", 0) or 0))
    return topics


def _did_you_mean(word: str, options: Iterable[str]) -> str | None:
    import difflib
    opts = list(options)
    close = difflib.get_close_matches(word, opts, n=1, cutoff=0.5)
    if close:
        return f"did you mean {close[0]!r}?"
    return None


def _check_topics(mapping: Mapping, topics: dict[str, tuple[str, int]], spath: str) -> None:
    """Every mapped topic is in the bag (else "did you mean"), with the type the mapping names."""
    wanted = [(name, sm.topic, sm.type) for name, sm in mapping.signals.items()]
    if mapping.task is not None:
        wanted.append(("task", mapping.task.topic, mapping.task.type))
    for who, topic, want in wanted:
        if topic not in topics:
            hint = _did_you_mean(topic, topics) or ("topics in this bag: " + (", ".join(sorted(topics))[:400] or
                                                                             "none"))
            raise BagError(f"{who}: topic {topic} is not in this bag", spath,
                           hint=hint + "; 'ethimon replay BAG --topics' lists the topics")
        have = topics[topic][0]
        if want is not None and msgtype_key(want) != msgtype_key(have):
            raise BagError(f"{who}: topic {topic} carries {have}, but the mapping says type {want}", spath,
                           hint="fix 'type:' in the mapping, or map the topic that carries that type")


class _Collector:
    """The samples of one mapped signal, gathered message by message (compact arrays, not lists)."""

    __slots__ = ("name", "sm", "fpath", "spath", "times", "values", "raw", "bad", "past_end", "read", "bools",
                 "zero", "header", "off", "where", "names_key", "names_idx", "names_last", "fast", "named", "pending")

    def __init__(self, name: str, sm: SignalMap, spath: str) -> None:
        self.name, self.sm, self.spath = name, sm, spath
        self.fpath = parse_field_path(sm.field)
        self.times, self.values = array("q"), array("d")
        self.raw: list[np.ndarray] | None = [] if sm.derive == "rate" else None
        self.bad = self.past_end = self.read = self.bools = self.zero = 0
        self.header = sm.time == "header"
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
        else:
            t = t_log
        self.times.append(t + self.off)
        pending = self.pending
        pending.append(v)
        if len(pending) >= _BATCH:
            self._flush(topic, msgtype)

    def _flush(self, topic: str, msgtype: str) -> None:
        """Reduce the pending field values: whole batches of same-shape numeric arrays at once, else one
        by one (:func:`reduce_value`, which refuses text, messages and other kinds with a located error)."""
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
                self.raw.append(_numbers_of(v, self.where, self.spath))
                continue
            x = reduce_value(v, sm, where=self.where, path=self.spath)
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
        if times.size and np.any(np.diff(times) < 0):  # header stamps (or offsets) out of order
            order = np.argsort(times, kind="stable")
            times, values = times[order], values[order]
        _same_time(self.name, topic, times, values, self.spath, sm)
        return Series(sm.topic, times, values, self.bad, self.read, kind, sm.time, msgtype, self.off)

    def _rate(self, times: np.ndarray, topic: str, msgtype: str, kind: str) -> Series:
        sm, raw = self.sm, self.raw
        assert raw is not None
        if kind == "bool":
            raise BagError(f"{self.where}: 'derive: rate' of a bool field", self.spath,
                           hint="a rate needs numbers")
        order = np.argsort(times, kind="stable")
        times = times[order]
        dup = np.flatnonzero(np.diff(times) == 0)
        if dup.size:
            raise BagError(f"signal {self.name!r}: {dup.size:,} messages on {topic} share a time with the one "
                           f"before (first at bag time {int(times[dup[0]])} ns): 'derive: rate' cannot divide by "
                           "0 s", self.spath, hint=_SAME_HINT)
        out = np.full(max(times.size - 1, 0), np.nan)
        bad = 0
        for j in range(1, times.size):
            a, b = raw[order[j - 1]], raw[order[j]]
            if a is None or b is None or a.size != b.size:
                bad += 1
                continue
            d = (b - a) * (1e9 / float(times[j] - times[j - 1]))
            x = _reduce_arr(d, sm) if sm.reduce != "value" else (float(d[0]) * sm.scale + sm.offset
                                                                  if d.size == 1 else math.nan)
            if x != x:
                bad += 1
            out[j - 1] = x
        self.raw = None
        return Series(sm.topic, times[1:], out, bad, self.read, "number", sm.time, msgtype, self.off)

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


def _read(reader: Any, spath: str, p: Path, ros1: bool, mapping: Mapping,
          on_progress: Callable[[int, int], None] | None = None) -> BagData:
    topics = _topics(reader)
    _check_topics(mapping, topics, spath)
    by_topic: dict[str, list[_Collector]] = {}
    cols: dict[str, _Collector] = {}
    for name, sm in mapping.signals.items():
        cols[name] = c = _Collector(name, sm, spath)
        by_topic.setdefault(sm.topic, []).append(c)
    task = mapping.task
    task_path = parse_field_path(task.field) if task is not None else None
    wanted = set(by_topic) | ({task.topic} if task is not None else set())
    conns = [c for c in reader.connections if c.topic in wanted]
    total = sum(int(getattr(c, "msgcount", 0) or 0) for c in conns)
    texts: list[tuple[int, str]] = []
    types: dict[str, str] = {}
    n = 0
    deserialize = reader.deserialize
    task_topic = task.topic if task is not None else None
    if conns:
        for conn, t_log, raw in reader.messages(connections=conns):
            n += 1
            if n > MAX_MESSAGES:
                raise BagError(f"more than {MAX_MESSAGES:,} messages on the mapped topics", spath,
                               hint="split the bag")
            if on_progress is not None and not n & 0x1FFF:
                on_progress(n, total)
            msgtype = conn.msgtype
            msg = deserialize(raw, msgtype)
            topic = conn.topic
            types[topic] = msgtype
            if topic == task_topic:
                text = _get(msg, task_path, topic, msgtype, task.field, spath, "task")
                if not isinstance(text, str):
                    raise BagError(f"task topic {topic} ({msgtype}): field {task.field!r} is "
                                   f"{type(text).__name__}, not text", spath,
                                   hint="the task topic carries std_msgs/String (field 'data')")
                texts.append((int(t_log), text[:MAX_TEXT]))
            for c in by_topic.get(topic, ()):
                c.add(msg, t_log, topic, msgtype)
    if on_progress is not None:
        on_progress(n, max(n, total))
    series = {name: c.series(c.sm.topic, types.get(c.sm.topic, topics.get(c.sm.topic, ("", 0))[0]))
              for name, c in cols.items()}
    texts.sort(key=lambda x: x[0])
    return BagData(spath, _storage(reader, p, ros1), series, texts, topics)


def _get(msg: Any, fpath: tuple, topic: str, msgtype: str, text: str, bag: str, who: str) -> Any:
    """Follow ``fpath`` (names and numeric indices) into a deserialised message (the task text)."""
    cur = msg
    for i, part in enumerate(fpath):
        if isinstance(part, int):
            try:
                cur = cur[part]
            except (IndexError, TypeError, KeyError):
                return math.nan
            continue
        if not hasattr(cur, "__dataclass_fields__") or part not in _fields(cur):
            have = _fields(cur)
            hint = _did_you_mean(part, have) or (
                f"fields here: {', '.join(have)}" if have else "this part of the message has no fields")
            raise BagError(f"{who}: {topic} ({msgtype}) has no field {part!r} for field path {text!r}", bag,
                           hint=hint)
        cur = getattr(cur, part)
    return cur


def _fields(obj: Any) -> list[str]:
    f = getattr(obj, "__dataclass_fields__", None)
    return [k for k in f if not k.startswith("_")] if f else []


def _stamp(msg: Any, topic: str, msgtype: str, bag: str, who: str) -> int:
    hdr = getattr(msg, "header", None)
    stamp = getattr(hdr, "stamp", None)
    if stamp is None or not hasattr(stamp, "sec"):
        raise BagError(f"{who}: {topic} ({msgtype}) has no header.stamp, but the mapping sets 'time: header'", bag,
                       hint="use 'time: log' (the bag's receive time) for messages without a header")
    return int(stamp.sec) * 1_000_000_000 + int(getattr(stamp, "nanosec", getattr(stamp, "nsec", 0)))


def _numbers(v: Any) -> np.ndarray | None:
    """An array field, a list of numbers or a vector message (x, y, z ...) as floats; None if not numeric."""
    if isinstance(v, np.ndarray):
        if v.dtype.kind in "biuf":
            return v.astype(np.float64, copy=False).ravel()
        return None
    if isinstance(v, (list, tuple)):
        out = []
        for x in v:
            if isinstance(x, (bool, np.bool_, int, float, np.integer, np.floating)):
                out.append(float(x))
            else:
                return None
        return np.asarray(out, dtype=np.float64)
    names = _fields(v)
    if names:
        vals = [getattr(v, k) for k in names]
        if vals and all(isinstance(x, (int, float, np.integer, np.floating)) and not isinstance(x, bool)
                        for x in vals):
            return np.asarray([float(x) for x in vals], dtype=np.float64)
    return None


def _numbers_of(v: Any, where: str, path: str) -> np.ndarray | None:
    """The numbers a ``derive: rate`` signal differentiates (a copy); None for an unusable message."""
    if isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, (bool, np.bool_)):
        return np.asarray([float(v)])
    arr = _numbers(v)
    if arr is None:
        if isinstance(v, float):
            return None
        raise BagError(f"{where} is {_kind(v)}: 'derive: rate' needs a number, an array of numbers or a vector "
                       "(x, y, z)", path, hint="point 'field' at e.g. 'pose.position'")
    return np.array(arr, dtype=np.float64)


_FLOATS = (float, np.float64, np.float32)
#: field values reduced together (bounded memory: a batch, never the bag)
_BATCH = 4096


def _reduce_rows(a: np.ndarray, sm: SignalMap) -> np.ndarray:
    """:func:`_reduce_arr` of every row of ``a`` (rows: messages), then ``* scale + offset``."""
    if a.shape[1] == 0:
        return np.full(a.shape[0], np.nan)
    red = sm.reduce
    if red == "index":
        if sm.index is None or sm.index >= a.shape[1]:
            return np.full(a.shape[0], np.nan)
        x = a[:, sm.index].copy()
    elif red == "max":
        x = a.max(axis=1)
    elif red == "min":
        x = a.min(axis=1)
    elif red == "max_abs":
        x = np.abs(a).max(axis=1)
    elif red == "norm":
        x = np.sqrt(np.einsum("ij,ij->i", a, a))
    else:  # mean
        x = a.mean(axis=1)
    return x * sm.scale + sm.offset


def _reduce_arr(arr: np.ndarray, sm: SignalMap) -> float:
    if arr.size == 0:
        return math.nan
    red = sm.reduce
    if red == "index":
        if sm.index is None or sm.index >= arr.size:
            return math.nan
        x = float(arr[sm.index])
    elif red == "max":
        x = float(arr.max())
    elif red == "min":
        x = float(arr.min())
    elif red == "max_abs":
        x = float(np.abs(arr).max())
    elif red == "norm":
        x = float(math.sqrt(float(np.dot(arr, arr))))
    else:  # mean
        x = float(arr.mean())
    return x * sm.scale + sm.offset


def reduce_value(v: Any, sm: SignalMap, *, where: str = "", path: str | None = None) -> float:
    """One number from a field value: the mapping's reduction, then ``* scale + offset``.

    NaN when the value cannot be formed from this message (an empty array, an index past the end);
    ±inf stays ±inf (the monitor then faults on it as what it is); a value of the wrong kind (text,
    a nested message) raises :class:`BagError`.
    """
    red = sm.reduce
    if red == "value":
        if isinstance(v, (bool, np.bool_)):
            x = 1.0 if v else 0.0
        elif isinstance(v, (int, float, np.integer, np.floating)):
            x = float(v)
        else:
            raise BagError(f"{where} is {_kind(v)}, not one number", path,
                           hint="map a numeric field" if isinstance(v, str) else
                           "pick a reduction: reduce: max | min | max_abs | norm | mean | index")
        return x * sm.scale + sm.offset
    arr = _numbers(v)
    if arr is None:
        if isinstance(v, float) and v != v:
            return math.nan
        raise BagError(f"{where} is {_kind(v)}: reduce {red!r} needs an array of numbers or a vector "
                       f"(x, y, z)", path, hint="point 'field' at a numeric array, e.g. 'velocity' or "
                       "'twist.linear'")
    return _reduce_arr(arr, sm)


def _kind(v: Any) -> str:
    if isinstance(v, str):
        return "text"
    if isinstance(v, (np.ndarray, list, tuple)):
        return f"an array of {len(v)}"
    t = getattr(v, "__msgtype__", None)
    return f"a message ({t})" if t else type(v).__name__



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
