"""ethimon ros2: the monitor live on ROS 2's wire (Cyclone DDS over loopback, no ROS 2 installation).

The wire is tested, not assumed: the CDR bytes the node sends and receives are
compared with rosbags' serializer (what a ROS 2 bag stores), the names with ROS 2's
conventions, the QoS with ROS 2's default profiles. Then a stand-in robot in this
process governs-by-wire an ``ethimon ros2`` child process: slow joint speeds, too
fast, then silence.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

pytestmark = pytest.mark.slow  # a DDS stand-in robot and ethimon ros2 in subprocesses

pytest.importorskip("cyclonedds")
pytest.importorskip("rosbags")

import ethimon  # noqa: E402
from ethimon.errors import Ros2Error, SpecError  # noqa: E402
from ethimon.replay import load_mapping_text  # noqa: E402
from ethimon.io import decision_json  # noqa: E402
from ethimon.ros2 import (DEFAULT, SENSOR_DATA, MessageTypes, Ros2Monitor, cyclone_config, dds_topic,  # noqa: E402
                          dds_type, normalize_type, ros_topic, security_available, to_cyclone)

ROOT = Path(__file__).resolve().parents[2]
#: a domain of its own per test run: other engineers' runs on this machine do not cross-talk
DOMAIN = 17 + os.getpid() % 200
LOOPBACK = cyclone_config(interface="lo", peers=["127.0.0.1"])

SPEC = """
ethimon: 1
name: ros2_standin
signals:
  joint_speed_max: {unit: rad/s, range: [0, 100]}
constants:
  w_max: {value: 2.0, unit: rad/s}
risk: {threshold: 0.5, release: {mode: auto, hysteresis: 0.05, hold_cycles: 2}}
on_fault: {response: stop_1, release: auto}
obligations:
  - id: joint_speed
    require: joint_speed_max <= w_max
    response: stop_1
    release: auto
"""

MAPPING = """
ethimon: 1
rate_hz: 100
max_age_s: 0.1
signals:
  joint_speed_max: {topic: /joint_states, type: sensor_msgs/msg/JointState, field: velocity, reduce: max_abs}
  p_unsafe: {topic: /ethimon_test/p_unsafe, type: std_msgs/msg/Float64, max_age_s: 1.0}
"""


def _spec():
    return ethimon.load_spec_text(SPEC)


class Peer:
    """The robot side: a DDS participant on the test's domain, over loopback."""

    def __init__(self, domain: int = DOMAIN) -> None:
        from cyclonedds.domain import Domain, DomainParticipant
        self.types = MessageTypes()
        self.domain = Domain(domain, LOOPBACK)
        self.dp = DomainParticipant(domain)

    def writer(self, topic: str, msgtype: str, profile=DEFAULT, dp=None):
        from cyclonedds.pub import DataWriter
        from cyclonedds.topic import Topic
        dp = dp or self.dp
        return DataWriter(dp, Topic(dp, dds_topic(topic), self.types.idl(msgtype)), to_cyclone(profile))

    def reader(self, topic: str, msgtype: str, profile=DEFAULT, **kw):
        from cyclonedds.sub import DataReader
        from cyclonedds.topic import Topic
        return DataReader(self.dp, Topic(self.dp, dds_topic(topic), self.types.idl(msgtype)),
                          to_cyclone(profile, **kw))

    def joint_state(self, v: float, n: int = 7):
        T = self.types
        Time, Header = T.idl("builtin_interfaces/msg/Time"), T.idl("std_msgs/msg/Header")
        now = time.time()
        return T.idl("sensor_msgs/msg/JointState")(
            header=Header(stamp=Time(sec=int(now), nanosec=int((now % 1) * 1e9)), frame_id="base"),
            name=[f"j{i}" for i in range(n)], position=[0.0] * n, velocity=[v] + [0.1] * (n - 1), effort=[])

    def close(self) -> None:
        self.dp.__del__()
        self.domain.__del__()


