"""Fleet scale: N ROS bags replayed serially vs on a local Ray instance of 1 and 2 workers.

Run by hand:  python -m bench.monitor.fleet_scale [--bags 16] [--duration 30] [--workers 1 2]
              [--repeats 2] [--json bench/results/monitor/fleet_scale.json]

Writes N ROS 2 (MCAP) bags like the example bag (``examples/replay/make_bag.py``'s
person walking in and arm speed; joint states, twist, wrench at 50 Hz, range at
20 Hz), each shifted in time and with a different slow-down delay, plus a
``/risk/p_unsafe`` topic (so no risk model is loaded: the time is reading,
resampling and checking). Then replays all of them against
``examples/replay/spec.yaml``: serially in this process (the loop of ``ethimon
replay``), and with :func:`ethimon.fleet.replay_records` on a fresh local Ray
instance of each worker count (start-up timed apart from the run). Checks that
every Ray run's records equal the serial ones. Prints a table and writes JSON
with the machine facts and the load average at the start and the end; the
machine may be shared, so read the ratios with the load beside them.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import logging
import math
import os
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np

from bench import RESULTS, ROOT
from bench._machine import loadavg, machine_facts

SPEC = ROOT / "examples" / "replay" / "spec.yaml"
MAPPING = """# examples/replay/mapping.yaml, with the risk input from a topic instead of a task text
ethimon: 1
rate_hz: 100
max_age_s: 0.1
signals:
  joint_speed_max: {topic: /joint_states, field: velocity, reduce: max_abs}
  ee_speed:        {topic: /ee/twist, field: twist.linear, reduce: norm}
  contact_force:   {topic: /ee/wrench, field: wrench.force, reduce: norm}
  human_distance:  {topic: /human/range, field: range, max_age_s: 0.15}
  p_unsafe:        {topic: /risk/p_unsafe, stale: false}
