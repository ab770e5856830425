"""Stops and the safe-pose retreat from random arm states (issue 14 item 8): distributions, worst cases.

Not the shipped scenarios: every run starts from a random arm configuration (uniform in
the Panda's rated range, 0.3 rad inside it, rejected when the arm touches the floor or
itself), drives a task motion towards another random configuration at a random joint
speed (0.3 .. 2.6 rad/s requested; the servo allows the rated speed at most) and takes the
response at a random moment of that motion:

* ``stop_0`` / ``stop_1`` / ``stop_2``: time to standstill (every joint < 0.01 rad/s),
  joint travel after the command (largest joint, rad) and grasp-frame travel (m), peak joint
  speed after the command over the speed at the command (1.0 = nothing adds speed), peak
  |q̈_j| / rated q̈_max,j;
* ``safe_pose``: time to the safe pose (cobot_cell: every joint within 0.02 rad; joint
  speed ≤ 1.0 rad/s), peak joint speed (from the override, and after the deceleration from
  the task's speed), peak acceleration ratio and the route; half of the
  runs with a person standing at a random place 0.7 .. 1.6 m from the base, where the
  retreat also obeys the spec's near-human speed rule (≤ 0.25 m/s within 1.5 m);
* ``safe_pose_person_moving`` (issue 23): a person who walks during the response, from a
  random place 2.0 .. 3.0 m from the base toward one 0.8 .. 1.3 m from it (random bearings,
  0.6 .. 1.6 m/s, starting 0 .. 0.5 s after the override); the retreat re-plans for them
  every cycle. Measured as above, plus the re-plans and the fastest link within 1.5 m of
  them after the deceleration.

    python -m bench.sim.sim_responses [--runs 40] [--seed 0] [--out bench/results/sim/sim_responses.json]
"""

from __future__ import annotations

import argparse
import json
import math
import time

import numpy as np

from bench import results_dir
from bench._machine import machine_facts

SAFE = (0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785)


def _random_q(rng, sim) -> np.ndarray:
    from ethimon.sim._limits import RATED_Q_MAX, RATED_Q_MIN
    lo, hi = np.array(RATED_Q_MIN) + 0.3, np.array(RATED_Q_MAX) - 0.3
    for _ in range(200):
        q = rng.uniform(lo, hi)
        pts = sim.link_points(q)
        if float(np.min(pts[2:, 2])) > 0.12 and sim.probe([q])[0]["obstacle"] > 0.03:
            return q
    raise RuntimeError("no collision-free random configuration found")


def _setup(rng, human: bool, moving: bool = False):
    from ethimon.sim import ArmSim, Human
    humans = []
    if moving:
        a0, a1 = rng.uniform(-math.pi, math.pi, 2)
        r0, r1 = rng.uniform(2.0, 3.0), rng.uniform(0.8, 1.3)
        p0 = (r0 * math.cos(a0), r0 * math.sin(a0))
        p1 = (r1 * math.cos(a1), r1 * math.sin(a1))
        v = rng.uniform(0.6, 1.6)
        t0 = rng.uniform(0.0, 0.5)  # after the override (the drive below takes its time first)
        humans = [Human(name="person", waypoints=[{"t_s": 0.0, "xy_m": p0}])]
        sim = ArmSim(control_hz=60, humans=humans)
        sim._moving_plan = (p0, p1, v, t0)
        for _ in range(100):
            q0, q1 = _random_q(rng, sim), _random_q(rng, sim)
            path = [q0 + (k / 20) * (q1 - q0) for k in range(21)]
            if min(p["human"] for p in sim.probe(path)) >= 0.15:
                break
        sim.reset_joints(q0)
        sim._apply_command()
        return sim, q0, q1
    if human:
        ang = rng.uniform(-math.pi, math.pi)
        r = rng.uniform(0.7, 1.6)
        humans = [Human(name="person", waypoints=[{"t_s": 0, "xy_m": (r * math.cos(ang), r * math.sin(ang))}])]
    sim = ArmSim(control_hz=60, humans=humans)
    for _ in range(100):  # a task motion that itself keeps 0.15 m from the person
        q0 = _random_q(rng, sim)
        q1 = _random_q(rng, sim)
        path = [q0 + (k / 20) * (q1 - q0) for k in range(21)]
        if not human or min(p["human"] for p in sim.probe(path)) >= 0.15:
            break
    sim.reset_joints(q0)
    sim._apply_command()
    return sim, q0, q1


def _drive(rng, sim, q0, q1):
    """Task motion q0 → q1 at a random requested speed; returns (v_task, cycles driven)."""
    from ethimon.sim._arm import Segment
    from ethimon.sim._control import TaskController, _timed
    v = float(rng.uniform(0.3, 2.6))
    dur = _timed(q0, q1, None, v)
    task = TaskController([Segment(q=q1, duration_s=dur)], q0, v)
    n = int(rng.uniform(0.05, 0.95) * dur * 60)
    for _ in range(n):
        task.command(sim)
        sim.step()
    return v, n


