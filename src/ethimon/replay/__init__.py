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
value reduction are ``ethimon.io``'s (the live node reads a mapping the same way); ``Mapping``,
``SignalMap``, ``load_mapping``, ``check_against_spec`` & co. stay importable from here. Bags are read with
``rosbags`` (``pip install 'ethimon[ros]'``), imported only when a bag is read:
``import ethimon`` and ``import ethimon.replay`` never import it.
"""

from __future__ import annotations

from ._bag import BagData, BagError, read_bag
from ._collect import Series, recorded_data
from ._verdicts import CycleResults, check_columns
from ._mapping import (Mapping, SignalMap, TaskMap, check_against_spec, lint_mapping, load_mapping,
                       load_mapping_text, mapping_json_schema)
from ._mcap import write_mcap
from ._record import ReplayReport, replay_paths
from ._columns import resample
from ._replay import replay_bag, replay_data
from ._result import BagReplay, CheckResult
from ._scoring import TaskScorer
from ._resample import cycle_grid, hold
from ._topics import TopicInfo, list_topics

__all__ = ["BagData", "BagError", "BagReplay", "CheckResult", "CycleResults", "Mapping", "ReplayReport", "Series",
           "SignalMap", "TaskMap", "TaskScorer", "TopicInfo", "check_against_spec", "check_columns", "cycle_grid",
           "hold", "lint_mapping", "list_topics", "load_mapping", "load_mapping_text", "mapping_json_schema",
           "read_bag", "recorded_data", "replay_bag", "replay_data", "replay_paths", "resample", "write_mcap"]
