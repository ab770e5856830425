"""A held object on power loss (issue 14): the grasp is the fingers' friction, a gripper that
is not self-locking lets go when motor power is removed (stop 0, or stop 1 at its power-off),
a self-locking one keeps it, and a pull beyond the friction slips the object out (DIRECT
PyBullet)."""

from __future__ import annotations

import numpy as np
import pytest

pytestmark = pytest.mark.sim

KNIFE = {"name": "knife", "shape": "box", "xyz_m": [0.3, 0.5, 0.02],
         "half_extents_m": [0.1, 0.012, 0.004], "mass_kg": 0.15, "hazard": "sharp"}


def _cell(gripper=None, obj=KNIFE):
    pytest.importorskip("pybullet")
    from ethimon.sim import ArmSim, SimBlock
    block = {"start_xyz_m": [0.5, 0.0, 0.4], "start_holding": obj["name"], "objects": [obj]}
    if gripper is not None:
        block["gripper"] = gripper
    return ArmSim.from_block(SimBlock.model_validate(block))


def _hold_still(sim, cycles):
    q, _ = sim.joint_state()
    for _ in range(cycles):
        sim.command_joints(q)
        sim.step()


@pytest.mark.slow
def test_a_powered_grasp_holds_the_object():
    with _cell() as sim:
        _hold_still(sim, 60)
        assert sim.held == "knife" and sim.dropped == []
        assert sim.object_z()["knife"] > 0.3
        assert sim.grip_capacity_n == pytest.approx(70.0)  # 2 x 0.5 x 70 N


@pytest.mark.slow
def test_stop_0_drops_the_object_from_a_gripper_that_is_not_self_locking():
    with _cell() as sim:
        _hold_still(sim, 10)
        sim.command_torque_off()
        for _ in range(90):
            sim.command_torque_off()
            sim.step()
        assert sim.held is None
        assert [(n, why) for n, _, why in sim.dropped] == [("knife", "power_off")]
        assert sim.object_z()["knife"] < 0.05          # on the floor, not in the hand


@pytest.mark.slow
def test_a_self_locking_gripper_keeps_the_object_without_power():
    with _cell({"self_locking": True}) as sim:
        _hold_still(sim, 10)
        z0 = sim.object_z()["knife"]
        for _ in range(90):
            sim.command_torque_off()
            sim.step()
        assert sim.held == "knife" and sim.dropped == []
        assert abs(sim.object_z()["knife"] - z0) < 0.12  # rides with the (slightly sagging) hand


@pytest.mark.slow
def test_stop_1_drops_the_object_at_its_power_off_not_before():
    from ethimon.sim._control import StopController
    with _cell() as sim:
        _hold_still(sim, 10)
        q, qd = sim.joint_state()
        stop = StopController(1, q, qd, 0.25)
        held_until_power_off = True
        for _ in range(120):
            stop.command(sim)
            if sim.powered and sim.held != "knife":
                held_until_power_off = False
            sim.step()
        assert stop.powered_off and held_until_power_off
        assert sim.dropped and sim.dropped[0][2] == "power_off"
        assert sim.object_z()["knife"] < 0.05


def test_a_pull_beyond_the_fingers_friction_slips_the_object_out():
    heavy = dict(KNIFE, name="brick", mass_kg=2.0, hazard=None)
    with _cell({"grasp_force_n": 5.0, "friction_coefficient": 0.5}, heavy) as sim:  # 5 N < 19.6 N weight
        _hold_still(sim, 60)
        assert [(n, why) for n, _, why in sim.dropped] == [("brick", "slipped")]
        assert sim.held is None


def test_expectation_keys_object_dropped_and_end_height():
    from ethimon.sim import SimBlock, check_sim_expectations
    from ethimon.sim._runner import SimResult
    block = SimBlock.model_validate({"objects": [KNIFE], "expect": {
        "object_dropped": True, "object_end_z_m": {"knife": [0.0, 0.05]}}})
    kept = SimResult(object_end_z_m={"knife": 0.4})
    probs = check_sim_expectations(block, kept)
    assert any("object_dropped: true" in p for p in probs)
    assert any("knife ends at height 0.4" in p for p in probs)
    fell = SimResult(dropped=(("knife", 0.33, "power_off"),), object_end_z_m={"knife": 0.004})
    assert check_sim_expectations(block, fell) == []
    with pytest.raises(ValueError, match="unknown object 'fork'"):
        SimBlock.model_validate({"objects": [KNIFE], "expect": {"object_end_z_m": {"fork": [0, 1]}}})
