"""µs per Monitor.step by spec size (1/4/16/64 obligations) and temporal window (10/100/1000 cycles).

Run by hand:  python -m bench.monitor.monitor_scaling [--cycles 20000] [--json bench/results/monitor/monitor_scaling.json]

Specs are generated: 8 signals, obligations cycling through five shapes (plain
bound, held(...), once(...), since(...), bounded response within_cycles), every
temporal bound equal to the window. The cost per step must not grow with the
window (O(1) counters, no buffers scanned). Prints a table and writes JSON with
the machine facts. Not a test: timings are never asserted. The machine may be
shared; the load average at start and end is recorded.
"""

from __future__ import annotations

import argparse
import gc
import json
import os
import random
import sys
import time

import ethimon
from bench import RESULTS
from bench._machine import machine_facts
from bench.monitor.monitor_step import pct, time_steps

N_SIGNALS = 8


def make_spec_text(n_obligations: int, window: int) -> str:
    """A spec with ``n_obligations`` generated obligations, every temporal bound ``window``."""
    lines = ["ethimon: 1", f"name: gen_{n_obligations}_{window}", "signals:"]
    for i in range(N_SIGNALS):
        lines.append(f"  s{i}: {{unit: m, range: [0, 10]}}")
    lines += ["risk: {threshold: 0.5}", "on_fault: stop_1", "obligations:"]
    for k in range(n_obligations):
        a, b, c = f"s{k % N_SIGNALS}", f"s{(k + 3) % N_SIGNALS}", f"s{(k + 5) % N_SIGNALS}"
        shape = k % 5
        if shape == 0:
            ob = f'{{id: o{k}, require: "{a} <= 9.9 and {b} >= 0.01"}}'
        elif shape == 1:
            ob = f'{{id: o{k}, require: "not held({a} > 9.5, {window})"}}'
        elif shape == 2:
            ob = f'{{id: o{k}, when: "once({a} < 0.05, {window})", require: "{b} <= 9.8"}}'
        elif shape == 3:
            ob = f'{{id: o{k}, require: "not since({a} > 9.0, {b} > 9.9, {window})"}}'
        else:
            ob = f'{{id: o{k}, when: "{a} > 9.7", require: "{c} <= 9.0", within_cycles: {window}}}'
        lines.append(f"  - {ob}")
    return "\n".join(lines) + "\n"


def make_frames(n: int, seed: int = 0) -> list[dict]:
    """Mostly safe values that still make the temporal conditions flip now and then."""
    rng = random.Random(seed)
    frames = []
    for _ in range(n):
        f = {"p_unsafe": 0.05}
        for i in range(N_SIGNALS):
            u = rng.random()
            # 2 %: above 9.5 (held/since operands flip), 1 %: below 0.05 (once triggers); no violation
            f[f"s{i}"] = 9.6 if u < 0.02 else (0.03 if u < 0.03 else 1.0 + 8.0 * rng.random())
        frames.append(f)
    return frames


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cycles", type=int, default=20_000)
    ap.add_argument("--sizes", default="1,4,16,64")
    ap.add_argument("--windows", default="10,100,1000")
    ap.add_argument("--json", default=str(RESULTS / "monitor" / "monitor_scaling.json"))
    args = ap.parse_args()
    sizes = [int(x) for x in args.sizes.split(",")]
    windows = [int(x) for x in args.windows.split(",")]
    load_start = os.getloadavg()
    frames = make_frames(2000)
    rows = []
    for n in sizes:
        for w in windows:
            spec = ethimon.load_spec_text(make_spec_text(n, w))
            row = {"obligations": n, "window": w, "cycles": args.cycles}
            for margins in (True, False):
                m = ethimon.Monitor(spec, margins=margins)
                time_steps(m, frames, 2000)  # warm-up
                m.reset()
                samples = sorted(time_steps(m, frames, args.cycles))
                m.reset()
                step, k = m.step, len(frames)
                gc.disable()
                t0 = time.perf_counter()
                for i in range(args.cycles):
                    step(frames[i % k])
                batched = (time.perf_counter() - t0) / args.cycles * 1e6
                gc.enable()
                tag = "" if margins else "_nomargins"
                row[f"median_us{tag}"] = round(pct(samples, 0.5), 3)
                row[f"p99_us{tag}"] = round(pct(samples, 0.99), 3)
                row[f"batched_mean_us{tag}"] = round(batched, 3)
                if margins:
                    overrides = sum(1 for i in range(2000) if m.step(frames[i % k]).override)
                    row["override_fraction"] = round(overrides / 2000, 3)
            rows.append(row)
            print(f"  {n:>3} obligations, window {w:>5}: median {row['median_us']:.2f} µs", file=sys.stderr)
    load_end = os.getloadavg()
    print(f"{'obl':>4} {'window':>7} {'median µs':>10} {'p99 µs':>8} {'batched µs':>11} "
          f"{'no-margins median':>18} {'p99':>7} {'override %':>11}")
    for r in rows:
        print(f"{r['obligations']:>4} {r['window']:>7} {r['median_us']:>10.2f} {r['p99_us']:>8.2f} "
              f"{r['batched_mean_us']:>11.2f} {r['median_us_nomargins']:>18.2f} {r['p99_us_nomargins']:>7.2f} "
              f"{100 * r['override_fraction']:>10.1f}%")
    # growth with the window at the largest size: ratio of medians window_max / window_min
    growth = {}
    for n in sizes:
        by_w = {r["window"]: r["median_us"] for r in rows if r["obligations"] == n}
        growth[str(n)] = round(by_w[max(windows)] / by_w[min(windows)], 3)
    print("median(window max) / median(window min) by size:", growth)
    facts = machine_facts()
    facts["loadavg_start"] = load_start
    facts["loadavg_end"] = load_end
    facts["note"] = "shared machine (other engineers' tests and a model training may run at the same time)"
    os.makedirs(os.path.dirname(args.json) or ".", exist_ok=True)
    with open(args.json, "w", encoding="utf-8") as fh:
        json.dump({"benchmark": "monitor_scaling", "machine": facts, "window_growth_ratio": growth,
                   "results": rows}, fh, indent=2)
    print(f"wrote {args.json}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
