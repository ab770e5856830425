"""Sensing as ISO/TS 15066 speed and separation monitoring needs it (issue 14 item 5, sim
side): the measured human speed, the speed of the arm's closest point toward the person,
and sensor latency, noise and stuck-at faults per signal; a stuck distance sensor is caught
by the staleness rule of specs/ssm_measured.yaml and hides the person without it."""

from __future__ import annotations

import math
import os

import numpy as np
import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def _filter(block):
    from ethimon.sim import SimBlock
    from ethimon.sim._runner import _signal_filter
    return _signal_filter(SimBlock.model_validate(block))


def test_latency_delays_by_whole_control_cycles():
    f = _filter({"control_hz": 60, "sensors": {"human_distance": {"latency_s": 0.05}}})  # 3 cycles
    seen = [f(k / 60, {"human_distance": float(k)})["human_distance"] for k in range(8)]
    assert seen == [0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0]


def test_noise_is_seeded_gaussian_and_clipped_at_zero():
    def run(seed, true=1.0, n=2000):
        f = _filter({"sensors": {"human_speed": {"noise": 0.1, "seed": seed}}})
        return np.array([f(k / 60, {"human_speed": true})["human_speed"] for k in range(n)])
    a, b, c = run(1), run(1), run(2)
    assert np.array_equal(a, b) and not np.array_equal(a, c)
    assert abs(a.mean() - 1.0) < 0.01 and abs(a.std() - 0.1) < 0.01
    assert run(1, true=0.0).min() == 0.0  # a speed or distance never reads negative


def test_noise_of_one_signal_does_not_change_another_signals_stream():
    f1 = _filter({"sensors": {"human_speed": {"noise": 0.1}}})
    f2 = _filter({"sensors": {"human_speed": {"noise": 0.1}, "human_distance": {"noise": 0.1}}})
    x1 = [f1(k / 60, {"human_speed": 1.0, "human_distance": 1.0})["human_speed"] for k in range(50)]
    x2 = [f2(k / 60, {"human_speed": 1.0, "human_distance": 1.0})["human_speed"] for k in range(50)]
    assert x1 == x2


def test_stuck_at_a_value_and_frozen_and_the_dropout_still_wins():
    f = _filter({"stuck_at": [{"signal": "human_distance", "from_s": 0.1, "to_s": 0.2},
                              {"signal": "human_speed", "from_s": 0.0, "value": 0.0}],
                 "dropouts": [{"signal": "human_distance", "from_s": 0.15, "to_s": 0.16}]})
    out = [f(k * 0.05, {"human_distance": 3.0 - k, "human_speed": 1.5}) for k in range(6)]
    assert [o["human_distance"] for o in out[:2]] == [3.0, 2.0]
    assert out[2]["human_distance"] == 1.0                # frozen at the reading at from_s
    assert math.isnan(out[3]["human_distance"])           # a dropout over a stuck sensor
    assert out[4]["human_distance"] == -1.0               # after to_s: live again
    assert all(o["human_speed"] == 0.0 for o in out)


def test_sensors_and_stuck_at_name_simulated_signals_only():
    from ethimon.sim import SimBlock
    with pytest.raises(ValueError, match="sensors names 'human_distnace'"):
        SimBlock.model_validate({"sensors": {"human_distnace": {"noise": 0.1}}})
    with pytest.raises(ValueError, match="stuck_at names 'p_unsafe'"):
        SimBlock.model_validate({"stuck_at": [{"signal": "p_unsafe", "from_s": 0}]})
    with pytest.raises(ValueError, match="finite"):
        SimBlock.model_validate({"stuck_at": [{"signal": "human_speed", "from_s": 0, "value": "nan"}]})


