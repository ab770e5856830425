"""µs per Monitor.step for each shipped spec (median and p99 over >= 100k cycles).

Run by hand:  python -m bench.monitor.monitor_step [--cycles 200000] [--json bench/results/monitor/monitor_step.json]
Prints a table and writes JSON with the machine facts. Not a test: timings are never asserted.
"""

from __future__ import annotations

import argparse
import gc
import glob
import json
import os
import random
import sys
import time

import ethimon
from bench import RESULTS
from bench._machine import loadavg, machine_facts


def make_frames(spec, n: int, seed: int = 0) -> list[dict]:
    rng = random.Random(seed)
    frames = []
    for _ in range(n):
        f = {"p_unsafe": rng.choice([0.02, 0.05, 0.1])}
        for name, sig in spec.signals.items():
            if sig.type == "bool":
                f[name] = rng.random() < 0.5
            else:
                lo, hi = sig.range or (0.0, 1.0)
                # mostly safe values: the common case in a control loop
                f[name] = lo + (hi - lo) * (0.3 + 0.1 * rng.random()) if name != "contact_force" else 0.0
        if "human_distance" in f:
            f["human_distance"] = 3.0 + rng.random()
        if "ee_speed" in f:
            f["ee_speed"] = 0.2 * rng.random()
        frames.append(f)
    return frames


def time_steps(monitor, frames, cycles: int) -> list[float]:
    step = monitor.step
    n = len(frames)
    out = [0.0] * cycles
    clock = time.perf_counter_ns
    gc.disable()
    try:
        for i in range(cycles):
            f = frames[i % n]
            t0 = clock()
            step(f)
            out[i] = (clock() - t0) / 1000.0
    finally:
        gc.enable()
    return out


def pct(sorted_vals: list[float], q: float) -> float:
    return sorted_vals[min(len(sorted_vals) - 1, int(q * len(sorted_vals)))]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--cycles", type=int, default=200_000)
    ap.add_argument("--json", default=str(RESULTS / "monitor" / "monitor_step.json"))
    args = ap.parse_args()
    load_start = loadavg()
    rows = []
    for path in sorted(glob.glob("specs/*.yaml")):
        spec = ethimon.load_spec(path)
        frames = make_frames(spec, 1000)
        for margins in (True, False):
            m = ethimon.Monitor(spec, margins=margins)
            time_steps(m, frames, 5000)  # warm-up
            m.reset()
            samples = sorted(time_steps(m, frames, args.cycles))
            # batched: one clock read per 10k steps, so the clock's own cost is not counted
            m.reset()
            step, n = m.step, len(frames)
            t0 = time.perf_counter()
            for i in range(args.cycles):
                step(frames[i % n])
            batched = (time.perf_counter() - t0) / args.cycles * 1e6
            rows.append({"spec": os.path.basename(path), "obligations": len(spec.obligations),
                         "margins": margins, "cycles": args.cycles, "median_us": round(pct(samples, 0.5), 3),
                         "p99_us": round(pct(samples, 0.99), 3), "p999_us": round(pct(samples, 0.999), 3),
                         "mean_us": round(sum(samples) / len(samples), 3),
                         "batched_mean_us": round(batched, 3)})
    print(f"{'spec':<18} {'obl':>4} {'margins':>8} {'median µs':>10} {'p99 µs':>8} {'p99.9 µs':>9} "
          f"{'batched µs':>11}")
    for r in rows:
        print(f"{r['spec']:<18} {r['obligations']:>4} {str(r['margins']):>8} {r['median_us']:>10.2f} "
              f"{r['p99_us']:>8.2f} {r['p999_us']:>9.2f} {r['batched_mean_us']:>11.2f}")
    os.makedirs(os.path.dirname(args.json), exist_ok=True)
    with open(args.json, "w", encoding="utf-8") as fh:
        json.dump({"benchmark": "monitor_step", "machine": machine_facts(loadavg_start=load_start),
                   "results": rows}, fh, indent=2)
    print(f"wrote {args.json}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
