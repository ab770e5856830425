"""Offline checking of a recorded trace: cycles per second.

Run by hand:  python -m bench.monitor.trace_check [--cycles 200000] [--trace FILE --spec SPEC]
              [--json bench/results/monitor/trace_check.json]

Without ``--trace`` it records a synthetic cobot_cell trace (a person walking
in and out, contact spikes, clamping, risk changes) as JSONL in a temp dir,
then times: reading and parsing the JSONL, checking it with the compiled
``Monitor`` (margins on and off), and with the ``ReferenceMonitor`` (on a
slice: it re-walks its history). The compiled and reference verdicts on that
slice are compared. Prints a table and writes JSON with the machine facts.
Not a test; the machine may be shared (load average recorded).
"""

from __future__ import annotations

import argparse
import gc
import json
import math
import os
import random
import sys
import tempfile
import time

import ethimon
from ethimon.testing import ReferenceMonitor
from bench import RESULTS
from bench._machine import machine_facts


def synth_trace(n: int, seed: int = 0) -> list[dict]:
    """A cobot_cell trace with incidents every few thousand cycles."""
    rng = random.Random(seed)
    rows = []
    d, v = 3.0, 0.15
    for t in range(n):
        phase = t % 5000
        walk = min(3.5, max(2.5, d + rng.uniform(-0.01, 0.01))) if phase < 1000 or phase >= 1200 else d
        d = walk - 0.025 if 1000 <= phase < 1100 else (walk + 0.025 if 1100 <= phase < 1200 else walk)
        v = max(0.05, min(0.24, v + rng.uniform(-0.005, 0.005)))
        force = 150.0 if phase == 2500 else (80.0 if 3000 <= phase < 3008 else rng.uniform(0, 5))
        rows.append({"t": round(t * 0.001, 3), "human_distance": round(d, 4), "ee_speed": round(v, 4),
                     "contact_force": round(force, 3), "joint_speed_max": round(rng.uniform(0, 1.5), 4),
                     "p_unsafe": 0.7 if 4000 <= phase < 4050 else 0.05})
    return rows


def check(monitor, rows) -> tuple[float, int]:
    step = monitor.step
    gc.disable()
    t0 = time.perf_counter()
    overrides = 0
    for r in rows:
        if step(r).override:
            overrides += 1
    dt = time.perf_counter() - t0
    gc.enable()
    return dt, overrides


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cycles", type=int, default=200_000)
    ap.add_argument("--reference-cycles", type=int, default=2000)
    ap.add_argument("--trace", help="a recorded JSONL trace (one object of inputs per line)")
    ap.add_argument("--spec", default="specs/cobot_cell.yaml")
    ap.add_argument("--json", default=str(RESULTS / "monitor" / "trace_check.json"))
    args = ap.parse_args()
    load_start = os.getloadavg()
    spec = ethimon.load_spec(args.spec)
    tmp = None
    if args.trace:
        path = args.trace
    else:
        tmp = tempfile.mkdtemp()
        path = os.path.join(tmp, "trace.jsonl")
        with open(path, "w", encoding="utf-8") as fh:
            for r in synth_trace(args.cycles):
                fh.write(json.dumps(r) + "\n")
    t0 = time.perf_counter()
    with open(path, encoding="utf-8") as fh:
        rows = [json.loads(line) for line in fh if line.strip()]
    t_parse = time.perf_counter() - t0
    n = len(rows)
    results = {"trace": args.trace or "synthetic cobot_cell", "spec": args.spec, "cycles": n,
               "parse_s": round(t_parse, 4), "parse_cycles_per_s": round(n / t_parse)}
    table = [("read + parse JSONL", n, t_parse, None)]
    for margins in (True, False):
        m = ethimon.Monitor(spec, margins=margins)
        check(m, rows[:2000])
        m.reset()
        dt, ov = check(m, rows)
        key = "monitor" if margins else "monitor_nomargins"
        results[f"{key}_s"] = round(dt, 4)
        results[f"{key}_cycles_per_s"] = round(n / dt)
        results[f"{key}_override_cycles"] = ov
        table.append((f"Monitor (margins={margins})", n, dt, ov))
    k = min(args.reference_cycles, n)
    ref = ReferenceMonitor(spec)
    t0 = time.perf_counter()
    ref_d = [ref.step(r) for r in rows[:k]]
    dt = time.perf_counter() - t0
    m = ethimon.Monitor(spec)
    agree = all(a == b for a, b in zip((m.step(r) for r in rows[:k]), ref_d))
    results.update({"reference_cycles": k, "reference_s": round(dt, 4),
                    "reference_cycles_per_s": round(k / dt), "reference_agrees": agree})
    table.append((f"ReferenceMonitor (first {k})", k, dt, sum(d.override for d in ref_d)))
    t0 = time.perf_counter()
    m = ethimon.Monitor(spec, margins=False)
    with open(path, encoding="utf-8") as fh:
        step, loads = m.step, json.loads
        for line in fh:
            step(loads(line))
    dt = time.perf_counter() - t0
    results["end_to_end_cycles_per_s"] = round(n / dt)
    table.append(("stream: parse + check", n, dt, None))
    print(f"{'stage':<34} {'cycles':>8} {'seconds':>9} {'cycles/s':>11} {'overrides':>10}")
    for name, c, s, ov in table:
        print(f"{name:<34} {c:>8} {s:>9.3f} {c / s if s > 0 else math.inf:>11,.0f} "
              f"{'' if ov is None else ov:>10}")
    print(f"compiled and reference verdicts agree on the slice: {agree}")
    facts = machine_facts()
    facts["loadavg_start"] = load_start
    facts["loadavg_end"] = os.getloadavg()
    facts["note"] = "shared machine (other engineers' tests and a model training may run at the same time)"
    os.makedirs(os.path.dirname(args.json) or ".", exist_ok=True)
    with open(args.json, "w", encoding="utf-8") as fh:
        json.dump({"benchmark": "trace_check", "machine": facts, "results": results}, fh, indent=2)
    print(f"wrote {args.json}")
    if tmp:
        os.remove(path)
        os.rmdir(tmp)
    return 0


if __name__ == "__main__":
    sys.exit(main())
