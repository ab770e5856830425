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
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .._files import file_kind
from ..errors import BagError, DependencyNotInstalled
from ._mapping import Mapping, SignalMap, parse_field_path

__all__ = ["MAX_MESSAGES", "BagData", "BagError", "Series", "read_bag", "reduce_value"]

#: most messages read from one bag (all mapped topics together)
MAX_MESSAGES = 50_000_000
#: longest task text kept (characters)
MAX_TEXT = 10_000


@dataclass
class Series:
    """Samples of one signal: ``times`` (int64 ns, ascending) and ``values`` (float64, NaN = unusable)."""

    topic: str
    times: np.ndarray
    values: np.ndarray
    bad: int = 0  # samples whose value could not be formed (NaN)


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


def _check_path(path: str) -> Path:
    p = Path(path)
    try:
        kind = file_kind(p)
    except FileNotFoundError:
        raise BagError("no such file or folder", path) from None
    except OSError as exc:
        raise BagError(f"cannot read this bag: {exc.strerror or exc}", path) from None
    if kind == "a directory":
        if not (p / "metadata.yaml").is_file():
            raise BagError("this folder is not a ROS 2 bag: it has no metadata.yaml", path,
                           hint="a ROS 2 bag is the folder 'ros2 bag record' writes; a ROS 1 bag is a .bag file")
        if p.suffix == ".bag":
            raise BagError("a ROS 2 bag folder whose name ends in '.bag' is read as a ROS 1 bag by rosbags", path,
                           hint="rename the folder (e.g. without '.bag'), or pass its .mcap/.db3 file")
        return p
    if kind is not None:
        raise BagError(f"expected a bag, found {kind}, not a regular file", path,
                       hint="ethimon reads bag files and folders only, not pipes or devices")
    if p.suffix not in (".bag", ".mcap", ".db3"):
        raise BagError(f"unknown bag file type {p.suffix or '(no suffix)'!r}", path,
                       hint="ROS 1 bags end in .bag; ROS 2 bags are folders (or one .mcap / .db3 file)")
    return p


def read_bag(path: str | os.PathLike, mapping: Mapping) -> BagData:
    """Read the mapped topics of one bag.

    Raises:
        BagError: missing or unreadable bag, corrupt storage, a mapped field the messages lack.
        DependencyNotInstalled: rosbags is not installed.
    """
    spath = os.fspath(path)
    p = _check_path(spath)
    AnyReader, Stores, get_typestore = _rosbags()
    ros1 = p.suffix == ".bag"
    default = get_typestore(Stores.ROS1_NOETIC if ros1 else Stores.ROS2_HUMBLE)
    try:
        reader = AnyReader([p], default_typestore=default)
        reader.open()
    except BagError:
        raise
    except Exception as exc:  # noqa: BLE001 - rosbags raises many kinds on corrupt input
        raise BagError(f"cannot open the bag: {_why(exc)}", spath) from None
    try:
        return _read(reader, spath, p, ros1, mapping)
    except (BagError, DependencyNotInstalled):
        raise
    except Exception as exc:  # noqa: BLE001
        raise BagError(f"cannot read the bag: {_why(exc)}", spath) from None
    finally:
        try:
            reader.close()
        except Exception:  # noqa: BLE001
            pass


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


