"""Latency of the risk estimator on this machine (run by hand; never in CI).

    python -m bench.risk.risk_latency [--model DIR] [--threads N] [--reps 300] [--modes onnx_fp32 ...]
                                      [--baseline SRC [--baseline-label TEXT]] [--json PATH]

Through the estimator's default reading (every sentence and plan step a view, the riskiest counts), cache
off, each mode loaded once and measured interleaved round by round (so the load of the shared cores hits
all alike):

* p50/p90/p95 of one **short command** and of an **8-step numbered plan** (``risk_cost.PLAN8``: 9 views);
* texts/s of **batches of 32 short commands** (``probs_batch``), and of the 8-step plan one at a time;
* a cache hit (``probs`` and ``estimate``) in µs;
* beside each wall time, the median process CPU time of a call (all threads): on shared cores the wall
  time also measures the other jobs.

Threads: by default what the product uses (``ethimon.risk.default_threads``: one thread for one text, as
``ethimon risk``, check, replay and the loop's child load it; up to two for the batch, fewer when the cores are
busy); ``--threads N`` pins N for every row. ``views`` counts the views a text is read as (the short
command is one view, the plan 15), ``tokens`` the tokens they run (what the time is proportional to).

``--baseline SRC`` (another tree's ``src/``, e.g. ``git -C /work/main archive 6175f7d src | tar -x -C
/tmp/base``) loads that tree's ``ethimon`` as a second package in the same process and times its estimator
(mode ``baseline_<mode>``) in the same rounds; the JSON then has ``ratios`` (baseline p50 / this p50, > 1:
this tree is faster) and ``agree`` (the largest difference of a probability between the two, which must be
at most 1e-6).

Modes: ``onnx_fp32`` (the default back-end, ``ethimon risk`` and a spec without ``estimator``),
``onnx_int8``, ``torch_fp32`` (TorchScript-frozen), ``torch_int8`` (and ``*_eager`` for torch without
freezing). Prints a table and writes bench/results/risk/risk_latency.json (or --json) with machine facts
and the load average at start and end.
"""

from __future__ import annotations

import argparse
import importlib
import json
import statistics
import time
from pathlib import Path

from bench import RESULTS, load_baseline
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