def stop_run(rng, category: int) -> dict:
    from ethimon.sim._control import StopController
    sim, q0, q1 = _setup(rng, False)
    try:
        v_task, n = _drive(rng, sim, q0, q1)
        q, qd = sim.joint_state()
        ee0 = sim.ee_pose()[0]
        v0 = float(np.max(np.abs(qd)))
        stop = StopController(category, q, qd, 0.25)
        peak = ratio = 0.0
        t_still = None
        for k in range(180):
            stop.command(sim)
            sim.step()
            peak = max(peak, sim.max_joint_speed_substep)
            ratio = max(ratio, sim.max_accel_ratio_substep)
            if t_still is None and float(np.max(np.abs(sim.joint_state()[1]))) < 0.01:
                t_still = (k + 1) / 60
                if category != 1:
                    break
            if category == 1 and stop.powered_off and t_still is not None:
                break
        q2, _ = sim.joint_state()
        return {"category": category, "v_task_rad_s": round(v_task, 3), "speed_at_command_rad_s": round(v0, 4),
                "time_to_standstill_s": t_still, "joint_travel_rad": round(float(np.max(np.abs(q2 - q))), 4),
                "ee_travel_m": round(float(np.linalg.norm(sim.ee_pose()[0] - ee0)), 4),
                "speed_gain": round(peak / v0, 4) if v0 > 0.05 else None,
                "accel_ratio": round(ratio, 3), "powered_at_end": sim.powered,
                "escalated": bool(stop.escalated)}
    finally:
        sim.close()


def _walk_from_now(sim) -> None:
    """Script the moving person from the override on: stand, then walk p0 -> p1."""
    import numpy as np_
    p0, p1, v, t0 = sim._moving_plan
    hb = sim.humans["person"]
    t = sim.time_s
    dur = float(np_.hypot(p1[0] - p0[0], p1[1] - p0[1])) / v
    hb.times = np_.array([0.0, t + t0, t + t0 + dur])
    hb.xy = np_.array([p0, p0, p1], dtype=float)


def safe_pose_run(rng, human: bool, moving: bool = False) -> dict:
    from ethimon.sim._safe_pose import SafePoseController
    sim, q0, q1 = _setup(rng, human, moving)
    human = human or moving
    try:
        v_task, n = _drive(rng, sim, q0, q1)
        if moving:
            _walk_from_now(sim)
        q, qd = sim.joint_state()
        sp = SafePoseController(q, SAFE, 1.0, near_human=(1.5, 0.25) if human else None)
        peak = ratio = peak_route = 0.0
        link_near = 0.0
        closest = math.inf
        t_safe = None
        for k in range(60 * 12):
            sp.command(sim)
            sim.step()
            peak = max(peak, sim.max_joint_speed_substep)
            ratio = max(ratio, sim.max_accel_ratio_substep)
            if not sp.decelerating and sp.route != "hold":  # a hold is a stop 2's deceleration
                peak_route = max(peak_route, sim.max_joint_speed_substep)
            if human:
                d = sim.human_distance()
                closest = min(closest, d)
                if d < 1.5 and k * sim.dt >= (sp._decel.T if sp._decel else 0.0):
                    link_near = max(link_near, sim.link_speed_max)
            if sp.route == "hold" or sp.holding is not None:
                break
            if float(np.max(np.abs(sim.joint_state()[0] - np.array(SAFE)))) <= 0.02:
                t_safe = (k + 1) / 60
                break
        return {"human": human, "moving": moving, "replans": len(getattr(sp, "replans", ())),
                "min_rate": round(float(getattr(sp, "min_rate", 1.0)), 4),
                "v_task_rad_s": round(v_task, 3),
                "speed_at_override_rad_s": round(float(np.max(np.abs(qd))), 4),
                "joint_distance_rad": round(float(np.max(np.abs(q - np.array(SAFE)))), 4),
                "route": sp.route, "time_to_safe_pose_s": t_safe, "planned_s": round(sp.plan_s, 3),
                "peak_joint_speed_rad_s": round(peak, 4),
                "peak_joint_speed_after_decel_rad_s": None if sp.route == "hold" else round(peak_route, 4),
                "accel_ratio": round(ratio, 3),
                "closest_approach_m": None if closest == math.inf else round(closest, 4),
                "link_speed_near_human_after_decel_m_s": round(link_near, 4) if human else None}
    finally:
        sim.close()