def _read(reader: Any, spath: str, p: Path, ros1: bool, mapping: Mapping) -> BagData:
    topics: dict[str, tuple[str, int]] = {}  # every topic in the bag: (type, message count)
    for c in reader.connections:
        _, cnt = topics.get(c.topic, (c.msgtype, 0))
        topics[c.topic] = (c.msgtype, cnt + int(getattr(c, "msgcount", 0) or 0))
    by_topic: dict[str, list[tuple[str, SignalMap, tuple]]] = {}
    for name, sm in mapping.signals.items():
        by_topic.setdefault(sm.topic, []).append((name, sm, parse_field_path(sm.field)))
    task = mapping.task
    task_path = parse_field_path(task.field) if task is not None else None
    wanted = set(by_topic) | ({task.topic} if task is not None else set())
    conns = [c for c in reader.connections if c.topic in wanted]
    samples: dict[str, tuple[list[int], list[float]]] = {n: ([], []) for n in mapping.signals}
    bad = dict.fromkeys(mapping.signals, 0)
    texts: list[tuple[int, str]] = []
    n = 0
    if conns:
        for conn, t_log, raw in reader.messages(connections=conns):
            n += 1
            if n > MAX_MESSAGES:
                raise BagError(f"more than {MAX_MESSAGES:,} messages on the mapped topics", spath,
                               hint="split the bag")
            msg = reader.deserialize(raw, conn.msgtype)
            topic = conn.topic
            if task is not None and topic == task.topic:
                text = _get(msg, task_path, topic, conn.msgtype, task.field, spath, "task")
                if not isinstance(text, str):
                    raise BagError(f"task topic {topic} ({conn.msgtype}): field {task.field!r} is "
                                   f"{type(text).__name__}, not text", spath,
                                   hint="the task topic carries std_msgs/String (field 'data')")
                texts.append((int(t_log), text[:MAX_TEXT]))
            for name, sm, fpath in by_topic.get(topic, ()):
                raw_v = _get(msg, fpath, topic, conn.msgtype, sm.field, spath, name)
                v = reduce_value(raw_v, sm, where=f"signal {name!r}: {topic} ({conn.msgtype}) field {sm.field!r}",
                                 path=spath)
                if v != v:
                    bad[name] += 1
                t = int(t_log) if sm.time == "log" else _stamp(msg, topic, conn.msgtype, spath, name)
                ts, vs = samples[name]
                ts.append(t)
                vs.append(v)
    series = {}
    for name, (ts, vs) in samples.items():
        times = np.asarray(ts, dtype=np.int64)
        values = np.asarray(vs, dtype=np.float64)
        if times.size and np.any(np.diff(times) < 0):  # header stamps can arrive out of order
            order = np.argsort(times, kind="stable")
            times, values = times[order], values[order]
        series[name] = Series(mapping.signals[name].topic, times, values, bad[name])
    texts.sort(key=lambda x: x[0])
    return BagData(spath, _storage(reader, p, ros1), series, texts, topics)


def _get(msg: Any, fpath: tuple, topic: str, msgtype: str, text: str, bag: str, who: str) -> Any:
    """Follow ``fpath`` (names and indices) into a deserialised message."""
    cur = msg
    for i, part in enumerate(fpath):
        if isinstance(part, int):
            try:
                cur = cur[part]
            except (IndexError, TypeError, KeyError):
                return math.nan  # an element this message does not have: no usable value
            continue
        if not hasattr(cur, "__dataclass_fields__") or part not in _fields(cur):
            have = _fields(cur)
            import difflib
            close = difflib.get_close_matches(part, have, n=1)
            hint = f"did you mean {close[0]!r}?" if close else (
                f"fields here: {', '.join(have)}" if have else "this part of the message has no fields")
            at = "" if i == 0 else f" (in {'.'.join(str(x) for x in fpath[:i])})"
            raise BagError(f"{who}: {topic} ({msgtype}) has no field {part!r}{at} for field path {text!r}", bag,
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


def reduce_value(v: Any, sm: SignalMap, *, where: str = "", path: str | None = None) -> float:
    """One number from a field value: the mapping's reduction, then ``* scale + offset``.

    NaN when the value cannot be formed from this message (an empty array, an index past the end);
    a value of the wrong kind (text, a nested message) raises :class:`BagError`.
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
    if arr.size == 0:
        return math.nan
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


def _kind(v: Any) -> str:
    if isinstance(v, str):
        return "text"
    if isinstance(v, (np.ndarray, list, tuple)):
        return f"an array of {len(v)}"
    t = getattr(v, "__msgtype__", None)
    return f"a message ({t})" if t else type(v).__name__

