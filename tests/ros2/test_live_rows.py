"""Issue 31, the live node read a mapping differently from replay; each row of the issue's table, live over
real DDS (in-process, loopback). Before: ``derive: rate`` on a position fed the position itself as the speed;
a std_msgs/Bool mapped to a distance was 1.0 m; a burst whose violating sample was replaced before the next
cycle was never judged nor counted; a header stamp up to ``max_age_s`` in the future was fresh for up to
2 x ``max_age_s``. Also: a second writer on /ethimon/override went unnoticed, and an acknowledgement was
applied in the DDS thread, where it can race ``Monitor.step``."""

from __future__ import annotations

import os
import threading
import time

import pytest

pytestmark = pytest.mark.slow  # a DDS participant and the node, in this process, over loopback

pytest.importorskip("cyclonedds")
pytest.importorskip("rosbags")

import ethimon  # noqa: E402
from ethimon.errors import SpecError  # noqa: E402
from ethimon.replay import load_mapping_text  # noqa: E402
from ethimon.ros2 import DEFAULT, MessageTypes, Ros2Monitor, cyclone_config, dds_topic, to_cyclone  # noqa: E402

DOMAIN = 17 + (os.getpid() + 57) % 200
LOOPBACK = cyclone_config(interface="lo", peers=["127.0.0.1"])

SPEC = """
ethimon: 1
name: rows
signals:
  joint_speed_max: {unit: rad/s, range: [0, 100]}
risk: {threshold: 0.5, release: {mode: auto, hysteresis: 0.05, hold_cycles: 2}}
on_fault: {response: stop_1, release: auto}
obligations:
  - {id: joint_speed, require: "joint_speed_max <= 2.0", response: stop_1, release: auto}
"""

MAPPING = """
ethimon: 1
rate_hz: 50
max_age_s: 0.5
signals:
  joint_speed_max: {topic: /joint_states, type: sensor_msgs/msg/JointState, field: velocity, reduce: max_abs}
  p_unsafe: {topic: /rows/p_unsafe, type: std_msgs/msg/Float64, max_age_s: 5.0}
ros2: {allow_unauthenticated_acknowledge: "a test on loopback"}
"""


class Robot:
    def __init__(self) -> None:
        from cyclonedds.domain import Domain, DomainParticipant
        self.types = MessageTypes()
        self.domain = Domain(DOMAIN, LOOPBACK)
        self.dp = DomainParticipant(DOMAIN)
        self.js = self.writer("/joint_states", "sensor_msgs/msg/JointState")
        self.pu = self.writer("/rows/p_unsafe", "std_msgs/msg/Float64")

    def writer(self, topic, msgtype, dp=None):
        from cyclonedds.pub import DataWriter
        from cyclonedds.topic import Topic
        dp = dp or self.dp
        return DataWriter(dp, Topic(dp, dds_topic(topic), self.types.idl(msgtype)), to_cyclone(DEFAULT))

    def joint_state(self, position=0.0, velocity=0.0, stamp=None):
        T = self.types
        Time, Header = T.idl("builtin_interfaces/msg/Time"), T.idl("std_msgs/msg/Header")
        st = time.time() if stamp is None else stamp
        return T.idl("sensor_msgs/msg/JointState")(
            header=Header(stamp=Time(sec=int(st), nanosec=int(round((st % 1) * 1e9)) % 1_000_000_000), frame_id="b"),
            name=["j0"], position=[position], velocity=[velocity], effort=[])

    def p(self):
        self.pu.write(self.types.idl("std_msgs/msg/Float64")(data=0.05))

    def close(self):
        self.dp.__del__()
        self.domain.__del__()


def _run(mapping: str, feed, seconds: float, **kw):
    """The node for ``seconds``, ``feed(robot, k)`` called every 10 ms meanwhile; its decisions."""
    robot = Robot()
    got = []
    node = Ros2Monitor(ethimon.load_spec_text(SPEC), load_mapping_text(mapping, "m.yaml"), domain_id=DOMAIN,
                       config=LOOPBACK, on_decision=got.append, **kw)
    try:
        node.start()
        end, k = time.monotonic() + seconds, 0
        while time.monotonic() < end:
            robot.p()
            feed(robot, k)
            k += 1
            time.sleep(0.01)
    finally:
        node.close()
        robot.close()
    return got, node


