"""Latency of `ethimon ros2` on loopback: a JointState sample published -> the override it causes published.

Run by hand:  python -m bench.monitor.ros2_latency [--samples 10000] [--rate 500] [--interval-ms 8]
              [--json bench/results/monitor/ros2_latency.json]

Two processes on one machine over loopback (Cyclone DDS, unicast, no multicast): this one is the
stand-in robot, the other is ``ethimon ros2`` (the CLI, as a user runs it) stepping a one-rule
spec (``joint_speed_max <= 2 rad/s``; the rule and the fault latch release after one good cycle,
so a missed deadline, which fails closed, does not hide the next samples) at ``--rate`` Hz. The
robot publishes ``sensor_msgs/msg/JointState`` every ``--interval-ms``, alternating a speed
that violates the rule and one that does not, so every sample flips ``/ethimon/override``. For
each sample it records the time it was written; every sample carries a speed of its own
(base + i * 1e-6 rad/s), so the first ``/ethimon/decision`` whose ``joint_speed`` margin is
``w_max - v_i`` is the first decision that used sample i (its override is checked to be the
flipped one), and it reports

* **sample -> override published**: the decision's ``t_unix`` (taken by the node just before it
  publishes) minus the sample's write time (same machine, same clock);
* **sample -> override received**: when the robot's listener got that decision (the round trip
  a robot sees).

Beside them: the monitor's cycle period and the node's own loop statistics (cycles, deadline
misses, max lateness) from its ``--json`` summary. Samples no decision used (lost, or replaced by
the next one before a cycle read them) are counted, not hidden. The machine may be shared: the
load average is recorded at the start and the end.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

from bench import RESULTS, ROOT
from bench._machine import loadavg, machine_facts

SPEC = """
ethimon: 1
name: ros2_latency
signals:
  joint_speed_max: {unit: rad/s, range: [0, 100]}
constants:
  w_max: {value: 2.0, unit: rad/s}
risk: {threshold: 0.5}
on_fault: {response: stop_1, release: {mode: auto, hold_cycles: 1}}
obligations:
  - id: joint_speed
    require: joint_speed_max <= w_max
    response: stop_1
    release: {mode: auto, hold_cycles: 1}
"""

MAPPING = """
ethimon: 1
rate_hz: {rate}
max_age_s: 0.5
signals:
  joint_speed_max: {{topic: /joint_states, type: sensor_msgs/msg/JointState, field: velocity, reduce: max_abs}}
  p_unsafe: {{topic: /bench/p_unsafe, type: std_msgs/msg/Float64, max_age_s: 2.0}}
