"""Issue 23: responses around people who move (DIRECT PyBullet): the retreat re-plans every
cycle for the people in range now; compliant people walk as scripted."""

from __future__ import annotations

import numpy as np
import pytest

from tests.sim._scenarios import run_scenario


pytestmark = pytest.mark.sim


@pytest.fixture(autouse=True)
def _pybullet():
    pytest.importorskip("pybullet")


def _scenario(name: str, **over):
    return run_scenario(name, over)


@pytest.mark.slow
def test_a_person_arriving_mid_retreat_slows_it_within_one_cycle():
    """Before: 0.51 m/s within 1.5 m of the worker (nobody in range at the override, no cap)."""
    from ethimon.sim import check_sim_expectations
    block, res = _scenario("person_arrives_mid_retreat")
    assert check_sim_expectations(block, res) == []
    assert res.retreat_max_link_speed_near_human_m_s <= 0.2 + 1e-3  # 0.8 x v_slow
    route = [r for r in res.trace if r.controller == "safe_pose" and r.retreat_rate is not None]
    assert route[0].retreat_rate == 1.0  # nobody in range when it set off: full planned speed
    # the first cycle that reads the worker within d_slow + 0.5 m already lowers the rate
    k = next(i for i, r in enumerate(route) if r.human_distance_true_m < 2.0)
    assert route[k].retreat_rate < route[k - 1].retreat_rate
    assert min(r.retreat_rate for r in route) < 0.5
    assert "slow_near_human" not in res.fired and "separation" not in res.fired
    assert res.time_to_safe_pose_s is not None


@pytest.mark.slow
def test_a_person_who_leaves_lets_the_retreat_speed_up_again():
    humans = [{"name": "worker", "waypoints": [
        {"t_s": 0.0, "xy_m": [-3.0, 0.6]}, {"t_s": 0.3, "xy_m": [-3.0, 0.6]},
        {"t_s": 1.3, "xy_m": [-1.2, 0.4]}, {"t_s": 1.8, "xy_m": [-1.2, 0.4]},
        {"t_s": 2.8, "xy_m": [-3.5, 0.6]}]}]
    _, res = _scenario("person_arrives_mid_retreat", humans=humans)
    rates = [r.retreat_rate for r in res.trace if r.controller == "safe_pose" and r.retreat_rate is not None]
    low = int(np.argmin(rates))
    assert rates[low] < 0.5 and max(rates[low:]) == 1.0
    assert res.retreat_max_link_speed_near_human_m_s <= 0.2 + 1e-3


@pytest.mark.slow
def test_a_fast_compliant_person_walks_as_scripted_and_stops_at_the_last_waypoint():
    """Before: 3.2 m/s against 2.0 scripted, 0.70 m past the last waypoint, 3860 N into the
    stopped arm."""
    from ethimon.sim import check_sim_expectations
    block, res = _scenario("fast_compliant_person")
    assert check_sim_expectations(block, res) == []
    assert res.max_human_speed_ratio <= 1.1 and res.human_overshoot_m <= 0.05
    assert res.max_contact_force_n == 0.0


@pytest.mark.slow
def test_a_compliant_person_held_up_catches_up_at_walking_speed_not_faster():
    """person_walks_into_arm: the arm stops the worker; the drive keeps pushing (at most 150 N)
    but the body never runs to catch up with its script."""
    _, res = _scenario("person_walks_into_arm")
    assert res.max_human_speed_ratio <= 1.1
    assert res.max_contact_force_n > 0.0  # the script does bring the worker into the arm


@pytest.mark.slow
def test_a_child_walking_round_a_knife_retreat_gets_the_blade_turned_away_on_arrival():
    """Before: the wrist turned once, for where she stood at the override: 58 deg at the end."""
    from ethimon.sim import check_sim_expectations
    block, res = _scenario("knife_child_walks_around")
    assert check_sim_expectations(block, res) == []
    assert res.hazard_axis_angle_end_deg >= 70 and res.route == "turn"
    assert res.time_to_safe_pose_s is not None  # it reached the safe pose, then turned the wrist
    turned = [r for r in res.trace if r.replanned]
    assert turned and turned[0].t_s >= res.time_to_safe_pose_s - 1e-9


def test_a_route_never_sweeps_a_held_blade_further_toward_a_person():
    """The planner's sweep check: the blade points 32 deg from the child; turning joint 7 one
    way sweeps it through her (0.3 deg on the way) and is refused, the other way turns it away
    (32 -> 126 deg) and passes."""
    from ethimon.sim import ArmSim, Human, SimObject
    from ethimon.sim._safe_pose import SafePoseController
    knife = SimObject(name="knife", shape="box", xyz_m=(0.55, 0.25, 0.32), half_extents_m=(0.1, 0.012, 0.004),
                      hazard="sharp", hazard_axis=(1, 0, 0), mass_kg=0.15)
    child = Human(name="child", radius_m=0.14, height_m=1.1, waypoints=[{"t_s": 0, "xy_m": (1.6, 0.9)}])
    with ArmSim(objects=[knife], humans=[child]) as sim:
        q = sim.solve_ik((0.55, 0.25, 0.35))
        sim.reset_joints(q)
        sim.hold_at_start("knife")
        sp = SafePoseController(q, (0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785), 1.0)
        assert 25 < sim.hazard_axis_angles_deg([q])[0] < 40
        through, away = q.copy(), q.copy()
        through[6] -= 1.0
        away[6] += 1.0
        assert min(sim.hazard_axis_angles_deg(sp._samples([q, through]))) < 5.0
        assert not sp._axis_ok(sim, sp._samples([q, through]))
        assert sp._axis_ok(sim, sp._samples([q, away]))
        assert max(sim.hazard_axis_angles_deg(sp._samples([q, away]))) > 80.0
