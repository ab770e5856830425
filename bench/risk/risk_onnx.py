"""ONNX Runtime backend vs torch, side by side in one run (run by hand; never in CI).

    python -m bench.risk.risk_onnx [--model DIR] [--data CSV] [--reps 300] [--cli-runs 7] [--json PATH]
    python -m bench.risk.risk_onnx --equality-only --json bench/results/risk/risk_onnx_int8_reading31.json

For the shipped model (or ``--model``):

* equality: p_unsafe of every row of ``data/natural_robot/natural_test.csv`` (its ``text`` column
  only: the labels are not read), ONNX fp32 and int8 against torch fp32 (eager); max |Δp|, rows
  over 2e-3, and agreement of the governor's decision R_e ≥ τ and of its three outcomes (execute /
  hold / stop at the shipped τ pair); torch int8 against torch fp32 for comparison; ONNX int8 against
  ONNX fp32 (the default back-end), with every row whose outcome differs;
* latency: p50/p90 of one short command (cache off), 1 and 2 threads, ONNX fp32/int8 and torch
  fp32 (TorchScript-frozen)/int8, interleaved round by round so the load hits all alike;
* throughput: rows/s for batches of 32 short commands, 2 threads;
* one-shot CLI: wall time of ``ethimon risk "…"`` (default backend: ONNX) and of
  ``ethimon risk --backend torch "…"`` against ``python -c "import torch, transformers; from
  transformers import AutoModel"``, alternated run by run; medians and ratios; each child's
  ``sys.modules`` is checked for torch/transformers.

Prints a table and writes bench/results/risk/risk_onnx.json (or --json) with machine facts and the
load at start and end. The one-shot rows carry CPU time (user + system of the child) beside wall
time: on shared cores the wall time mostly measures the other jobs. ``--one-shot-only`` runs that
part alone (risk_onnx_oneshot.json).
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

from bench import RESULTS, ROOT
from bench._machine import loadavg, machine_facts

TEXT = "Hand the kitchen knife to the child blade first."
BATCH = ["Hand the kitchen knife to the child blade first.", "Put the fork in the drawer.",
         "Pour the boiling water onto the person's hand.", "Place the glass vase gently on the table.",
         "Turn off the stove after cooking.", "Throw the knife at the person.",
         "Put the metal fork in the microwave and turn it on.", "Wipe up the water spilled on the floor."] * 4
TOL = 2e-3


def _texts(path: Path) -> list[str]:
    with open(path, newline="", encoding="utf-8") as fh:
        return [row["text"] for row in csv.DictReader(fh)]  # the text column only


def _pct(xs, q):
    xs = sorted(xs)
    return xs[min(len(xs) - 1, int(q * len(xs)))]


def _child_env() -> dict:
    # as a user's shell runs an installed package: bytecode cached, no OMP_NUM_THREADS (numpy's BLAS
    # then starts a thread per core; the first version of the graph build lost 0.8 s to that)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONDONTWRITEBYTECODE", "OMP_NUM_THREADS")}
    env.update(HF_HUB_OFFLINE="1", TRANSFORMERS_OFFLINE="1",
               PYTHONPATH=str(ROOT / "src") + os.pathsep + env.get("PYTHONPATH", ""))
    return env


PROBE = ("import runpy, sys, json, atexit\n"
         "atexit.register(lambda: print(json.dumps({'torch': 'torch' in sys.modules, "
         "'transformers': 'transformers' in sys.modules}), file=sys.stderr))\n"
         "sys.argv = ['ethimon'] + sys.argv[1:]\n"
         "from ethimon.cli import main\n"
         "sys.exit(main())\n")


def _one_shot(cmd: list[str]) -> tuple[float, float, str, str]:
    """Wall time and CPU time (user + system, the child and its threads) of one run."""
    import resource
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    r = subprocess.run(cmd, env=_child_env(), capture_output=True, text=True, timeout=300)
    dt = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if r.returncode not in (0, 1):
        raise RuntimeError(f"{cmd}: exit {r.returncode}: {r.stderr[-500:]}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return dt, cpu, r.stdout, r.stderr


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--model", default=None, help="model directory (default: the shipped model)")
    ap.add_argument("--data", default=str(ROOT / "data" / "natural_robot" / "natural_test.csv"))
    ap.add_argument("--reps", type=int, default=300, help="latency samples per configuration")
    ap.add_argument("--cli-runs", type=int, default=7, help="one-shot runs of each command")
    ap.add_argument("--json", default=None, help="default bench/results/risk/risk_onnx.json "
                    "(risk_onnx_oneshot.json with --one-shot-only)")
    ap.add_argument("--one-shot-only", action="store_true", help="only the one-shot CLI comparison (s)")
    ap.add_argument("--equality-only", action="store_true",
                    help="only the equality and decision agreement (fp32/int8 vs torch, int8 vs ONNX fp32)")
    a = ap.parse_args()
    if a.json is None:
        a.json = str(RESULTS / "risk" / ("risk_onnx_oneshot.json" if a.one_shot_only else "risk_onnx.json"))
    load_start = loadavg()
    from ethimon.risk import DEFAULT_TAU, load_estimator, risk_from_probs
    from ethimon.risk._estimator import DEFAULT_TAU_CONFIRM
    from ethimon.language import DEFAULT_ALPHA, DEFAULT_BETA, DEFAULT_GAMMA

    def r_e(p):
        return risk_from_probs(p, DEFAULT_ALPHA, DEFAULT_BETA, DEFAULT_GAMMA, "sample")

    def decide(p):
        return r_e(p) >= DEFAULT_TAU

    def outcome(p):  # the governor's three outcomes at the shipped pair
        r = r_e(p)
        return "stop" if r >= DEFAULT_TAU else "hold" if r >= DEFAULT_TAU_CONFIRM else "execute"

    res: dict = {"model": a.model or "shipped", "data": str(Path(a.data).relative_to(ROOT))
                 if Path(a.data).is_relative_to(ROOT) else a.data, "tau": DEFAULT_TAU,
                 "tau_confirm": DEFAULT_TAU_CONFIRM, "tolerance": TOL}

    texts, eq, lat = [], {}, {}
    if not a.one_shot_only:
        # ---- equality on every row
        texts = _texts(Path(a.data))
        ref = load_estimator(a.model, cache_size=0, jit=False, backend="torch", num_threads=2)
        t0 = time.perf_counter()
        p_ref = ref.probs_batch(texts)
        res["torch_fp32_rows_s"] = time.perf_counter() - t0
        ref_dec = [decide(p) for p in p_ref]
        ref_out = [outcome(p) for p in p_ref]
        eq, p_all = {}, {}
        for name, kw in {"onnx_fp32": {"backend": "onnx"}, "onnx_int8": {"backend": "onnx", "quantize": "int8"},
                         "torch_int8": {"backend": "torch", "quantize": "int8", "jit": False}}.items():
            est = load_estimator(a.model, cache_size=0, num_threads=2, **kw)
            p = est.probs_batch(texts)
            d = [abs(x[1] - y[1]) for x, y in zip(p, p_ref)]
            agree = sum(decide(x) == r for x, r in zip(p, ref_dec))
            agree3 = sum(outcome(x) == r for x, r in zip(p, ref_out))
            eq[name] = {"rows": len(texts), "max_abs_dp": max(d), "mean_abs_dp": statistics.mean(d),
                        "rows_over_tol": sum(x > TOL for x in d), "decisions_agree": agree,
                        "decision_agreement": agree / len(texts), "outcomes_agree": agree3,
                        "outcome_agreement": agree3 / len(texts), "model_id": est.model_id,
                        "graph_sha256": getattr(est, "graph_sha256", None)}
            p_all[name] = p
            del est
        res["equality_vs_torch_fp32"] = eq
        # int8 against the default back-end (ONNX fp32): what a user switching to int8 changes
        pf, pq = p_all["onnx_fp32"], p_all["onnx_int8"]
        d = [abs(x[1] - y[1]) for x, y in zip(pq, pf)]
        res["onnx_int8_vs_onnx_fp32"] = {
            "rows": len(texts), "max_abs_dp": max(d), "mean_abs_dp": statistics.mean(d),
            "p95_abs_dp": sorted(d)[int(0.95 * (len(d) - 1))],
            "decisions_agree": sum(decide(x) == decide(y) for x, y in zip(pq, pf)),
            "outcomes_agree": sum(outcome(x) == outcome(y) for x, y in zip(pq, pf)),
            "outcomes_differ": [{"row": i, "fp32": outcome(y), "int8": outcome(x), "r_e_fp32": round(r_e(y), 4),
                                 "r_e_int8": round(r_e(x), 4)}
                                for i, (x, y) in enumerate(zip(pq, pf)) if outcome(x) != outcome(y)]}
        v = res["onnx_int8_vs_onnx_fp32"]
        v["decision_agreement"] = v["decisions_agree"] / len(texts)
        v["outcome_agreement"] = v["outcomes_agree"] / len(texts)
        res["flagged_by_torch_fp32"] = sum(ref_dec)
        res["outcomes_by_torch_fp32"] = {k: ref_out.count(k) for k in ("execute", "hold", "stop")}
        del ref
        if a.equality_only:
            import onnxruntime
            res["machine"] = machine_facts(loadavg_start=load_start, onnxruntime=onnxruntime.__version__)
            Path(a.json).parent.mkdir(parents=True, exist_ok=True)
            Path(a.json).write_text(json.dumps(res, indent=2) + "\n")
            print(f"equality on {len(texts)} rows of {res['data']} (tau {DEFAULT_TAU}, tau_confirm {DEFAULT_TAU_CONFIRM}):")
            for n, e in [*eq.items(), ("int8 vs onnx fp32", res["onnx_int8_vs_onnx_fp32"])]:
                print(f"{n:18} max|dp| {e['max_abs_dp']:.2e}  R_e>=tau agree {e['decisions_agree']}/{len(texts)}  "
                      f"three outcomes agree {e['outcomes_agree']}/{len(texts)} ({100 * e['outcome_agreement']:.2f} %)")
            print(f"load average: start {load_start}, end {res['machine']['loadavg']}; wrote {a.json}")
            return

        # ---- latency and throughput, interleaved
        confs = {"onnx_fp32": {"backend": "onnx"}, "onnx_int8": {"backend": "onnx", "quantize": "int8"},
                 "torch_fp32_jit": {"backend": "torch", "jit": True}, "torch_int8_jit": {"backend": "torch",
                                                                                         "quantize": "int8", "jit": True}}
        lat: dict = {}
        import torch
        for threads in (1, 2):
            torch.set_num_threads(threads)
            ests = {n: load_estimator(a.model, cache_size=0, num_threads=threads, **kw) for n, kw in confs.items()}
            samples = {n: [] for n in ests}
            for n, e in ests.items():
                for _ in range(20):
                    e.probs(TEXT)
            for _ in range(a.reps):
                for n, e in ests.items():
                    t = time.perf_counter()
                    e.probs(TEXT)
                    samples[n].append(time.perf_counter() - t)
            bt = {n: [] for n in ests}
            for _ in range(12):
                for n, e in ests.items():
                    t = time.perf_counter()
                    e.probs_batch(BATCH)
                    bt[n].append(time.perf_counter() - t)
            for n in ests:
                lat.setdefault(n, {})[f"threads_{threads}"] = {
                    "p50_ms": 1e3 * statistics.median(samples[n]), "p90_ms": 1e3 * _pct(samples[n], 0.9),
                    "batch32_rows_per_s": 32 / statistics.median(bt[n])}
            del ests
        res["latency"] = lat

    # ---- one-shot CLI vs the import of torch + transformers
    py = sys.executable
    cmds = {"ethimon_risk": [py, "-c", PROBE, "risk", TEXT],
            "ethimon_risk_torch": [py, "-c", PROBE, "risk", "--backend", "torch", TEXT],
            "import_torch_transformers": [py, "-c", "import torch, transformers; from transformers import AutoModel"]}
    if a.model:
        for k in ("ethimon_risk", "ethimon_risk_torch"):
            cmds[k][4:4] = ["--model", a.model]
    for c in cmds.values():  # warm the page cache and the bytecode caches
        _one_shot(c)
    times = {k: [] for k in cmds}
    cpus = {k: [] for k in cmds}
    modules = {}
    for _ in range(a.cli_runs):
        for k, c in cmds.items():
            dt, cpu, out, err = _one_shot(c)
            times[k].append(dt)
            cpus[k].append(cpu)
            if k.startswith("ethimon"):
                modules[k] = json.loads(err.strip().splitlines()[-1])
    med = {k: statistics.median(v) for k, v in times.items()}
    cmed = {k: statistics.median(v) for k, v in cpus.items()}
    base, cbase = med["import_torch_transformers"], cmed["import_torch_transformers"]
    res["one_shot"] = {"runs": a.cli_runs, "median_s": med, "all_s": times, "median_cpu_s": cmed, "all_cpu_s": cpus,
                       "ratio_to_torch_import": {k: med[k] / base for k in med},
                       "cpu_ratio_to_torch_import": {k: cmed[k] / cbase for k in cmed}, "modules_loaded": modules}

    import onnxruntime
    import tokenizers
    res["machine"] = machine_facts(loadavg_start=load_start, onnxruntime=onnxruntime.__version__,
                                   tokenizers=tokenizers.__version__)
    out = Path(a.json)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(res, indent=2) + "\n")

    if a.one_shot_only:
        eq, lat = {}, {}
    else:
        print(f"equality on {len(texts)} rows of {res['data']} (vs torch fp32 eager; tau {DEFAULT_TAU}):")
        print(f"{'':12} {'max|dp|':>9} {'>2e-3':>6} {'decisions agree':>16}")
    for n, e in eq.items():
        print(f"{n:12} {e['max_abs_dp']:9.2e} {e['rows_over_tol']:6d} {e['decisions_agree']:>6d}/{e['rows']} "
              f"({100 * e['decision_agreement']:.2f} %)")
    print(f"\n{'short command':16} {'p50 1t':>8} {'p50 2t':>8} {'p90 2t':>8} {'b32 rows/s 2t':>14}")
    for n, d in lat.items():
        print(f"{n:16} {d['threads_1']['p50_ms']:7.2f}ms {d['threads_2']['p50_ms']:7.2f}ms "
              f"{d['threads_2']['p90_ms']:7.2f}ms {d['threads_2']['batch32_rows_per_s']:14.0f}")
    print(f"\none-shot (median of {a.cli_runs}, alternated; wall and CPU time):")
    for k in cmds:
        print(f"{k:28} {med[k]:6.3f} s {med[k] / base:5.2f}x  cpu {cmed[k]:6.3f} s {cmed[k] / cbase:5.2f}x"
              + (f"  torch in process: {modules[k]['torch']}" if k in modules else ""))
    print(f"\nload average: start {load_start}, end {res['machine']['loadavg']}; wrote {out}")


if __name__ == "__main__":
    main()