def _wait(pred, timeout: float, step: float = 0.01) -> bool:
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if pred():
            return True
        time.sleep(step)
    return pred()


# --------------------------------------------------------------------------- names, QoS, bytes
def test_ros2_names_follow_the_wire_conventions():
    assert dds_topic("/joint_states") == "rt/joint_states"
    assert dds_topic("ns/scan") == "rt/ns/scan"
    assert ros_topic("rt/ethimon/override") == "/ethimon/override"
    assert dds_type("sensor_msgs/msg/JointState") == "sensor_msgs::msg::dds_::JointState_"
    assert dds_type("std_msgs/Bool") == "std_msgs::msg::dds_::Bool_"
    assert normalize_type("geometry_msgs/Twist") == "geometry_msgs/msg/Twist"
    with pytest.raises(ValueError):
        normalize_type("JointState")
    T = MessageTypes()
    assert T.idl("sensor_msgs/msg/JointState").__idl__.idl_transformed_typename == \
        "sensor_msgs::msg::dds_::JointState_"
    assert T.idl("builtin_interfaces/msg/Time").__idl__.idl_transformed_typename == \
        "builtin_interfaces::msg::dds_::Time_"


def test_qos_profiles_are_ros2_defaults():
    from cyclonedds.qos import Policy
    # rmw_qos_profile_default: reliable, keep last 10, volatile; rmw_qos_profile_sensor_data: best effort, 5
    assert (DEFAULT.reliable, DEFAULT.depth, DEFAULT.transient_local) == (True, 10, False)
    assert (SENSOR_DATA.reliable, SENSOR_DATA.depth, SENSOR_DATA.transient_local) == (False, 5, False)
    q = to_cyclone(DEFAULT, deadline_s=0.03)
    assert q[Policy.History] == Policy.History.KeepLast(10)
    assert isinstance(q[Policy.Reliability], Policy.Reliability.Reliable)
    assert q[Policy.Durability] == Policy.Durability.Volatile
    assert q[Policy.Deadline] == Policy.Deadline(30_000_000)
    assert q[Policy.DataRepresentation].use_cdrv0_representation
    s = to_cyclone(SENSOR_DATA)
    assert s[Policy.Reliability] == Policy.Reliability.BestEffort
    assert s[Policy.History] == Policy.History.KeepLast(5)


def _rosbags_msg(store, msgtype: str, **fields):
    return store.types[msgtype](**fields)


def test_cdr_bytes_equal_rosbags_serializer():
    """The bytes a node puts on the wire are the bytes rosbags writes into a ROS 2 bag, and back."""
    T = MessageTypes()
    st = T.store
    RT, RH = st.types["builtin_interfaces/msg/Time"], st.types["std_msgs/msg/Header"]
    cases = []
    hdr = RH(stamp=RT(sec=1_700_000_000, nanosec=123_456_789), frame_id="panda_link0")
    cases.append(("sensor_msgs/msg/JointState",
                  st.types["sensor_msgs/msg/JointState"](header=hdr, name=["j1", "joint_two", "j3"],
                                                         position=np.array([0.1, -0.2, 0.3]),
                                                         velocity=np.array([1.5, -2.5, 0.0]),
                                                         effort=np.array([], dtype=np.float64))))
    cases.append(("std_msgs/msg/Bool", st.types["std_msgs/msg/Bool"](data=True)))
    cases.append(("std_msgs/msg/String", st.types["std_msgs/msg/String"](data='{"override":true,"é":1}')))
    cases.append(("std_msgs/msg/Float64", st.types["std_msgs/msg/Float64"](data=0.125)))
    V3 = st.types["geometry_msgs/msg/Vector3"]
    cases.append(("geometry_msgs/msg/WrenchStamped", st.types["geometry_msgs/msg/WrenchStamped"](
        header=hdr, wrench=st.types["geometry_msgs/msg/Wrench"](force=V3(x=1.0, y=2.0, z=-3.0),
                                                              torque=V3(x=0.0, y=0.5, z=0.25)))))
    cases.append(("sensor_msgs/msg/Range", st.types["sensor_msgs/msg/Range"](
        header=hdr, radiation_type=1, field_of_view=0.5, min_range=0.1, max_range=8.0, range=1.25)))
    cases.append(("std_msgs/msg/Empty", st.types["std_msgs/msg/Empty"]()))
    for msgtype, rmsg in cases:
        want = bytes(st.serialize_cdr(rmsg, msgtype))
        cls = T.idl(msgtype)
        got_obj = cls.deserialize(want)             # what the node receives, from a bag's bytes
        again = got_obj.serialize()                 # what it sends (default representation: XCDR1)
        assert again == want, msgtype
        back = st.deserialize_cdr(again, msgtype)   # and rosbags reads the node's bytes
        assert bytes(st.serialize_cdr(back, msgtype)) == want, msgtype


