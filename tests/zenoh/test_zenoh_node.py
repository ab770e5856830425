"""The zenoh node's writers and readers over loopback: the override on rmw_zenoh's exact key with its
attachment, an acknowledgement round trip, and the writers it does not accept (fail closed)."""

from __future__ import annotations

import json
import time

import pytest

pytestmark = pytest.mark.slow  # two zenoh sessions in this process, over loopback

pytest.importorskip("zenoh")
pytest.importorskip("rosbags")

import ethimon  # noqa: E402
from ethimon.errors import SpecError  # noqa: E402
from ethimon.io import load_mapping_text  # noqa: E402

from tests._estimators import FakeClock  # noqa: E402
from tests.zenoh._robot import DOMAIN, node, recv, unpack_attachment  # noqa: E402

SPEC = """
ethimon: 1
name: zrows
signals:
  joint_speed_max: {unit: rad/s, range: [0, 100]}
risk: {threshold: 0.5, release: {mode: auto, hysteresis: 0.05, hold_cycles: 2}}
on_fault: {response: stop_1, release: auto}
obligations:
  - {id: joint_speed, require: "joint_speed_max <= 2.0", response: stop_1, release: manual}
"""

MAPPING = """
ethimon: 1
rate_hz: 100
max_age_s: 0.5
signals:
  joint_speed_max: {topic: /joint_states, type: sensor_msgs/msg/JointState, field: position, reduce: max_abs}
  p_unsafe: {topic: /zrows/p_unsafe, type: std_msgs/msg/Float64, max_age_s: 5.0}
"""
ALLOW = 'ros2: {allow_unauthenticated_acknowledge: "a test on loopback"}\n'
JS, F64 = "sensor_msgs/msg/JointState", "std_msgs/msg/Float64"


def _cycles(n, robot, clock, k0, count, speed=0.0, **put_kw):
    """``count`` cycles from cycle ``k0``, each after a /joint_states and a p_unsafe sample came off the wire."""
    out = []
    for k in range(k0, k0 + count):
        clock.t = 1000.0 + k * 0.01
        robot.put("/joint_states", JS, robot.msg(JS, position=[speed]), **put_kw)
        robot.put("/zrows/p_unsafe", F64, robot.msg(F64, data=0.05))
        _received(n, 2)
        out.append(n.loop.cycle())
    return out


def _received(n, more):
    """Poll until ``more`` samples more came off the read topics (used or not; bounded)."""
    want = n.channel.received + more
    end = time.monotonic() + 3.0
    while n.channel.received < want and time.monotonic() < end:
        n.channel.poll()
    assert n.channel.received >= want


def test_the_override_is_on_rmw_zenohs_key_with_its_attachment_and_an_ack_goes_round():
    clock = FakeClock(1000.0)
    n, robot = node(ethimon.load_spec_text(SPEC), load_mapping_text(MAPPING + ALLOW), clock)
    try:
        store = robot.store
        exact = f"{DOMAIN}/ethimon/override/std_msgs::msg::dds_::Bool_/{store.hash_rihs01('std_msgs/msg/Bool')}"
        import zenoh
        ov = robot.session.declare_subscriber(exact, zenoh.handlers.FifoChannel(1024))
        res = robot.listen("/ethimon/acknowledge_result", "std_msgs/msg/String")
        time.sleep(0.05)  # the two subscriptions reach the node
        d = _cycles(n, robot, clock, 0, 5, speed=3.0)  # joint_speed violated, then held (manual release)
        d += _cycles(n, robot, clock, 5, 3)
        assert all(x.override for x in d) and d[-1].latched and not d[-1].violations
        s = recv(ov)
        assert s is not None and store.deserialize_cdr(s.payload.to_bytes(), "std_msgs/msg/Bool").data is True
        assert unpack_attachment(s.attachment.to_bytes()).gid == n.channel.gid
        # the operator acknowledges over zenoh; the loop thread applies it after the next cycle
        req = json.dumps({"operator": "ada", "reason": "arm checked"})
        robot.put("/ethimon/acknowledge", "std_msgs/msg/String", robot.msg("std_msgs/msg/String", data=req))
        got = None
        for k in range(8, 60):
            _cycles(n, robot, clock, k, 1)
            a = recv(res) if got is None and k > 6 else None
            if a is not None:
                got = json.loads(store.deserialize_cdr(a.payload.to_bytes(), "std_msgs/msg/String").data)
                break
        assert got is not None and got["operator"] == "ada", got
        assert got["released"] is True and "joint_speed" in got["rules"], got
        assert n.acks_refused == 0
    finally:
        n.close()
        robot.close()


