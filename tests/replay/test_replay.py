"""ethimon replay: real bags written with rosbags (ROS 2 sqlite3, ROS 2 MCAP, ROS 1), verdicts checked
cycle by cycle against Monitor.step fed zero-order-held samples computed here, independently."""

from __future__ import annotations

import ast
import json
import math
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

import ethimon
from ethimon.errors import SpecError

rosbags = pytest.importorskip("rosbags")

from rosbags.rosbag1 import Writer as Writer1  # noqa: E402
from rosbags.rosbag2 import StoragePlugin, Writer  # noqa: E402
from rosbags.typesys import Stores, get_typestore  # noqa: E402

from ethimon.replay import BagError, load_mapping, load_mapping_text, replay_bag  # noqa: E402

from tests._cli import ROOT, call_cli  # noqa: E402

SPEC = """
ethimon: 1
name: replay_test
signals:
  human_distance:  {unit: m,     range: [0, 10]}
  ee_speed:        {unit: m/s,   range: [0, 3]}
  joint_speed_max: {unit: rad/s, range: [0, 10]}
risk: {threshold: 0.5, release: {mode: auto, hysteresis: 0.05, hold_cycles: 4}}
on_fault: stop_1
obligations:
  - {id: separation, require: human_distance >= 0.5, response: stop_2}
  - {id: slow_near, when: human_distance < 1.5, require: ee_speed <= 0.25, within_cycles: 3}
  - {id: joint_speed, require: "not held(joint_speed_max > 1.5, 3)", response: stop_1}
"""

MAPPING = """
ethimon: 1
rate_hz: 50
max_age_s: 0.08
samples: latest
signals:
  joint_speed_max: {topic: /joint_states, field: velocity, reduce: max_abs}
  human_distance:  {topic: /human/distance_cm, field: data, scale: 0.01, max_age_s: 0.15}
  ee_speed:        {topic: /ee/twist, field: twist.linear, reduce: norm}
task: {topic: /task}
"""

TEXTS = {"Stack the boxes.": (0.9, 0.1), "Throw the box at the person.": (0.2, 0.8)}
T0 = 1_000 * 10**9


def _score(text):
    return TEXTS[text]


def make_messages(seed: int = 0, n_js: int = 160, dropout: tuple[float, float] | None = (2.0, 2.3)):
    """(time_ns, topic, kind, value) of a 4 s recording with jittered publication times."""
    rng = np.random.default_rng(seed)
    msgs = []
    for i in range(n_js):  # ~40 Hz joint states with jitter
        t = 0.025 * i + rng.uniform(0, 0.01)
        vel = rng.uniform(-1.0, 1.0, 7)
        if 1.0 <= t < 1.3 or 3.0 <= t < 3.05:
            vel[3] = 1.8  # over 1.5 for 0.3 s (held 3 cycles at 50 Hz) and then only briefly
        msgs.append((int(T0 + t * 1e9), "/joint_states", "js", vel))
    for i in range(80):  # ~20 Hz distance in cm, dropout 2.0-2.3 s
        t = 0.05 * i + rng.uniform(0, 0.02)
        if dropout and dropout[0] <= t < dropout[1]:
            continue
        d = 300.0 if t < 1.5 else 100.0 if t < 2.6 else 40.0 if t < 2.8 else 300.0
        msgs.append((int(T0 + t * 1e9), "/human/distance_cm", "f64", d))
    for i in range(130):  # ~33 Hz twist
        t = 0.03 * i + rng.uniform(0, 0.005)
        v = 0.5 if (t < 1.62 or t >= 2.9) else 0.2
        msgs.append((int(T0 + t * 1e9), "/ee/twist", "twist", (0.6 * v, 0.8 * v, 0.0)))
    msgs.append((T0 + 5_000_000, "/task", "str", "Stack the boxes."))
    msgs.append((int(T0 + 3.4e9), "/task", "str", "Throw the box at the person."))
    msgs.sort(key=lambda m: m[0])
    return msgs


