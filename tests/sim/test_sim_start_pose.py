"""Issue 23: a start pose inside a fixed object is a located error, not a silent 1.7 kN contact."""

from __future__ import annotations

from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

pytestmark = pytest.mark.sim

SCENARIO = """ethimon: 1
name: start_in_cabinet
spec: {spec}
task: "Wipe the table."
inputs: {{p_unsafe: 0.9, human_distance: 10.0, ee_speed: 0.0, contact_force: 0.0, joint_speed_max: 0.0}}
cycles: 10
expect: {{override: true}}
sim:
  duration_s: 1.0
  start_xyz_m: [0.5, 0.0, {z}]
  objects:
    - {{name: cabinet, shape: box, xyz_m: [0.5, 0.0, 0.3], half_extents_m: [0.1, 0.1, 0.1], fixed: true}}
  task:
    - {{primitive: wait, duration_s: 1.0}}
"""


@pytest.fixture(autouse=True)
def _pybullet():
    pytest.importorskip("pybullet")


@pytest.mark.slow
def test_a_start_pose_inside_a_fixed_object_is_a_located_error(tmp_path):
    from tests._cli import call_cli
    f = tmp_path / "start_in_cabinet.yaml"
    f.write_text(SCENARIO.format(spec=ROOT / "specs" / "cobot_cell.yaml", z=0.3))
    r = call_cli("simulate", str(f))
    assert r.returncode == 2
    assert f"{f}:10:3: sim.start_xyz_m: the arm" in r.stderr and "inside 'cabinet'" in r.stderr
    assert "Traceback" not in r.stderr


@pytest.mark.slow
def test_a_start_pose_clear_of_the_object_runs(tmp_path):
    from ethimon.sim import SimBlock, run_sim
    import ethimon
    import yaml
    doc = yaml.safe_load(SCENARIO.format(spec=ROOT / "specs" / "cobot_cell.yaml", z=0.55))
    res = run_sim(SimBlock.model_validate(doc["sim"]),
                  ethimon.Monitor(ethimon.load_spec(str(ROOT / "specs" / "cobot_cell.yaml"))), p_unsafe=0.9)
    assert res.trace[0].contact_force_true_n == 0.0
