"""The PyBullet arm pieces on their own: cell, signals, controllers, model (DIRECT mode)."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
from pydantic import ValidationError

from ethimon.sim import SimBlock

SAFE = (0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785)


@pytest.fixture(autouse=True)
def _needs_pybullet(request):
    if request.node.get_closest_marker("sim"):
        pytest.importorskip("pybullet")


@pytest.mark.slow
def test_import_is_light():
    code = ("import sys, ethimon.sim, ethimon.sim._model; "
            "assert 'pybullet' not in sys.modules, 'ethimon.sim imported pybullet'")
    subprocess.run([sys.executable, "-c", code], check=True)


def test_sim_block_forbids_unknown_keys_and_checks_names():
    with pytest.raises(ValidationError, match="duraton_s"):
        SimBlock.model_validate({"duraton_s": 3})
    with pytest.raises(ValidationError, match="unknown object 'cup'"):
        SimBlock.model_validate({"task": [{"primitive": "pick", "object": "cup"}]})
    with pytest.raises(ValidationError, match="must divide"):
        SimBlock.model_validate({"control_hz": 50})
    with pytest.raises(ValidationError, match="exactly one"):
        SimBlock.model_validate({"task": [{"primitive": "reach"}]})


@pytest.fixture
def sim(_needs_pybullet):
    from ethimon.sim import ArmSim
    s = ArmSim(control_hz=60)
    yield s
    s.close()


@pytest.mark.sim
def test_human_capsule_distance_is_right():
    """Capsule (r = 0.2) at x = 1.0 and a 0.1 m box at the origin: 1.0 − 0.2 − 0.1 = 0.7 m."""
    from ethimon.sim import ArmSim, Human, SimObject
    human = Human(name="h", radius_m=0.2, height_m=1.7, waypoints=[{"t_s": 0, "xy_m": (1.0, 3.0)}])
    box = SimObject(name="b", xyz_m=(0.0, 3.0, 0.5), half_extents_m=(0.1, 0.1, 0.1), fixed=True)
    with ArmSim(humans=[human], objects=[box]) as s:
        d = s.distance(s.objects["b"], s.humans["h"].body)
        assert d == pytest.approx(0.7, abs=2e-3)
        # the arm is ~3 m away: the human_distance signal sees the arm, not the box
        assert s.signals()["human_distance"] > 2.5


@pytest.mark.sim
def test_human_follows_waypoints():
    from ethimon.sim import ArmSim, Human
    h = Human(name="w", waypoints=[{"t_s": 0, "xy_m": (3.0, 0.0)}, {"t_s": 1.0, "xy_m": (1.0, 0.0)}])
    with ArmSim(control_hz=60, humans=[h]) as s:
        d0 = s.signals()["human_distance"]
        for _ in range(30):
            s.step()
        assert s.human_position("w")[0] == pytest.approx(2.0, abs=1e-9)
        assert s.signals()["human_distance"] == pytest.approx(d0 - 1.0, abs=0.02)


@pytest.mark.sim
def test_safe_pose_controller_respects_limit_and_arrives(sim):
    from ethimon.sim._safe_pose import SafePoseController
    start = np.array([0.6, -0.2, 0.3, -1.8, 0.2, 1.9, 0.4])
    sim.reset_joints(start)
    sp = SafePoseController(start, SAFE, 1.0)
    peak = 0.0
    for k in range(120):
        sp.command(sim)
        sim.step()
        peak = max(peak, sim.max_joint_speed_substep)
        q, _ = sim.joint_state()
        if np.max(np.abs(q - SAFE)) <= 0.02:
            break
    assert np.max(np.abs(q - SAFE)) <= 0.02
    assert (k + 1) / 60 <= 1.5
    assert peak <= 1.0


@pytest.mark.sim
def test_stop_0_leaves_motors_unpowered(sim):
    from ethimon.sim._control import StopController
    from ethimon.sim._limits import BRAKE_ENGAGE_S
    q, qd = sim.joint_state()
    stop = StopController(0, q, qd, 0.25)
    stop.command(sim)  # the very first command of the stop removes power
    assert not sim.powered
    assert not sim.brakes_engaged  # the (assumed) engagement delay: the joints coast first
    engaged_at = None
    for k in range(31):
        sim.step()
        if engaged_at is None and sim.brakes_engaged:
            engaged_at = (k + 1) / 60
        stop.command(sim)
    assert engaged_at == pytest.approx(BRAKE_ENGAGE_S, abs=1 / 60)
    q2, qd2 = sim.joint_state()
    assert np.max(np.abs(qd2)) < 1e-3            # braked to rest ...
    assert np.max(np.abs(q2 - q)) < 0.1          # ... after a sag while the brakes engage
    for _ in range(30):
        stop.command(sim)
        sim.step()
    assert np.max(np.abs(sim.joint_state()[0] - q2)) < 1e-3  # and the brakes hold against gravity


@pytest.mark.sim
def test_stop_0_without_brakes_sags():
    from ethimon.sim import ArmSim
    from ethimon.sim._control import StopController
    with ArmSim(control_hz=60, brakes=False) as s:
        q, qd = s.joint_state()
        stop = StopController(0, q, qd, 0.25)
        for _ in range(31):
            stop.command(s)
            s.step()
        assert not s.powered
        assert np.max(np.abs(s.joint_state()[0] - q)) > 0.05  # nothing holds the arm up


def _mid_motion(sim):
    """Drive the arm for 1 s of a 2 s joint move; returns the joint state mid-motion."""
    from ethimon.sim._arm import Segment
    from ethimon.sim._control import TaskController
    target = np.array(SAFE) + np.array([0.8, 0.3, 0.0, 0.3, 0.0, 0.0, 0.0])
    q0, _ = sim.joint_state()
    task = TaskController([Segment(q=target, duration_s=2.0)], q0, 0.8)
    for _ in range(60):  # mid-motion
        task.command(sim)
        sim.step()
    q, qd = sim.joint_state()
    return q, qd


@pytest.mark.sim
@pytest.mark.parametrize("category", [1, 2])
def test_controlled_stops(sim, category):
    from ethimon.sim._control import StopController
    q, qd = _mid_motion(sim)
    assert np.max(np.abs(qd)) > 0.3
    stop = StopController(category, q, qd, 0.25)
    for _ in range(15):  # the 0.25 s ramp
        stop.command(sim)
        sim.step()
    assert np.max(np.abs(sim.joint_state()[1])) < 0.1  # a controlled stop: speed ramped out
    for _ in range(15):
        stop.command(sim)
        sim.step()
    q_end, qd_end = sim.joint_state()
    if category == 2:
        assert sim.powered and np.max(np.abs(qd_end)) < 0.02   # held still, power on
        for _ in range(30):
            stop.command(sim)
            sim.step()
        assert np.max(np.abs(sim.joint_state()[0] - q_end)) < 0.01
    else:
        assert not sim.powered                       # stopped, then power off
        for _ in range(30):
            stop.command(sim)
            sim.step()
        assert np.max(np.abs(sim.joint_state()[0] - q_end)) < 0.02  # unpowered, held by the brakes


@pytest.mark.sim
def test_stop_0_brakes_a_moving_arm_to_rest(sim):
    from ethimon.sim._control import StopController
    q, qd = _mid_motion(sim)
    assert np.max(np.abs(qd)) > 0.3
    stop = StopController(0, q, qd, 0.25)
    for _ in range(30):  # 0.5 s after power off
        stop.command(sim)
        sim.step()
    assert not sim.powered and np.max(np.abs(sim.joint_state()[1])) < 0.05
