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
topic carries the task text that the risk estimator scores. Bags are read with
``rosbags`` (``pip install 'ethimon[ros]'``), imported only when a bag is read:
``import ethimon`` and ``import ethimon.replay`` never import it.
"""

from __future__ import annotations

from ._bag import BagData, BagError, Series, read_bag
from ._check import CycleResults, check_columns
from ._mapping import (Mapping, SignalMap, TaskMap, check_against_spec, load_mapping, load_mapping_text,
                       mapping_json_schema)
from ._replay import BagReplay, CheckResult, TaskScorer, replay_bag, replay_data, resample
from ._resample import cycle_grid, hold

__all__ = ["BagData", "BagError", "BagReplay", "CheckResult", "CycleResults", "Mapping", "Series", "SignalMap",
           "TaskMap", "TaskScorer", "check_against_spec", "check_columns", "cycle_grid", "hold", "load_mapping",
           "load_mapping_text", "mapping_json_schema", "read_bag", "replay_bag", "replay_data", "resample"]