def test_bytes_on_the_wire_equal_rosbags(monkeypatch):
    """Captured off a real DDS exchange (loopback): the serialized sample a reader gets from the wire."""
    peer = Peer()
    T = peer.types
    try:
        cls = T.idl("std_msgs/msg/Bool")
        seen: list[bytes] = []
        orig = cls.__idl__.deserialize

        def spy(data, *a, **kw):
            seen.append(bytes(data))
            return orig(data, *a, **kw)

        monkeypatch.setattr(cls.__idl__, "deserialize", spy)
        r = peer.reader("/ethimon_test/wire", "std_msgs/msg/Bool")
        w = peer.writer("/ethimon_test/wire", "std_msgs/msg/Bool")
        assert _wait(lambda: len(w.get_matched_subscriptions()) > 0, 5.0)
        w.write(cls(data=True))
        assert _wait(lambda: bool(r.take(N=4)) or bool(seen), 5.0)
        want = bytes(T.store.serialize_cdr(T.store.types["std_msgs/msg/Bool"](data=True), "std_msgs/msg/Bool"))
        assert seen and seen[0][:len(want)] == want and set(seen[0][len(want):]) <= {0}
    finally:
        peer.close()


# --------------------------------------------------------------------------- mapping checks
def test_mapping_type_is_checked_against_the_message(tmp_path):
    spec = _spec()
    bad = MAPPING.replace("field: velocity", "field: velocty")
    with pytest.raises(SpecError) as e:
        Ros2Monitor(spec, load_mapping_text(bad, "m.yaml"), domain_id=DOMAIN, config=LOOPBACK)
    assert "did you mean 'velocity'" in str(e.value) and "m.yaml:" in str(e.value)
    no_type = MAPPING.replace(" type: sensor_msgs/msg/JointState,", "")
    with pytest.raises(SpecError, match="needs its message type"):
        Ros2Monitor(spec, load_mapping_text(no_type, "m.yaml"), domain_id=DOMAIN, config=LOOPBACK)
    scalar = MAPPING.replace("reduce: max_abs", "reduce: value")
    with pytest.raises(SpecError, match="not one number"):
        Ros2Monitor(spec, load_mapping_text(scalar, "m.yaml"), domain_id=DOMAIN, config=LOOPBACK)
    unknown = MAPPING.replace("std_msgs/msg/Float64", "acme_msgs/msg/Risk")
    with pytest.raises(SpecError, match="unknown message type acme_msgs/msg/Risk"):
        Ros2Monitor(spec, load_mapping_text(unknown, "m.yaml"), domain_id=DOMAIN, config=LOOPBACK)
    # ... a .msg file makes it known
    d = tmp_path / "acme_msgs" / "msg"
    d.mkdir(parents=True)
    (d / "Risk.msg").write_text("float64 data\nstring source\n")
    T = MessageTypes([tmp_path / "acme_msgs"])
    assert T.resolve("acme_msgs/msg/Risk", ("data",)) == ("number", "float64")
    with pytest.raises(SpecError, match="unknown key 'typ'"):
        load_mapping_text(MAPPING.replace("type: std_msgs", "typ: std_msgs"), "m.yaml")