def _dist(xs):
    xs = sorted(x for x in xs if x is not None)
    if not xs:
        return None
    q = lambda f: xs[min(len(xs) - 1, int(f * (len(xs) - 1) + 0.5))]  # noqa: E731
    return {"n": len(xs), "min": xs[0], "median": q(0.5), "p95": q(0.95), "max": xs[-1]}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=40, help="runs per stop category and per safe-pose variant")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--moving-runs", type=int, default=40, help="safe-pose runs with a person walking during it")
    ap.add_argument("--out", default=str(results_dir("sim") / "sim_responses.json"))
    args = ap.parse_args()
    t0 = time.perf_counter()
    rng = np.random.default_rng(args.seed)
    stops = {c: [stop_run(rng, c) for _ in range(args.runs)] for c in (0, 1, 2)}
    poses = [safe_pose_run(rng, human=(i % 2 == 1)) for i in range(2 * args.runs)]
    poses += [safe_pose_run(rng, human=True, moving=True) for _ in range(args.moving_runs)]
    summary = {}
    print(f"{'response':<22}{'n':>4}  {'t_standstill/safe s (med/p95/max)':<36}{'travel rad (max)':>18}"
          f"{'speed gain max':>16}{'accel/rated max':>17}")
    for c, rows in stops.items():
        s = {"time_to_standstill_s": _dist([r["time_to_standstill_s"] for r in rows]),
             "joint_travel_rad": _dist([r["joint_travel_rad"] for r in rows]),
             "ee_travel_m": _dist([r["ee_travel_m"] for r in rows]),
             "speed_gain": _dist([r["speed_gain"] for r in rows]),
             "accel_ratio": _dist([r["accel_ratio"] for r in rows]),
             "speed_at_command_rad_s": _dist([r["speed_at_command_rad_s"] for r in rows]),
             "escalated": sum(r["escalated"] for r in rows),
             "powered_at_end": sum(r["powered_at_end"] for r in rows)}
        summary[f"stop_{c}"] = s
        t = s["time_to_standstill_s"]
        print(f"{'stop_' + str(c):<22}{len(rows):>4}  {t['median']:.3f} / {t['p95']:.3f} / {t['max']:.3f}{'':<14}"
              f"{s['joint_travel_rad']['max']:>18.3f}{(s['speed_gain'] or {}).get('max', 0):>16.3f}"
              f"{s['accel_ratio']['max']:>17.2f}")
    for human, moving in ((False, False), (True, False), (True, True)):
        rows = [r for r in poses if r["human"] == human and r.get("moving", False) == moving]
        if not rows:
            continue
        key = "safe_pose_person_moving" if moving else "safe_pose_near_person" if human else "safe_pose"
        s = {"time_to_safe_pose_s": _dist([r["time_to_safe_pose_s"] for r in rows]),
             "reached": sum(r["time_to_safe_pose_s"] is not None for r in rows),
             "held": sum(r["route"] == "hold" for r in rows),
             "routes": {k: sum(r["route"] == k for r in rows) for k in ("direct", "fold", "lift", "away", "hold", "none")},
             "peak_joint_speed_rad_s": _dist([r["peak_joint_speed_rad_s"] for r in rows]),
             "peak_joint_speed_after_decel_rad_s": _dist([r["peak_joint_speed_after_decel_rad_s"] for r in rows]),
             "accel_ratio": _dist([r["accel_ratio"] for r in rows]),
             "joint_distance_rad": _dist([r["joint_distance_rad"] for r in rows])}
        if moving:
            s["replans"] = _dist([r["replans"] for r in rows])
            s["min_rate"] = _dist([r["min_rate"] for r in rows])
        if human:
            s["closest_approach_m"] = _dist([r["closest_approach_m"] for r in rows])
            s["link_speed_near_human_after_decel_m_s"] = _dist([r["link_speed_near_human_after_decel_m_s"] for r in rows])
        summary[key] = s
        t = s["time_to_safe_pose_s"]
        t = t or {"median": math.nan, "p95": math.nan, "max": math.nan}
        print(f"{key:<22}{len(rows):>4}  {t['median']:.3f} / {t['p95']:.3f} / {t['max']:.3f}{'':<14}"
              f"{s['joint_distance_rad']['max']:>18.3f}{'':>16}{s['accel_ratio']['max']:>17.2f}"
              f"   reached {s['reached']}, held {s['held']}")
    out = {"what": __doc__.splitlines()[0], "runs_per_case": args.runs, "seed": args.seed,
           "wall_s": round(time.perf_counter() - t0, 1), "summary": summary,
           "stops": {f"stop_{c}": rows for c, rows in stops.items()}, "safe_pose": poses,
           "machine": machine_facts()}
    with open(args.out, "w", encoding="utf-8") as fh:
        json.dump(out, fh, indent=1)
    print(f"wrote {args.out} ({out['wall_s']} s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
