"""The monitor in the PyBullet loop: same-cycle switch, safe pose, stops, determinism."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

import ethimon

pytest.importorskip("pybullet")
pytestmark = pytest.mark.sim

ROOT = Path(__file__).resolve().parents[2]
SCENARIOS = sorted((ROOT / "scenarios" / "sim").glob("*.yaml"))
SPEC = ROOT / "specs" / "cobot_cell.yaml"

_cache: dict[str, tuple] = {}


def _run(name: str):
    """Run a shipped sim scenario once per test session."""
    from ethimon.sim import SimBlock, run_sim
    if name not in _cache:
        doc = yaml.safe_load((ROOT / "scenarios" / "sim" / f"{name}.yaml").read_text())
        block = SimBlock.model_validate(doc["sim"])
        spec = ethimon.load_spec(str((ROOT / "scenarios" / "sim" / doc["spec"]).resolve()))  # its own spec
        # scenarios scored by the risk model in `ethimon check` get a fixed stand-in here,
        # so these sim tests stay model-free: unsafe if the scenario expects the risk rule
        p_unsafe = doc["inputs"].get("p_unsafe")
        if p_unsafe is None:
            p_unsafe = 0.95 if "risk" in doc["expect"].get("fired", ()) else 0.03
        res = run_sim(block, ethimon.Monitor(spec), p_unsafe=p_unsafe)
        _cache[name] = (block, res, spec)
    return _cache[name]


def test_ships_at_least_eight_sim_scenarios():
    assert len(SCENARIOS) >= 8


@pytest.mark.slow
@pytest.mark.parametrize("path", SCENARIOS, ids=lambda p: p.stem)
def test_shipped_scenario_meets_its_sim_expectations(path):
    from ethimon.sim import check_sim_expectations
    block, res, _ = _run(path.stem)
    assert check_sim_expectations(block, res) == []
    doc = yaml.safe_load(path.read_text())
    assert res.override == doc["expect"]["override"]
    if res.override:
        assert res.override_reaction_cycles == 0
    assert res.realtime_factor > 0  # measured, never asserted against wall time (bench/sim/sim_realtime.py)


@pytest.mark.slow
def test_override_switches_controller_in_the_same_cycle():
    _, res, _ = _run("person_enters_cell")
    i = res.first_override_cycle
    assert i is not None and i > 0
    assert res.trace[i - 1].controller == "task" and not res.trace[i - 1].override
    assert res.trace[i].override and res.trace[i].controller == "safe_pose"
    # the separation rule later escalates to a category-2 stop; while an override lasts the
    # arm never backs down (the spec releases slow_near_human automatically once the arm is
    # slow, hold_cycles 10: since the retreat decelerates within the rated limits it can, and
    # the task resumes until the worker crosses S_p)
    order = ["task", "safe_pose", "stop_2", "stop_1", "stop_0"]
    seen = [r.controller for r in res.trace[i:]]
    assert "stop_2" in seen
    assert res.trace[-1].override and res.trace[-1].controller == "stop_2"
    for a, b in zip(res.trace[i:], res.trace[i + 1:]):
        if a.override and b.override:
            assert order.index(a.controller) <= order.index(b.controller)


@pytest.mark.slow
def test_text_risk_sends_arm_to_safe_pose_under_the_speed_limit():
    _, res, spec = _run("knife_handover_child")
    assert res.first_override_cycle == 0 and "risk" in res.trace[0].violations
    assert res.trace[0].controller == "safe_pose"
    # the child stands within 1.5 m: the retreat keeps the spec's 0.25 m/s near-human rule
    # for every link and the knife (issue 14), so it takes longer than at full joint speed
    assert res.time_to_safe_pose_s is not None and res.time_to_safe_pose_s <= 3.5
    assert res.retreat_max_link_speed_near_human_m_s <= 0.25
    assert res.max_joint_speed_safe_pose_rad_s <= spec.safe_pose.max_joint_speed_rad_s
    last = res.trace[-1]
    assert last.safe_pose_error_rad <= spec.safe_pose.tolerance_rad
    # the arm does not go on with the hand-over
    assert not res.task_completed


@pytest.mark.slow
def test_sensor_dropout_fails_closed_with_stop_1():
    _, res, _ = _run("sensor_dropout")
    rec = res.trace[res.first_override_cycle]
    assert rec.t_s == pytest.approx(2.0)
    assert math.isnan(rec.signals["human_distance"]) and rec.faults
    assert rec.controller == "stop_1"


@pytest.mark.slow
def test_release_resumes_and_completes_the_task():
    _, res, _ = _run("release_after_person_leaves")
    assert res.released and res.task_completed
    after = [r.controller for r in res.trace if r.cycle > res.first_override_cycle]
    assert "task" in after


@pytest.mark.slow
def test_two_runs_are_identical():
    from ethimon.sim import SimBlock, run_sim
    doc = yaml.safe_load((ROOT / "scenarios" / "sim" / "hot_pour_near_person.yaml").read_text())
    block = SimBlock.model_validate(doc["sim"])
    mon = ethimon.Monitor(ethimon.load_spec(str(SPEC)))
    a = run_sim(block, mon, p_unsafe=0.05)
    b = run_sim(block, mon, p_unsafe=0.05)  # run_sim resets the monitor
    assert len(a.trace) == len(b.trace)
    for ra, rb in zip(a.trace, b.trace):
        assert json.dumps(ra.signals, sort_keys=True) == json.dumps(rb.signals, sort_keys=True)
        assert (ra.override, ra.response, ra.violations, ra.controller) == \
               (rb.override, rb.response, rb.violations, rb.controller)
    assert a.time_to_safe_pose_s == b.time_to_safe_pose_s


@pytest.mark.slow
def test_governed_arm_in_a_user_loop():
    from ethimon.sim import ArmSim, GovernedArm
    spec = ethimon.load_spec(str(SPEC))
    with ArmSim(control_hz=120, start_joints_rad=(0.5, -0.3, 0.2, -2.0, 0.0, 1.8, 0.6)) as sim:
        arm = GovernedArm(sim, ethimon.Monitor(spec), inputs={"p_unsafe": 0.97})
        recs = [arm.step() for _ in range(180)]
    assert recs[0].override and recs[0].controller == "safe_pose"
    assert recs[-1].safe_pose_error_rad <= spec.safe_pose.tolerance_rad
    assert max(r.joint_speed_max_rad_s for r in recs) <= spec.safe_pose.max_joint_speed_rad_s


@pytest.mark.slow
def test_record_writes_frames_trace_and_plot(tmp_path):
    from ethimon.sim import SimBlock, run_sim
    block = SimBlock.model_validate({"duration_s": 0.5, "start_xyz_m": [0.5, 0.2, 0.3]})
    res = run_sim(block, ethimon.Monitor(ethimon.load_spec(str(SPEC))), p_unsafe=0.9,
                  record_dir=str(tmp_path))
    names = sorted(p.name for p in tmp_path.iterdir())
    assert {"trace.jsonl", "trace.csv", "plot.png", "summary.json"} <= set(names)
    # events of one cycle share a frame (b43e01c: e.g. frame_00000_first_violation-override.png)
    assert any(n.startswith("frame_00000_") and "override" in n.split("_", 2)[2] for n in names)
    assert any(n.endswith("_start.png") for n in names)
    rows = (tmp_path / "trace.jsonl").read_text().splitlines()
    assert len(rows) == len(res.trace) == 30
    assert json.loads(rows[0])["override"] is True
    assert (tmp_path / "plot.png").read_bytes()[:4] == b"\x89PNG"


def test_signal_producer_copes_with_a_subset_spec():
    from ethimon.sim import SimBlock, run_sim
    spec = ethimon.load_spec_text("""
