"""Stop 0 measured (issue 32 item 2): random arm states, payloads up to the rated 3 kg.

Every run starts from a random configuration (as ``sim_responses``: uniform in the Panda's rated
range, 0.3 rad inside it, clear of the floor and itself) holding a payload of random mass
0 .. 3 kg (a 6 cm cube in a self-locking gripper, so it stays in the hand and loads the brakes);
half the runs stop from rest, half during a task motion toward another random configuration at a
random requested joint speed (0.3 .. 2.6 rad/s), at a random moment of it. Then stop 0: motor
power off, the brakes (``ethimon._robot.BRAKE_TABLE``, estimates; 30 ms to engage, assumed) hold.
Measured per run, from the command: time to standstill (every joint < 0.01 rad/s), joint travel
(largest joint, rad), Cartesian travel of the grasp point (largest distance from where it was, m),
how far the grasp point sank after power-off (m) and below where it was at the command (m, any
power state: a refused power-off's powered hold included), peak |q̈_j| / rated q̈_max,j, and the furthest any joint went past
its rated position limit (mrad). Refused power-offs (brakes that cannot hold arm + payload with the
safety factor ``ethimon._robot.BRAKE_SAFETY_FACTOR``: a powered stop 2 instead) are counted; their
standstill is the powered hold's.

    python -m bench.sim.sim_stop0 [--runs 40] [--seed 0] [--out bench/results/sim/sim_stop0.json]
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

from bench import results_dir
from bench._machine import machine_facts
from bench.sim.sim_responses import _dist, _drive, _random_q


def stop0_run(rng, moving: bool) -> dict:
    from ethimon.sim import ArmSim, SimObject
    from ethimon.sim._control import StopController
    from ethimon.sim._model import Gripper
    mass = float(rng.uniform(0.0, 3.0))
    pot = SimObject(name="payload", shape="box", xyz_m=(0.0, 1.5, 0.03), half_extents_m=(0.03,) * 3,
                    mass_kg=mass)
    sim = ArmSim(objects=[pot], gripper=Gripper(self_locking=True))
    try:
        q0, q1 = _random_q(rng, sim), _random_q(rng, sim)
        sim.reset_joints(q0)
        sim._apply_command()
        sim.hold_at_start("payload")
        if moving:
            _drive(rng, sim, q0, q1)
        else:
            for _ in range(10):
                sim.command_joints(q0)
                sim.step()
        q, qd = sim.joint_state()
        ee0 = sim.ee_pose()[0]
        z0 = z_min = sim._grasp_z()
        v0 = float(np.max(np.abs(qd)))
        load = np.abs(sim.gravity_load()) / sim.brake_torque
        stop = StopController(0, q, qd, 0.25)
        ratio, t_still, travel_m = 0.0, None, 0.0
        for k in range(240):
            stop.command(sim)
            sim.step()
            ratio = max(ratio, sim.max_accel_ratio_substep)
            travel_m = max(travel_m, float(np.linalg.norm(sim.ee_pose()[0] - ee0)))
            z_min = min(z_min, sim._grasp_z())
            held = sim.brakes_engaged or (sim.powered and sim.power_off_refused is not None)
            if float(np.max(np.abs(sim.joint_state()[1]))) < 0.01 and held:
                if t_still is None:
                    t_still = (k + 1) / 60
            else:
                t_still = None  # standstill is the last time it came to rest
        q2, _ = sim.joint_state()
        return {"moving": moving, "payload_kg": round(mass, 3), "speed_at_command_rad_s": round(v0, 4),
                "brake_load_ratio": round(float(np.max(load)), 3),
                "time_to_standstill_s": t_still, "joint_travel_rad": round(float(np.max(np.abs(q2 - q))), 4),
                "ee_travel_m": round(travel_m, 4), "drop_m": round(sim.max_drop_unpowered_m, 4),
                "hand_drop_m": round(z0 - z_min, 4),
                "accel_ratio": round(ratio, 3), "past_limit_mrad": round(1000 * sim.max_past_limit_rad, 3),
                "refused": sim.power_off_refused is not None, "held_at_end": sim.held == "payload"}
    finally:
        sim.close()


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=40, help="runs (half from rest, half moving)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--out", default=str(results_dir("sim") / "sim_stop0.json"))
    args = ap.parse_args()
    t0 = time.perf_counter()
    rng = np.random.default_rng(args.seed)
    rows = [stop0_run(rng, moving=bool(i % 2)) for i in range(args.runs)]
    keys = ("time_to_standstill_s", "joint_travel_rad", "ee_travel_m", "drop_m", "accel_ratio",
            "past_limit_mrad", "hand_drop_m", "payload_kg", "brake_load_ratio", "speed_at_command_rad_s")
    summary = {}
    print(f"{'stop 0':<10}{'n':>4}  " + "".join(f"{k:>24}" for k in keys[:7]))
    for name, sel in (("from_rest", [r for r in rows if not r["moving"]]),
                      ("moving", [r for r in rows if r["moving"]]), ("all", rows)):
        s = {k: _dist([r[k] for r in sel]) for k in keys}
        s["refused"] = sum(r["refused"] for r in sel)
        s["never_still"] = sum(r["time_to_standstill_s"] is None for r in sel)
        summary[name] = s
        print(f"{name:<10}{len(sel):>4}  " + "".join(
            f"{'%.3f / %.3f' % (s[k]['median'], s[k]['max']) if s[k] else '-':>24}" for k in keys[:7]))
    out = {"what": __doc__.splitlines()[0], "runs": args.runs, "seed": args.seed,
           "wall_s": round(time.perf_counter() - t0, 1), "columns": "median / max", "summary": summary,
           "runs_detail": rows, "machine": machine_facts()}
    with open(args.out, "w", encoding="utf-8") as fh:
        json.dump(out, fh, indent=1)
    print(f"wrote {args.out} ({out['wall_s']} s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
