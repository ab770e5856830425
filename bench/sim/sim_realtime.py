"""Sim + monitor speed and safe-pose timing for every shipped sim scenario.

Measures, per scenario (median of --repeats runs, DIRECT mode, no recording):
the realtime factor of the governed loop (simulated s / wall s, 240 Hz physics,
monitor every control cycle), the wall time of a whole run (setup, IK planning
and loop), the override cycle, the reaction in cycles, the time to the safe
pose and the peak joint speed on the way there. Each run's constant risk input comes by the
library's one rule for ``simulate`` and ``check --sim`` (:func:`ethimon.scenario.sim_risk_inputs`):
the scenario's own ``risk``/``p_unsafe``/``p``, else its task text scored by the spec's risk
model (torch; loaded once). Then it times the whole
``ethimon check scenarios/ --sim`` command (all shipped scenarios, YAML
timelines plus sims) in a fresh process.

    python -m bench.sim.sim_realtime [--repeats 3] [--out bench/results/sim/sim_realtime.json]
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

import yaml

import ethimon
from bench import RESULTS, ROOT
from bench._machine import machine_facts
from ethimon.scenario import ScenarioSession, load_scenario
from ethimon.sim import SimBlock, run_sim

SESSION = ScenarioSession()  # risk models loaded once, shared by every scenario


def machine() -> dict:
    """The shared machine facts plus the PyBullet API version."""
    import pybullet
    return machine_facts(pybullet_api=pybullet.getAPIVersion())


def risk_kwargs(path: Path, spec) -> dict:
    """The run's constant risk input (``risk``, ``p_unsafe`` or ``p``), as ``simulate`` feeds it."""
    return SESSION.sim_inputs(load_scenario(path), spec)


def bench_scenario(path: Path, repeats: int) -> dict:
    doc = yaml.safe_load(path.read_text())
    block = SimBlock.model_validate(doc["sim"])
    spec = ethimon.load_spec(str((path.parent / doc["spec"]).resolve()))
    monitor = ethimon.Monitor(spec)
    kw = risk_kwargs(path, spec)
    runs = [run_sim(block, monitor, **kw) for _ in range(repeats)]
    r = runs[0]
    return {
        "scenario": doc["name"],
        "sim_time_s": r.sim_time_s,
        "control_hz": block.control_hz,
        "cycles": len(r.trace),
        "realtime_factor": round(statistics.median(x.realtime_factor for x in runs), 1),
        "wall_time_s": round(statistics.median(x.wall_time_s for x in runs), 3),
        "first_override_cycle": r.first_override_cycle,
        "override_reaction_cycles": r.override_reaction_cycles,
        "executed_response": r.executed_response,
        "time_to_safe_pose_s": r.time_to_safe_pose_s,
        "max_joint_speed_safe_pose_rad_s": (round(r.max_joint_speed_safe_pose_rad_s, 4)
                                            if r.max_joint_speed_safe_pose_rad_s is not None else None),
        "joint_speed_limit_rad_s": r.joint_speed_limit_rad_s,
        "task_completed": r.task_completed,
        "deterministic": all(len(x.trace) == len(r.trace) and x.first_override_cycle == r.first_override_cycle
                             and x.time_to_safe_pose_s == r.time_to_safe_pose_s for x in runs),
    }


def time_check_sim() -> dict:
    exe = Path(sys.executable).with_name("ethimon")
    cmd = [str(exe) if exe.exists() else "ethimon", "check", "scenarios/", "--sim", "-q"]
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    return {"command": "ethimon check scenarios/ --sim -q", "wall_time_s": round(wall, 2),
            "exit_code": proc.returncode, "summary": proc.stdout.strip().splitlines()[-1:]}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--out", default=str(RESULTS / "sim" / "sim_realtime.json"))
    ap.add_argument("--no-check", action="store_true", help="skip timing 'ethimon check --sim'")
    args = ap.parse_args()
    rows = [bench_scenario(p, args.repeats) for p in sorted((ROOT / "scenarios" / "sim").glob("*.yaml"))]
    head = ("scenario", "sim s", "RTF", "wall s", "override@", "react", "response", "to safe pose",
            "max qd", "task done")
    table = [(r["scenario"], f"{r['sim_time_s']:.1f}", f"{r['realtime_factor']:.0f}x",
              f"{r['wall_time_s']:.2f}", "-" if r["first_override_cycle"] is None else r["first_override_cycle"],
              "-" if r["override_reaction_cycles"] is None else r["override_reaction_cycles"],
              r["executed_response"],
              "-" if r["time_to_safe_pose_s"] is None else f"{r['time_to_safe_pose_s']:.3f} s",
              "-" if r["max_joint_speed_safe_pose_rad_s"] is None else f"{r['max_joint_speed_safe_pose_rad_s']:.3f}",
              "yes" if r["task_completed"] else "no") for r in rows]
    widths = [max(len(str(x[i])) for x in (head, *table)) for i in range(len(head))]
    for line in (head, tuple("-" * w for w in widths), *table):
        print("  ".join(str(c).ljust(w) for c, w in zip(line, widths)).rstrip())
    total_sim = sum(r["sim_time_s"] for r in rows)
    total_wall = sum(r["wall_time_s"] for r in rows)
    print(f"all sim scenarios: {total_sim:.1f} s simulated in {total_wall:.2f} s wall "
          f"(overall {total_sim / total_wall:.0f}x real time, setup included)")
    out = {"machine": machine(), "repeats": args.repeats, "scenarios": rows,
           "total_sim_time_s": round(total_sim, 2), "total_wall_time_s": round(total_wall, 3),
           "overall_realtime_factor": round(total_sim / total_wall, 1),
           "targets": {"override_reaction_cycles": 0, "time_to_safe_pose_s_max": 1.5,
                       "realtime_factor_min": 1.0, "check_sim_wall_s_max": 60}}
    if not args.no_check:
        out["check_sim"] = time_check_sim()
        print(f"{out['check_sim']['command']}: {out['check_sim']['wall_time_s']:.2f} s "
              f"(exit {out['check_sim']['exit_code']}) {' '.join(out['check_sim']['summary'])}")
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(out, indent=2) + "\n")
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