def test_enclave_without_security_plugins_is_refused(tmp_path):
    with pytest.raises(Ros2Error, match="no such enclave"):
        cyclone_config(enclave=tmp_path / "nope")
    enc = tmp_path / "enclave"
    enc.mkdir()
    for f in ("identity_ca.cert.pem", "cert.pem", "key.pem", "permissions_ca.cert.pem", "governance.p7s",
              "permissions.p7s"):
        (enc / f).write_text("x")
    if security_available():
        assert "<Security>" in cyclone_config(enclave=enc)
    else:
        with pytest.raises(Ros2Error, match="no security plugins"):
            cyclone_config(enclave=enc)


def test_decision_json_is_strict_json():
    m = ethimon.Monitor(_spec())
    d = m.step({"p_unsafe": 0.1})  # joint_speed_max missing: a fault
    doc = json.loads(decision_json(d, m.obligation_ids))
    assert doc["override"] is True and doc["faults"][0]["kind"] == "missing"
    assert doc["faults"][0]["subject"] == "joint_speed_max"
    assert set(doc) >= {"cycle", "response", "violations", "margins", "risk"}


# --------------------------------------------------------------------------- in-process node
def _node(mapping: str = MAPPING, **kw):
    return Ros2Monitor(_spec(), load_mapping_text(mapping, "m.yaml"), domain_id=DOMAIN, config=LOOPBACK, **kw)


def test_second_publisher_is_a_fault_naming_it():
    from cyclonedds.domain import DomainParticipant
    peer = Peer()
    node = _node()
    try:
        js = peer.writer("/joint_states", "sensor_msgs/msg/JointState")
        pu = peer.writer("/ethimon_test/p_unsafe", "std_msgs/msg/Float64")
        F64 = peer.types.idl("std_msgs/msg/Float64")
        node.start()

        def feed():
            js.write(peer.joint_state(0.5))
            pu.write(F64(data=0.05))

        assert _wait(lambda: (feed(), node.loop.last_decision is not None
                              and not node.loop.last_decision.override)[1], 8.0, 0.02)
        intruder_dp = DomainParticipant(DOMAIN)  # another participant (as another process would be)
        intruder = peer.writer("/joint_states", "sensor_msgs/msg/JointState", dp=intruder_dp)
        intruder.write(peer.joint_state(0.1))

        def foreign():
            feed()
            d = node.loop.last_decision
            return d is not None and any(f.kind == "signals" and f.subject == "/joint_states" for f in d.faults)
        assert _wait(foreign, 5.0, 0.02)
        d = node.loop.last_decision
        f = next(f for f in d.faults if f.subject == "/joint_states")
        assert d.override and "another publisher on /joint_states: writer" in f.message
        assert str(intruder_dp.guid) in f.message  # names the intruder's participant
        intruder_dp.__del__()
        assert _wait(lambda: (feed(), not node.loop.last_decision.override)[1], 5.0, 0.02)
    finally:
        node.close()
        peer.close()


