"""One-shot CLI wall times: what a user waits for `ethimon risk "…"` and `ethimon check scenarios/`.

    python -m bench.monitor.cli_oneshot [--runs 3] [--sim]

Each command runs ``--runs`` times in a fresh process (the imports are part of what a user
waits for), interleaved so that a change of load hits every command alike. Per run: wall time,
CPU time of the child (user + sys, from ``resource.getrusage``: close to the wall time a quiet
machine would show, since the one-shot commands are single-threaded) and the 1-minute load
average. Prints a table (median and max per command); writes
bench/results/monitor/cli_oneshot.json with the machine facts.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import statistics
import subprocess
import time

from bench import ROOT, results_dir
from bench._machine import machine_facts

TEXT = "Hand the kitchen knife to the child blade first."


def _run(cmd: list[str]) -> dict:
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    load = os.getloadavg()[0]
    t0 = time.perf_counter()
    p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                       env={**os.environ, "HF_HUB_OFFLINE": "1", "TRANSFORMERS_OFFLINE": "1"})
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if p.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} exited {p.returncode}: {p.stderr[-400:]}")
    return {"wall_s": round(wall, 3), "cpu_s": round(cpu, 3), "load1": round(load, 2)}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--sim", action="store_true", help="also time `ethimon check scenarios/ --sim -q`")
    ap.add_argument("--json", default=None, help="output file (default bench/results/monitor/cli_oneshot.json)")
    a = ap.parse_args()
    exe = shutil.which("ethimon")
    if exe is None:
        raise SystemExit("ethimon is not on PATH: pip install -e '.[all]' in this venv first")
    cmds = {"ethimon risk TEXT": [exe, "risk", TEXT],
            "ethimon check scenarios/": [exe, "check", "scenarios/", "-q"]}
    if a.sim:
        cmds["ethimon check scenarios/ --sim"] = [exe, "check", "scenarios/", "--sim", "-q"]
    runs: dict[str, list[dict]] = {k: [] for k in cmds}
    for _ in range(a.runs):
        for k, c in cmds.items():
            runs[k].append(_run(c))
    print(f"{'command':34} {'wall median':>11} {'wall max':>9} {'cpu median':>10} {'load1':>11}")
    rows = {}
    for k, rs in runs.items():
        w = [r["wall_s"] for r in rs]
        c = [r["cpu_s"] for r in rs]
        ld = [r["load1"] for r in rs]
        rows[k] = {"wall_median_s": statistics.median(w), "wall_max_s": max(w), "cpu_median_s": statistics.median(c),
                   "load1_range": [min(ld), max(ld)], "runs": rs}
        print(f"{k:34} {statistics.median(w):10.2f}s {max(w):8.2f}s {statistics.median(c):9.2f}s "
              f"{min(ld):5.2f}-{max(ld):<5.2f}")
    out = {"what": "one-shot CLI wall and CPU times (fresh process per run)", "text": TEXT, "results": rows,
           "machine": machine_facts()}
    path = a.json or str(results_dir("monitor") / "cli_oneshot.json")
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
