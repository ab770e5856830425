"""Issue 32 item 4, restarts per the standards: an acknowledgement is refused until the stop it
would end has completed; an accepted one (a reset) never starts motion, the spec's
``restart.start`` does; a restarted task keeps the slow zone's speed inside the zone."""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

import ethimon
from ethimon.errors import SpecError
from tests.sim._scenarios import run_scenario

ROOT = Path(__file__).resolve().parents[2]
SPEC = ROOT / "specs" / "cobot_cell.yaml"


def _fake_sim(*, powered=True, brakes_engaged=False, qd=0.0):
    return SimpleNamespace(powered=powered, brakes=True, brakes_engaged=brakes_engaged,
                           joint_state=lambda: (np.zeros(7), np.full(7, qd)))


def test_a_stop_1_is_incomplete_until_power_is_off_and_the_brakes_have_engaged():
    from ethimon.sim._control import StopController, stop_incomplete
    stop = StopController(1, np.zeros(7), np.zeros(7), 0.25)
    assert "still braking" in stop_incomplete(stop, _fake_sim())
    stop.powered_off = True
    assert "brakes have not engaged" in stop_incomplete(stop, _fake_sim(powered=False))
    assert "not at standstill" in stop_incomplete(stop, _fake_sim(powered=False, brakes_engaged=True, qd=0.05))
    assert stop_incomplete(stop, _fake_sim(powered=False, brakes_engaged=True)) is None


def test_a_stop_2_is_incomplete_while_it_decelerates():
    from ethimon.sim._control import StopController, stop_incomplete
    stop = StopController(2, np.zeros(7), np.full(7, 0.5), 0.25)
    assert "still decelerating" in stop_incomplete(stop, _fake_sim(qd=0.5))
    stop.t = stop.decel.T
    assert stop_incomplete(stop, _fake_sim()) is None


def test_the_restart_margin_covers_latency_grace_one_cycle_and_the_slow_down_at_walking_speed():
    from ethimon.sim._control import restart_margin_m
    from ethimon.sim._rules import near_human_grace_cycles
    assert near_human_grace_cycles(ethimon.load_spec(str(SPEC))) == 3
    assert restart_margin_m(0.1, 3, 60) == pytest.approx(1.6 * (0.1 + 4 / 60 + 0.3))
    assert restart_margin_m(0.0, 0, 60) == pytest.approx(1.6 * (1 / 60 + 0.3))


_SPEC_START = """\
ethimon: 1
name: start_input
signals:
  human_distance: {unit: m, range: [0, 10]}
  start_button: {type: %s}
obligations:
  - {id: near, require: human_distance > 0.5, response: stop_1}
restart: {start: %s}
"""


def test_restart_start_defaults_to_a_command_and_may_name_a_bool_input(tmp_path):
    assert ethimon.load_spec(str(SPEC)).restart.start == "command"
    f = tmp_path / "s.yaml"
    f.write_text(_SPEC_START % ("bool", "start_button"))
    assert ethimon.load_spec(str(f)).restart.start == "start_button"
    f.write_text(_SPEC_START % ("bool", "go"))
    with pytest.raises(SpecError, match="restart: start: .go. is not a declared signal"):
        ethimon.load_spec(str(f))
    f.write_text(_SPEC_START % ("number", "start_button"))
    with pytest.raises(SpecError, match="needs a bool input"):
        ethimon.load_spec(str(f))


@pytest.mark.sim
@pytest.mark.slow
def test_ack_refused_while_the_stop_1_brakes_then_the_reset_waits_for_the_start():
    pytest.importorskip("pybullet")
    from ethimon.sim import check_sim_expectations
    block, res = run_scenario("restart_ack_while_braking")
    assert check_sim_expectations(block, res) == []
    (t1, ok1, m1), (t2, ok2, _) = res.acknowledgements
    assert not ok1 and "still braking" in m1 and ok2 and res.starts == ((2.0, True, "started"),)
    # between the accepted acknowledgement and the start: braked, unpowered, nothing moves
    between = [r for r in res.trace if t2 <= r.t_s < 2.0]
    assert between and all(r.controller == "stop_1" and not r.powered and r.joint_speed_max_rad_s < 0.01
                           for r in between)
    assert not res.reset_started_motion and res.task_completed


@pytest.mark.sim
@pytest.mark.slow
@pytest.mark.parametrize("name", ["restart_auto_release_in_zone", "restart_ack_worker_at_edge"])
def test_a_restart_never_exceeds_the_slow_zone_speed_inside_it(name):
    pytest.importorskip("pybullet")
    from ethimon.sim import check_sim_expectations
    block, res = run_scenario(name)
    assert check_sim_expectations(block, res) == []
    assert res.task_resumes >= 1 and res.restart_max_speed_in_zone_m_s is not None
    assert res.restart_zone_breaches == 0 and res.restart_max_speed_in_zone_m_s <= 0.25


@pytest.mark.sim
@pytest.mark.slow
def test_a_start_input_restarts_on_its_rising_edge_only(tmp_path):
    pytest.importorskip("pybullet")
    from ethimon.sim import ArmSim, GovernedArm
    text = SPEC.read_text().replace("signals:\n", "signals:\n  start_button: {type: bool}\n", 1)
    text += "\nrestart: {start: start_button}\n"
    f = tmp_path / "cell.yaml"
    f.write_text(text)
    monitor = ethimon.Monitor(ethimon.load_spec(str(f)))
    with ArmSim() as sim:
        arm = GovernedArm(sim, monitor, inputs={"p_unsafe": 0.03, "start_button": True})
        assert not arm.start() and "no acknowledged stop" in arm.start().message
        arm.signal_filter = lambda t, fed: {**fed, "human_distance": float("nan")}
        arm.step()                                   # a fault: stop 1
        arm.signal_filter = None
        for _ in range(40):                          # the stop completes: power off, brakes on
            arm.step()
        assert not sim.powered
        assert arm.acknowledge()
        for _ in range(5):                           # the button is held down: no rising edge
            assert arm.step().controller == "stop_1"
        arm.inputs["start_button"] = False
        arm.step()
        arm.inputs["start_button"] = True            # pressed: motion may resume
        arm.step()
        assert not arm.awaiting_start and arm.step().controller == "task"