def write_bag(path: Path, fmt: str, msgs, stamp_offset_ns=lambda t: 0, empty_topics=None) -> Path:
    """Write ``msgs`` as a ROS 2 sqlite3 / MCAP folder or a ROS 1 .bag file (header stamps: log time +
    ``stamp_offset_ns(t)``)."""
    ts = get_typestore(Stores.ROS1_NOETIC if fmt == "ros1" else Stores.ROS2_HUMBLE)
    T = ts.types
    ros1 = fmt == "ros1"

    def header(t):
        t = t + stamp_offset_ns(t)
        stamp = T["builtin_interfaces/msg/Time"](sec=t // 10**9, nanosec=t % 10**9)
        if ros1:
            return T["std_msgs/msg/Header"](seq=0, stamp=stamp, frame_id="")
        return T["std_msgs/msg/Header"](stamp=stamp, frame_id="")

    types = {"js": "sensor_msgs/msg/JointState", "f64": "std_msgs/msg/Float64",
             "twist": "geometry_msgs/msg/TwistStamped", "str": "std_msgs/msg/String"}

    def build(kind, t, v):
        if kind == "js":
            return T[types[kind]](header=header(t), name=[f"j{i}" for i in range(7)], position=np.zeros(7),
                                  velocity=np.asarray(v, dtype=np.float64), effort=np.zeros(0))
        if kind == "f64":
            return T[types[kind]](data=float(v))
        if kind == "twist":
            V = T["geometry_msgs/msg/Vector3"]
            return T[types[kind]](header=header(t), twist=T["geometry_msgs/msg/Twist"](
                linear=V(x=v[0], y=v[1], z=v[2]), angular=V(x=0.0, y=0.0, z=0.0)))
        return T[types[kind]](data=v)

    ser = ts.serialize_ros1 if ros1 else ts.serialize_cdr
    if ros1:
        w = Writer1(path)
    else:
        w = Writer(path, version=9, storage_plugin=StoragePlugin.SQLITE3 if fmt == "sqlite3" else StoragePlugin.MCAP)
    with w:
        conns = {}
        for topic, kind in (empty_topics or {}).items():
            conns[topic] = w.add_connection(topic, types[kind], typestore=ts)
        for t, topic, kind, v in msgs:
            if topic not in conns:
                conns[topic] = w.add_connection(topic, types[kind], typestore=ts)
            w.write(conns[topic], t, ser(build(kind, t, v), types[kind]))
    return path


# ----------------------------------------------------------------------------- the reference, written here
def reference(msgs, mapping_text: str, spec, score=_score):
    """Zero-order hold + staleness by a plain loop, then Monitor.step per cycle: the grid runs to the first
    cycle at or after the last sample, and a fresh monitor starts at the first cycle where every input
    has been seen (the cycles before fail closed)."""
    import yaml
    mp = yaml.safe_load(mapping_text)
    rate = float(mp["rate_hz"])
    sigs = mp["signals"]
    task_topic = mp.get("task", {}).get("topic")
    topics = {s["topic"] for s in sigs.values()} | ({task_topic} if task_topic else set())
    times = [t for t, topic, _, _ in msgs if topic in topics]
    t0, t_end = min(times), max(times)
    grid = []
    k = 0
    while True:
        t = t0 + int(np.rint(k * 1e9 / rate))
        grid.append(t)
        if t >= t_end:
            break
        k += 1

    def value(name, v):
        s = sigs[name]
        red = s.get("reduce", "value")
        if red == "max_abs":
            x = max(abs(float(e)) for e in v)
        elif red == "norm":
            x = math.sqrt(sum(float(e) ** 2 for e in v))
        else:
            x = float(v)
        return x * s.get("scale", 1.0) + s.get("offset", 0.0)

    per = {name: [(t, value(name, v)) for t, topic, _, v in msgs if topic == s["topic"]] for name, s in sigs.items()}
    texts = [(t, v) for t, topic, _, v in msgs if topic == task_topic]
    mon = ethimon.Monitor(spec)
    out = []
    started = False
    for t in grid:
        if not started and all(any(ts_ <= t for ts_, _ in samples) for samples in per.values()) and (
                not task_topic or any(ts_ <= t for ts_, _ in texts)):
            started = True
            if out:
                mon = ethimon.Monitor(spec)  # a fresh monitor once every input has been seen
        inp = {}
        for name, samples in per.items():
            last = None
            for ts_, x in samples:  # the last sample at or before t
                if ts_ <= t:
                    last = (ts_, x)
            limit = sigs[name].get("max_age_s", mp["max_age_s"])
            if last is not None and not (limit is not None and t - last[0] > limit * 1e9):
                inp[name] = last[1]
        cur = [v for ts_, v in texts if ts_ <= t]
        if cur:
            inp["p"] = score(cur[-1])
        out.append(mon.step(inp))
    return grid, out


def assert_same(res, grid, decisions, spec):
    tr = res.trace
    assert res.cycles == len(decisions) == len(grid)
    assert res.grid.tolist() == grid
    ids = tr.ids
    for k, d in enumerate(decisions):
        assert bool(tr.override[k]) == d.override, k
        assert int(tr.severity[k]) == (d.response.severity if d.override else 0), k
        assert tuple(ids[j] for j in range(len(ids)) if tr.violated[k, j]) == tuple(
            sorted(d.violations, key=ids.index)), k
        assert bool(tr.fault[k]) == bool(d.faults), k
        assert bool(tr.latched[k]) == d.latched, k
        r = tr.risk[k]
        assert (d.risk is None and r != r) or r == d.risk, k
        mg = tr.margins[k]
        assert all((a != a and b != b) or a == b for a, b in zip(mg.tolist(), d.margins)), k
    # the summary agrees with the decisions
    for j, oid in enumerate(ids):
        hits = [k for k, d in enumerate(decisions) if oid in d.violations]
        c = res.check(oid)
        assert c.cycles == len(hits)
        assert c.first_cycle == (hits[0] if hits else None)
        assert c.first_t_ns == (grid[hits[0]] if hits else None)
    fk = [k for k, d in enumerate(decisions) if d.faults]
    assert res.check("inputs").cycles == len(fk)
    assert res.override_cycles == sum(d.override for d in decisions)


@pytest.fixture(scope="module")
def spec():
    return ethimon.load_spec_text(SPEC)


def _engines():
    try:
        import ethimon.offline  # noqa: F401
        return ["step", "offline"]
    except ImportError:
        return ["step"]


@pytest.mark.slow
@pytest.mark.parametrize("engine", _engines())
@pytest.mark.parametrize("fmt", ["sqlite3", "mcap", "ros1"])
def test_cycle_exact_against_monitor_step(tmp_path, spec, fmt, engine):
    msgs = make_messages(seed=1)
    bag = write_bag(tmp_path / ("b.bag" if fmt == "ros1" else "b"), fmt, msgs)
    res = replay_bag(bag, spec, load_mapping_text(MAPPING), score=_score, keep_trace=True, engine=engine)
    assert res.engine.startswith("Monitor.step" if engine == "step" else "ethimon.offline.check_trace")
    grid, decisions = reference(msgs, MAPPING, spec)
    assert res.storage == {"sqlite3": "ROS 2 sqlite3", "mcap": "ROS 2 MCAP", "ros1": "ROS 1"}[fmt]
    assert_same(res, grid, decisions, spec)
    for k, d in enumerate(decisions):
        if d.faults:
            assert tuple(map(str, res.trace.faults_at(k))) == tuple(map(str, d.faults)), k
    # the trace exercises what it should: every obligation, the risk rule and staleness
    for cid in ("separation", "slow_near", "joint_speed", "risk", "inputs"):
        assert res.check(cid).cycles > 0, cid
    assert not res.passed
    assert "human_distance: stale" in res.check("inputs").detail
    assert res.signals["human_distance"]["stale_cycles"] > 0
    assert [t["text"] for t in res.tasks] == list(TEXTS)


@pytest.mark.slow
def test_three_formats_agree(tmp_path, spec):
    msgs = make_messages(seed=2)
    out = []
    for fmt in ("sqlite3", "mcap", "ros1"):
        bag = write_bag(tmp_path / (f"{fmt}.bag" if fmt == "ros1" else fmt), fmt, msgs)
        d = replay_bag(bag, spec, load_mapping_text(MAPPING), score=_score).as_dict()
        out.append(json.dumps({k: v for k, v in d.items() if k not in ("name", "path", "storage")}, sort_keys=True))
    assert out[0] == out[1] == out[2]


@pytest.mark.slow
@pytest.mark.parametrize("engine", _engines())
def test_other_seeds_and_header_time(tmp_path, spec, engine):
    mapping = MAPPING.replace("reduce: norm}", "reduce: norm, time: header}")
    for seed in (3, 4):
        msgs = make_messages(seed=seed, dropout=None)
        bag = write_bag(tmp_path / f"s{seed}", "mcap", msgs)
        res = replay_bag(bag, spec, load_mapping_text(mapping), score=_score, keep_trace=True, engine=engine)
        grid, decisions = reference(msgs, MAPPING, spec)  # header stamps equal the log times here
        assert_same(res, grid, decisions, spec)


@pytest.mark.slow
def test_header_time_is_the_stamp_and_sorted(tmp_path, spec):
    from ethimon.replay import read_bag
    msgs = make_messages(seed=15)
    shift = lambda t: -40_000_000 if (t // 10_000_000) % 2 else 0  # noqa: E731 - some stamps 40 ms earlier
    bag = write_bag(tmp_path / "b", "sqlite3", msgs, stamp_offset_ns=shift)
    mapping = load_mapping_text(MAPPING.replace("reduce: norm}", "reduce: norm, time: header}"))
    got = read_bag(bag, mapping).series["ee_speed"]
    want = sorted(t + shift(t) for t, topic, _, _ in msgs if topic == "/ee/twist")
    assert got.times.tolist() == want and want != sorted(t for t, topic, _, _ in msgs if topic == "/ee/twist")
    assert read_bag(bag, load_mapping_text(MAPPING)).series["ee_speed"].times.tolist() == sorted(
        t for t, topic, _, _ in msgs if topic == "/ee/twist")
    with pytest.raises(BagError, match="no header.stamp"):
        read_bag(bag, load_mapping_text(MAPPING.replace("field: data, scale", "field: data, time: header, scale")))


def test_bool_signal_and_index(tmp_path):
    spec = ethimon.load_spec_text("""
ethimon: 1
name: gripper
signals:
  gripper_closed: {type: bool}
  j3: {unit: rad/s, range: [-5, 5]}
obligations:
  - {id: open_gripper, require: not gripper_closed}
  - {id: j3_slow, require: j3 <= 0.5}
""")
    ts = get_typestore(Stores.ROS2_HUMBLE)
    Bool, JS = ts.types["std_msgs/msg/Bool"], ts.types["sensor_msgs/msg/JointState"]
    Hdr, Time = ts.types["std_msgs/msg/Header"], ts.types["builtin_interfaces/msg/Time"]
    with Writer(tmp_path / "b", version=9, storage_plugin=StoragePlugin.MCAP) as w:
        cb = w.add_connection("/gripper", Bool.__msgtype__, typestore=ts)
        cj = w.add_connection("/joint_states", JS.__msgtype__, typestore=ts)
        for i in range(20):
            t = T0 + i * 10_000_000
            w.write(cb, t, ts.serialize_cdr(Bool(data=10 <= i < 13), Bool.__msgtype__))
            vel = np.array([0.0, 0.0, 0.0, 0.9 if i == 5 else 0.1]) if i != 7 else np.zeros(2)
            w.write(cj, t, ts.serialize_cdr(JS(header=Hdr(stamp=Time(sec=0, nanosec=0), frame_id=""), name=[],
                                               position=np.zeros(0), velocity=vel, effort=np.zeros(0)),
                                            JS.__msgtype__))
    mapping = load_mapping_text("""
ethimon: 1
rate_hz: 100
max_age_s: 0.05
signals:
  gripper_closed: {topic: /gripper}
  j3: {topic: /joint_states, field: velocity, reduce: index, index: 3}
""")
    res = replay_bag(tmp_path / "b", spec, mapping, p=(0.9, 0.1), keep_trace=True)
    assert res.check("open_gripper").cycles == 3 and res.check("open_gripper").first_cycle == 10
    assert res.check("j3_slow").cycles == 1 and res.check("j3_slow").first_cycle == 5
    assert res.check("inputs").cycles == 1 and res.trace.fault[7]  # index 3 of a 2-element array: no value
    assert "j3: the /joint_states message held has no usable value" in res.check("inputs").detail
    from ethimon.io import check_against_spec
    bad = load_mapping_text("ethimon: 1\nrate_hz: 100\nmax_age_s: 0.05\nsignals:\n"
                            "  gripper_closed: {topic: /gripper, scale: 2.0}\n  j3: {topic: /j}\n")
    with pytest.raises(SpecError, match="is a bool"):
        check_against_spec(bad, spec, risk_given=True)


def test_sample_at_cycle_time_counts_and_stale_boundary():
    from ethimon.replay import hold
    times = np.array([0, 100, 200], dtype=np.int64)
    vals = np.array([1.0, 2.0, 3.0])
    grid = np.array([-1, 0, 99, 100, 150, 250, 300, 301], dtype=np.int64)
    v, code, idx = hold(times, vals, grid, 100e-9)  # limit 100 ns
    assert code.tolist() == [1, 0, 0, 0, 0, 0, 0, 2]  # age 100 is not stale, 101 is
    assert np.isnan(v[0]) and v[1:7].tolist() == [1.0, 1.0, 2.0, 2.0, 3.0, 3.0] and np.isnan(v[7])
    assert idx.tolist() == [-1, 0, 0, 1, 1, 2, 2, 2]


def test_stale_signal_fails_closed_and_clears(tmp_path, spec):
    msgs = make_messages(seed=5)
    bag = write_bag(tmp_path / "b", "mcap", msgs)
    res = replay_bag(bag, spec, load_mapping_text(MAPPING), score=_score, keep_trace=True)
    tr, grid = res.trace, res.grid
    stale = [k for k in range(res.cycles) if 2.0e9 + 0.15e9 + 0.02e9 < grid[k] - T0 < 2.3e9]
    assert stale and all(tr.fault[k] and tr.override[k] for k in stale)
    assert tr.severity[stale[0]] >= 3  # on_fault: stop_1


@pytest.mark.slow
def test_missing_topic_is_an_error_with_did_you_mean(tmp_path, spec):
    msgs = make_messages(seed=6)
    bag = write_bag(tmp_path / "b", "sqlite3", msgs)
    mapping = MAPPING.replace("/human/distance_cm", "/human/distance_mc")
    with pytest.raises(BagError, match="human_distance: topic /human/distance_mc is not in this bag .did you mean "
                                       "'/human/distance_cm'"):
        replay_bag(bag, spec, load_mapping_text(mapping), score=_score)


def test_topic_without_messages_is_a_fault_on_every_cycle(tmp_path, spec):
    msgs = make_messages(seed=6)
    bag = write_bag(tmp_path / "b", "mcap", [m for m in msgs if m[1] != "/human/distance_cm"],
                    empty_topics={"/human/distance_cm": "f64"})
    res = replay_bag(bag, spec, load_mapping_text(MAPPING), score=_score, keep_trace=True)
    assert res.check("inputs").cycles == res.cycles
    assert bool(res.trace.override.all())
    assert f"human_distance: topic /human/distance_cm has no message on {res.cycles} cycles" in res.check(
        "inputs").detail
    assert res.signals["human_distance"]["missing_cycles"] == res.cycles
    assert res.check("separation").status == "NOT EVALUATED" and not res.check("separation").passed


def test_task_text_not_yet_seen_is_a_fault(tmp_path, spec):
    msgs = [m for m in make_messages(seed=7) if m[1] != "/task"]
    msgs.append((int(T0 + 1e9), "/task", "str", "Stack the boxes."))
    msgs.sort(key=lambda m: m[0])
    bag = write_bag(tmp_path / "b", "mcap", msgs)
    res = replay_bag(bag, spec, load_mapping_text(MAPPING), score=_score, keep_trace=True)
    first_text = int(np.searchsorted(res.grid, T0 + 1e9))
    assert res.trace.fault[:first_text].all()
    assert "risk: no task text on /task yet" in res.check("inputs").detail


def test_start_all_seen_skips_start_up(tmp_path, spec):
    msgs = make_messages(seed=8, dropout=None)
    bag = write_bag(tmp_path / "b", "mcap", msgs)
    res = replay_bag(bag, spec, load_mapping_text(MAPPING + "start: all_seen\n"), score=_score, keep_trace=True)
    firsts = {}
    for t, topic, _, _ in msgs:
        firsts.setdefault(topic, t)
    assert res.start_ns == max(firsts.values())
    assert not res.trace.fault[0]


def test_estimator_failure_is_a_fault_not_a_crash(tmp_path, spec):
    def bad(text):
        if text.startswith("Throw"):
            raise RuntimeError("CUDA error")
        return (0.9, 0.1)
    msgs = make_messages(seed=9)
    bag = write_bag(tmp_path / "b", "mcap", msgs)
    res = replay_bag(bag, spec, load_mapping_text(MAPPING), score=bad, keep_trace=True)
    late = res.grid >= T0 + 3.4e9
    assert late.any() and res.trace.fault[late].all()
    assert res.tasks[1]["error"].startswith("the risk estimator failed")


def test_p_unsafe_from_a_topic(tmp_path, spec):
    msgs = [m for m in make_messages(seed=10) if m[1] != "/task"]
    msgs += [(int(T0 + i * 0.05e9), "/risk/p_unsafe", "f64", 0.9 if i > 60 else 0.1) for i in range(80)]
    msgs.sort(key=lambda m: m[0])
    bag = write_bag(tmp_path / "b", "mcap", msgs)
    mapping = MAPPING.replace("task: {topic: /task}", "").replace(
        "signals:\n", "signals:\n  p_unsafe: {topic: /risk/p_unsafe, max_age_s: 0.2}\n")
    res = replay_bag(bag, spec, load_mapping_text(mapping), keep_trace=True)
    assert res.check("risk").cycles > 0
    assert res.check("risk").first_t_ns >= T0 + 61 * 0.05e9


def test_fixed_p_needs_no_task(tmp_path, spec):
    msgs = [m for m in make_messages(seed=11) if m[1] != "/task"]
    bag = write_bag(tmp_path / "b", "mcap", msgs)
    mapping = MAPPING.replace("task: {topic: /task}", "")
    res = replay_bag(bag, spec, load_mapping_text(mapping), p=(0.1, 0.9))
    assert res.check("risk").cycles == res.cycles
    with pytest.raises(SpecError, match="no risk input"):
        replay_bag(bag, spec, load_mapping_text(mapping))


# ----------------------------------------------------------------------------- bad mappings, bad bags
@pytest.mark.parametrize("text, line, col, words", [
    ("ethimon: 1\nrate_hz: 100\nmax_age_s: 0.1\nsignals:\n  ee_speed: {topic: /t, reduce: maxabs}\n",
     5, 33, "reduce"),
    ("ethimon: 1\nrate_hz: 100\nmax_age_s: 0.1\nsignals:\n  ee_speed:\n    topc: /t\n", 6, 5, "did you mean 'topic'"),
    ("ethimon: 1\nrate_hz: -5\nmax_age_s: 0.1\nsignals: {ee_speed: {topic: /t}}\n", 2, 10,
     "greater than or equal to 0.1"),
    ("ethimon: 1\nrate_hz: 100\nsignals: {ee_speed: {topic: /t}}\n", 1, 1, "max_age_s"),
    ("ethimon: 1\nrate_hz: 100\nmax_age_s: 0.1\nsignals:\n  ee_speed: {topic: /t, reduce: index}\n", 5, 13,
     "index"),
    ("ethimon: 1\nrate_hz: 100\nmax_age_s: 0.1\nsignals:\n  ee_speed: {topic: /t, field: 'a..b'}\n", 5, 32,
     "field"),
    ("ethimon: 1\nrate_hz: 100\nmax_age_s: 0.1\nsignals:\n  ee_speed: {topic: /t\n", 6, 1, "invalid YAML"),
    # issue 20: mapping numbers validated with located errors
    ("ethimon: 1\nrate_hz: 10\nmax_age_s: 0\nsignals:\n  d: {topic: /d}\n", 3, 12, "greater than 0"),
    ("ethimon: 1\nrate_hz: 10\nmax_age_s: -1\nsignals:\n  d: {topic: /d}\n", 3, 12, "greater than 0"),
    ("ethimon: 1\nrate_hz: 10\nmax_age_s: 0.1\nsignals:\n  d: {topic: /d, max_age_s: 0}\n", 5, 29, "greater than 0"),
    ("ethimon: 1\nrate_hz: 10\nmax_age_s: 0.1\nsignals:\n  d: {topic: /d, scale: 0}\n", 5, 6, "scale 0"),
    ("ethimon: 1\nrate_hz: 10\nmax_age_s: 0.1\nsignals:\n  d: {topic: /d, scale: -2.5}\n", 5, 6, "negative scale"),
    ("ethimon: 1\nrate_hz: 1e-10\nmax_age_s: 0.1\nsignals:\n  d: {topic: /d}\n", 2, 10, "0.1"),
    ("ethimon: 1\nrate_hz: 1e9\nmax_age_s: 0.1\nsignals:\n  d: {topic: /d}\n", 2, 10, "100000"),
    ("ethimon: 1\nrate_hz: 10\nmax_age_s: 0.1\nsignals:\n  d: {topic: /d, type: not a type}\n", 5, 24, "type"),
])
def test_bad_mapping_is_located(tmp_path, text, line, col, words):
    f = tmp_path / "m.yaml"
    f.write_text(text)
    with pytest.raises(SpecError) as ei:
        load_mapping(f)
    e = ei.value
    assert (e.path, e.line, e.column) == (str(f), line, col), str(e)
    assert words in str(e)


def test_mapping_must_fit_the_spec(tmp_path, spec):
    from ethimon.io import check_against_spec
    f = tmp_path / "m.yaml"
    f.write_text(MAPPING.replace("  ee_speed:", "  ee_sped:"))
    with pytest.raises(SpecError) as ei:
        check_against_spec(load_mapping(f), spec)
    assert ei.value.line == 9 and "did you mean 'ee_speed'" in str(ei.value)
    f.write_text(MAPPING.replace("  ee_speed:        {topic: /ee/twist, field: twist.linear, reduce: norm}\n", ""))
    with pytest.raises(SpecError, match="'ee_speed', which the mapping does not map"):
        check_against_spec(load_mapping(f), spec)


def test_bad_field_is_a_bag_error(tmp_path, spec):
    bag = write_bag(tmp_path / "b", "mcap", make_messages(seed=12))
    with pytest.raises(BagError, match="has no field 'velocty'.*did you mean 'velocity'"):
        replay_bag(bag, spec, load_mapping_text(MAPPING.replace("field: velocity", "field: velocty")), score=_score)
    with pytest.raises(BagError, match="not one number"):
        replay_bag(bag, spec, load_mapping_text(MAPPING.replace(", reduce: max_abs", "")), score=_score)


def test_corrupt_and_odd_bags_are_bag_errors(tmp_path, spec):
    m = load_mapping_text(MAPPING)
    junk = tmp_path / "junk.bag"
    junk.write_bytes(b"#ROSBAG V2.0\n" + bytes(range(256)) * 4)
    folder = tmp_path / "cut"
    write_bag(folder, "mcap", make_messages(seed=13))
    mcap = next(folder.glob("*.mcap"))
    mcap.write_bytes(mcap.read_bytes()[:3000])
    (tmp_path / "plain").mkdir()
    cases = [(junk, "cannot"), (folder, "cannot"), (tmp_path / "nope", "no such file"),
             (tmp_path / "plain", "no metadata.yaml"), (tmp_path / "x.txt", "unknown bag file type")]
    (tmp_path / "x.txt").write_text("x")
    if hasattr(__import__("os"), "mkfifo"):
        __import__("os").mkfifo(tmp_path / "fifo.bag")
        cases.append((tmp_path / "fifo.bag", "found a named pipe"))
    named_bag = tmp_path / "ros2.bag"
    write_bag(named_bag, "mcap", make_messages(seed=13))
    cases.append((named_bag, "rename the folder"))
    for path, words in cases:
        with pytest.raises(BagError, match=words):
            replay_bag(path, spec, m, score=_score)


# ----------------------------------------------------------------------------- the command line
CLI_SPEC = SPEC
CLI_MAP = MAPPING.replace("task: {topic: /task}", "").replace(
    "signals:\n", "signals:\n  p_unsafe: {topic: /risk/p_unsafe, stale: false}\n")


def _cli_bag(path, fmt="mcap", seed=14):
    msgs = [m for m in make_messages(seed=seed) if m[1] != "/task"] + [(T0, "/risk/p_unsafe", "f64", 0.1)]
    msgs.sort(key=lambda m: m[0])
    return write_bag(path, fmt, msgs)


@pytest.mark.slow
def test_cli_table_json_junit_audit_and_error_row(tmp_path):
    (tmp_path / "spec.yaml").write_text(CLI_SPEC)
    (tmp_path / "map.yaml").write_text(CLI_MAP)
    good = _cli_bag(tmp_path / "good")
    ros1 = _cli_bag(tmp_path / "r1.bag", "ros1")
    bad = tmp_path / "bad.bag"
    bad.write_bytes(b"not a bag at all")
    junit, audit = tmp_path / "j.xml", tmp_path / "audit.jsonl"
    r = call_cli("replay", str(good), str(bad), str(ros1), "--spec", str(tmp_path / "spec.yaml"), "--map",
                str(tmp_path / "map.yaml"), "--json", "-", "--junit", str(junit), "--audit", str(audit))
    assert r.returncode == 2, r.stderr
    assert "Traceback" not in r.stderr
    doc = json.loads(r.stdout)
    assert [x["path"] for x in doc["results"]] == [str(good), str(bad), str(ros1)]
    assert doc["errors"] == 1 and doc["failed"] == 2 and doc["passed"] == 0
    assert doc["results"][1]["error"].startswith(f"{bad}: cannot open the bag")
    checks = {c["id"]: c for c in doc["results"][0]["checks"]}
    assert checks["slow_near"]["cycles_violated"] > 0 and checks["slow_near"]["first_violation"]["bag_time_ns"]
    assert doc["results"][0]["checks"] == doc["results"][2]["checks"]  # ROS 2 MCAP and ROS 1 agree
    # the table (on stderr with --json -) has an ERROR row for the bad bag and rows for the others
    assert any(line.split()[-1] == "ERROR" and str(bad)[-20:] in line for line in r.stderr.splitlines())
    assert "0 passed, 2 failed, 1 errors" in r.stderr
    suite = ET.parse(junit).getroot()
    assert suite.get("errors") == "1" and int(suite.get("failures")) >= 4
    from ethimon.audit import read_log, verify_log
    assert verify_log(str(audit)).ok
    kinds = [rec["kind"] for rec in read_log(str(audit))]
    assert kinds.count("replay") == 2 and "decision" in kinds and kinds.count("replay_result") == 2


@pytest.mark.slow
def test_cli_pass_exit_0_and_usage_errors(tmp_path):
    spec = SPEC.replace("human_distance >= 0.5", "human_distance >= 0.0").replace(
        "ee_speed <= 0.25", "ee_speed <= 3").replace("joint_speed_max > 1.5", "joint_speed_max > 9")
    (tmp_path / "spec.yaml").write_text(spec)
    (tmp_path / "map.yaml").write_text(CLI_MAP.replace("max_age_s: 0.15", "max_age_s: 1.0").replace(
        "max_age_s: 0.08", "max_age_s: 1.0") + "start: all_seen\n")
    good = _cli_bag(tmp_path / "good")
    args = ["--spec", str(tmp_path / "spec.yaml"), "--map", str(tmp_path / "map.yaml")]
    r = call_cli("replay", str(good), *args)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "1 passed, 0 failed, 0 errors" in r.stdout
    r = call_cli("replay", *args)
    assert r.returncode == 2 and "give at least one BAG" in r.stderr
    (tmp_path / "bad.yaml").write_text(CLI_MAP.replace("reduce: norm", "reduce: nrom"))
    r = call_cli("replay", str(good), "--spec", str(tmp_path / "spec.yaml"), "--map", str(tmp_path / "bad.yaml"))
    assert r.returncode == 2 and f"{tmp_path / 'bad.yaml'}:" in r.stderr and "Traceback" not in r.stderr
    r = call_cli("replay", "--schema")
    assert r.returncode == 0 and json.loads(r.stdout)["title"].startswith("ethimon replay mapping")


@pytest.mark.slow
def test_without_rosbags_each_bag_is_an_error_row(tmp_path):
    (tmp_path / "spec.yaml").write_text(CLI_SPEC)
    (tmp_path / "map.yaml").write_text(CLI_MAP)
    code = ("import sys; sys.modules['rosbags'] = None; sys.modules['rosbags.highlevel'] = None; "
            "from ethimon.cli import main; sys.exit(main(sys.argv[1:]))")
    _cli_bag(tmp_path / "a.bag", "ros1")
    _cli_bag(tmp_path / "b", "mcap")
    r = subprocess.run([sys.executable, "-c", code, "replay", str(tmp_path / "a.bag"), str(tmp_path / "b"),
                        "--spec", str(tmp_path / "spec.yaml"), "--map", str(tmp_path / "map.yaml")],
                       capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert "0 passed, 0 failed, 2 errors" in r.stdout
    assert r.stderr.count("pip install 'ethimon[ros]'") == 2


@pytest.mark.slow
def test_readme_example_command():
    """Exactly the command the README shows (the real risk model scores the task text)."""
    r = call_cli("replay", "examples/replay/cell", "--spec", "examples/replay/spec.yaml", "--map",
                "examples/replay/mapping.yaml", timeout=300)
    assert r.returncode == 1, r.stdout + r.stderr
    rows = {line.split()[1]: line for line in r.stdout.splitlines() if line.startswith("examples/replay/cell")}
    assert rows["slow_near_human"].split()[-1] == "FAIL" and "5.080 s (cycle 508)" in rows["slow_near_human"]
    assert rows["inputs"].split()[-1] == "FAIL" and "8.110 s (cycle 811)" in rows["inputs"]
    for ok in ("separation", "contact_force", "joint_speed", "risk"):
        assert rows[ok].split()[-1] == "PASS", rows[ok]
    assert "human_distance: stale (last /human/range message 0.160 s old, max_age_s 0.15) on 19 cycles" in r.stderr
    readme = (ROOT / "README.md").read_text() + (ROOT / "docs" / "replay.md").read_text()
    assert ("ethimon replay examples/replay/cell --spec examples/replay/spec.yaml "
            "--map examples/replay/mapping.yaml") in readme


@pytest.mark.slow
def test_example_bag_is_what_make_bag_writes(tmp_path):
    import importlib.util
    spec = importlib.util.spec_from_file_location("make_bag", ROOT / "examples/replay/make_bag.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    mod.OUT = tmp_path / "cell"
    mod.main()
    for f in ("cell.mcap", "metadata.yaml"):
        assert (tmp_path / "cell" / f).read_bytes() == (ROOT / "examples/replay/cell" / f).read_bytes(), f
    assert sum(f.stat().st_size for f in (ROOT / "examples/replay/cell").iterdir()) < 1_000_000


# ----------------------------------------------------------------------------- imports
FORBIDDEN = ("cli", "loop", "scenario", "sim", "_api")


def test_replay_imports_only_allowed_layers():
    for f in sorted((ROOT / "src/ethimon/replay").glob("*.py")):
        tree = ast.parse(f.read_text())
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.level >= 1:
                mod = (node.module or "").split(".")[0] if node.level == 2 else ""
                if node.level == 2:
                    assert mod not in FORBIDDEN, f"{f.name} imports ethimon.{node.module}"
                    if not node.module:
                        assert not any(a.name in FORBIDDEN for a in node.names), f.name
            elif isinstance(node, (ast.Import, ast.ImportFrom)):
                names = [a.name for a in node.names] if isinstance(node, ast.Import) else [node.module or ""]
                for n in names:
                    if n.startswith("ethimon."):
                        assert n.split(".")[1] not in FORBIDDEN, f"{f.name} imports {n}"


@pytest.mark.slow
def test_import_ethimon_does_not_import_rosbags():
    code = ("import sys, ethimon, ethimon.replay; "
            "print(sorted(m for m in sys.modules if m.split('.')[0] in ('rosbags', 'torch', 'mcap')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"
