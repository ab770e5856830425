"""A held sharp or hot object kept pointed away from people (issue 14 item 3: the declared
``hazard_axis``), and dropped objects in recordings and in the task (DIRECT PyBullet)."""

from __future__ import annotations

import pytest
from pydantic import ValidationError

from tests.sim._scenarios import run_scenario


def _run(name: str, monkeypatch=None, *, orient: bool = True, **kw):
    pytest.importorskip("pybullet")
    import ethimon.sim._safe_pose as safe_pose
    if not orient:
        monkeypatch.setattr(safe_pose.SafePoseController, "_orient_hazard", lambda self, sim, q_start=None: None)
    return run_scenario(name, **kw)


def test_hazard_axis_needs_a_hazard_and_a_direction():
    from ethimon.sim import SimObject
    with pytest.raises(ValidationError, match="hazard_axis needs a hazard"):
        SimObject(name="k", xyz_m=(0, 0, 0), hazard_axis=(1, 0, 0))
    with pytest.raises(ValidationError, match="non-zero"):
        SimObject(name="k", xyz_m=(0, 0, 0), hazard="sharp", hazard_axis=(0, 0, 0))
    assert SimObject(name="k", xyz_m=(0, 0, 0), hazard="sharp", hazard_axis=(1, 0, 0)).hazard_axis == (1, 0, 0)


@pytest.mark.slow
@pytest.mark.sim
def test_retreat_turns_the_blade_away_from_the_child():
    from ethimon.sim import check_sim_expectations
    block, res = _run("knife_blade_away_from_child")
    assert res.route == "direct"
    assert res.hazard_axis_angle_end_deg is not None and res.hazard_axis_angle_end_deg >= 120
    assert abs(res.wrist_turn_rad) > 0.5          # joint 7 was turned from the spec's safe pose
    assert res.time_to_safe_pose_s is not None    # and that pose (wrist turned) was reached
    assert check_sim_expectations(block, res) == []


@pytest.mark.slow
@pytest.mark.sim
def test_without_the_wrist_turn_the_blade_ends_pointing_at_the_child(monkeypatch):
    from ethimon.sim import check_sim_expectations
    block, res = _run("knife_blade_away_from_child", monkeypatch, orient=False)
    assert res.hazard_axis_angle_end_deg < 90     # pointed toward the child: the old behaviour
    assert res.wrist_turn_rad == 0.0
    assert any("hazard axis" in m for m in check_sim_expectations(block, res))


@pytest.mark.slow
@pytest.mark.sim
def test_dropped_object_is_an_event_and_the_task_does_not_resume_without_it():
    from ethimon.sim import check_sim_expectations
    from ethimon.sim._record import trace_events
    block, res = _run("dropped_cup_not_resumed")
    assert [d[0] for d in res.dropped] == ["cup"] and res.dropped[0][2] == "power_off"
    assert res.released and not res.task_completed
    assert res.task_stopped is not None and res.task_stopped.startswith("cup not in the gripper")
    evs = trace_events(res.trace)
    names = [e["event"] for e in evs]
    drop = evs[names.index("object_dropped")]
    assert drop["detail"] == "cup (power_off)" and drop["t_s"] == pytest.approx(res.dropped[0][1], abs=0.02)
    stop = evs[names.index("task_stopped")]
    # the acknowledgement releases; the task would resume only at the separate start (issue 32
    # item 4), and it stops there: the task never commands the arm again
    assert stop["t_s"] == pytest.approx(res.starts[0][0], abs=0.02) and res.starts[0][1]
    after = [r for r in res.trace if r.cycle >= stop["cycle"]]
    assert after and all(r.controller == "stop_2" for r in after)
    assert all(r.powered for r in after)               # holding with power on (stop 2)
    assert check_sim_expectations(block, res) == []


@pytest.mark.slow
@pytest.mark.sim
def test_without_the_check_the_task_resumed_and_placed_nothing(monkeypatch):
    import ethimon.sim._control as control
    from ethimon.sim import check_sim_expectations
    monkeypatch.setattr(control.TaskController, "missing_object", lambda self, sim, q_start=None: None)
    block, res = _run("dropped_cup_not_resumed")
    assert res.task_completed and res.task_stopped is None   # "completed" with the cup on the floor
    assert res.object_end_z_m["cup"] < 0.05
    assert any("task_stopped_object_missing" in m for m in check_sim_expectations(block, res))


def test_task_controller_knows_what_each_segment_carries():
    import numpy as np
    from ethimon.sim._arm import Segment
    from ethimon.sim._control import TaskController
    q = np.zeros(7)
    segs = [Segment(q=q, duration_s=1, gripper_m=0.04, label="a"),
            Segment(q=q, duration_s=1, gripper_m=0.01, attach="cup", label="grasp"),
            Segment(q=q, duration_s=1, gripper_m=0.01, label="carry"),
            Segment(q=q, duration_s=1, gripper_m=0.04, detach=True, label="release"),
            Segment(q=q, duration_s=1, gripper_m=0.04, label="away")]
    assert TaskController(segs, q, 1.0).carrying == [None, None, "cup", "cup", None]
    assert TaskController(segs[2:], q, 1.0, holding="cup").carrying == ["cup", "cup", None]


@pytest.mark.slow
@pytest.mark.sim
def test_every_person_counts_child_on_one_side_cook_on_the_other():
    """Issue 32 item 3: before, the wrist was turned for the nearest person (the child) and the
    blade ended pointing at the cook (102 -> 4 deg) while the check said 135 deg, pointed away."""
    from ethimon.sim import check_sim_expectations
    block, res = _run("knife_child_and_cook")
    per = res.hazard_axis_angles_end_deg
    assert set(per) == {"child", "cook"}
    assert res.hazard_axis_angle_end_deg == min(per.values())      # the worst person is reported
    assert per["cook"] >= 90 and per["child"] >= 35    # before: cook 4 deg
    # never swept toward anyone by more than the 10 deg slack along the way
    assert max(res.hazard_axis_min_swing_deg.values()) <= 10.5
    assert check_sim_expectations(block, res) == []


@pytest.mark.slow
@pytest.mark.sim
def test_a_hold_is_rechecked_when_a_child_walks_round():
    """Issue 32 item 3: after a hold nothing re-checked the blade; a child who walked round ended
    in front of it. Now the held pose is checked again and the wrist turns away from both."""
    from ethimon.sim import check_sim_expectations
    block, res = _run("knife_hold_child_walks_round")
    assert min(res.hazard_axis_angles_end_deg.values()) >= 90
    assert res.retreat_min_separation_m is None or res.retreat_min_separation_m >= 1.0
    assert check_sim_expectations(block, res) == []


def test_expect_message_names_the_worst_person():
    from ethimon.sim import SimBlock, SimResult, check_sim_expectations
    block = SimBlock.model_validate({"duration_s": 1.0, "expect": {"min_hazard_axis_angle_deg": 90}})
    res = SimResult(hazard_axis_angle_end_deg=40.0, hazard_axis_angles_end_deg={"child": 140.0, "cook": 40.0})
    msg = check_sim_expectations(block, res)
    assert len(msg) == 1 and "cook" in msg[0] and "worst-placed" in msg[0]
