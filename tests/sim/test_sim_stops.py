"""Stops that stop (issue 14 items 1 and 4): rated-limited deceleration from the current
velocity, stop 1 to standstill then power off, stop 2 standstill monitoring, the brake
model, and the rated Panda limits in every controller (DIRECT PyBullet)."""

from __future__ import annotations

import numpy as np
import pytest

pytestmark = pytest.mark.sim

SAFE = np.array([0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785])


@pytest.fixture
def sim():
    pytest.importorskip("pybullet")
    from ethimon.sim import ArmSim
    s = ArmSim(control_hz=60)
    yield s
    s.close()


def _fast_motion(sim, v_task=2.6, cycles=40):
    """A fast base-joint sweep; returns the joint state after ``cycles`` control cycles."""
    from ethimon.sim._arm import Segment
    from ethimon.sim._control import TaskController, _timed
    q0, _ = sim.joint_state()
    target = q0.copy()
    target[0], target[1] = 2.4, -0.4
    task = TaskController([Segment(q=target, duration_s=_timed(q0, target, None, v_task))], q0, v_task)
    for _ in range(cycles):
        task.command(sim)
        sim.step()
    return sim.joint_state()


def _run(sim, ctrl, cycles):
    speeds, ratios = [], []
    for _ in range(cycles):
        ctrl.command(sim)
        sim.step()
        speeds.append(sim.max_joint_speed_substep)
        ratios.append(sim.max_accel_ratio_substep)
    return speeds, ratios


def test_task_motion_keeps_the_rated_speed(sim):
    """A task asking for 2.6 rad/s gets the rated 2.175 rad/s at most (joint 1)."""
    from ethimon.sim._limits import RATED_DQ_MAX
    peak = 0.0
    from ethimon.sim._arm import Segment
    from ethimon.sim._control import TaskController
    q0, _ = sim.joint_state()
    target = q0.copy()
    target[0] = 2.4
    task = TaskController([Segment(q=target, duration_s=0.25)], q0, 2.6)  # far too short
    for _ in range(90):
        task.command(sim)
        sim.step()
        peak = max(peak, sim.max_joint_speed_substep)
        assert sim.max_accel_ratio_substep <= 1.02
    assert peak <= RATED_DQ_MAX[0] * 1.01


@pytest.mark.parametrize("category", [1, 2])
def test_controlled_stop_never_speeds_up_and_keeps_rated_acceleration(sim, category):
    from ethimon.sim._control import StopController
    q, qd = _fast_motion(sim)
    v0 = float(np.max(np.abs(qd)))
    assert v0 > 1.5
    stop = StopController(category, q, qd, 0.25)
    speeds, ratios = _run(sim, stop, 60)
    assert max(speeds) <= v0 * 1.01 + 1e-3          # nothing adds speed (was +45..73 %)
    assert max(ratios) <= 1.02                      # within the rated acceleration of each joint
    assert stop.standstill_s is not None and stop.standstill_s <= stop.stop_time_s + 0.2
    if category == 1:
        assert stop.powered_off and not sim.powered
    else:
        assert sim.powered and not stop.escalated


def test_stop_1_engages_brakes_at_standstill_so_the_arm_does_not_sag(sim):
    from ethimon.sim._control import StopController
    q, qd = _fast_motion(sim)
    stop = StopController(1, q, qd, 0.25)
    _run(sim, stop, 45)
    assert not sim.powered
    q_off, _ = sim.joint_state()
    speeds, ratios = _run(sim, stop, 30)
    assert max(speeds) < 0.01 and np.max(np.abs(sim.joint_state()[0] - q_off)) < 1e-3


def test_stop_2_drift_escalates_to_stop_0(sim):
    from ethimon.sim._control import StopController
    q, qd = sim.joint_state()
    stop = StopController(2, q, qd, 0.25, standstill_tol_rad=0.02)
    _run(sim, stop, 20)
    assert stop.name == "stop_2" and sim.powered
    # an external push the motors cannot hold: move the held pose from outside
    p = sim._p
    p.resetJointState(sim.robot, 0, float(q[0]) + 0.05, 0.0, physicsClientId=sim.cid)
    stop.command(sim)
    assert stop.escalated and stop.name == "stop_0" and not sim.powered


