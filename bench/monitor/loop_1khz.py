"""A 1 kHz GovernedLoop for 60 s with a 20 Hz estimator: deadline misses, stale overrides, CPU.

Run by hand:  python -m bench.monitor.loop_1khz [--duration 60] [--rate 1000] [--estimator-hz 20]
              [--latency-ms 8] [--max-age-ms 150] [--deadline-ms 1] [--audit-every-cycle]
              [--real-estimator]
              [--json bench/results/monitor/loop_1khz.json]

The fake estimator sleeps ``--latency-ms`` per call (like a forward pass that
releases the GIL) and returns fixed probabilities; ``--real-estimator`` uses
``ethimon.risk.load_estimator()`` instead (needs ethimon[risk]). The loop
steps ``specs/cobot_cell.yaml`` with safe synthetic signals, so every override
counted here is a fault (missed deadline, stale or missing estimate), not a
rule violation. State changes go to an audit log in a temp dir (verified at
the end). Prints a table and writes JSON with the machine facts. The machine
may be shared: load average and this process's CPU time are recorded.
"""

from __future__ import annotations

import argparse
import json
import os
import random
import resource
import sys
import tempfile
import time

import ethimon
from bench import RESULTS
from bench._machine import machine_facts
from ethimon.audit import AuditLog, verify_log
from ethimon.loop import AsyncRiskSource, GovernedLoop, LoopConfig


class SleepyEstimator:
    """Deterministic stand-in: sleeps like an inference, returns fixed probabilities."""

    model_id = "fake-sleepy@bench"

    def __init__(self, latency_s: float, probs=(0.95, 0.05)) -> None:
        self.latency_s = latency_s
        self.p = probs
        self.calls = 0

    def probs(self, text: str):
        self.calls += 1
        time.sleep(self.latency_s)
        return self.p


