"""At rest, nothing moves (issue 32): a 3 kg hot pot whose upright axis (its declared hazard axis,
the open top) cannot be pointed away from the cook (it ends at 90 deg): the retreat holds (a stop 2)
and, with nobody moving, nothing is re-planned cycle after cycle and the arm stays still. A guard:
the re-plan storm reported (363 re-plans in 6 s after arrival) was fixed on main in bda17d5; this
test passed on arrival here, it did not fail first."""

from __future__ import annotations

import pytest

import ethimon
from tests.sim._scenarios import SPEC

pytestmark = [pytest.mark.sim, pytest.mark.slow]

BLOCK = {
    "duration_s": 5.0,
    "start_joints_rad": [0.0, -0.5, 0.0, -2.2, 0.0, 1.7, 0.785],
    "start_holding": "pot",
    "objects": [{"name": "pot", "shape": "cylinder", "xyz_m": [0.5, 0.0, 0.3], "radius_m": 0.08,
                 "height_m": 0.12, "hazard": "hot", "hazard_axis": [0, 0, 1], "mass_kg": 3.0}],
    "humans": [{"name": "cook", "waypoints": [{"t_s": 0, "xy_m": [1.3, 0.4]}]}],
    "gripper": {"self_locking": True},
}


def test_no_replan_storm_after_arrival():
    pytest.importorskip("pybullet")
    from ethimon.sim import SimBlock, run_sim
    res = run_sim(SimBlock.model_validate(BLOCK), ethimon.Monitor(ethimon.load_spec(str(SPEC))), p_unsafe=0.9)
    assert res.first_override_cycle == 0
    replans = [r for r in res.trace if r.replanned]
    # nobody moves: a plan is made at the override, perhaps once more on arrival, never every cycle
    assert len(replans) <= 3, [(r.t_s, r.replanned) for r in replans[:5]]
    tail = res.trace[-60:]  # the last second: the arm rests
    assert max(r.joint_speed_max_rad_s for r in tail) < 0.02
