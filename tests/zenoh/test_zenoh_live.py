"""Issue 33 item 3: the io seam carries a second transport. The monitor live over zenoh (rmw_zenoh's key
expressions, CDR payloads, attachments; a robot in a second zenoh session on loopback) and the replay of its
own recording give the same verdict on every cycle; a stale gap and a future stamp are faults; an
acknowledgement goes round; a foreign writer on /ethimon/override and a second publisher are faults."""

from __future__ import annotations

import json

import pytest

pytestmark = pytest.mark.slow  # two zenoh sessions in this process, over loopback

pytest.importorskip("zenoh")
pytest.importorskip("rosbags")

from ethimon.io import load_mapping_text  # noqa: E402

from tests._estimators import FakeClock  # noqa: E402
from tests.io._drive import MAPPING, replay_of, spec  # noqa: E402
from tests.zenoh._robot import node, recv, unpack_attachment, wait_in  # noqa: E402

TYPES = {"/js": "sensor_msgs/msg/JointState", "/range": "sensor_msgs/msg/Range", "/estop": "std_msgs/msg/Bool",
         "/p": "std_msgs/msg/Float64"}
LIVE = (MAPPING.replace("topic: /js,", "topic: /js, type: sensor_msgs/msg/JointState,")
        .replace("topic: /range,", "topic: /range, type: sensor_msgs/msg/Range,")
        .replace("topic: /estop,", "topic: /estop, type: std_msgs/msg/Bool,")
        .replace("topic: /p,", "topic: /p, type: std_msgs/msg/Float64,")
        + 'ros2: {allow_unauthenticated_acknowledge: "a test on loopback"}\n')


def _feed(robot, k, t, *, dist_stamp=None, skip=()):
    """Cycle ``k``'s messages (every other cycle: 50 Hz at a 100 Hz monitor); how many samples they give."""
    if k % 2:
        return 0
    n = 0
    if "js" not in skip:
        robot.put("/js", TYPES["/js"], robot.msg(TYPES["/js"], position=[0.1 * ((k // 2) % 10), 0.0], stamp=t))
        n += 1
    if "range" not in skip:
        robot.put("/range", TYPES["/range"], robot.msg(TYPES["/range"], range=1.0,
                                                       stamp=t if dist_stamp is None else dist_stamp(t)))
        n += 1
    robot.put("/estop", TYPES["/estop"], robot.msg(TYPES["/estop"], data=False))
    robot.put("/p", TYPES["/p"], robot.msg(TYPES["/p"], data=0.05))
    return n + 2


def _run(cycles=60, range_from=None, **feed_kw):
    """The node stepped ``cycles`` times on a fake 100 Hz clock, the robot's messages in before each cycle
    (``/range`` none from cycle ``range_from`` on); the decisions, the node, the mapping."""
    mapping = load_mapping_text(LIVE, "live.yaml")
    clock = FakeClock(1000.0)
    n, robot = node(spec(), mapping, clock, record=True)
    decisions = []
    try:
        for k in range(cycles):
            clock.t = 1000.0 + k * 0.01
            skip = ("range",) if range_from is not None and k >= range_from else ()
            want = _feed(robot, k, clock.t, skip=skip, **feed_kw)
            assert wait_in(n.channel, want) >= want  # every wait bounded
            decisions.append(n.loop.cycle())
    finally:
        n.close()
        robot.close()
    return decisions, n, mapping


def _same(decisions, n, mapping):
    """Live and the replay of its recording, cycle by cycle from the replay's first judged cycle."""
    res = replay_of(n.live.recording, spec(), mapping)
    assert int(res.grid[0]) == round(1000.0 * 1e9)  # the replay's cycle k is the live cycle k
    tr, ids = res.trace, res.trace.ids
    ks = range(res.started["cycle"], min(len(res.grid), len(decisions)))
    rep = [(bool(tr.override[k]), int(tr.severity[k]), bool(tr.latched[k]), bool(tr.fault[k]),
            frozenset(ids[j] for j in range(len(ids)) if tr.violated[k, j])) for k in ks]
    liv = [(d.override, d.response.severity, d.latched, bool(d.faults), frozenset(d.violations) - {"fault"})
           for d in (decisions[k] for k in ks)]
    assert len(liv) == len(rep) > 20
    bad = [(k, a, b) for k, a, b in zip(ks, liv, rep) if a != b]
    assert not bad, bad[:3]
    return liv, res


def test_live_over_zenoh_and_the_replay_of_its_recording_agree_on_every_cycle():
    decisions, n, mapping = _run()
    liv, res = _same(decisions, n, mapping)
    # positions 0.0 .. 0.9, 0.1 per 20 ms: 5 rad/s > 2.0, the 'slow' rule violated, live as in replay
    assert sum("slow" in v for *_, v in liv) > len(liv) // 2
    assert n.channel.undecodable == 0 and all(t.messages > 20 for t in n.channel.topics)


def test_a_stale_gap_over_zenoh_is_a_fault_and_the_replay_agrees():
    # /range (dist, max_age_s 35.5 ms) stops from cycle 30 on: stale from cycle 32, fail closed
    decisions, n, mapping = _run(cycles=50, range_from=30)
    _same(decisions, n, mapping)
    stale = [d for d in decisions[32:] if any(f.kind == "stale" and "dist" in f.message for f in d.faults)]
    assert len(stale) == len(decisions) - 32 and all(d.override for d in stale)
    assert not any(d.faults for d in decisions[5:30])


def test_a_header_stamp_in_the_future_over_zenoh_is_a_fault_and_the_replay_agrees():
    # /range stamped 30 ms ahead of its arrival from cycle 30 (beyond the 5 ms tolerance)
    decisions, n, mapping = _run(cycles=50, dist_stamp=lambda t: t + 0.03 if t >= 1000.3 - 1e-9 else t)
    _same(decisions, n, mapping)
    future = [d for d in decisions[30:] if any("future" in f.message for f in d.faults)]
    assert len(future) >= 10 and all(d.override for d in future)
    assert not any(d.faults for d in decisions[5:29])
