"""Issue 23, payload: decelerating with a held object up to the Panda's rated 3 kg stays
within the rated accelerations, and the speed never rises after the command (DIRECT)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import yaml

import ethimon

ROOT = Path(__file__).resolve().parents[2]
SPEC = ROOT / "specs" / "cobot_cell.yaml"

pytestmark = pytest.mark.sim


@pytest.fixture(autouse=True)
def _pybullet():
    pytest.importorskip("pybullet")


@pytest.mark.slow
def test_the_planning_probe_keeps_the_held_objects_velocity():
    """The cause of the spikes: resetting the held object's pose to probe zeroed its velocity."""
    from ethimon.sim import ArmSim, SimObject
    pot = SimObject(name="pot", shape="cylinder", xyz_m=(0.3, -0.5, 0.3), radius_m=0.08,
                    height_m=0.12, mass_kg=3.0)
    with ArmSim(objects=[pot], start_joints_rad=[-1.2, -0.6, 0.0, -2.2, 0.0, 1.6, 0.785]) as sim:
        sim.hold_at_start("pot")
        q, _ = sim.joint_state()
        for i in range(30):
            sim.command_joints(q + np.array([0.02 * (i + 1), 0, 0, 0, 0, 0, 0]),
                               np.array([1.2, 0, 0, 0, 0, 0, 0]))
            sim.step()
        body = sim.objects["pot"]
        before = np.array(sim._p.getBaseVelocity(body, physicsClientId=sim.cid)[0])
        sim.probe([q, q + 0.1])
        after = np.array(sim._p.getBaseVelocity(body, physicsClientId=sim.cid)[0])
        assert np.linalg.norm(before) > 0.2
        assert np.allclose(before, after)


@pytest.mark.slow
@pytest.mark.parametrize("mass", [0.0, 0.6, 3.0])
def test_safe_pose_deceleration_with_any_payload_up_to_3_kg_keeps_the_ratings(mass):
    """Before: 14.7 x rated with 3 kg (2.85 x with 0.6 kg), the speed rising 1.71 -> 1.83 rad/s."""
    from ethimon.sim import SimBlock, check_sim_expectations, run_sim
    doc = yaml.safe_load((ROOT / "scenarios" / "sim" / "hot_pot_full_speed.yaml").read_text())
    if mass == 0.0:
        doc["sim"].pop("start_holding")
        doc["sim"]["expect"].pop("object_dropped")
    else:
        doc["sim"]["objects"][0]["mass_kg"] = mass
    block = SimBlock.model_validate(doc["sim"])
    res = run_sim(block, ethimon.Monitor(ethimon.load_spec(str(SPEC))), p_unsafe=0.02)
    assert check_sim_expectations(block, res) == []
    assert res.max_accel_ratio <= 1.0 and res.stop_speed_gain <= 1.01
