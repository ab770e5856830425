"""Throughput of ``ethimon risk --file`` (the batch path: ``probs_batch`` in chunks) on this machine.

Scores the frozen test slices of writers w13-w21 (540 rows, one text per row, mixed forms) through
the CLI's batch mode in-process, with the shipped model and the default backend, and prints a
table and a JSON object (texts/s, the load average before and after, machine facts).

    python -m bench.risk.risk_batch [--rows N] [--data CSV] [--json bench/results/risk/risk_batch.json]
"""

from __future__ import annotations

import argparse
import contextlib
import csv
import glob
import io
import json
import os
import time
from pathlib import Path

from bench._machine import loadavg, machine_facts

ROOT = Path(__file__).resolve().parents[2]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rows", type=int, default=540, help="rows scored (default: all 540)")
    ap.add_argument("--json", metavar="PATH", help="also write the JSON here")
    ap.add_argument("--data", metavar="CSV", default=None,
                    help="score this CSV's text column instead (e.g. data/natural_robot/natural_test.csv: one-line "
                         "commands)")
    a = ap.parse_args(argv)
    rows: list[str] = []
    files = ([a.data] if a.data else sorted(glob.glob(str(ROOT / "data/writers/w1[3-9]/test.csv")) +
                                           glob.glob(str(ROOT / "data/writers/w2[01]/test.csv"))))
    for f in files:
        with open(f, encoding="utf-8") as fh:
            rows += [r["text"] for r in csv.DictReader(fh)]
    rows = rows[:a.rows]
    tmp = Path(os.environ.get("TMPDIR", "/tmp")) / f"risk_batch_{os.getpid()}.csv"
    with open(tmp, "w", encoding="utf-8", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["id", "text"])
        w.writerows([(i, t) for i, t in enumerate(rows)])
    from ethimon.cli import main as cli
    load0 = loadavg()
    out = io.StringIO()
    t0 = time.perf_counter()
    with contextlib.redirect_stdout(out):
        rc = cli(["risk", "--file", str(tmp), "--column", "text"])
    dt = time.perf_counter() - t0
    tmp.unlink()
    docs = [json.loads(ln) for ln in out.getvalue().splitlines()]
    outcomes = {k: sum(d["outcome"] == k for d in docs) for k in ("execute", "confirm", "stop")}
    res = {"data": a.data or "data/writers/w13-w21/test.csv", "rows": len(rows), "scored": len(docs), "exit": rc, "seconds": round(dt, 2),
           "texts_per_s": round(len(docs) / dt, 1), "outcomes": outcomes, "loadavg_start": load0,
           "note": "wall time includes loading the model (~1-3 s)" + ("" if a.data else "; texts are mixed forms, many "
                   "multi-sentence or plans (several views each), not one-line commands"),
           "machine": machine_facts()}
    print(f"| rows | seconds | texts/s | execute / confirm / stop | load before -> after |")
    print(f"|---|---|---|---|---|")
    print(f"| {len(docs)} | {dt:.1f} | {len(docs) / dt:.1f} | {outcomes['execute']} / {outcomes['confirm']} / "
          f"{outcomes['stop']} | {load0} -> {res['machine'].get('loadavg')} |")
    print(json.dumps(res, indent=1))
    if a.json:
        Path(a.json).write_text(json.dumps(res, indent=1) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