def pct(xs: list[float], q: float) -> float:
    xs = sorted(xs)
    return xs[min(len(xs) - 1, int(q * len(xs)))] if xs else float("nan")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--duration", type=float, default=60.0, help="seconds (default 60)")
    ap.add_argument("--rate", type=float, default=1000.0, help="control rate, Hz")
    ap.add_argument("--estimator-hz", type=float, default=20.0)
    ap.add_argument("--latency-ms", type=float, default=8.0, help="fake inference time per call")
    ap.add_argument("--max-age-ms", type=float, default=150.0, help="oldest usable estimate")
    ap.add_argument("--deadline-ms", type=float, default=None, help="decision deadline (default: one period)")
    ap.add_argument("--audit-every-cycle", action="store_true")
    ap.add_argument("--real-estimator", action="store_true")
    ap.add_argument("--spec", default="specs/cobot_cell.yaml")
    ap.add_argument("--json", default=str(RESULTS / "monitor" / "loop_1khz.json"))
    args = ap.parse_args()

    spec = ethimon.load_spec(args.spec)
    if args.real_estimator:
        from ethimon.risk import load_estimator
        est = load_estimator(num_threads=1)
    else:
        est = SleepyEstimator(args.latency_ms / 1000.0)
    src = AsyncRiskSource(est, text="Wipe the table next to the person.", rate_hz=args.estimator_hz)
    t_wait = time.monotonic()
    while src.fault is not None and time.monotonic() - t_wait < 60:
        time.sleep(0.005)

    rng = random.Random(0)
    frames = [{"human_distance": 3.0 + rng.random(), "ee_speed": 0.1 + 0.1 * rng.random(),
               "contact_force": 5.0 * rng.random(), "joint_speed_max": rng.random()} for _ in range(1000)]
    idx = [0]

    def signals():
        i = idx[0]
        idx[0] = i + 1
        return frames[i % 1000]

    stamps: list[float] = []
    clock = time.perf_counter

    def on_decision(d, _append=stamps.append, _clock=clock):
        _append(_clock())

    tmp = tempfile.mkdtemp()
    log_path = os.path.join(tmp, "loop_audit.jsonl")
    log = AuditLog(log_path, fsync="interval", fsync_interval_s=0.05,
                   meta={"spec_sha256": ethimon.audit.spec_hash(spec), "model_id": src.model_id})
    period = 1.0 / args.rate
    deadline = None if args.deadline_ms is None else args.deadline_ms / 1000.0
    loop = GovernedLoop(ethimon.Monitor(spec), signals=signals, risk=src, audit=log, on_decision=on_decision,
                        config=LoopConfig(period_s=period, deadline_s=deadline, max_risk_age_s=args.max_age_ms / 1000.0,
                                          audit_every_cycle=args.audit_every_cycle))
    load_start = os.getloadavg()
    ru0 = resource.getrusage(resource.RUSAGE_SELF)
    cpu0, wall0 = time.process_time(), time.perf_counter()
    stats = loop.run(duration_s=args.duration)
    cpu1, wall1 = time.process_time(), time.perf_counter()
    ru1 = resource.getrusage(resource.RUSAGE_SELF)
    src.stop()
    log.close()
    rep = verify_log(log_path, require_closed=True)
    load_end = os.getloadavg()

    wall = wall1 - wall0
    intervals = [(b - a) * 1e3 for a, b in zip(stamps, stamps[1:])]
    expected = int(args.duration * args.rate)
    res = {
        "duration_s": args.duration, "rate_hz": args.rate, "estimator_hz": args.estimator_hz,
        "estimator": src.model_id, "fake_latency_ms": None if args.real_estimator else args.latency_ms,
        "max_risk_age_ms": args.max_age_ms, "deadline_ms": loop.deadline_s * 1e3, "audit_every_cycle": args.audit_every_cycle,
        "cycles": stats.cycles, "expected_cycles": expected,
        "deadline_misses": stats.deadline_misses,
        "deadline_miss_pct": round(100.0 * stats.deadline_misses / max(1, stats.cycles), 4),
        "skipped_slots": stats.skipped_slots, "stale_overrides": stats.stale_overrides,
        "risk_fault_cycles": stats.risk_faults, "override_cycles": stats.overrides,
        "fault_cycles": stats.fault_cycles,
        "estimator_calls": getattr(est, "calls", None), "estimator_errors": src.errors,
        "max_cycle_compute_ms": round(stats.max_cycle_s * 1e3, 4),
        "max_late_ms": round(stats.max_late_s * 1e3, 4),
        "interval_median_ms": round(pct(intervals, 0.5), 4), "interval_p99_ms": round(pct(intervals, 0.99), 4),
        "interval_p999_ms": round(pct(intervals, 0.999), 4), "interval_max_ms": round(max(intervals), 4),
        "cpu_s": round(cpu1 - cpu0, 3), "wall_s": round(wall, 3),
        "cpu_pct_of_one_core": round(100.0 * (cpu1 - cpu0) / wall, 1),
        "voluntary_ctx_switches": ru1.ru_nvcsw - ru0.ru_nvcsw,
        "involuntary_ctx_switches": ru1.ru_nivcsw - ru0.ru_nivcsw,
        "audit_records": rep.records, "audit_ok": rep.ok, "audit_drops": stats.audit_drops,
    }
    rows = [("cycles (expected)", f"{res['cycles']} ({expected})"),
            ("deadline misses", f"{res['deadline_misses']} ({res['deadline_miss_pct']} %)"),
            ("skipped slots", res["skipped_slots"]),
            ("stale-estimate overrides", res["stale_overrides"]),
            ("risk-fault cycles", res["risk_fault_cycles"]),
            ("override cycles (all faults)", res["override_cycles"]),
            ("estimator calls / errors", f"{res['estimator_calls']} / {res['estimator_errors']}"),
            ("cycle interval median / p99 / p99.9 / max ms",
             f"{res['interval_median_ms']} / {res['interval_p99_ms']} / {res['interval_p999_ms']} / "
             f"{res['interval_max_ms']}"),
            ("max cycle compute ms", res["max_cycle_compute_ms"]),
            ("CPU % of one core (whole process)", res["cpu_pct_of_one_core"]),
            ("audit records (chain ok)", f"{res['audit_records']} ({res['audit_ok']})")]
    w = max(len(r[0]) for r in rows)
    for k, v in rows:
        print(f"{k:<{w}}  {v}")
    facts = machine_facts()
    facts["loadavg_start"] = load_start
    facts["loadavg_end"] = load_end
    facts["note"] = "shared machine (other engineers' tests and a model training may run at the same time)"
    os.makedirs(os.path.dirname(args.json) or ".", exist_ok=True)
    with open(args.json, "w", encoding="utf-8") as fh:
        json.dump({"benchmark": "loop_1khz", "machine": facts, "results": res}, fh, indent=2)
    print(f"wrote {args.json}")
    os.remove(log_path)
    os.rmdir(tmp)
    return 0


if __name__ == "__main__":
    sys.exit(main())
