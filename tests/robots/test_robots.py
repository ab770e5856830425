"""Robots as data (issue 34 item 4): shipped robot descriptions (Panda, UR5e) a spec names with
``robot:``; lint and verify check the safe pose against that robot; the simulation is Panda-only."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

import ethimon
from ethimon import _robot
from ethimon.errors import SpecError

ROOT = Path(__file__).resolve().parents[2]
UR5E_SPEC = ROOT / "examples" / "ur5e" / "spec.yaml"

BASE = """ethimon: 1
name: t
signals:
  d: {unit: m, range: [0, 10]}
obligations:
  - id: near
    require: d >= 0.5
    response: stop_2
"""


def _load(tmp_path: Path, text: str) -> ethimon.Spec:
    p = tmp_path / "spec.yaml"
    p.write_text(text, encoding="utf-8")
    return ethimon.load_spec(p)


def test_shipped_descriptions_cite_every_number_and_the_panda_names_come_from_panda_yaml() -> None:
    for name in _robot.SHIPPED_ROBOTS:
        robot = _robot.shipped_robot(name)
        for key in ("position_min_rad", "position_max_rad", "speed_rad_s", "acceleration_rad_s2",
                    "brake_holding_n_m", "payload_kg", "reach_m"):
            assert robot.facts[key].source and "http" not in robot.facts[key].source
        assert "ESTIMATE" in robot.source("brake_holding_n_m")  # no maker publishes these
    panda, ur5e = _robot.shipped_robot("panda"), _robot.shipped_robot("ur5e")
    assert _robot.RATED_Q_MIN == panda.q_min and _robot.RATED_DQ_MAX == panda.dq_max
    assert _robot.BRAKE_HOLDING_N_M == panda.holding_n_m and _robot.RATED_PAYLOAD_KG == panda.payload_kg == 3.0
    assert _robot.PANDA_HOME_JOINTS_RAD == panda.home_joints_rad
    assert ur5e.n_joints == 6 and ur5e.payload_kg == 5.0 and ur5e.reach_m == 0.85
    assert ur5e.dq_max == (3.1416,) * 6 and "ESTIMATE" in ur5e.source("acceleration_rad_s2")


@pytest.mark.slow
def test_ur5e_spec_loads_with_its_robot_and_lints_clean() -> None:
    spec = ethimon.load_spec(UR5E_SPEC)
    assert spec.robot == "ur5e" and len(spec.safe_pose.joints_rad) == 6
    from ethimon._lint import lint_paths
    report = lint_paths([UR5E_SPEC])
    assert [ln.kind for ln in report.lines] == ["ok"], [ln.text for ln in report.lines]


def test_seven_value_safe_pose_in_a_ur5e_spec_is_a_located_error(tmp_path: Path) -> None:
    text = BASE + "robot: ur5e\nsafe_pose:\n  joints_rad: [0, -0.785, 0, -2.356, 0, 1.571, 0.785]\n"
    with pytest.raises(SpecError) as ei:
        _load(tmp_path, text)
    e = ei.value
    assert e.line == 11 and "7 values" in e.message and "UR5e" in e.message and "6 joints" in e.message
    assert "shoulder_pan_joint" in (e.hint or "")


def test_a_named_robot_without_a_safe_pose_or_an_unknown_robot_is_a_located_error(tmp_path: Path) -> None:
    with pytest.raises(SpecError) as ei:
        _load(tmp_path, BASE + "robot: ur5e\n")
    assert ei.value.line == 9 and "no default safe pose" in ei.value.message
    with pytest.raises(SpecError) as ei:
        _load(tmp_path, BASE + "robot: kuka_lbr\n")
    assert ei.value.line == 9 and "unknown robot 'kuka_lbr'" in ei.value.message and "ur5e" in ei.value.hint


def test_a_users_robot_file_is_data_with_located_errors(tmp_path: Path) -> None:
    ur5e = (ROOT / "src" / "ethimon" / "robots" / "ur5e.yaml").read_text(encoding="utf-8")
    (tmp_path / "arm.yaml").write_text(ur5e.replace("name: ur5e", "name: my_arm"), encoding="utf-8")
    spec = _load(tmp_path, BASE + "robot: arm.yaml\nsafe_pose: {joints_rad: [0, -1.5, 1.5, -1.5, -1.5, 0]}\n")
    from ethimon.language._robots import robot_of
    assert robot_of(spec).name == "my_arm"
    # a number without its source: located in the robot file
    broken = ur5e.replace('    source: "Universal Robots UR5e technical specifications: maximum speed', "    note: \"x")
    (tmp_path / "arm.yaml").write_text(broken, encoding="utf-8")
    with pytest.raises(SpecError) as ei:
        _load(tmp_path, BASE + "robot: arm.yaml\nsafe_pose: {joints_rad: [0, -1.5, 1.5, -1.5, -1.5, 0]}\n")
    assert ei.value.path.endswith("arm.yaml") and ei.value.line is not None and "note" in ei.value.message
    with pytest.raises(SpecError) as ei:  # a Python tag is refused, never constructed
        (tmp_path / "evil.yaml").write_text("!!python/object/apply:os.system ['true']\n", encoding="utf-8")
        _load(tmp_path, BASE + "robot: evil.yaml\nsafe_pose: {joints_rad: [0]}\n")
    assert "not allowed" in ei.value.message


def test_lint_checks_the_safe_pose_against_the_named_robots_range(tmp_path: Path) -> None:
    from ethimon._lint import lint_safe_pose
    spec = _load(tmp_path, BASE + "robot: ur5e\nsafe_pose: {joints_rad: [0, -1.5, 3.5, -1.5, -1.5, 0]}\n")
    with pytest.raises(SpecError) as ei:
        lint_safe_pose(spec)
    assert "UR5e" in ei.value.message and "joint 3 = 3.5" in ei.value.message and ei.value.line == 10
    # the same pose is inside the range of a 6-joint robot with a wider elbow: no error
    assert math.isclose(_robot.shipped_robot("ur5e").q_max[2], 3.1416)


@pytest.mark.slow
def test_sim_refuses_another_robot_with_a_located_error() -> None:
    pytest.importorskip("pybullet")
    from ethimon.sim._runner import GovernedArm
    spec = ethimon.load_spec(UR5E_SPEC)
    with pytest.raises(SpecError) as ei:
        GovernedArm(None, ethimon.Monitor(spec))
    assert "Franka Panda only" in ei.value.message and ei.value.line == 8


@pytest.mark.slow
def test_ur5e_spec_verifies_with_no_panda_warning() -> None:
    pytest.importorskip("z3")
    from ethimon.verify import verify_spec
    report = verify_spec(UR5E_SPEC)
    text = "\n".join(f"{f.name} {f.status} {f.message}" for f in report.findings)
    assert "Panda" not in text
    assert not [f for f in report.findings if f.status not in ("ok", "proved", "skipped")], text
    pose = [f for f in report.findings if f.name == "lint.safe_pose_range"]
    assert pose and pose[0].status == "ok" and "UR5e" in pose[0].message