def test_stop_0_brake_delay_and_deceleration(sim):
    """Power off from 2 rad/s: the joints coast for BRAKE_ENGAGE_S, then slow at about the
    assumed brake deceleration (not the 25 ms / 0.018 rad of an instant brake)."""
    from ethimon.sim._control import StopController
    from ethimon.sim._limits import BRAKE_DECEL_RAD_S2, BRAKE_ENGAGE_S
    q, qd = _fast_motion(sim)
    v0 = abs(float(qd[0]))
    stop = StopController(0, q, qd, 0.25)
    t = 0.0
    while float(np.max(np.abs(sim.joint_state()[1]))) > 0.01 and t < 1.0:
        stop.command(sim)
        sim.step()
        t += sim.dt
    expect = BRAKE_ENGAGE_S + v0 / BRAKE_DECEL_RAD_S2[0]
    assert t >= expect - 2 * sim.dt
    assert t <= expect + 0.1
    moved = abs(float(sim.joint_state()[0][0] - q[0]))
    assert moved >= v0 * BRAKE_ENGAGE_S + 0.5 * v0 * v0 / BRAKE_DECEL_RAD_S2[0] * 0.8


@pytest.mark.slow
def test_safe_pose_switch_respects_the_current_velocity(sim):
    """The switch from a fast task motion to the safe pose keeps the rated acceleration
    (was 45..74 rad/s² at the switch)."""
    from ethimon.sim._safe_pose import SafePoseController
    q, qd = _fast_motion(sim, v_task=1.5, cycles=90)
    assert float(np.max(np.abs(qd))) > 1.0
    sp = SafePoseController(q, SAFE, 1.0)
    speeds, ratios = _run(sim, sp, 240)
    assert max(ratios) <= 1.02
    assert np.max(np.abs(sim.joint_state()[0] - SAFE)) <= 0.02


def test_commands_are_clipped_to_the_rated_position_range(sim):
    from ethimon.sim._limits import RATED_Q_MAX
    q, _ = sim.joint_state()
    target = q.copy()
    target[3] = 0.3  # beyond the rated -0.0698 rad of joint 4 (URDF allows 0.0)
    from ethimon.sim._arm import Segment
    from ethimon.sim._control import TaskController
    task = TaskController([Segment(q=target, duration_s=1.5)], q, 0.8)
    for _ in range(150):
        task.command(sim)
        sim.step()
    assert sim.joint_state()[0][3] <= RATED_Q_MAX[3] + 0.005


def test_safe_pose_outside_the_rated_range_is_named():
    from ethimon.sim._limits import safe_pose_problem
    msg = safe_pose_problem((0.0, -0.785, 0.0, -2.356, 0.0, -0.3, 3.0))
    assert "joint 6 = -0.3" in msg and "joint 7 = 3" in msg and "joint 1" not in msg
    assert safe_pose_problem(tuple(SAFE)) is None


def test_lint_names_safe_pose_joints_outside_the_rated_range(tmp_path, capsys):
    """A spec whose safe pose lies outside the Panda's rated range fails `ethimon lint`
    with the file, line and column of the first bad joint (it passed before)."""
    from pathlib import Path

    from ethimon.cli import main
    src = (Path(__file__).resolve().parents[2] / "specs" / "cobot_cell.yaml").read_text()
    good = "joints_rad: [0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785]"
    assert good in src
    bad = tmp_path / "bad.yaml"
    bad.write_text(src.replace(good, "joints_rad: [0.0, -0.785, 0.0, 0.2, 0.0, 1.571, 3.1]"))
    assert main(["lint", str(bad)]) == 2
    err = capsys.readouterr().err
    line = next(i for i, ln in enumerate(bad.read_text().splitlines(), 1) if "joints_rad" in ln)
    assert f"bad.yaml:{line}:" in err and "joint 4 = 0.2" in err and "joint 7 = 3.1" in err


def test_inputs_at_cannot_override_a_simulated_signal():
    """issue 14: an inputs_at value replaced a simulated signal (a stuck value hid a person
    at 0.04 m), contrary to the README; now it is refused at validation."""
    from pydantic import ValidationError

    from ethimon.sim import SimBlock
    with pytest.raises(ValidationError, match="human_distance.*dropouts"):
        SimBlock.model_validate({"inputs_at": [{"t_s": 1.0, "inputs": {"human_distance": 2.0}}]})
    SimBlock.model_validate({"inputs_at": [{"t_s": 1.0, "inputs": {"p_unsafe": 0.9}}]})
