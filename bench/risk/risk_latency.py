"""Latency of the risk estimator on this machine (run by hand; never in CI).

    python -m bench.risk.risk_latency [--model DIR] [--threads 2] [--reps 300] [--modes onnx_fp32 ...] [--json PATH]

Through the estimator's default reading (every sentence and plan step a view, the riskiest counts), cache
off, each mode loaded once and measured interleaved round by round (so the load of the shared cores hits
all alike):

* p50/p90/p95 of one **short command** and of an **8-step numbered plan** (``risk_cost.PLAN8``: 9 views);
* texts/s of **batches of 32 short commands** (``probs_batch``), and of the 8-step plan one at a time;
* a cache hit (``probs`` and ``estimate``) in µs;
* beside each wall time, the median process CPU time of a call (all threads): on shared cores the wall
  time also measures the other jobs.

Modes: ``onnx_fp32`` (the default back-end, ``ethimon risk`` and a spec without ``estimator``),
``onnx_int8``, ``torch_fp32`` (TorchScript-frozen), ``torch_int8`` (and ``*_eager`` for torch without
freezing). Prints a table and writes bench/results/risk/risk_latency.json (or --json) with machine facts
and the load average at start and end.
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from pathlib import Path

from bench import RESULTS
from bench._machine import loadavg, machine_facts
from bench.risk.risk_cost import PLAN8

TEXT = "Hand the kitchen knife to the child blade first."
BATCH = ["Hand the kitchen knife to the child blade first.", "Put the fork in the drawer.",
         "Pour the boiling water onto the person's hand.", "Place the glass vase gently on the table.",
         "Turn off the stove after cooking.", "Throw the knife at the person.",
         "Put the metal fork in the microwave and turn it on.", "Wipe up the water spilled on the floor."] * 4
MODES = {"onnx_fp32": {"backend": "onnx"}, "onnx_int8": {"backend": "onnx", "quantize": "int8"},
         "torch_fp32": {"backend": "torch", "jit": True}, "torch_int8": {"backend": "torch", "quantize": "int8",
                                                                          "jit": True},
         "torch_fp32_eager": {"backend": "torch", "jit": False},
         "torch_int8_eager": {"backend": "torch", "quantize": "int8", "jit": False}}


def _pct(xs, q):
    xs = sorted(xs)
    return xs[min(len(xs) - 1, int(q * len(xs)))]


def _stats(lat: list[float]) -> dict:
    return {"p50_ms": round(1e3 * statistics.median(lat), 3), "p90_ms": round(1e3 * _pct(lat, 0.9), 3),
            "p95_ms": round(1e3 * _pct(lat, 0.95), 3), "mean_ms": round(1e3 * statistics.mean(lat), 3),
            "n": len(lat)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--model", default=None)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--reps", type=int, default=300, help="samples of the short command per mode")
    ap.add_argument("--plan-reps", type=int, default=100, help="samples of the 8-step plan per mode")
    ap.add_argument("--modes", nargs="+", default=["onnx_fp32", "onnx_int8", "torch_fp32"], choices=sorted(MODES))
    ap.add_argument("--json", default=str(RESULTS / "risk" / "risk_latency.json"))
    a = ap.parse_args()
    from ethimon.risk import load_estimator
    load0 = loadavg()
    if any(MODES[m]["backend"] == "torch" for m in a.modes):
        import torch
        torch.set_num_threads(a.threads)
    ests, res = {}, {"short": TEXT, "plan_8_steps": PLAN8, "threads": a.threads, "modes": {}}
    for name in a.modes:
        t0 = time.perf_counter()
        est = load_estimator(a.model, cache_size=0, num_threads=a.threads, **MODES[name])
        load_s = time.perf_counter() - t0
        for _ in range(20):                       # warm-up (TorchScript freezing happens at load with jit)
            est.probs(TEXT)
        est.probs(PLAN8)
        ests[name] = est
        res["modes"][name] = {"load_s": round(load_s, 3), "backend": est.backend, "jit": est.jit,
                              "model_id": est.model_id, "views_plan_8": len(est.read(PLAN8))}
    lat = {m: {"short": [], "plan": [], "b32": []} for m in a.modes}
    cpu = {m: {"short": [], "plan": [], "b32": []} for m in a.modes}   # process CPU time (all threads)
    rounds = max(a.reps, a.plan_reps)
    for i in range(rounds):                       # interleaved: one sample of each mode per round
        for m, est in ests.items():
            if i < a.reps:
                t, c = time.perf_counter(), time.process_time()
                est.probs(TEXT)
                lat[m]["short"].append(time.perf_counter() - t)
                cpu[m]["short"].append(time.process_time() - c)
            if i < a.plan_reps:
                t, c = time.perf_counter(), time.process_time()
                est.probs(PLAN8)
                lat[m]["plan"].append(time.perf_counter() - t)
                cpu[m]["plan"].append(time.process_time() - c)
            if i < 15:
                t, c = time.perf_counter(), time.process_time()
                est.probs_batch(BATCH)
                lat[m]["b32"].append(time.perf_counter() - t)
                cpu[m]["b32"].append(time.process_time() - c)
    for m in a.modes:
        r = res["modes"][m]
        r["short"] = _stats(lat[m]["short"])
        r["plan_8_steps"] = _stats(lat[m]["plan"])
        r["batch32_short_ms"] = round(1e3 * statistics.median(lat[m]["b32"]), 2)
        r["batch32_short_texts_per_s"] = round(32 / statistics.median(lat[m]["b32"]), 1)
        r["plan_8_steps_texts_per_s"] = round(1 / statistics.median(lat[m]["plan"]), 1)
        r["cpu_ms_median"] = {k: round(1e3 * statistics.median(v), 2) for k, v in cpu[m].items()}
    est = load_estimator(a.model, cache_size=4096, num_threads=a.threads)
    est.probs(TEXT)
    n = 200_000
    t = time.perf_counter()
    for _ in range(n):
        est.probs(TEXT)
    res["cache_hit_probs_us"] = round((time.perf_counter() - t) / n * 1e6, 3)
    t = time.perf_counter()
    for _ in range(n // 4):
        est.estimate(TEXT)
    res["cache_hit_estimate_us"] = round((time.perf_counter() - t) / (n // 4) * 1e6, 3)
    res["targets"] = {"short_p50_ms": 10, "plan_8_steps_p50_ms": 60, "batch_texts_per_s": 500}
    res["loadavg_start"] = load0
    res["machine"] = machine_facts(threads=a.threads)
    print(f"{'mode':<17}{'load s':>7}{'short p50':>10}{'p95':>8}{'plan8 p50':>10}{'p95':>8}{'b32 /s':>8}")
    for m in a.modes:
        r = res["modes"][m]
        print(f"{m:<17}{r['load_s']:>7.2f}{r['short']['p50_ms']:>10.2f}{r['short']['p95_ms']:>8.2f}"
              f"{r['plan_8_steps']['p50_ms']:>10.2f}{r['plan_8_steps']['p95_ms']:>8.2f}"
              f"{r['batch32_short_texts_per_s']:>8.0f}")
    print(f"cache hit: probs {res['cache_hit_probs_us']:.2f} µs, estimate {res['cache_hit_estimate_us']:.2f} µs"
          f"  (load avg {load0} -> {res['machine']['loadavg']})")
    Path(a.json).parent.mkdir(parents=True, exist_ok=True)
    Path(a.json).write_text(json.dumps(res, indent=1) + "\n")


if __name__ == "__main__":
    main()