def test_an_acknowledgement_is_refused_without_the_mappings_reason():
    clock = FakeClock(1000.0)
    n, robot = node(ethimon.load_spec_text(SPEC), load_mapping_text(MAPPING), clock)
    try:
        res = robot.listen("/ethimon/acknowledge_result", "std_msgs/msg/String")
        time.sleep(0.05)
        _cycles(n, robot, clock, 0, 3, speed=3.0)
        robot.put("/ethimon/acknowledge", "std_msgs/msg/String",
                  robot.msg("std_msgs/msg/String", data=json.dumps({"operator": "ada", "reason": "x"})))
        end = time.monotonic() + 3.0
        while n.acks_refused == 0 and time.monotonic() < end:
            _cycles(n, robot, clock, 3, 1)
        a = recv(res)
        out = json.loads(robot.store.deserialize_cdr(a.payload.to_bytes(), "std_msgs/msg/String").data)
        assert out["released"] is False and "unauthenticated" in out["message"]
    finally:
        n.close()
        robot.close()


def test_another_writer_on_the_override_and_a_second_publisher_are_faults():
    clock = FakeClock(1000.0)
    n, robot = node(ethimon.load_spec_text(SPEC), load_mapping_text(MAPPING), clock)
    try:
        d = _cycles(n, robot, clock, 0, 3)
        assert not d[-1].faults and not d[-1].override
        # a second publisher GID on /joint_states: its samples are not used, and it is a fault
        d = _cycles(n, robot, clock, 3, 2, speed=9.0, gid=b"\x01" * 16)
        assert all(x.override for x in d)
        assert any("another publisher on /joint_states: publisher 0101" in f.message for f in d[-1].faults)
        assert "joint_speed" not in d[-1].violations  # its 9 rad/s was never used
        # a sample without rmw_zenoh's attachment: its publisher cannot be told; not used, a fault
        robot.put("/joint_states", JS, robot.msg(JS, position=[0.0]), attach=False)
        _received(n, 1)
        # another writer on /ethimon/override (a robot reading it would take its values for the node's)
        robot.put("/ethimon/override", "std_msgs/msg/Bool", robot.msg("std_msgs/msg/Bool", data=False))
        end = time.monotonic() + 3.0
        while time.monotonic() < end and not any("/ethimon/override" in f.message for f in n.channel.faults()):
            time.sleep(0.001)
        d = _cycles(n, robot, clock, 5, 1)
        msgs = " | ".join(f.message for f in d[-1].faults)
        assert d[-1].override and "another writer on /ethimon/override" in msgs, msgs
        assert "attaches no rmw_zenoh GID" in msgs, msgs
    finally:
        n.close()
        robot.close()


def test_a_mapping_that_does_not_fit_the_message_types_is_a_located_error():
    bad = MAPPING.replace("field: position, reduce: max_abs", "field: nope, reduce: max_abs")
    clock = FakeClock(1000.0)
    with pytest.raises(SpecError) as e:
        node(ethimon.load_spec_text(SPEC), load_mapping_text(bad, "m.yaml"), clock)
    assert "m.yaml:" in str(e.value) and "nope" in str(e.value)