def _tokens(est, text: str) -> int:
    """Tokens the estimator runs for ``text`` (every window of every view, padding not counted)."""
    from ethimon.risk._estimator import normalize_text
    from ethimon.risk._reading import views
    vs = views(normalize_text(text), est.reading)
    return sum(len(s) for w in est._m.encode([(v.context, v.focus) for v in vs]) for s in w)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--model", default=None)
    ap.add_argument("--threads", type=int, default=None,
                    help="threads of every row (default: the product's rule, default_threads)")
    ap.add_argument("--baseline", default=None, help="a src/ directory of another tree, timed in the same rounds")
    ap.add_argument("--baseline-label", default=None, help="what the baseline is (a commit), for the JSON")
    ap.add_argument("--reps", type=int, default=300, help="samples of the short command per mode")
    ap.add_argument("--plan-reps", type=int, default=100, help="samples of the 8-step plan per mode")
    ap.add_argument("--batch-reps", type=int, default=15, help="samples of the batch of 32 per mode")
    ap.add_argument("--modes", nargs="+", default=["onnx_fp32", "onnx_int8", "torch_fp32"], choices=sorted(MODES))
    ap.add_argument("--json", default=str(RESULTS / "risk" / "risk_latency.json"))
    a = ap.parse_args()
    from ethimon.risk import default_threads, load_estimator
    load0 = loadavg()
    one, batch_threads = (a.threads, a.threads) if a.threads else (default_threads(1), default_threads(len(BATCH)))
    if any(MODES[m]["backend"] == "torch" for m in a.modes):
        import torch
        torch.set_num_threads(one)
    loaders = {"": load_estimator}
    if a.baseline:
        load_baseline(a.baseline)
        loaders["baseline_"] = importlib.import_module("ethimon_baseline.risk").load_estimator
    ests, bests = {}, {}   # per mode: the estimator of one text, and the one of the batch (its threads)
    res = {"short": TEXT, "plan_8_steps": PLAN8, "threads": {"one_text": one, "batch": batch_threads},
           "baseline": {"src": a.baseline, "label": a.baseline_label} if a.baseline else None, "modes": {}}
    for name in a.modes:
        for tag, load in loaders.items():
            t0 = time.perf_counter()
            est = load(a.model, cache_size=0, num_threads=one, **MODES[name])
            load_s = time.perf_counter() - t0
            best = est if batch_threads == one else load(a.model, cache_size=0, num_threads=batch_threads,
                                                         **MODES[name])
            for _ in range(20):                   # warm-up (TorchScript freezing happens at load with jit)
                est.probs(TEXT)
            est.probs(PLAN8)
            best.probs_batch(BATCH)
            ests[tag + name], bests[tag + name] = est, best
            res["modes"][tag + name] = {"load_s": round(load_s, 3), "backend": est.backend, "jit": est.jit,
                                        "model_id": est.model_id, "views_short": len(est.read(TEXT)),
                                        "views_plan_8": len(est.read(PLAN8)), "tokens_short": _tokens(est, TEXT),
                                        "tokens_plan_8": _tokens(est, PLAN8),
                                        "batch32_unique_texts": len(set(BATCH))}
    lat = {m: {"short": [], "plan": [], "b32": []} for m in ests}
    cpu = {m: {"short": [], "plan": [], "b32": []} for m in ests}   # process CPU time (all threads)
    outs: dict = {m: {} for m in ests}
    rounds = max(a.reps, a.plan_reps)
    for i in range(rounds):                       # interleaved: one sample of each mode per round
        for m, est in ests.items():
            if i < a.reps:
                t, c = time.perf_counter(), time.process_time()
                p = est.probs(TEXT)
                lat[m]["short"].append(time.perf_counter() - t)
                cpu[m]["short"].append(time.process_time() - c)
                outs[m]["short"] = p
            if i < a.plan_reps:
                t, c = time.perf_counter(), time.process_time()
                p = est.probs(PLAN8)
                lat[m]["plan"].append(time.perf_counter() - t)
                cpu[m]["plan"].append(time.process_time() - c)
                outs[m]["plan"] = p
            if i < a.batch_reps:
                t, c = time.perf_counter(), time.process_time()
                p = bests[m].probs_batch(BATCH)
                lat[m]["b32"].append(time.perf_counter() - t)
                cpu[m]["b32"].append(time.process_time() - c)
                outs[m]["b32"] = p
    if a.baseline:
        res["ratios"], res["agree"] = {}, {}
        for m in a.modes:
            b = "baseline_" + m
            res["ratios"][m] = {k: round(statistics.median(lat[b][k]) / statistics.median(lat[m][k]), 3)
                                for k in ("short", "plan", "b32")}
            pa = [outs[m]["short"], outs[m]["plan"], *outs[m]["b32"]]
            pb = [outs[b]["short"], outs[b]["plan"], *outs[b]["b32"]]
            res["agree"][m] = {"max_abs_prob_diff": max(abs(x - y) for u, v in zip(pa, pb) for x, y in zip(u, v))}
    for m in ests:
        r = res["modes"][m]
        r["short"] = _stats(lat[m]["short"])
        r["plan_8_steps"] = _stats(lat[m]["plan"])
        r["batch32_short_ms"] = round(1e3 * statistics.median(lat[m]["b32"]), 2)
        r["batch32_short_texts_per_s"] = round(32 / statistics.median(lat[m]["b32"]), 1)
        r["plan_8_steps_texts_per_s"] = round(1 / statistics.median(lat[m]["plan"]), 1)
        r["cpu_ms_median"] = {k: round(1e3 * statistics.median(v), 2) for k, v in cpu[m].items()}
    est = load_estimator(a.model, cache_size=4096, num_threads=one)
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
    res["machine"] = machine_facts(threads=res["threads"])
    print(f"{'mode':<26}{'load s':>7}{'short p50':>10}{'p95':>8}{'plan8 p50':>10}{'p95':>8}{'b32 /s':>8}")
    for m in ests:
        r = res["modes"][m]
        print(f"{m:<26}{r['load_s']:>7.2f}{r['short']['p50_ms']:>10.2f}{r['short']['p95_ms']:>8.2f}"
              f"{r['plan_8_steps']['p50_ms']:>10.2f}{r['plan_8_steps']['p95_ms']:>8.2f}"
              f"{r['batch32_short_texts_per_s']:>8.0f}")
    for m, r in res.get("ratios", {}).items():
        print(f"baseline / this tree, {m}: short {r['short']:.3f}x, plan {r['plan']:.3f}x, batch {r['b32']:.3f}x; "
              f"largest probability difference {res['agree'][m]['max_abs_prob_diff']:.2e}")
    print(f"cache hit: probs {res['cache_hit_probs_us']:.2f} µs, estimate {res['cache_hit_estimate_us']:.2f} µs"
          f"  (load avg {load0} -> {res['machine']['loadavg']})")
    Path(a.json).parent.mkdir(parents=True, exist_ok=True)
    Path(a.json).write_text(json.dumps(res, indent=1) + "\n")


if __name__ == "__main__":
    main()