def test_acknowledge_refused_unless_authenticated_or_allowed(tmp_path):
    from ethimon.audit import AuditLog, read_log
    manual = SPEC.replace("    response: stop_1\n    release: auto", "    response: stop_1\n    release: manual")
    assert manual != SPEC
    peer = Peer()
    ack = peer.writer("/ethimon/acknowledge", "std_msgs/msg/String")
    res = peer.reader("/ethimon/acknowledge_result", "std_msgs/msg/String")
    S = peer.types.idl("std_msgs/msg/String")
    js = peer.writer("/joint_states", "sensor_msgs/msg/JointState")
    pu = peer.writer("/ethimon_test/p_unsafe", "std_msgs/msg/Float64")
    F64 = peer.types.idl("std_msgs/msg/Float64")
    for allow in (False, True):
        log = tmp_path / f"audit_{allow}.jsonl"
        audit = AuditLog(log)
        mp = MAPPING + ("ros2: {allow_unauthenticated_acknowledge: test bench}\n" if allow else "")
        node = Ros2Monitor(ethimon.load_spec_text(manual), load_mapping_text(mp, "m.yaml"), domain_id=DOMAIN,
                           config=LOOPBACK, audit=audit)
        try:
            node.start()
            assert _wait(lambda: len(ack.get_matched_subscriptions()) > 0 and len(js.get_matched_subscriptions())
                         > 0, 5.0)
            for v in [3.5] * 10 + [0.5] * 20:  # too fast: joint_speed latches (manual); then slow again
                js.write(peer.joint_state(v))
                pu.write(F64(data=0.05))
                time.sleep(0.01)
            d = node.loop.last_decision
            assert d.override and d.latched and not d.faults, (allow, d)
            ack.write(S(data=json.dumps({"operator": "ana", "reason": "inputs back"})))
            got: list = []
            assert _wait(lambda: (js.write(peer.joint_state(0.5)), pu.write(F64(data=0.05)),
                                  got.extend(s for s in res.take(N=4) if hasattr(s, "data")), bool(got))[-1], 5.0, 0.01)
            answer = json.loads(got[0].data)
            assert answer["released"] is allow, answer
            if not allow:
                assert "unauthenticated" in answer["message"]
        finally:
            node.close()
            audit.close()
        recs = [r for r in read_log(log) if r.get("kind") == "acknowledge"]
        assert recs and recs[0]["operator"] == "ana" and recs[0]["released"] is allow
        if allow:
            assert "unauthenticated, allowed by the mapping: test bench" in recs[0]["reason"]
    peer.close()


def test_deadline_qos_tells_the_robot_the_node_went_silent():
    peer = Peer()
    node = _node()
    try:
        r = peer.reader("/ethimon/override", "std_msgs/msg/Bool", deadline_s=0.1)
        node.start()
        assert _wait(lambda: bool(r.take(N=10)), 5.0)
        before = r.get_requested_deadline_missed_status().total_count
        node.stop()   # the loop stops publishing (the participant is still there)
        assert _wait(lambda: r.get_requested_deadline_missed_status().total_count > before, 3.0)
    finally:
        node.close()
        peer.close()


