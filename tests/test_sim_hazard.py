"""A held sharp or hot object kept pointed away from people (issue 14 item 3: the declared
``hazard_axis``), and dropped objects in recordings and in the task (DIRECT PyBullet)."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml
from pydantic import ValidationError

import ethimon

ROOT = Path(__file__).resolve().parents[1]
SPEC = ROOT / "specs" / "cobot_cell.yaml"


def _run(name: str, monkeypatch=None, *, orient: bool = True, **kw):
    pytest.importorskip("pybullet")
    from ethimon.sim import SimBlock, run_sim
    import ethimon.sim._control as control
    if not orient:
        monkeypatch.setattr(control.SafePoseController, "_orient_hazard", lambda self, sim: None)
    doc = yaml.safe_load((ROOT / "scenarios" / "sim" / f"{name}.yaml").read_text())
    block = SimBlock.model_validate(doc["sim"])
    res = run_sim(block, ethimon.Monitor(ethimon.load_spec(str(SPEC))),
                  p_unsafe=doc["inputs"].get("p_unsafe", 0.9), **kw)
    return block, res


def test_hazard_axis_needs_a_hazard_and_a_direction():
    from ethimon.sim import SimObject
    with pytest.raises(ValidationError, match="hazard_axis needs a hazard"):
        SimObject(name="k", xyz_m=(0, 0, 0), hazard_axis=(1, 0, 0))
    with pytest.raises(ValidationError, match="non-zero"):
        SimObject(name="k", xyz_m=(0, 0, 0), hazard="sharp", hazard_axis=(0, 0, 0))
    assert SimObject(name="k", xyz_m=(0, 0, 0), hazard="sharp", hazard_axis=(1, 0, 0)).hazard_axis == (1, 0, 0)


@pytest.mark.sim
def test_retreat_turns_the_blade_away_from_the_child():
    from ethimon.sim import check_sim_expectations
    block, res = _run("knife_blade_away_from_child")
    assert res.route == "direct"
    assert res.hazard_axis_angle_end_deg is not None and res.hazard_axis_angle_end_deg >= 120
    assert abs(res.wrist_turn_rad) > 0.5          # joint 7 was turned from the spec's safe pose
    assert res.time_to_safe_pose_s is not None    # and that pose (wrist turned) was reached
    assert check_sim_expectations(block, res) == []


@pytest.mark.sim
def test_without_the_wrist_turn_the_blade_ends_pointing_at_the_child(monkeypatch):
    from ethimon.sim import check_sim_expectations
    block, res = _run("knife_blade_away_from_child", monkeypatch, orient=False)
    assert res.hazard_axis_angle_end_deg < 90     # pointed toward the child: the old behaviour
    assert res.wrist_turn_rad == 0.0
    assert any("hazard axis" in m for m in check_sim_expectations(block, res))