@pytest.mark.slow
@pytest.mark.sim
def test_human_speed_is_measured_from_the_persons_motion():
    pytest.importorskip("pybullet")
    from ethimon.sim import ArmSim, Human
    walker = Human.model_validate({"name": "w", "waypoints": [{"t_s": 0, "xy_m": [3.0, 0]},
                                                               {"t_s": 2.0, "xy_m": [1.0, 0]}]})
    still = Human.model_validate({"name": "s", "waypoints": [{"t_s": 0, "xy_m": [0, 2.0]}]})
    with ArmSim(humans=[walker]) as sim:
        speeds = []
        for _ in range(60):
            speeds.append(sim.signals()["human_speed"])
            sim.step()
        assert speeds[0] == 0.0                            # no previous reading yet
        assert speeds[10:] == pytest.approx([1.0] * 50, rel=1e-6)   # 2 m in 2 s
    with ArmSim(humans=[still]) as sim:
        for _ in range(5):
            assert sim.signals()["human_speed"] == 0.0
            sim.step()


@pytest.mark.slow
@pytest.mark.sim
def test_robot_speed_toward_human_is_the_closest_points_approach_speed():
    pytest.importorskip("pybullet")
    from ethimon.sim import ArmSim, Human
    h = Human.model_validate({"name": "w", "waypoints": [{"t_s": 0, "xy_m": [0.45, -1.2]}]})
    with ArmSim(humans=[h]) as sim:
        q, _ = sim.joint_state()
        toward, away = [], []
        for k in range(30):       # joint 1 turns the arm toward the person (-y) ...
            sim.command_joints(q - np.array([0.02 * k, 0, 0, 0, 0, 0, 0]))
            sim.step()
            s = sim.signals()
            toward.append(s["robot_speed_toward_human"])
        q2, _ = sim.joint_state()
        for k in range(30):       # ... then away from them
            sim.command_joints(q2 + np.array([0.02 * k, 0, 0, 0, 0, 0, 0]))
            sim.step()
            away.append(sim.signals()["robot_speed_toward_human"])
        assert max(toward[5:]) > 0.2
        assert max(away[10:]) == 0.0                       # moving away: 0, never negative
    with ArmSim() as sim:                                  # nobody in the cell
        assert sim.signals()["robot_speed_toward_human"] == 0.0 and sim.signals()["human_speed"] == 0.0


def _scenario(name):
    import yaml
    with open(os.path.join(ROOT, "scenarios", "sim", name)) as fh:
        return yaml.safe_load(fh)


@pytest.mark.slow
@pytest.mark.sim
def test_a_stuck_distance_sensor_is_caught_by_the_staleness_rule_and_hides_the_person_without_it():
    pytest.importorskip("pybullet")
    import yaml
    import ethimon
    from ethimon.sim import SimBlock, run_sim
    doc = _scenario("stuck_distance_sensor.yaml")
    block = SimBlock.model_validate(doc["sim"])
    path = os.path.join(ROOT, "specs", "ssm_measured.yaml")
    caught = run_sim(block, ethimon.Monitor(ethimon.load_spec(path)), p_unsafe=0.0)
    assert caught.executed_response == "stop_1" and "distance_sensor_alive" in caught.fired
    assert caught.first_override_cycle == 69            # the fault at cycle 60 + 9 repeats
    assert caught.min_separation_m > 0.1 and caught.max_contact_force_n == 0.0
    with open(path) as fh:
        spec_doc = yaml.safe_load(fh)
    spec_doc["obligations"] = [o for o in spec_doc["obligations"] if o["id"] != "distance_sensor_alive"]
    blind = run_sim(block, ethimon.Monitor(_spec_from(spec_doc)), p_unsafe=0.0)
    assert "separation" not in blind.fired             # the stuck reading hides the person ...
    assert blind.min_separation_m < 0.05                # ... and the arm reaches them


def _spec_from(doc):
    import tempfile
    import yaml
    import ethimon
    with tempfile.NamedTemporaryFile("w", suffix=".yaml", delete=False) as fh:
        yaml.safe_dump(doc, fh)
    try:
        return ethimon.load_spec(fh.name)
    finally:
        os.unlink(fh.name)
