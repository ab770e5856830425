"""Replaying ROS bags through the monitor: bags in, verdicts out.

::

    import ethimon
    from ethimon.replay import load_mapping, replay_bag

    spec = ethimon.load_spec("examples/replay/spec.yaml")
    res = replay_bag("examples/replay/cell", spec, load_mapping("examples/replay/mapping.yaml"))
    for c in res.checks:
        print(c.id, c.cycles, c.first_t_s, c.worst_margin)

A mapping file says which topic and field gives which signal (with a reduction
and unit scaling), the monitor's cycle rate (inputs are zero-order held), a
staleness limit per signal (a stale or missing input fails closed), and which
topic carries the task text that the risk estimator scores (or ``risk: none``:
the risk rule is then reported NOT CHECKED). :func:`list_topics` lists a bag's
topics to write a mapping from; :func:`replay_paths` replays many bags as
``ethimon replay`` does; :func:`write_mcap` writes the verdicts as MCAP topics; :func:`recorded_data`
reads back what a live :class:`~ethimon.io.LiveMonitor` recorded. The mapping format, the hold and the
value reduction are ``ethimon.io``'s (the live node reads a mapping the same way; ``Mapping``,
``load_mapping`` and ``load_mapping_text`` are importable from here too; ``Mapping.check`` / ``Mapping.lint``
check one against a spec). Bags are read with
``rosbags`` (``pip install 'ethimon[ros]'``), imported only when a bag is read:
``import ethimon`` and ``import ethimon.replay`` never import it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from ._bag import BagData, BagError, read_bag
from ._collect import Series, _Collector
from ._verdicts import CycleResults, check_columns
from ..io import Mapping, SignalMap, hold, load_mapping, load_mapping_text
from ._mcap import write_mcap
from ._record import ReplayReport, replay_paths
from ._columns import resample
from ._replay import replay_bag, replay_data
from ._result import BagReplay, CheckResult
from ._scoring import TaskScorer
from ._topics import TopicInfo, list_topics

__all__ = ["BagReplay", "CheckResult", "Mapping", "ReplayReport", "check_columns", "list_topics", "load_mapping",
           "replay_bag", "replay_paths", "write_mcap"]


@dataclass
class _Stamp:
    sec: int
    nanosec: int


@dataclass
class _Header:
    stamp: _Stamp


@dataclass
class _Recorded:
    data: Any
    header: Any = None


def recorded_data(recording: Any, mapping: Any, path: str = "<recording>") -> Any:
    """A live run's :class:`~ethimon.io.Recording` (every sample :class:`~ethimon.io.LiveMonitor` received)
    as the :class:`BagData` a bag gives: replayed (:func:`~ethimon.replay.replay_data`), it is read by the
    same rules as a bag (receive times as log time, header stamps as header time, ``offset_s``, ``derive``).
    A ``time: header`` sample's log time is its receive time moved onto the header clock (by the difference of
    the two clocks at the cycle that took it): live holds it from that cycle, or from its stamp if that is still
    ahead, and its age counts from its stamp; replayed, the same.
    A header stamp that was further than ``future_tolerance_s`` ahead of the cycle that took it (a fault live
    until its time came) is an unusable sample at that cycle's time, then its value at its own time."""
    def header(t_s: float, minus_ns: int = 0) -> _Header:
        ns = int(round(t_s * 1e9)) - minus_ns
        return _Header(_Stamp(ns // 1_000_000_000, ns % 1_000_000_000))

    taken, cycles = getattr(recording, "taken", []), getattr(recording, "cycles", [])
    tol_ns = mapping.future_tolerance_s * 1e9
    series: dict[str, Series] = {}
    for name, sm in mapping.signals.items():
        c = _Collector(name, sm.model_copy(update={"field": "data"}), path)
        msgtype = sm.type or "recorded"
        off = int(round(sm.offset_s * 1e9))
        for i, s in enumerate(recording.samples):
            if s.signal != name:
                continue
            hdr = None
            t_log = int(round(s.t_log * 1e9))
            if s.t_header is not None:
                hdr = header(s.t_header)
                k = taken[i] if i < len(taken) else None
                if sm.time == "header" and k is not None and k < len(cycles) and cycles[k][1] is not None:
                    wall = cycles[k][1]
                    # received then, on the clock of the stamps (the live log clock may be another one)
                    t_log += int(round(wall * 1e9)) - int(round(cycles[k][0] * 1e9))
                    if int(round(s.t_header * 1e9)) + off - int(round(wall * 1e9)) > tol_ns:
                        # 1 ns before the cycle: a sample stamped at the cycle's time, taken by it, replaces the
                        # mark (live, its time has come), instead of sharing the mark's time
                        c.add(_Recorded(math.nan, header(wall, off + 1)), int(round(cycles[k][0] * 1e9)),
                              sm.topic, msgtype)
            c.add(_Recorded(s.value, hdr), t_log, sm.topic, msgtype)
        series[name] = c.series(sm.topic, msgtype)
    texts = [(int(round(s.t_log * 1e9)), s.value) for s in recording.samples
             if s.is_task and isinstance(s.value, str)]
    topics = {sm.topic: (sm.type or "recorded", series[n].read) for n, sm in mapping.signals.items()}
    return BagData(path, "recording", series, texts, topics)