def test_derive_rate_gives_the_rate_live():
    # positions 0.0 .. 0.9 in steps of 0.1 about every 20 ms: ~5 rad/s, while every position is below 2.0
    mapping = MAPPING.replace("field: velocity, reduce: max_abs}", "field: position, reduce: max_abs, "
                              "derive: rate, time: header}")

    def feed(robot, k):
        if k % 2 == 0:
            robot.js.write(robot.joint_state(position=0.1 * ((k // 2) % 10)))
    got, _ = _run(mapping, feed, 1.5)
    late = got[len(got) // 3:]
    assert late and sum("joint_speed" in d.violations for d in late) > len(late) // 2, late[-3:]


def test_a_bool_field_on_a_number_signal_is_the_located_error_replay_gives():
    mapping = MAPPING.replace("{topic: /joint_states, type: sensor_msgs/msg/JointState, field: velocity, "
                              "reduce: max_abs}", "{topic: /flag, type: std_msgs/msg/Bool}")
    with pytest.raises(SpecError) as e:
        Ros2Monitor(ethimon.load_spec_text(SPEC), load_mapping_text(mapping, "m.yaml"), domain_id=DOMAIN,
                    config=LOOPBACK).close()
    assert "m.yaml:6:" in str(e.value) and "a bool is not a number" in str(e.value)


def test_a_burst_replaced_before_a_cycle_is_not_silently_unjudged():
    def feed(robot, k):
        robot.js.write(robot.joint_state(velocity=0.5))
        if k % 10 == 5:  # a burst: 9.0 rad/s, replaced at once by 0.5
            robot.js.write(robot.joint_state(velocity=9.0))
            robot.js.write(robot.joint_state(velocity=0.5))
    got, _ = _run(MAPPING, feed, 2.0)
    seen = [d for d in got if "joint_speed" in d.violations or any("never judge" in f.message for f in d.faults)]
    assert len(seen) >= 5, f"{len(seen)} of {len(got)} cycles judged or refused the bursts"


def test_a_header_stamp_in_the_future_is_a_fault():
    mapping = MAPPING.replace("reduce: max_abs}", "reduce: max_abs, time: header, max_age_s: 0.1}")

    def feed(robot, k):  # stamped 80 ms ahead: within max_age_s, beyond any clock tolerance
        robot.js.write(robot.joint_state(velocity=0.5, stamp=time.time() + 0.08))
    got, _ = _run(mapping, feed, 1.0)
    late = got[len(got) // 2:]
    assert late and all(d.override and any("future" in f.message for f in d.faults) for d in late), late[-2:]


def test_a_second_writer_on_the_override_topic_is_a_fault():
    from cyclonedds.domain import DomainParticipant
    other = {}

    def feed(robot, k):
        robot.js.write(robot.joint_state(velocity=0.5))
        if k == 40:
            other["dp"] = DomainParticipant(DOMAIN)
            other["w"] = robot.writer("/ethimon/override", "std_msgs/msg/Bool", dp=other["dp"])
        if "w" in other:
            other["w"].write(robot.types.idl("std_msgs/msg/Bool")(data=False))
    try:
        got, _ = _run(MAPPING, feed, 1.5)
    finally:
        if "dp" in other:
            other["dp"].__del__()
    hit = [d for d in got if any(f.subject == "/ethimon/override" for f in d.faults)]
    assert hit and all(d.override for d in hit), f"{len(hit)} of {len(got)}"
    assert "another writer on /ethimon/override" in next(f for f in hit[-1].faults
                                                          if f.subject == "/ethimon/override").message


def test_an_acknowledgement_is_applied_in_the_loop_thread():
    robot = Robot()
    node = Ros2Monitor(ethimon.load_spec_text(SPEC), load_mapping_text(MAPPING, "m.yaml"), domain_id=DOMAIN,
                       config=LOOPBACK)
    where = []
    real = node.loop._ack_now  # where GovernedLoop applies a request to the monitor

    def spy(*a, **k):
        where.append(threading.current_thread().name)
        return real(*a, **k)
    node.loop._ack_now = spy
    runner = threading.Thread(target=node.run, args=(3.0,), name="the-loop")  # run(), not start()
    try:
        runner.start()
        ack = robot.writer("/ethimon/acknowledge", "std_msgs/msg/String")
        S = robot.types.idl("std_msgs/msg/String")
        end = time.monotonic() + 2.5
        while time.monotonic() < end and not where:
            robot.p()
            robot.js.write(robot.joint_state(velocity=0.5))
            ack.write(S(data='{"operator": "ana", "reason": "test"}'))
            time.sleep(0.05)
    finally:
        node.stop()
        runner.join(5)
        node.close()
        robot.close()
    assert where and set(where) == {"the-loop"}, where
