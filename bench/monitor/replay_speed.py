"""Replay speed: ``ethimon replay`` of one bag side by side with rosbags alone reading it (issue 20).

Run by hand:  python -m bench.monitor.replay_speed [--mb 100] [--repeats 3] [--bag PATH --spec S --map M]
              [--json bench/results/monitor/replay_speed.json]

Writes (once, into a temporary folder) a ROS 2 MCAP bag of ``sensor_msgs/JointState`` at
1 kHz (7 named Franka joints, positions, velocities, efforts) of about ``--mb`` MB, then, in
one process and interleaved (A B A B ...), times

* **rosbags alone**: ``AnyReader`` over the mapped topic, every message deserialised (the
  floor: what reading the bag costs, with nothing checked), and
* **ethimon replay**: :func:`ethimon.replay.replay_bag` of the same bag (read, deserialise,
  reduce, resample at 1 kHz, check every cycle with the offline checker),

and reports the ratio of the medians (target: at most 1.5x). Peak memory is measured in a
fresh subprocess per method (``VmHWM``, Linux), on the full bag and on a quarter of it, so that
the growth with the bag (streamed: 16 bytes per sample, not the bag's bytes) is visible.
``--bag/--spec/--map`` time a bag of your own (its mapped topics) instead of the generated one.
Prints a table and writes JSON with the machine facts and the load average at start and end:
the machine may be shared, so read the ratio with the load beside it.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from bench import RESULTS, ROOT
from bench._machine import loadavg, machine_facts

SPEC = """
ethimon: 1
name: replay_speed
signals:
  joint_speed_max: {unit: rad/s, range: [0, 10]}
  j4: {unit: rad, range: [-4, 4]}
obligations:
  - {id: joint_speed, require: joint_speed_max <= 2.0, response: stop_1}
  - {id: j4_limit, require: j4 >= -3.0}
"""
MAPPING = """
ethimon: 1
rate_hz: 1000
max_age_s: 0.01
risk: none
signals:
  joint_speed_max: {topic: /joint_states, field: velocity, reduce: max_abs}
  j4: {topic: /joint_states, field: 'position[panda_joint4]'}
