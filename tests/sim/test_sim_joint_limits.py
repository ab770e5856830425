"""Issue 23, limits never crossed: stops plan inside the rated range, the servo sheds speed
before a limit, an engaged brake holds its position (DIRECT PyBullet)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import yaml

import ethimon

ROOT = Path(__file__).resolve().parents[2]
SPEC = ROOT / "specs" / "cobot_cell.yaml"


def test_a_stop_never_plans_a_joint_past_its_rated_limit():
    from ethimon.sim._control import _Decel
    from ethimon.sim._limits import LIMIT_MARGIN_RAD, RATED_Q_MAX
    q0 = np.array([2.85, -0.3, 0.0, -0.12, 0.0, 1.6, 0.785])
    qd0 = np.array([0.6, 0.1, 0.0, 0.5, 0.0, 0.0, 0.0])
    d = _Decel(q0, qd0, 0.25)
    assert d.q_end[0] <= RATED_Q_MAX[0] - LIMIT_MARGIN_RAD + 1e-12
    assert d.q_end[3] <= RATED_Q_MAX[3] - LIMIT_MARGIN_RAD + 1e-12
    # the other joints keep the common deceleration time (the stop keeps the path's direction)
    assert d.Tj[1] == pytest.approx(d.T) and d.Tj[0] < d.T
    for t in np.linspace(0, d.T, 50):  # the speed only falls, for every joint
        _, qd = d.at(float(t))
        assert np.all(np.abs(qd) <= np.abs(qd0) + 1e-12)


@pytest.mark.slow
@pytest.mark.sim
def test_stop_1_near_joint_limits_ends_inside_and_the_brakes_do_not_creep():
    """Before: 2.07 mrad past (joint 4 creeping 0.55 mrad/s with the brakes on)."""
    pytest.importorskip("pybullet")
    from ethimon.sim import SimBlock, check_sim_expectations, run_sim
    doc = yaml.safe_load((ROOT / "scenarios" / "sim" / "stop_near_joint_limit.yaml").read_text())
    block = SimBlock.model_validate(doc["sim"])
    res = run_sim(block, ethimon.Monitor(ethimon.load_spec(str(SPEC))), p_unsafe=0.02)
    assert check_sim_expectations(block, res) == []
    assert res.max_past_limit_mrad == 0.0 and not res.powered_at_end


@pytest.mark.slow
@pytest.mark.sim
def test_an_engaged_brake_holds_the_position_it_stopped_at():
    pytest.importorskip("pybullet")
    from ethimon.sim import ArmSim
    q = [0.0, 0.6, 0.0, -0.3, 0.0, 1.6, 0.785]  # stretched forward: gravity loads the elbow
    with ArmSim(start_joints_rad=q) as sim:
        for _ in range(10):
            sim.command_joints(q)
            sim.step()
        sim.command_torque_off(brakes_already_engaged=True)
        sim.step()
        held, _ = sim.joint_state()
        for _ in range(180):  # 3 s braked
            sim.command_torque_off()
            sim.step()
        now, _ = sim.joint_state()
        assert float(np.max(np.abs(now - held))) < 1e-4