ethimon: 1
name: only_distance
signals: {human_distance: {unit: m, range: [0, 10]}}
obligations:
  - {id: keep_away, require: "human_distance >= 0.5"}
""")
    block = SimBlock.model_validate({"duration_s": 0.5, "humans": [
        {"name": "h", "waypoints": [{"t_s": 0, "xy_m": [0.7, 0.0]}]}]})
    res = run_sim(block, ethimon.Monitor(spec), p_unsafe=0.0)
    assert res.first_override_cycle == 0 and res.fired == ("keep_away",)
    assert np.isfinite(res.min_separation_m) and res.min_separation_m < 0.5


@pytest.mark.slow
@pytest.mark.parametrize("control_hz", [30, 120, 240])
def test_control_rate_is_configurable(control_hz):
    from ethimon.sim import SimBlock, run_sim
    spec = ethimon.load_spec(str(SPEC))
    block = SimBlock.model_validate({"control_hz": control_hz, "duration_s": 1.6,
                                     "start_xyz_m": [0.5, -0.25, 0.3]})
    res = run_sim(block, ethimon.Monitor(spec), p_unsafe=0.95)
    assert len(res.trace) == round(1.6 * control_hz)
    assert res.first_override_cycle == 0 and res.override_reaction_cycles == 0
    assert res.time_to_safe_pose_s is not None and res.time_to_safe_pose_s <= 1.5
    assert res.max_joint_speed_safe_pose_rad_s <= spec.safe_pose.max_joint_speed_rad_s


def test_missing_signal_dropout_and_hazard_distance():
    from ethimon.sim import SimBlock, run_sim
    spec = ethimon.load_spec_text("""
