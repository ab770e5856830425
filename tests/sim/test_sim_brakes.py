"""Issue 32, brakes and payload as data: each joint's brake holding torque is a sourced number
(``ethimon._robot.BRAKE_TABLE``), the gravity load of arm + payload is computed at every power-off,
a power-off the brakes cannot hold is refused (a powered hold, with the reason), and
``verify``'s ``lint.brakes`` names poses and payloads where a stop 0/1 would let the arm fall."""

from __future__ import annotations

import types

import numpy as np
import pytest

import ethimon
from ethimon import _robot
from tests.sim._scenarios import ROOT, SPEC, run_scenario

STRETCHED = (0.0, 1.0, 0.0, -0.4, 0.0, 1.4, 0.785)
#: the worst pose for joint 2 with the rated 3 kg at the grasp point (maximised from 30 starts)
WORST_J2 = (1.108, 1.351, 0.014, -0.472, 2.603, 2.444, -1.753)
WEAK = (60.0, 60.0, 60.0, 60.0, 10.0, 10.0, 10.0)  # the brakes the sim assumed before issue 32


def test_every_brake_number_says_where_it_comes_from():
    assert len(_robot.BRAKE_TABLE) == 7
    for j, (joint, torque, source) in enumerate(_robot.BRAKE_TABLE):
        assert joint == j + 1 and torque == _robot.BRAKE_HOLDING_N_M[j] and "ESTIMATE" in source
    assert _robot.RATED_PAYLOAD_KG == 3.0 and "data sheet" in _robot.RATED_PAYLOAD_SOURCE


def test_the_issue_case_needs_more_than_the_old_brakes_and_less_than_the_table():
    """2.9 kg stretched forward: joint 2 needs 68.6 N·m; the old 60 N·m brake slips, the table holds."""
    load = _robot.gravity_torque(STRETCHED, 2.9)
    assert abs(load[1]) == pytest.approx(68.6, abs=0.05)
    problem = _robot.brake_problem(STRETCHED, 2.9, holding_n_m=WEAK)
    assert problem is not None and "joint 2 needs 68.6" in problem and "60 N·m" in problem
    assert _robot.brake_problem(STRETCHED, 2.9) is None


def test_the_rated_payload_is_held_at_the_worst_pose():
    assert abs(_robot.gravity_torque(WORST_J2, 3.0)[1]) == pytest.approx(79.3, abs=0.1)
    assert _robot.brake_problem(WORST_J2, 3.0) is None
    assert _robot.brake_problem(WORST_J2, 4.0) is not None  # the margin is finite, and said


def _lint(spec_path, monkeypatch=None, holding=None):
    from ethimon.compiler._plans import plan_of
    from ethimon.verify._lints import brakes
    if holding is not None:
        monkeypatch.setattr(_robot, "BRAKE_HOLDING_N_M", holding)
    spec = ethimon.load_spec(str(spec_path))
    return brakes(types.SimpleNamespace(plan=plan_of(spec), spec=spec))


def test_lint_brakes_judges_the_rated_payload_with_the_safety_factor():
    """With BRAKE_SAFETY_FACTOR (1.5, issue 32) the table's 87 N·m do not hold the rated 3 kg at the
    stretched poses (79.3 N·m: 1.10 x): lint.brakes warns and says which factor it used."""
    f = _lint(SPEC)
    assert f.status == "warning" and "rated 3 kg" in f.message and "safety factor 1.5" in f.message
    assert "from 0.73 kg" in f.message and "87 N·m, 1.10 x" in f.message


def test_lint_brakes_names_poses_and_payloads_where_a_stop_would_let_the_arm_fall(monkeypatch):
    f = _lint(SPEC, monkeypatch, WEAK)
    assert f.status == "warning"
    assert "transient_contact" in f.message and "on_fault" in f.message  # the rules that cut power
    assert "joint 2 needs" in f.message and "from 0.00 kg" in f.message and "[0.00, -1.76" in f.message


def test_lint_brakes_is_quiet_without_a_stop_that_cuts_power(tmp_path, monkeypatch):
    text = (ROOT / "specs" / "cobot_cell.yaml").read_text()
    text = text.replace("response: stop_0", "response: stop_2").replace("response: stop_1", "response: stop_2")
    text = text.replace("on_fault: stop_1", "on_fault: stop_2")
    (tmp_path / "s.yaml").write_text(text)
    f = _lint(tmp_path / "s.yaml", monkeypatch, WEAK)
    assert f.status == "ok" and "no rule cuts motor power" in f.message


