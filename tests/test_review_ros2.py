"""Review findings on `ethimon ros2` (issue 21): a live topic always has a staleness limit."""

from __future__ import annotations

import os

import pytest

pytest.importorskip("cyclonedds")
pytest.importorskip("rosbags")

import ethimon  # noqa: E402
from ethimon.errors import SpecError  # noqa: E402
from ethimon.replay import load_mapping_text  # noqa: E402
from ethimon.ros2 import Ros2Monitor, cyclone_config  # noqa: E402

DOMAIN = 17 + (os.getpid() + 101) % 200
LOOPBACK = cyclone_config(interface="lo", peers=["127.0.0.1"])

SPEC = """
ethimon: 1
name: ros2_review
signals:
  joint_speed_max: {unit: rad/s, range: [0, 100]}
obligations:
  - {id: speed, require: "joint_speed_max <= 2.0", response: stop_1}
on_fault: {response: stop_1, release: auto}
"""

MAPPING = """
ethimon: 1
rate_hz: 100
max_age_s: null
signals:
  joint_speed_max: {topic: /joint_states, type: sensor_msgs/msg/JointState, field: velocity, reduce: max_abs}
  p_unsafe: {topic: /ethimon_test/p_unsafe, type: std_msgs/msg/Float64, max_age_s: 1.0}
"""


def _try(mapping_text):
    spec = ethimon.load_spec_text(SPEC)
    node = None
    try:
        node = Ros2Monitor(spec, load_mapping_text(mapping_text, "m.yaml"), domain_id=DOMAIN, config=LOOPBACK)
    finally:
        if node is not None:
            node.close()


def test_live_refuses_a_signal_that_can_never_go_stale():
    # Before: `max_age_s: null` (replay's "signals are never stale") was accepted live: the robot
    # publishes /joint_states once, dies, and its last value is held forever: override false.
    with pytest.raises(SpecError) as e:
        _try(MAPPING)
    msg = str(e.value)
    assert "m.yaml:4:" in msg and "joint_speed_max" in msg and "stale" in msg


def test_live_accepts_a_per_signal_limit_or_an_explicit_latched_topic():
    _try(MAPPING.replace("reduce: max_abs}", "reduce: max_abs, max_age_s: 0.1}"))
    _try(MAPPING.replace("reduce: max_abs}", "reduce: max_abs, stale: false}"))  # stated, not defaulted
