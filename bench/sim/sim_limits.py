"""Rated joint limits in stops and the safe pose from random states near a limit (issue 23 row 4).

Every run starts from a random collision-free configuration (0.3 rad inside the rated range)
and drives a task motion (min-jerk, random requested speed 0.3 .. 2.6 rad/s) whose target puts
one random joint exactly at one of its rated position limits (the others random); the response
is taken at a random moment between 50 % and 99 % of that motion. It runs until standstill,
then 1 s more (for stops 0 and 1: with motor power off and the brakes holding). Measured: the
furthest any joint goes past its rated limit (mrad, every 240 Hz physics step, from the
response command on), per response: ``stop_0``, ``stop_1``, ``stop_2``, ``safe_pose``.

    python -m bench.sim.sim_limits [--runs 40] [--seed 0] [--out bench/results/sim/sim_limits.json]
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

from bench import results_dir
from bench._machine import machine_facts
from bench.sim.sim_responses import SAFE, _dist, _random_q


def run(rng, response: str) -> dict:
    from ethimon.sim import ArmSim
    from ethimon.sim._arm import Segment
    from ethimon.sim._control import StopController, TaskController, _timed
    from ethimon.sim._safe_pose import SafePoseController
    from ethimon.sim._limits import RATED_Q_MAX, RATED_Q_MIN
    sim = ArmSim(control_hz=60)
    try:
        for _ in range(100):
            q0, q1 = _random_q(rng, sim), _random_q(rng, sim)
            j = int(rng.integers(0, 7))
            up = bool(rng.integers(0, 2))
            q1[j] = RATED_Q_MAX[j] if up else RATED_Q_MIN[j]
            pts = sim.link_points(q1)
            if float(np.min(pts[2:, 2])) > 0.12 and sim.probe([q1])[0]["obstacle"] > 0.03:
                break
        sim.reset_joints(q0)
        sim._apply_command()
        v = float(rng.uniform(0.3, 2.6))
        dur = _timed(q0, q1, None, v)
        task = TaskController([Segment(q=q1, duration_s=dur)], q0, v)
        frac = float(rng.uniform(0.5, 0.99))
        for _ in range(int(frac * dur * 60)):
            task.command(sim)
            sim.step()
        q, qd = sim.joint_state()
        sim.max_past_limit_rad = 0.0  # from the response command on
        if response == "safe_pose":
            ctl = SafePoseController(q, SAFE, 1.0)
        else:
            ctl = StopController(int(response[-1]), q, qd, 0.25)
        still = None
        for k in range(60 * 8):
            ctl.command(sim)
            sim.step()
            moving = float(np.max(np.abs(sim.joint_state()[1]))) >= 0.01
            done = ctl.done if response != "stop_2" else ctl.done and not moving
            if still is None and done and not moving:
                still = k
            if still is not None and k >= still + 60:
                break
        return {"response": response, "joint": j + 1, "limit": "max" if up else "min",
                "fraction_of_reach": round(frac, 3), "v_task_rad_s": round(v, 3),
                "speed_toward_limit_rad_s": round(float(qd[j] if up else -qd[j]), 4),
                "past_limit_mrad": round(1000.0 * sim.max_past_limit_rad, 4),
                "powered_at_end": bool(sim.powered)}
    finally:
        sim.close()


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=40, help="runs per response")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--out", default=str(results_dir("sim") / "sim_limits.json"))
    args = ap.parse_args()
    t0 = time.perf_counter()
    rng = np.random.default_rng(args.seed)
    rows = {r: [run(rng, r) for _ in range(args.runs)] for r in ("stop_0", "stop_1", "stop_2", "safe_pose")}
    summary = {}
    print(f"{'response':<12}{'n':>4}{'past limit mrad: median':>26}{'p95':>8}{'max':>8}{'runs past':>11}")
    for r, rs in rows.items():
        d = _dist([x["past_limit_mrad"] for x in rs])
        n_past = sum(x["past_limit_mrad"] > 0 for x in rs)
        worst = max(rs, key=lambda x: x["past_limit_mrad"])
        summary[r] = {"past_limit_mrad": d, "runs_past": n_past, "worst": worst}
        print(f"{r:<12}{len(rs):>4}{d['median']:>26.3f}{d['p95']:>8.3f}{d['max']:>8.3f}{n_past:>11}")
    out = {"what": __doc__.splitlines()[0], "runs_per_response": args.runs, "seed": args.seed,
           "wall_s": round(time.perf_counter() - t0, 1), "summary": summary, "runs": rows,
           "machine": machine_facts()}
    with open(args.out, "w", encoding="utf-8") as fh:
        json.dump(out, fh, indent=1)
    print(f"wrote {args.out} ({out['wall_s']} s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
