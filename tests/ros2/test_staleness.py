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


def test_a_header_stamp_from_the_future_is_a_fault_not_a_value_that_never_ages():
    # Before: with 'time: header' the age is (now - header stamp); a stamp 100 s ahead (a robot PC
    # whose clock runs ahead, or a forged stamp) gave a negative age, never above max_age_s: once
    # the topic died its last value stayed in force for those 100 s (override off).
    import time
    mp = MAPPING.replace("max_age_s: null", "max_age_s: 0.1").replace(
        "reduce: max_abs}", "reduce: max_abs, time: header}")
    spec = ethimon.load_spec_text(SPEC)
    node = Ros2Monitor(spec, load_mapping_text(mp, "m.yaml"), domain_id=DOMAIN, config=LOOPBACK)
    try:
        slot, risk = node.live.holds["joint_speed_max"], node.live.holds["p_unsafe"]  # the io holds
        risk.put(0.0, time.monotonic())
        slot.put([0.5], time.time() + 100.0, now=time.time())  # as the node takes it
        frame = node.live.frame()
        assert "joint_speed_max" not in frame
        assert [(f.kind, f.subject) for f in frame.faults] == [("stale", "joint_speed_max")]
        assert "future" in frame.faults[0].message
        slot.put([0.5], time.time(), now=time.time())  # a fresh stamp, newer than that take, is a value
        frame = node.live.frame()
        assert frame["joint_speed_max"] == 0.5 and not frame.faults
    finally:
        node.close()