ethimon: 1
name: hazards
on_fault: stop_2
signals: {hazard_distance: {unit: m, range: [0, 10]}}
obligations:
  - {id: hot_away, require: "hazard_distance >= 0.5", response: safe_pose}
""")
    block = SimBlock.model_validate({
        "duration_s": 1.0,
        "objects": [{"name": "kettle", "xyz_m": [0.5, 0.0, 0.05], "hazard": "hot", "fixed": True}],
        "humans": [{"name": "h", "radius_m": 0.2,
                    "waypoints": [{"t_s": 0, "xy_m": [1.5, 0.0]}, {"t_s": 0.5, "xy_m": [0.9, 0.0]}]}],
        "dropouts": [{"signal": "hazard_distance", "from_s": 0.1, "to_s": 0.2, "mode": "missing"}]})
    res = run_sim(block, ethimon.Monitor(spec), p_unsafe=0.0)
    first = res.trace[0]
    assert first.signals["hazard_distance"] == pytest.approx(1.5 - 0.2 - 0.5 - 0.03, abs=0.01)
    dropped = [r for r in res.trace if 0.1 <= r.t_s < 0.2]
    assert dropped and all("hazard_distance" not in r.signals and r.faults for r in dropped)
    assert dropped[0].controller == "stop_2"


def test_safe_pose_with_wrong_joint_count_is_a_spec_error():
    from ethimon.sim import ArmSim, GovernedArm
    spec = ethimon.load_spec_text("""
ethimon: 1
name: six_joints
safe_pose: {joints_rad: [0, 0, 0, 0, 0, 0]}
""")
    with ArmSim() as sim, pytest.raises(ethimon.SpecError, match="needs 7"):
        GovernedArm(sim, ethimon.Monitor(spec))


@pytest.mark.slow
def test_unreachable_target_is_a_sim_error():
    from ethimon.sim import SimBlock, SimError, run_sim
    block = SimBlock.model_validate({"task": [{"primitive": "reach", "xyz_m": [1.5, 0.0, 0.3]}]})
    with pytest.raises(SimError, match=r"sim.task\[0\] \(reach\): the Panda cannot reach"):
        run_sim(block, ethimon.Monitor(ethimon.load_spec(str(SPEC))), p_unsafe=0.0)
