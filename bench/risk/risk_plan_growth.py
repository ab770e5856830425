"""Before/after in one run: a plan scored as a planner emits it (step 1, steps 1-2, ..., steps 1-8),
an 8-step plan cold, one short command cold and 32 short commands, for two source trees.

    python -m bench.risk.risk_plan_growth --base /tmp/base5/src [--rounds 4] [--json PATH]

``--base``: the ``src`` folder of the code to compare against (e.g. ``git archive base5 src | tar -x``);
the other tree is this checkout's ``src``. Each round runs one child per tree, alternating (so the
load of shared cores hits both alike); a child loads the shipped model (ONNX, 2 threads), warms
up, and times each case a few times. Prints medians, after/before ratios and the load average;
writes bench/results/risk/risk_plan_growth.json (or --json).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

from bench._machine import machine_facts

ROOT = Path(__file__).resolve().parents[2]

CHILD = r"""
import json, statistics, sys, time
from bench.risk.risk_cost import PLAN8
from bench.risk.risk_latency import BATCH, TEXT
from ethimon.risk import load_estimator
cold = load_estimator(cache_size=0, num_threads=2, backend="onnx")
warm = load_estimator(num_threads=2, backend="onnx")
steps = PLAN8.splitlines()
for _ in range(3):
    cold.probs(TEXT); cold.probs(PLAN8)
def t(f, n):
    xs = []
    for _ in range(n):
        a = time.perf_counter(); f(); xs.append(time.perf_counter() - a)
    return statistics.median(xs)
def grow():
    warm.cache_clear()
    for k in range(1, 9):
        warm.probs("\n".join(steps[:k]))
print(json.dumps({"short_ms": 1e3 * t(lambda: cold.probs(TEXT), 20),
                  "plan8_cold_ms": 1e3 * t(lambda: cold.probs(PLAN8), 3),
                  "plan8_grown_step_by_step_ms": 1e3 * t(grow, 3),
                  "batch32_short_texts_per_s": 32 / t(lambda: cold.probs_batch(BATCH), 3)}))
"""


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--base", required=True, help="src folder of the code before")
    ap.add_argument("--rounds", type=int, default=4)
    ap.add_argument("--json", default=str(ROOT / "bench" / "results" / "risk" / "risk_plan_growth.json"))
    a = ap.parse_args()
    trees = {"before": str(Path(a.base).resolve()), "after": str(ROOT / "src")}
    got: dict = {k: [] for k in trees}
    load0 = os.getloadavg()
    for _ in range(a.rounds):
        for name, src in trees.items():
            env = {**os.environ, "PYTHONPATH": os.pathsep.join([src, str(ROOT)])}
            out = subprocess.run([sys.executable, "-c", CHILD], env=env, capture_output=True, text=True,
                                 check=True, cwd=str(ROOT))
            got[name].append(json.loads(out.stdout.strip().splitlines()[-1]))
    res: dict = {"rounds": a.rounds, "loadavg_start": load0, "cases": {}}
    for case in got["before"][0]:
        b = statistics.median(r[case] for r in got["before"])
        f = statistics.median(r[case] for r in got["after"])
        res["cases"][case] = {"before": round(b, 2), "after": round(f, 2), "after_over_before": round(f / b, 3)}
        print(f"{case:<32}{b:>10.2f}{f:>10.2f}{f / b:>8.2f}x")
    res["machine"] = machine_facts(threads=2)
    res["loadavg_end"] = os.getloadavg()
    print(f"load average {load0} -> {res['loadavg_end']}")
    Path(a.json).write_text(json.dumps(res, indent=1) + "\n")


if __name__ == "__main__":
    main()
