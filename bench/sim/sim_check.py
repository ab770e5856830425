"""`ethimon check scenarios/ --sim`: how long it takes, and proof that a faster run changes nothing.

    python -m bench.sim.sim_check time [--jobs N] [--runs 1] [--base SRC]  # wall + CPU time of the CLI
    python -m bench.sim.sim_check dump OUT.json [PATH...]       # every sim scenario's figures + trace hash
    python -m bench.sim.sim_check diff BEFORE.json AFTER.json   # exit 1 on any difference

``time`` runs the command as a user types it (``-j N`` when given) and records wall time, the
child's CPU time and the load average before and after (the machine may be shared), writing
bench/results/sim/sim_check.json. ``--base SRC`` (another checkout's ``src``, e.g. a ``git
worktree`` of main) runs that code too, alternating with this one run by run, so before and after
are measured in one sitting under the same load. ``dump`` runs every ``sim:`` block serially through
``ethimon.scenario.simulate_paths`` (public API only, so it also runs against an older checkout:
``PYTHONPATH=/other/src``) and stores per scenario its verdict, ``SimResult.summary()`` without
the wall-clock fields, and a SHA-256 of its whole cycle-by-cycle trace. ``diff`` compares two
dumps: equal hashes mean every cycle of every scenario is bit-for-bit the same.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import math
import os
import resource
import subprocess
import sys
import time
from dataclasses import asdict

#: wall-clock fields: they differ from run to run and say nothing about behaviour
_CLOCK = ("wall_time_s", "realtime_factor", "files")


def _clean(v):
    if isinstance(v, float) and not math.isfinite(v):
        return repr(v)
    if isinstance(v, dict):
        return {k: _clean(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_clean(x) for x in v]
    return v


def dump(out: str, paths: list[str]) -> int:
    from ethimon.scenario import simulate_paths
    report = simulate_paths(paths or ["scenarios/sim"])
    rows = {}
    for o in report.outcomes:
        res = o.result
        if res is None:
            rows[o.path] = {"status": o.status, "messages": o.messages}
            continue
        summary = {k: v for k, v in res.summary().items() if k not in _CLOCK}
        trace = json.dumps(_clean([asdict(r) for r in res.trace]), sort_keys=True)
        rows[o.path] = {"status": o.status, "messages": o.messages, "summary": _clean(summary),
                        "trace_sha256": hashlib.sha256(trace.encode()).hexdigest(), "cycles": len(res.trace)}
    with open(out, "w", encoding="utf-8") as f:
        json.dump(rows, f, indent=1, sort_keys=True)
    print(f"{len(rows)} scenarios -> {out} ({report.seconds:.1f} s)")
    return 0


def diff(before: str, after: str) -> int:
    with open(before, encoding="utf-8") as f:
        a = json.load(f)
    with open(after, encoding="utf-8") as f:
        b = json.load(f)
    bad = 0
    for path in sorted(set(a) | set(b)):
        if path not in a or path not in b:
            print(f"{path}: only in {'after' if path not in a else 'before'}")
            continue  # a scenario added meanwhile is not a difference of behaviour
        x, y = a[path], b[path]
        if x == y:
            continue
        bad += 1
        keys = sorted(k for k in set(x.get("summary", {})) | set(y.get("summary", {}))
                      if x.get("summary", {}).get(k) != y.get("summary", {}).get(k))
        print(f"{path}: DIFFERS status {x.get('status')}->{y.get('status')} trace "
              f"{'same' if x.get('trace_sha256') == y.get('trace_sha256') else 'differs'}; fields: {keys}")
    print(f"{len(set(a) & set(b))} scenarios compared, {bad} differ")
    return 1 if bad else 0


def _run_once(cmd: list[str], src: str | None) -> dict:
    env = dict(os.environ)
    if src is not None:
        env["PYTHONPATH"] = os.path.abspath(src)
    load0 = os.getloadavg()[0]
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env)
    wall = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    return {"code": "base" if src is not None else "this", "wall_s": round(wall, 2), "cpu_s": round(cpu, 2),
            "load_start": round(load0, 2), "load_end": round(os.getloadavg()[0], 2), "rc": proc.returncode,
            "summary": proc.stdout.strip().splitlines()[-1] if proc.stdout.strip() else ""}


def timed(jobs: int | None, runs: int, base: str | None = None) -> int:
    from bench import results_dir
    from bench._machine import machine_facts
    cmd = [sys.executable, "-m", "ethimon.cli", "check", "scenarios/", "--sim", "-q"]
    if jobs is not None:
        cmd += ["-j", str(jobs)]
    out = []
    for _ in range(runs):
        for src in ((base, None) if base is not None else (None,)):
            row = _run_once(cmd, src)
            print(json.dumps(row))
            out.append(row)
    dest = os.path.join(results_dir("sim"), "sim_check.json")
    doc = {"command": " ".join(cmd[1:]), "runs": out, "machine": machine_facts()}
    if base is not None:
        doc["base_src"] = base
    with open(dest, "w", encoding="utf-8") as f:
        json.dump(doc, f, indent=1)
    return 0 if all(r["rc"] == 0 for r in out) else 1


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="what", required=True)
    t = sub.add_parser("time")
    t.add_argument("--jobs", "-j", type=int, default=None)
    t.add_argument("--runs", type=int, default=1)
    t.add_argument("--base", default=None, help="another checkout's src/ to time alternately (before vs after)")
    d = sub.add_parser("dump")
    d.add_argument("out")
    d.add_argument("paths", nargs="*")
    f = sub.add_parser("diff")
    f.add_argument("before")
    f.add_argument("after")
    args = ap.parse_args(argv)
    if args.what == "dump":
        return dump(args.out, args.paths)
    if args.what == "diff":
        return diff(args.before, args.after)
    return timed(args.jobs, args.runs, args.base)


if __name__ == "__main__":
    raise SystemExit(main())
