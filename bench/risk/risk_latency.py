"""Latency of the risk estimator on this machine (run by hand; never in CI).

    python -m bench.risk.risk_latency [--model DIR] [--threads 2] [--json PATH]

One short sentence, cache off: p50/p90 for fp32 (TorchScript-frozen, the
default), fp32 eager, int8 and int8 eager; a cache hit
(``probs`` and ``estimate``) in µs; batch-32 throughput of short commands.
Prints a table and writes bench/results/risk/risk_latency.json (or --json) with machine facts.
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from pathlib import Path

from bench import RESULTS
from bench._machine import machine_facts

TEXT = "Hand the kitchen knife to the child blade first."
BATCH = ["Hand the kitchen knife to the child blade first.", "Put the fork in the drawer.",
         "Pour the boiling water onto the person's hand.", "Place the glass vase gently on the table.",
         "Turn off the stove after cooking.", "Throw the knife at the person.",
         "Put the metal fork in the microwave and turn it on.", "Wipe up the water spilled on the floor."] * 4


def _pct(xs, q):
    xs = sorted(xs)
    return xs[min(len(xs) - 1, int(q * len(xs)))]


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--model", default=None)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--reps", type=int, default=300)
    ap.add_argument("--json", default=str(RESULTS / "risk" / "risk_latency.json"))
    a = ap.parse_args()
    import torch
    from ethimon.risk import load_estimator
    torch.set_num_threads(a.threads)
    res = {"text": TEXT, "threads": a.threads}
    modes = {"fp32": (None, True), "fp32_eager": (None, False), "int8": ("int8", True),
             "int8_eager": ("int8", False)}
    for name, (mode, jit) in modes.items():
        t0 = time.perf_counter()
        est = load_estimator(a.model, quantize=mode, cache_size=0, jit=jit, backend="torch")
        load_s = time.perf_counter() - t0
        for _ in range(20):
            est.probs(TEXT)
        lat = []
        for _ in range(a.reps):
            t = time.perf_counter()
            est.probs(TEXT)
            lat.append(time.perf_counter() - t)
        for _ in range(3):
            est.probs_batch(BATCH)
        bt = []
        for _ in range(15):
            t = time.perf_counter()
            est.probs_batch(BATCH)
            bt.append(time.perf_counter() - t)
        res[name] = {"load_s": load_s, "jit": est.jit, "p50_ms": 1e3 * statistics.median(lat), "p90_ms": 1e3 * _pct(lat, 0.9),
                     "mean_ms": 1e3 * statistics.mean(lat),
                     "batch32_ms": 1e3 * statistics.median(bt),
                     "batch32_throughput_per_s": 32 / statistics.median(bt), "model_id": est.model_id}
    est = load_estimator(a.model, cache_size=4096, backend="torch")
    est.probs(TEXT)
    n = 200_000
    t = time.perf_counter()
    for _ in range(n):
        est.probs(TEXT)
    hit_probs = (time.perf_counter() - t) / n
    t = time.perf_counter()
    for _ in range(n // 4):
        est.estimate(TEXT)
    hit_est = (time.perf_counter() - t) / (n // 4)
    res["cache_hit_probs_us"] = hit_probs * 1e6
    res["cache_hit_estimate_us"] = hit_est * 1e6
    res["machine"] = machine_facts(threads=torch.get_num_threads())
    print(f"{'mode':<11}{'jit':>4}{'load s':>8}{'p50 ms':>9}{'p90 ms':>9}{'b32 ms':>9}{'rows/s':>9}")
    for m in modes:
        r = res[m]
        print(f"{m:<11}{'y' if r['jit'] else 'n':>4}{r['load_s']:>8.2f}{r['p50_ms']:>9.2f}{r['p90_ms']:>9.2f}{r['batch32_ms']:>9.1f}"
              f"{r['batch32_throughput_per_s']:>9.0f}")
    print(f"cache hit: probs {res['cache_hit_probs_us']:.2f} µs, estimate {res['cache_hit_estimate_us']:.2f} µs"
          f"  (load avg {res['machine']['loadavg']})")
    Path(a.json).parent.mkdir(parents=True, exist_ok=True)
    Path(a.json).write_text(json.dumps(res, indent=1) + "\n")


if __name__ == "__main__":
    main()