@pytest.mark.sim
@pytest.mark.slow
def test_gravity_model_equals_pybullets_inverse_dynamics():
    pytest.importorskip("pybullet")
    from ethimon.sim import ArmSim
    rng = np.random.default_rng(3)
    with ArmSim() as sim:
        p, cid, r = sim._p, sim.cid, sim.robot
        for _ in range(40):
            q = rng.uniform(_robot.RATED_Q_MIN, _robot.RATED_Q_MAX)
            full = list(q) + [0.04, 0.04]
            tau = np.array(p.calculateInverseDynamics(r, full, [0.0] * 9, [0.0] * 9, physicsClientId=cid)[:7])
            J = np.array(p.calculateJacobian(r, 11, [0, 0, 0], full, [0.0] * 9, [0.0] * 9,
                                             physicsClientId=cid)[0])[:, :7]
            expected = tau + J.T @ np.array([0.0, 0.0, 9.81 * 2.0])  # 2 kg at the grasp point
            assert np.allclose(_robot.gravity_torque(q, 2.0), expected, atol=1e-6)


@pytest.mark.sim
@pytest.mark.slow
def test_stop1_with_2_9_kg_stretched_out_holds():
    """Failed first: joint 2 fell and the pot ended 0.04 m up (on the floor). Since the brake safety
    factor (1.5; 87 N·m against 68.6 N·m is 1.27 x) the power-off is refused: held powered."""
    pytest.importorskip("pybullet")
    from ethimon.sim import check_sim_expectations
    block, res = run_scenario("payload_stop1_stretched")
    assert check_sim_expectations(block, res) == []
    assert res.powered_at_end and res.brakes_escalated and res.dropped == ()
    assert "joint 2 needs 68.6 N·m" in res.brake_log[0][1] and "safety factor 1.5" in res.brake_log[0][1]


@pytest.mark.sim
@pytest.mark.slow
def test_brakes_that_cannot_hold_turn_the_power_off_into_a_powered_hold_with_the_reason():
    """Failed first (the key did not exist; with 60 N·m brakes the arm fell 0.42 rad)."""
    pytest.importorskip("pybullet")
    from ethimon.sim import check_sim_expectations
    block, res = run_scenario("payload_weak_brakes_held_powered")
    assert check_sim_expectations(block, res) == []
    assert res.powered_at_end and res.brakes_escalated
    why = res.brake_log[0][1]
    assert why.startswith("stop 1: power-off refused") and "joint 2 needs 68.6" in why and "60 N·m" in why
    assert res.object_end_z_m["pot"] > 0.3


@pytest.mark.sim
@pytest.mark.slow
@pytest.mark.parametrize("response", ["stop_0", "stop_1", "stop_2"])
def test_the_rated_payload_never_falls_at_any_stop_at_the_worst_pose(response):
    """3 kg at joint 2's worst pose, each stop: the arm is held. After a stop 1's power-off it does
    not move (under 1 mm); a stop 2 holds powered (the controlled stop itself lets the grasp point
    sink under 1 mm; before issue 32 it crept 0.0098 rad at joint 4 and the stop 2 fell as a stop 0).
    A stop 0 or 1 there is escalated to a powered stop 2: the brake holds the 79.3 N·m load with
    1.10 x, under BRAKE_SAFETY_FACTOR (before that factor a stop 0 sagged 0.15 m)."""
    pytest.importorskip("pybullet")
    from ethimon.sim import ArmSim, SimObject
    from ethimon.sim._control import StopController
    from ethimon.sim._model import Gripper
    pot = SimObject(name="pot", shape="box", xyz_m=(0.5, 0.0, 0.5), half_extents_m=(0.03,) * 3, mass_kg=3.0)
    with ArmSim(objects=[pot], start_joints_rad=WORST_J2, gripper=Gripper(self_locking=True)) as sim:
        sim.hold_at_start("pot")
        q0, _ = sim.joint_state()
        for _ in range(20):
            sim.command_joints(q0)
            sim.step()
        z0 = sim._grasp_z()
        stop = StopController(int(response[-1]), *sim.joint_state(), 0.25)
        for _ in range(120):
            stop.command(sim)
            sim.step()
        assert sim.held == "pot"
        drop = z0 - sim._grasp_z()
        assert drop < 0.003, drop
        if response != "stop_2":  # 87 N·m against 79.3 N·m is under the safety factor 1.5: held powered
            assert sim.powered and sim.power_off_refused is not None
        assert float(np.max(np.abs(sim.joint_state()[1]))) < 0.01  # held, at rest