"""


#: the per-sample offset of the joint speed (rad/s): sample i publishes base + i * STEP
STEP = 1e-6


def pct(xs: list[float], q: float) -> float:
    xs = sorted(xs)
    return xs[min(len(xs) - 1, int(q * len(xs)))] if xs else float("nan")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--samples", type=int, default=10_000, help="JointState samples (each flips the override)")
    ap.add_argument("--rate", type=float, default=500.0, help="the monitor's rate_hz")
    ap.add_argument("--interval-ms", type=float, default=8.0, help="time between samples")
    ap.add_argument("--domain", type=int, default=None, help="DDS domain (default: one from this pid)")
    ap.add_argument("--json", default=str(RESULTS / "monitor" / "ros2_latency.json"))
    args = ap.parse_args()

    from cyclonedds.core import Listener
    from cyclonedds.domain import Domain, DomainParticipant
    from cyclonedds.pub import DataWriter
    from cyclonedds.sub import DataReader
    from cyclonedds.topic import Topic
    from ethimon.ros2 import DEFAULT, MessageTypes, cyclone_config, dds_topic, to_cyclone

    domain = args.domain if args.domain is not None else 17 + os.getpid() % 200
    cfg = cyclone_config(interface="lo", peers=["127.0.0.1"])
    tmp = Path(tempfile.mkdtemp(prefix="ethimon_ros2_lat_"))
    (tmp / "spec.yaml").write_text(SPEC)
    (tmp / "map.yaml").write_text(MAPPING.format(rate=args.rate))
    duration = args.samples * args.interval_ms / 1000.0 + 8.0
    load0 = loadavg()
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"), CYCLONEDDS_URI=cfg)
    node = subprocess.Popen([sys.executable, "-m", "ethimon.cli", "ros2", "--spec", str(tmp / "spec.yaml"),
                             "--map", str(tmp / "map.yaml"), "--domain", str(domain), "--duration-s",
                             f"{duration:.1f}", "--interface", "lo", "--peer", "127.0.0.1", "--json",
                             str(tmp / "node.json"), "-q"], env=env)
    T = MessageTypes()
    dom = Domain(domain, cfg)
    dp = DomainParticipant(domain)
    JS, Hdr, Tm = (T.idl(t) for t in ("sensor_msgs/msg/JointState", "std_msgs/msg/Header",
                                       "builtin_interfaces/msg/Time"))
    F64, Str = T.idl("std_msgs/msg/Float64"), T.idl("std_msgs/msg/String")
    got: list[tuple[float, float, bool, float | None]] = []  # (received monotonic, t_unix, override, margin)
    lock = threading.Lock()

    def on_data(reader):
        now = time.monotonic()
        for s in reader.take(N=256):
            if hasattr(s, "data"):
                d = json.loads(s.data)
                with lock:
                    got.append((now, d["t_unix"], d["override"], d["margins"].get("joint_speed")))

    listener = Listener(on_data_available=on_data)
    reader = DataReader(dp, Topic(dp, dds_topic("/ethimon/decision"), Str), to_cyclone(DEFAULT),  # noqa: F841
                        listener=listener)  # kept: a reader that is garbage-collected leaves the domain
    w_js = DataWriter(dp, Topic(dp, dds_topic("/joint_states"), JS), to_cyclone(DEFAULT))
    w_p = DataWriter(dp, Topic(dp, dds_topic("/bench/p_unsafe"), F64), to_cyclone(DEFAULT))
    t0 = time.monotonic()
    while not (got and w_js.get_matched_subscriptions()):
        if time.monotonic() - t0 > 30 or node.poll() is not None:
            print("the node did not come up", file=sys.stderr)
            node.kill()
            return 1
        time.sleep(0.02)
    names = [f"j{i}" for i in range(7)]

    def js(v: float):
        now = time.time()
        return JS(header=Hdr(stamp=Tm(sec=int(now), nanosec=int((now % 1) * 1e9)), frame_id="base"),
                  name=names, position=[0.0] * 7, velocity=[v] + [0.1] * 6, effort=[])

    # warm up: risk input and a few good samples, until the override is off
    t_w = time.monotonic()
    while time.monotonic() - t_w < 10:
        w_p.write(F64(data=0.05))
        w_js.write(js(0.5))
        time.sleep(0.01)
        with lock:
            if got and got[-1][2] is False and time.monotonic() - t_w > 1.0:
                break
    sent: list[tuple[float, float, bool]] = []  # (write monotonic, write unix, expected override)
    interval = args.interval_ms / 1000.0
    nxt = time.monotonic()
    state = False
    for i in range(args.samples):
        state = not state
        v = (3.5 if state else 0.5) + i * STEP  # a value of its own: the decision's margin names the sample
        if i % 10 == 0:
            w_p.write(F64(data=0.05))
        msg = js(v)
        tm, tu = time.monotonic(), time.time()
        w_js.write(msg)
        sent.append((tm, tu, state))
        nxt += interval
        wait = nxt - time.monotonic()
        if wait > 0:
            time.sleep(wait)
    time.sleep(0.5)
    node.wait(timeout=duration + 30)
    load1 = loadavg()
    with lock:
        dec = list(got)
    # match: the decisions that used sample i are those whose joint_speed margin is w_max - v_i; the
    # first of them, and the first of them whose override is the flipped one (a fast sample overrides
    # in the cycle that reads it; the release after a slow one waits for hold_cycles: 1 good cycle)
    used: dict[int, tuple[float, float]] = {}
    flip: dict[int, tuple[float, float]] = {}
    for rx, tu_d, over, m in dec:
        if m is None or not isinstance(m, float):
            continue
        v = 2.0 - m
        i = round((v - (3.5 if v > 2.0 else 0.5)) / STEP)
        if not 0 <= i < len(sent):
            continue
        used.setdefault(i, (rx, tu_d))
        if over == sent[i][2]:
            flip.setdefault(i, (rx, tu_d))
    use_ms = [(used[i][1] - tu) * 1e3 for i, (tm, tu, want) in enumerate(sent) if i in used]
    pub_ms = [(flip[i][1] - tu) * 1e3 for i, (tm, tu, want) in enumerate(sent) if i in flip]
    rx_ms = [(flip[i][0] - tm) * 1e3 for i, (tm, tu, want) in enumerate(sent) if i in flip]
    on_ms = [(flip[i][1] - tu) * 1e3 for i, (tm, tu, want) in enumerate(sent) if i in flip and want]
    missed = len(sent) - len(used)
    wrong = len(used) - len(flip)
    try:
        node_stats = json.loads((tmp / "node.json").read_text())
    except OSError:
        node_stats = None
    dp.__del__()
    dom.__del__()
    rows = [("sample -> first decision using it, published", use_ms),
            ("sample -> override on published (fast samples)", on_ms),
            ("sample -> override flip published (all)", pub_ms),
            ("sample -> override flip received (round trip)", rx_ms)]
    print(f"ethimon ros2 latency on loopback: {len(sent)} samples every {args.interval_ms:g} ms, monitor at "
          f"{args.rate:g} Hz (cycle {1e3 / args.rate:g} ms); load {load0} -> {load1}")
    print(f"{'measure':44s} {'p50 ms':>8s} {'p90 ms':>8s} {'p99 ms':>8s} {'max ms':>8s} {'n':>7s}")
    for name, xs in rows:
        print(f"{name:44s} {pct(xs, .5):8.3f} {pct(xs, .9):8.3f} {pct(xs, .99):8.3f} "
              f"{max(xs) if xs else float('nan'):8.3f} {len(xs):7d}")
    print(f"samples no decision used (a newer one arrived within the same cycle): {missed}; used but the "
          f"override never flipped before the next sample: {wrong}")
    if node_stats:
        print(f"node: {node_stats['cycles']} cycles, {node_stats['deadline_misses']} deadline misses, "
              f"max late {node_stats['max_late_ms']:.2f} ms")
    doc = {"samples": len(sent), "interval_ms": args.interval_ms, "rate_hz": args.rate,
           "cycle_ms": 1e3 / args.rate, "not_used": missed, "not_flipped": wrong,
           "sample_to_first_decision_published_ms": _summary(use_ms),
           "sample_to_override_on_published_ms": _summary(on_ms),
           "sample_to_override_published_ms": _summary(pub_ms),
           "sample_to_override_received_ms": _summary(rx_ms),
           "node": node_stats, "transport": "Cyclone DDS over loopback, unicast peers, two processes",
           "machine": machine_facts(loadavg_start=load0, cyclonedds=_version("cyclonedds"))}
    Path(args.json).parent.mkdir(parents=True, exist_ok=True)
    Path(args.json).write_text(json.dumps(doc, indent=2) + "\n")
    print(f"wrote {args.json}")
    return 0


def _summary(xs: list[float]) -> dict:
    return {"p50": pct(xs, .5), "p90": pct(xs, .9), "p99": pct(xs, .99), "max": max(xs) if xs else None,
            "n": len(xs)}


def _version(name: str) -> str | None:
    try:
        from importlib.metadata import version
        return version(name)
    except Exception:  # noqa: BLE001
        return None


if __name__ == "__main__":
    sys.exit(main())
