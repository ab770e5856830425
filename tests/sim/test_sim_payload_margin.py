"""Issue 32 (item 1 remainder): a rated payload never falls at any stop. A brake must hold the
gravity load with the project's safety factor (``ethimon._robot.BRAKE_SAFETY_FACTOR``, 1.5, a lead's
decision); a stop 0/1 with less margin where the arm is escalates to a powered stop 2 (the reason in
the brake log, so in the cycle record's ``escalated`` and the audit log), and power goes off only
once the arm at rest is held with the factor."""

from __future__ import annotations

import numpy as np
import pytest

from ethimon import _robot

pytestmark = pytest.mark.sim

#: the worst pose for joint 2 with the rated 3 kg at the grasp point: 79.3 N·m against 87 N·m
WORST_J2 = (1.108, 1.351, 0.014, -0.472, 2.603, 2.444, -1.753)


def test_the_safety_factor_is_a_stated_data_constant():
    assert _robot.BRAKE_SAFETY_FACTOR == 1.5
    load = abs(_robot.gravity_torque(WORST_J2, 3.0)[1])
    assert _robot.BRAKE_HOLDING_N_M[1] / load < _robot.BRAKE_SAFETY_FACTOR  # 1.10: under the factor


def _held_3kg_at_worst_pose(sim_objects_mass: float = 3.0):
    from ethimon.sim import ArmSim, SimObject
    from ethimon.sim._model import Gripper
    pot = SimObject(name="pot", shape="box", xyz_m=(0.5, 0.0, 0.5), half_extents_m=(0.03,) * 3,
                    mass_kg=sim_objects_mass)
    sim = ArmSim(objects=[pot], start_joints_rad=WORST_J2, gripper=Gripper(self_locking=True))
    sim.hold_at_start("pot")
    q0, _ = sim.joint_state()
    for _ in range(10):
        sim.command_joints(q0)
        sim.step()
    return sim


@pytest.mark.slow
def test_stop0_with_the_rated_payload_at_the_worst_pose_drops_the_hand_under_5_mm():
    """Failed first: the power went off (87 N·m brake, 79.3 N·m load, 8 N·m to arrest the 30 ms
    coast) and the grasp point sank about 0.15 m before the brakes held."""
    pytest.importorskip("pybullet")
    from ethimon.sim._control import StopController
    sim = _held_3kg_at_worst_pose()
    try:
        z0 = sim._grasp_z()
        stop = StopController(0, *sim.joint_state(), 0.25)
        for _ in range(45):
            stop.command(sim)
            sim.step()
        drop = z0 - min(z0, sim._grasp_z())
        assert drop < 0.005, drop
        assert sim.powered and sim.held == "pot"  # held powered: a stop 2
        why = sim.power_off_refused
        assert why is not None and why.startswith("stop 0: power-off refused")
        assert "safety factor 1.5" in why and "joint 2 needs 79.3 N·m" in why and "held powered (a stop 2)" in why
        assert sim.brake_log and "refused" in sim.brake_log[0][1]
        assert float(np.max(np.abs(sim.joint_state()[1]))) < 0.01
    finally:
        sim.close()


@pytest.mark.slow
def test_the_powered_hold_cuts_power_once_the_arm_is_held_with_the_factor():
    """The refused power-off holds powered; when the load at rest falls within the factor (here the
    payload is put down) the next power-off check at standstill removes power, brakes engaged."""
    pytest.importorskip("pybullet")
    from ethimon.sim._control import StopController
    sim = _held_3kg_at_worst_pose()
    try:
        stop = StopController(0, *sim.joint_state(), 0.25)
        for _ in range(6):
            stop.command(sim)
            sim.step()
        assert sim.powered and sim.power_off_refused is not None
        sim.detach()  # the pot is taken from the hand: arm alone, within the factor
        for _ in range(6):
            stop.command(sim)
            sim.step()
        assert not sim.powered and sim.brakes_engaged and sim.power_off_refused is None
        assert "power off" in sim.brake_log[-1][1] and "after the powered hold" in sim.brake_log[-1][1]
        assert sim.max_drop_unpowered_m < 0.001
    finally:
        sim.close()


@pytest.mark.slow
def test_scenario_payload_rated_stop0_worst_pose_holds_and_says_why():
    """Failed first: powered_off true, brakes_escalated false, the pot ended 0.15 m low."""
    pytest.importorskip("pybullet")
    from ethimon.sim import check_sim_expectations
    from tests.sim._scenarios import run_scenario
    block, res = run_scenario("payload_rated_stop0_worst_pose")
    assert check_sim_expectations(block, res) == []
    esc = [r for r in res.trace if r.escalated]
    assert esc and esc[0].powered and "safety factor 1.5" in esc[0].escalated
    assert res.dropped == ()
