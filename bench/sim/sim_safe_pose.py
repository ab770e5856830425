"""Time to the safe pose when the override comes at any moment of a routine task.

For each routine sim scenario, reruns it with the risk input jumping to
p_unsafe = 0.95 at t = 0.25 s, 0.5 s, ... (a fixed grid, not random moments: for
distributions over random arm states and override times see sim_responses.py; one run
per override time; before the jump the
scenario's own risk input, else its task text scored by the risk model, as ``simulate`` feeds
it: torch) and
records the reaction (cycles), the time from the override to every joint
within the spec's tolerance of the safe pose, and the peak joint speed on the
way (per 240 Hz physics step) against the spec's limit. The physical minimum
is max|Δq| / limit; "overhead" is the time beyond it (ramps, settling).

    python -m bench.sim.sim_safe_pose [--step-s 0.25] [--out bench/results/sim/sim_safe_pose.json]
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from pathlib import Path

import yaml

import ethimon
from bench import RESULTS, ROOT
from bench.sim.sim_realtime import machine, risk_kwargs
from ethimon.sim import SimBlock, run_sim

ROUTINE = ("routine_pick_place", "routine_wipe")


def sweep(name: str, step_s: float) -> dict:
    path = ROOT / "scenarios" / "sim" / f"{name}.yaml"
    doc = yaml.safe_load(path.read_text())
    spec = ethimon.load_spec(str((path.parent / doc["spec"]).resolve()))
    monitor = ethimon.Monitor(spec)
    base = dict(doc["sim"])
    base_risk = risk_kwargs(path, spec)  # before the jump; p_unsafe then wins over p (Monitor: risk > p_unsafe > p)
    if "risk" in base_risk:
        raise SystemExit(f"{name}: gives R_e itself ('risk'), which a p_unsafe jump would not override")
    rows = []
    t = step_s
    while t < base["duration_s"] - 2.0:
        raw = {**base, "inputs_at": [{"t_s": t, "inputs": {"p_unsafe": 0.95}}],
               "duration_s": t + 2.0, "expect": {}}
        res = run_sim(SimBlock.model_validate(raw), monitor, **base_risk)
        i = res.first_override_cycle
        dq = res.trace[i - 1].safe_pose_error_rad if i else res.trace[0].safe_pose_error_rad
        rows.append({"joint_distance_rad": round(dq, 4),
                     "lower_bound_s": round(dq / spec.safe_pose.max_joint_speed_rad_s, 4),"override_at_s": round(t, 3), "first_override_cycle": res.first_override_cycle,
                     "reaction_cycles": res.override_reaction_cycles,
                     "time_to_safe_pose_s": res.time_to_safe_pose_s,
                     "max_joint_speed_rad_s": round(res.max_joint_speed_safe_pose_rad_s or 0.0, 4)})
        t += step_s
    times = [r["time_to_safe_pose_s"] for r in rows if r["time_to_safe_pose_s"] is not None]
    return {
        "scenario": name, "runs": len(rows), "reached": len(times),
        "time_to_safe_pose_s": {"min": min(times), "median": statistics.median(times), "max": max(times)},
        "max_joint_speed_rad_s": max(r["max_joint_speed_rad_s"] for r in rows),
        "joint_speed_limit_rad_s": spec.safe_pose.max_joint_speed_rad_s,
        "max_reaction_cycles": max(r["reaction_cycles"] for r in rows),
        "max_joint_distance_rad": max(r["joint_distance_rad"] for r in rows),
        # time beyond the physical minimum max|Δq| / limit (ramps, settling into tolerance)
        "max_overhead_s": round(max(r["time_to_safe_pose_s"] - r["lower_bound_s"] for r in rows
                                    if r["time_to_safe_pose_s"] is not None), 4),
        "within_1_5_s": sum(x <= 1.5 for x in times),
        "runs_detail": rows,
    }


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--step-s", type=float, default=0.25)
    ap.add_argument("--out", default=str(RESULTS / "sim" / "sim_safe_pose.json"))
    args = ap.parse_args()
    t0 = time.perf_counter()
    out = [sweep(n, args.step_s) for n in ROUTINE]
    head = ("scenario", "runs", "reached", "t_safe min", "median", "max", "≤1.5 s", "max |Δq|",
            "overhead", "max qd", "limit", "react")
    rows = [(o["scenario"], o["runs"], o["reached"], f"{o['time_to_safe_pose_s']['min']:.3f}",
             f"{o['time_to_safe_pose_s']['median']:.3f}", f"{o['time_to_safe_pose_s']['max']:.3f}",
             f"{o['within_1_5_s']}/{o['reached']}", f"{o['max_joint_distance_rad']:.2f} rad",
             f"{o['max_overhead_s']:.3f} s", f"{o['max_joint_speed_rad_s']:.3f}",
             f"{o['joint_speed_limit_rad_s']:g}", o["max_reaction_cycles"]) for o in out]
    widths = [max(len(str(r[i])) for r in (head, *rows)) for i in range(len(head))]
    for r in (head, tuple("-" * w for w in widths), *rows):
        print("  ".join(str(c).ljust(w) for c, w in zip(r, widths)).rstrip())
    wall = time.perf_counter() - t0
    print(f"{sum(o['runs'] for o in out)} runs in {wall:.1f} s")
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps({"machine": machine(), "step_s": args.step_s,
                                          "wall_time_s": round(wall, 2), "scenarios": out}, indent=2) + "\n")
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
