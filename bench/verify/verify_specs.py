"""How long ``ethimon verify`` takes per spec: every proof and lint, timed.

Usage::

    python -m bench.verify.verify_specs                 # shipped specs, 3 repeats
    python -m bench.verify.verify_specs specs/ tests/verify_fixtures/ --repeat 5

Prints a table (spec, check, result, median seconds) and a per-spec summary,
and writes ``bench/results/verify/verify.json`` with the machine facts.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time

from bench import RESULTS, ROOT
from bench._machine import machine_facts


def machine() -> dict:
    import z3

    return machine_facts(z3=z3.get_version_string())


def main(argv=None) -> int:
    from ethimon.verify import find_specs, verify_spec

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("paths", nargs="*", default=[str(ROOT / "specs")])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--out", default=str(RESULTS / "verify" / "verify.json"))
    args = ap.parse_args(argv)

    rows, specs = [], []
    for path in find_specs(args.paths):
        totals, per = [], {}
        rep = None
        for _ in range(max(1, args.repeat)):
            t0 = time.perf_counter()
            rep = verify_spec(path)
            totals.append(time.perf_counter() - t0)
            for f in rep.findings:
                per.setdefault(f.name, []).append(f.seconds)
        rel = os.path.relpath(path, ROOT)
        for f in rep.findings:
            rows.append({"spec": rel, "check": f.name, "kind": f.kind, "status": f.status,
                         "median_s": statistics.median(per[f.name])})
        props = [f for f in rep.findings if f.kind == "property"]
        specs.append({"spec": rel, "name": rep.name, "error": rep.error, "unroll_cycles": rep.unroll,
                      "obligations": sum(1 for f in props if f.name.endswith(".response")),
                      "proved": sum(f.status == "proved" for f in props),
                      "refuted": sum(f.status == "refuted" for f in props),
                      "lint_warnings": len(rep.warnings),
                      "total_median_s": statistics.median(totals), "total_min_s": min(totals),
                      "total_max_s": max(totals), "repeats": len(totals)})

    w = max(len(r["check"]) for r in rows) if rows else 10
    ws = max(len(r["spec"]) for r in rows) if rows else 10
    print(f"{'spec':<{ws}}  {'check':<{w}}  {'result':<8}  median")
    for r in rows:
        print(f"{r['spec']:<{ws}}  {r['check']:<{w}}  {r['status']:<8}  {r['median_s'] * 1000:8.1f} ms")
    print()
    print(f"{'spec':<{ws}}  unroll  proved  refuted  lint  total (median of {args.repeat})")
    for s in specs:
        print(f"{s['spec']:<{ws}}  {str(s['unroll_cycles']):>6}  {s['proved']:>6}  {s['refuted']:>7}  "
              f"{s['lint_warnings']:>4}  {s['total_median_s']:.3f} s")
    doc = {"bench": "verify_specs", "machine": machine(), "specs": specs, "checks": rows}
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w", encoding="utf-8") as fh:
        json.dump(doc, fh, indent=2)
        fh.write("\n")
    print(f"\nwrote {os.path.relpath(args.out, ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
