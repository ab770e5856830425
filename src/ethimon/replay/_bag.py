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

import os
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .._files import file_kind
from ..errors import BagError, DependencyNotInstalled
from ._collect import Series, _Collector, task_text
from ..io import Mapping
from ._values import _did_you_mean

__all__ = ["MAX_MESSAGES", "BagData", "BagError", "read_bag"]

#: most messages read from one bag (all mapped topics together)
MAX_MESSAGES = 50_000_000



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
        if want is not None and not Mapping.same_type(want, have):
            raise BagError(f"{who}: topic {topic} carries {have}, but the mapping says type {want}", spath,
                           hint="fix 'type:' in the mapping, or map the topic that carries that type")



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
    task_path = task.field_path if task is not None else None
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
                texts.append((int(t_log), task_text(msg, task_path, topic, msgtype, task.field, spath)))
            for c in by_topic.get(topic, ()):
                c.add(msg, t_log, topic, msgtype)
    if on_progress is not None:
        on_progress(n, max(n, total))
    series = {name: c.series(c.sm.topic, types.get(c.sm.topic, topics.get(c.sm.topic, ("", 0))[0]))
              for name, c in cols.items()}
    texts.sort(key=lambda x: x[0])
    return BagData(spath, _storage(reader, p, ros1), series, texts, topics)