"""
JOINTS = [f"panda_joint{i}" for i in range(1, 8)]


def write_bag(out: Path, mb: float) -> int:
    """A ROS 2 MCAP folder of JointState at 1 kHz of about ``mb`` MB; returns the message count."""
    from rosbags.rosbag2 import StoragePlugin, Writer
    from rosbags.typesys import Stores, get_typestore
    ts = get_typestore(Stores.ROS2_HUMBLE)
    T = ts.types
    JS, Hdr, Time = T["sensor_msgs/msg/JointState"], T["std_msgs/msg/Header"], T["builtin_interfaces/msg/Time"]
    rng = np.random.default_rng(0)
    t0 = 1_700_000_000 * 10**9
    probe = ts.serialize_cdr(JS(header=Hdr(stamp=Time(sec=0, nanosec=0), frame_id="panda_link0"), name=JOINTS,
                                position=np.zeros(7), velocity=np.zeros(7), effort=np.zeros(7)), JS.__msgtype__)
    n = int(mb * 1e6 / (len(probe) + 60))  # + MCAP record and index overhead per message
    with Writer(out, version=9, storage_plugin=StoragePlugin.MCAP) as w:
        c = w.add_connection("/joint_states", JS.__msgtype__, typestore=ts)
        for i in range(n):
            t = t0 + i * 1_000_000
            q = np.sin(i / 1000.0 + np.arange(7)) * 0.5
            v = rng.normal(0.0, 0.3, 7)
            msg = JS(header=Hdr(stamp=Time(sec=t // 10**9, nanosec=t % 10**9), frame_id="panda_link0"), name=JOINTS,
                     position=q, velocity=v, effort=rng.normal(0.0, 1.0, 7))
            w.write(c, t, ts.serialize_cdr(msg, JS.__msgtype__))
    return n


def rosbags_alone(bag: str, topics: set[str]) -> int:
    """Read and deserialise every message of ``topics``: the floor ethimon is compared with."""
    from rosbags.highlevel import AnyReader
    from rosbags.typesys import Stores, get_typestore
    p = Path(bag)
    paths = sorted(p.glob("*.mcap")) if p.is_dir() and any(p.glob("*.mcap")) else [p]
    ros1 = paths[0].suffix == ".bag"
    n = 0
    with AnyReader(paths, default_typestore=get_typestore(Stores.ROS1_NOETIC if ros1 else Stores.ROS2_HUMBLE)) as r:
        conns = [c for c in r.connections if c.topic in topics]
        for conn, _t, raw in r.messages(connections=conns):
            r.deserialize(raw, conn.msgtype)
            n += 1
    return n


def ethimon_replay(bag: str, spec_text: str, map_text: str) -> dict:
    import ethimon
    from ethimon.replay import load_mapping_text, replay_bag
    res = replay_bag(bag, ethimon.load_spec_text(spec_text), load_mapping_text(map_text))
    return {"cycles": res.cycles, "passed": res.passed, "engine": res.engine,
            "judged": {k: v.get("judged") for k, v in res.signals.items()}}


def _peak_rss(method: str, bag: str, spec_text: str, map_text: str, topics: list[str]) -> float:
    """Peak resident memory (MiB) of a fresh process running one method once."""
    # VmHWM (the peak resident set since exec): ru_maxrss would carry the forking parent's peak
    code = ("import json, sys; from bench.monitor import replay_speed as B; a = json.loads(sys.argv[1]); "
            "(B.rosbags_alone(a['bag'], set(a['topics'])) if a['method'] == 'rosbags' else "
            "B.ethimon_replay(a['bag'], a['spec'], a['map'])); "
            "print([ln.split()[1] for ln in open('/proc/self/status') if ln.startswith('VmHWM')][0])")
    arg = json.dumps({"method": method, "bag": bag, "spec": spec_text, "map": map_text, "topics": topics})
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src") + os.pathsep + os.environ.get("PYTHONPATH", ""))
    out = subprocess.run([sys.executable, "-c", code, arg], capture_output=True, text=True, cwd=ROOT, env=env,
                         check=True).stdout
    return int(out.strip().splitlines()[-1]) / 1024.0


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--mb", type=float, default=100.0, help="size of the generated bag (MB)")
    ap.add_argument("--repeats", type=int, default=3, help="interleaved runs of each method")
    ap.add_argument("--bag", help="time this bag instead of a generated one (with --spec and --map)")
    ap.add_argument("--spec", help="spec file for --bag")
    ap.add_argument("--map", dest="mapping", help="mapping file for --bag")
    ap.add_argument("--no-memory", action="store_true", help="skip the peak-memory subprocesses")
    ap.add_argument("--json", default=str(RESULTS / "monitor" / "replay_speed.json"))
    args = ap.parse_args(argv)
    load_start = loadavg()
    from ethimon.replay import load_mapping_text
    with tempfile.TemporaryDirectory() as tmp:
        if args.bag:
            if not (args.spec and args.mapping):
                ap.error("--bag needs --spec and --map")
            bag, spec_text, map_text = args.bag, Path(args.spec).read_text(), Path(args.mapping).read_text()
            n_msgs, quarter = None, None
        else:
            spec_text, map_text = SPEC, MAPPING
            bag = os.path.join(tmp, "js_1khz")
            t = time.perf_counter()
            n_msgs = write_bag(Path(bag), args.mb)
            print(f"wrote {n_msgs:,} JointState messages at 1 kHz in {time.perf_counter() - t:.1f} s")
            quarter = os.path.join(tmp, "js_1khz_quarter")
            write_bag(Path(quarter), args.mb / 4)
        size = sum(f.stat().st_size for f in Path(bag).rglob("*") if f.is_file()) if Path(bag).is_dir() \
            else Path(bag).stat().st_size
        mp = load_mapping_text(map_text)
        topics = sorted({s.topic for s in mp.signals.values()} | ({mp.task.topic} if mp.task else set()))
        times: dict[str, list[float]] = {"rosbags": [], "ethimon": []}
        info = {}
        for _ in range(args.repeats):
            t = time.perf_counter()
            n_read = rosbags_alone(bag, set(topics))
            times["rosbags"].append(time.perf_counter() - t)
            t = time.perf_counter()
            info = ethimon_replay(bag, spec_text, map_text)
            times["ethimon"].append(time.perf_counter() - t)
        med = {k: statistics.median(v) for k, v in times.items()}
        ratio = med["ethimon"] / med["rosbags"]
        mem = {}
        if not args.no_memory:
            mem["full"] = {m: _peak_rss(m, bag, spec_text, map_text, topics) for m in ("rosbags", "ethimon")}
            if quarter:
                mem["quarter"] = {m: _peak_rss(m, quarter, spec_text, map_text, topics) for m in ("rosbags", "ethimon")}
    rows = [("method", "median s", "runs (s)", "messages/s", "peak RSS MiB")]
    for k, label in (("rosbags", "rosbags alone (read + deserialise)"), ("ethimon", "ethimon replay_bag")):
        rss = mem.get("full", {}).get(k)
        rows.append((label, f"{med[k]:.2f}", " ".join(f"{x:.2f}" for x in times[k]), f"{n_read / med[k]:,.0f}",
                     "-" if rss is None else f"{rss:.0f}"))
    widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
    for r in rows:
        print("  ".join(c.ljust(w) for c, w in zip(r, widths)))
    print(f"bag {size / 1e6:.1f} MB, {n_read:,} messages on {', '.join(topics)}; {info.get('cycles', 0):,} cycles; "
          f"ratio ethimon / rosbags = {ratio:.2f}x (target <= 1.5x); load {load_start} -> {loadavg()}")
    if "quarter" in mem:
        print(f"peak RSS, quarter bag: rosbags {mem['quarter']['rosbags']:.0f} MiB, ethimon "
              f"{mem['quarter']['ethimon']:.0f} MiB (growth with 4x the bag: rosbags "
              f"{mem['full']['rosbags'] - mem['quarter']['rosbags']:+.0f} MiB, ethimon "
              f"{mem['full']['ethimon'] - mem['quarter']['ethimon']:+.0f} MiB)")
    doc = {"bag": args.bag or "generated: sensor_msgs/JointState at 1 kHz, ROS 2 MCAP", "bytes": size,
           "messages": n_read, "topics": topics, "cycles": info.get("cycles"), "engine": info.get("engine"),
           "judged": info.get("judged"), "seconds": times, "median_s": med, "ratio": ratio, "target_ratio": 1.5,
           "peak_rss_mib": mem, "loadavg_start": load_start, "spec": spec_text, "mapping": map_text,
           "machine": machine_facts()}
    Path(args.json).parent.mkdir(parents=True, exist_ok=True)
    Path(args.json).write_text(json.dumps(doc, indent=2) + "\n")
    print(f"wrote {args.json}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