"""


def _example():
    """The example bag's writer module (its signal shapes), loaded from its file."""
    spec = importlib.util.spec_from_file_location("make_bag", ROOT / "examples" / "replay" / "make_bag.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def write_bag(out: Path, i: int, duration_s: float) -> None:
    """Bag ``i``: the example's recording stretched to ``duration_s`` (the walk repeats every 10 s),
    starting ``i`` hours later, the arm slowing down ``0.04 * (i % 8)`` s later than in the example."""
    from rosbags.rosbag2 import StoragePlugin, Writer
    from rosbags.typesys import Stores, get_typestore
    ex = _example()
    ts = get_typestore(Stores.ROS2_HUMBLE)
    T = ts.types
    Time, Header = T["builtin_interfaces/msg/Time"], T["std_msgs/msg/Header"]
    Vector3 = T["geometry_msgs/msg/Vector3"]
    t0 = ex.T0 + i * 3600 * 10**9
    lag = 0.04 * (i % 8)

    def header(t_ns: int, frame: str):
        return Header(stamp=Time(sec=t_ns // 10**9, nanosec=t_ns % 10**9), frame_id=frame)

    joints = [f"panda_joint{j}" for j in range(1, 8)]
    with Writer(out, version=9, storage_plugin=StoragePlugin.MCAP) as w:
        c_js = w.add_connection("/joint_states", "sensor_msgs/msg/JointState", typestore=ts)
        c_tw = w.add_connection("/ee/twist", "geometry_msgs/msg/TwistStamped", typestore=ts)
        c_wr = w.add_connection("/ee/wrench", "geometry_msgs/msg/WrenchStamped", typestore=ts)
        c_hr = w.add_connection("/human/range", "sensor_msgs/msg/Range", typestore=ts)
        c_p = w.add_connection("/risk/p_unsafe", "std_msgs/msg/Float64", typestore=ts)
        msgs = [(t0, 0, c_p, T["std_msgs/msg/Float64"](data=0.1))]
        for k in range(int(duration_s * 50) + 1):
            t_ns, t = t0 + k * 20_000_000, k / 50
            vel = np.array([0.5 * math.sin(0.8 * t + j) for j in range(7)])
            msgs.append((t_ns, 1, c_js, T["sensor_msgs/msg/JointState"](
                header=header(t_ns, ""), name=joints, position=np.zeros(7), velocity=vel, effort=np.zeros(7))))
            v = ex.ee_speed(max(0.0, t % 10.0 - lag))
            msgs.append((t_ns, 2, c_tw, T["geometry_msgs/msg/TwistStamped"](
                header=header(t_ns, "panda_hand"), twist=T["geometry_msgs/msg/Twist"](
                    linear=Vector3(x=0.8 * v, y=0.6 * v, z=0.0), angular=Vector3(x=0.0, y=0.0, z=0.1)))))
            msgs.append((t_ns, 3, c_wr, T["geometry_msgs/msg/WrenchStamped"](
                header=header(t_ns, "panda_hand"), wrench=T["geometry_msgs/msg/Wrench"](
                    force=Vector3(x=0.0, y=0.0, z=4.0 + 2.0 * math.sin(3.0 * t)),
                    torque=Vector3(x=0.0, y=0.0, z=0.0)))))
        for k in range(int(duration_s * 20) + 1):
            t_ns, t = t0 + k * 50_000_000, k / 20
            msgs.append((t_ns, 4, c_hr, T["sensor_msgs/msg/Range"](
                header=header(t_ns, "lidar"), radiation_type=1, field_of_view=3.1, min_range=0.05,
                max_range=10.0, range=ex.human_distance(t % 10.0))))
        for t_ns, _, conn, msg in sorted(msgs, key=lambda m: (m[0], m[1])):
            w.write(conn, t_ns, ts.serialize_cdr(msg, conn.msgtype))


def serial(bags: list[str], spec, mapping) -> tuple[float, list[dict]]:
    """The loop of ``ethimon replay`` without ``--ray``."""
    from ethimon.replay import TaskScorer
    from ethimon.replay._record import bag_record
    t = time.perf_counter()
    scorer = TaskScorer(spec)
    recs = [bag_record(b, spec, mapping, score=scorer) for b in bags]
    return time.perf_counter() - t, recs


def on_ray(bags: list[str], spec_path: str, map_path: str, workers: int) -> tuple[float, float, list[dict]]:
    """(start-up s, run s, records) on a fresh local Ray instance of ``workers`` CPUs."""
    import ray

    from ethimon.fleet import replay_records
    t = time.perf_counter()
    ray.init(num_cpus=workers, include_dashboard=False, logging_level=logging.ERROR, log_to_driver=False)
    startup = time.perf_counter() - t
    try:
        t = time.perf_counter()
        recs = replay_records(bags, spec=spec_path, mapping=map_path)
        run = time.perf_counter() - t
    finally:
        ray.shutdown()
    return startup, run, recs


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bags", type=int, default=16, help="number of bags (default 16)")
    ap.add_argument("--duration", type=float, default=30.0, help="seconds per bag (default 30: 3000 cycles)")
    ap.add_argument("--workers", type=int, nargs="+", default=[1, 2], help="Ray worker counts (default 1 2)")
    ap.add_argument("--repeats", type=int, default=2, help="runs per configuration; the median is reported")
    ap.add_argument("--json", default=str(RESULTS / "monitor" / "fleet_scale.json"))
    args = ap.parse_args()

    import ethimon
    from ethimon.io import check_against_spec, load_mapping
    load_start = loadavg()
    with tempfile.TemporaryDirectory() as tmp:
        map_path = os.path.join(tmp, "mapping.yaml")
        Path(map_path).write_text(MAPPING)
        t = time.perf_counter()
        bags = []
        for i in range(args.bags):
            write_bag(Path(tmp) / f"bag{i:03d}", i, args.duration)
            bags.append(os.path.join(tmp, f"bag{i:03d}"))
        write_s = time.perf_counter() - t
        size = sum(f.stat().st_size for b in bags for f in Path(b).iterdir())
        spec = ethimon.load_spec(str(SPEC))
        mapping = load_mapping(map_path)
        check_against_spec(mapping, spec)
        serial(bags[:1], spec, mapping)  # warm-up: imports, the offline checker's first call
        runs: dict[str, dict] = {}
        times = []
        for _ in range(args.repeats):
            dt, ref = serial(bags, spec, mapping)
            times.append(dt)
        runs["serial"] = {"workers": 1, "run_s": statistics.median(times), "runs_s": times, "startup_s": 0.0}
        for w in args.workers:
            times, starts = [], []
            for _ in range(args.repeats):
                st, dt, recs = on_ray(bags, str(SPEC), map_path, w)
                times.append(dt)
                starts.append(st)
                if recs != json.loads(json.dumps(ref)):
                    raise SystemExit(f"Ray with {w} workers gave other records than the serial run")
            runs[f"ray_{w}"] = {"workers": w, "run_s": statistics.median(times), "runs_s": times,
                                "startup_s": statistics.median(starts), "startups_s": starts}
    failed = sum(1 for r in ref if not r.get("passed"))
    base = runs["serial"]["run_s"]
    print(f"{args.bags} bags x {args.duration:g} s ({int(args.duration * 100)} cycles each, "
          f"{size / 2**20:.1f} MiB in all; written in {write_s:.1f} s); {failed} bags with a violation or fault; "
          f"load at start {load_start}")
    print(f"{'run':10} {'workers':>7} {'run s':>8} {'bags/s':>8} {'speed-up':>9} {'Ray start s':>12}")
    for name, r in runs.items():
        r["bags_per_s"] = args.bags / r["run_s"]
        r["speedup_vs_serial"] = base / r["run_s"]
        print(f"{name:10} {r['workers']:7d} {r['run_s']:8.2f} {r['bags_per_s']:8.2f} "
              f"{r['speedup_vs_serial']:8.2f}x {r['startup_s']:12.1f}")
    import ray
    doc = {"what": "ethimon replay of N bags: serial vs ethimon.fleet.replay_records on a local Ray instance",
           "bags": args.bags, "duration_s": args.duration, "cycles_per_bag": int(args.duration * 100),
           "bytes": size, "repeats": args.repeats, "records_equal_serial": True, "bags_failed": failed,
           "runs": runs, "machine": machine_facts(ray=ray.__version__, loadavg_start=load_start)}
    Path(args.json).parent.mkdir(parents=True, exist_ok=True)
    Path(args.json).write_text(json.dumps(doc, indent=2) + "\n")
    print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