# --------------------------------------------------------------------------- two processes
def test_standin_robot_governed_live_by_ethimon_ros2(tmp_path):
    """A robot publishing JointState slow, then too fast, then nothing, governed by `ethimon ros2`."""
    spec_p, map_p = tmp_path / "spec.yaml", tmp_path / "map.yaml"
    spec_p.write_text(SPEC)
    map_p.write_text(MAPPING)
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"), CYCLONEDDS_URI=LOOPBACK)
    proc = subprocess.Popen([sys.executable, "-m", "ethimon.cli", "ros2", "--spec", str(spec_p), "--map",
                             str(map_p), "--domain", str(DOMAIN), "--duration-s", "8", "--json", "-",
                             "--interface", "lo", "--peer", "127.0.0.1"],
                            env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    peer = Peer()
    got: list[tuple[float, dict]] = []
    try:
        import threading
        from cyclonedds.core import Listener
        from cyclonedds.sub import DataReader
        from cyclonedds.topic import Topic

        def on_data(reader):
            for s in reader.take(N=64):
                if hasattr(s, "data"):  # not an InvalidSample (the node's writer leaving)
                    got.append((time.monotonic(), json.loads(s.data)))

        r = DataReader(peer.dp, Topic(peer.dp, "rt/ethimon/decision", peer.types.idl("std_msgs/msg/String")),
                       to_cyclone(DEFAULT), listener=Listener(on_data_available=on_data))
        js = peer.writer("/joint_states", "sensor_msgs/msg/JointState")
        pu = peer.writer("/ethimon_test/p_unsafe", "std_msgs/msg/Float64")
        F64 = peer.types.idl("std_msgs/msg/Float64")
        assert _wait(lambda: bool(got) and len(js.get_matched_subscriptions()) > 0, 8.0), proc.stderr
        stop = threading.Event()

        def risk():
            while not stop.is_set():
                pu.write(F64(data=0.05))
                time.sleep(0.02)
        threading.Thread(target=risk, daemon=True).start()

        def publish(v: float, seconds: float) -> float:
            t0 = time.monotonic()
            while time.monotonic() - t0 < seconds:
                js.write(peer.joint_state(v))
                time.sleep(0.01)  # 100 Hz
            return t0

        t_slow = publish(0.5, 1.5)
        t_fast = publish(3.5, 0.8)
        t_none = time.monotonic()
        time.sleep(0.8)
        stop.set()
    finally:
        try:
            out, errs = proc.communicate(timeout=15)
        except subprocess.TimeoutExpired:
            proc.kill()
            out, errs = proc.communicate()
        peer.close()
    assert proc.returncode == 0, errs
    summary = json.loads(out)
    assert summary["cycles"] > 100

    def phase(a, b):
        return [d for t, d in got if a <= t < b]

    slow = phase(t_slow + 0.5, t_fast)  # after the held values settled (auto release, 2 good cycles)
    # off while slow; the only overrides allowed are a loaded machine's missed deadlines (they fail closed)
    timing = {"deadline", "stall"}
    over = [d for d in slow if d["override"]]
    # (and the auto release of such a fault latch, a few cycles with no fault of their own)
    assert slow and all({f["kind"] for f in d["faults"]} <= timing and not d["violations"] for d in over), over[:2]
    assert len(over) <= 0.1 * len(slow), f"{len(over)} of {len(slow)} slow-phase decisions overrode"
    on = [t for t, d in got if t >= t_fast and d["override"] and "joint_speed" in d["violations"]]
    assert on and on[0] - t_fast <= 0.15, f"override {on[0] - t_fast if on else None} s after the fast samples"
    assert all(d["override"] for d in phase(t_fast + 0.15, t_none))
    stale = phase(t_none + 0.1 + 0.05, t_none + 0.8)
    assert stale and all(d["override"] for d in stale)
    assert all(any(f["kind"] == "stale" and f["subject"] == "joint_speed_max" for f in d["faults"]) for d in stale)


class _Words:
    """A stand-in estimator: texts with 'knife' are unsafe."""

    model_id = "words@test"

    def probs(self, text):
        return (0.1, 0.9) if "knife" in text else (0.95, 0.05)


def test_example_mapping_fits_its_types_and_spec():
    spec = ethimon.load_spec(ROOT / "examples" / "replay" / "spec.yaml")
    node = Ros2Monitor(spec, str(ROOT / "examples" / "ros2" / "mapping.yaml"), domain_id=DOMAIN, config=LOOPBACK,
                       estimator=_Words())
    try:
        assert {s.topic: s.msgtype for s in node.topics} == {
            "/joint_states": "sensor_msgs/msg/JointState", "/ee/twist": "geometry_msgs/msg/TwistStamped",
            "/ee/wrench": "geometry_msgs/msg/WrenchStamped", "/human/range": "sensor_msgs/msg/Range",
            "/task": "std_msgs/msg/String"}
    finally:
        node.close()


def test_task_text_is_scored_live():
    mp = ("ethimon: 1\nrate_hz: 100\nmax_age_s: 0.2\nsignals:\n  joint_speed_max: {topic: /joint_states, "
          "type: sensor_msgs/msg/JointState, field: velocity, reduce: max_abs}\ntask: {topic: /ethimon_test/task}\n")
    peer = Peer()
    node = Ros2Monitor(_spec(), load_mapping_text(mp, "m.yaml"), domain_id=DOMAIN, config=LOOPBACK,
                       estimator=_Words())
    try:
        js = peer.writer("/joint_states", "sensor_msgs/msg/JointState")
        task = peer.writer("/ethimon_test/task", "std_msgs/msg/String")
        S = peer.types.idl("std_msgs/msg/String")
        node.start()
        assert _wait(lambda: len(task.get_matched_subscriptions()) > 0, 5.0)
        d0 = node.loop.last_decision
        assert d0 is None or any(f.kind == "estimator" for f in d0.faults) or d0.override  # no text yet
        task.write(S(data="wipe the table"))

        def state(over: bool):
            js.write(peer.joint_state(0.5))
            d = node.loop.last_decision
            return d is not None and d.override is over and d.risk is not None
        assert _wait(lambda: state(False), 5.0, 0.01)
        task.write(S(data="hand the knife to the child"))
        assert _wait(lambda: state(True), 5.0, 0.01)
        assert "risk" in node.loop.last_decision.violations
    finally:
        node.close()
        peer.close()


def test_publication_handles_compare_unsigned():
    """Regression: the matched-publications list gives instance handles as signed int64, a sample's
    info as uint64; a handle with the top bit set made every sample of the one accepted writer look
    foreign (dropped: the signal went missing and the node failed closed for good). The DDS side now
    lives in :class:`ethimon.ros2._channel.DdsChannel` (the io seam); the sample must reach the loop."""
    import threading
    import uuid
    from types import SimpleNamespace

    from ethimon.ros2._channel import DdsChannel, Subscription

    h_unsigned = (1 << 63) + 12345
    h_signed = h_unsigned - (1 << 64)
    ep = SimpleNamespace(key=uuid.UUID(int=1), participant_key=uuid.UUID(int=2))

    class Reader:
        def __init__(self):
            self.pending = [(SimpleNamespace(data=1.5), SimpleNamespace(publication_handle=h_unsigned))]

        def get_matched_publications(self):
            return [h_signed]

        def get_matched_publication_data(self, h):
            assert h == h_signed
            return ep

    sub = Subscription("/joint_states", "std_msgs/msg/Float64", fields=[("v", ("data",))], reader=Reader())
    ch = object.__new__(DdsChannel)
    ch.subs, ch.publishers, ch._lock, ch._closed = [sub], 1, threading.Lock(), False
    ch._own_dirty, ch._own_foreign = False, ()
    ch._take = staticmethod(lambda reader, n: [reader.pending.pop()] if reader.pending else [])
    ch.check_publishers(sub)
    assert sub.foreign == () and sub.pinned == (str(ep.key),) and sub.pinned_handles == {h_unsigned}
    got = ch.take()
    assert sub.messages == 1 and [(s.signal, s.value) for s in got] == [("v", 1.5)]
    assert ch.faults() == ()


def test_the_dds_outlet_writes_the_three_topics_and_nothing_once_closed():
    """``DdsChannel.out``: the node's three writers as an ``io.Outlet``; the channel closes it before its
    participant leaves, so a watchdog's late override is not written into a deleted writer."""
    from ethimon.io import Outlet
    from ethimon.ros2._channel import DdsOutlet

    class W:
        def __init__(self):
            self.got = []

        def write(self, msg):
            self.got.append(msg)

    wo, wd, wa = W(), W(), W()
    out = DdsOutlet(wo, wd, wa, lambda data: ("Bool", data), lambda data: ("String", data))
    assert isinstance(out, Outlet)
    out.write_override(1)
    out.write_decision('{"cycle": 0}')
    out.write_ack_result('{"released": false}')
    assert (wo.got, wd.got, wa.got) == ([("Bool", True)], [("String", '{"cycle": 0}')],
                                        [("String", '{"released": false}')])
    out.closed = True
    out.write_override(True)
    assert wo.got == [("Bool", True)]
