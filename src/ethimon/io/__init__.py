"""The seam between the monitor and the world: one mapping, one hold, one way to make a number.

A mapping file (:func:`load_mapping`) says which topic and field gives which monitor input; replay
(``ethimon replay``) and the live node (``ethimon ros2``) read it here, and both hold, age, reduce and
differentiate samples the same way (:func:`hold` over a recording, :class:`Hold` one sample at a time,
:func:`reduce_value`, :func:`rate_between`). Live, a transport is a :class:`Channel` (samples and
acknowledgement requests in) with an :class:`Outlet` (``channel.out``: the override, the decision and the
answers to acknowledgements out), and :class:`LiveMonitor` runs a :class:`~ethimon.loop.GovernedLoop` on it;
:class:`MemoryChannel` is one in memory::

    import ethimon
    from ethimon.io import LiveMonitor, MemoryChannel, load_mapping

    spec = ethimon.load_spec("examples/replay/spec.yaml")
    loop = ethimon.GovernedLoop(ethimon.Monitor(spec), period_s=0.01)
    live = LiveMonitor(loop, load_mapping("examples/ros2/mapping.yaml"), MemoryChannel())
"""

from __future__ import annotations

from ._channel import TASK_TEXT, AckRequest, Channel, Frame, MemoryChannel, Sample
from ._hold import MAX_CYCLES, MISSING, OK, STALE, Hold, cycle_grid, hold, judged
from ._live import LiveMonitor, Recording, mapping_error
from ._outlet import MemoryOutlet, Outlet, decision_json
from ._node import LiveNode, TopicPlan, plan_topics
from ._mapping import (FIELD_PATH, FUTURE_TOLERANCE_S, MSGTYPE, REDUCTIONS, RISK_INPUTS, ByName, Mapping, Ros2Map,
                       SignalMap, TaskMap, bool_mismatch, check_against_spec, lint_mapping, load_mapping,
                       load_mapping_text, mapping_json_schema, msgtype_key, parse_field_path)
from ._values import follow, is_truth, numbers_of, rate_between, reduce_array, reduce_value

__all__ = ["AckRequest", "ByName", "Channel", "Frame", "Hold", "LiveMonitor", "LiveNode", "Mapping", "MemoryChannel",
           "Outlet", "Sample", "SignalMap", "TopicPlan", "hold", "judged", "load_mapping", "load_mapping_text"]
