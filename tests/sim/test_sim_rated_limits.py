"""Rated limits in lint and verify (issue 14 item 4): the Panda's rated-limit table lives on the
lowest floor (``ethimon._robot``), the simulator re-uses it, and ``ethimon verify`` reports a safe
pose outside the rated range (lint.safe_pose_range, naming each joint, its limits and the spec's
line) as ``ethimon lint`` does (an error there), with no import of ``sim``."""

from __future__ import annotations

import os

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

BAD = """ethimon: 1
name: bad_pose
signals:
  human_distance: {unit: m, range: [0, 10]}
obligations:
  - id: near
    require: human_distance >= 0.5
    response: stop_2
safe_pose:
  joints_rad: [0.0, -0.785, 0.0, 0.2, 0.0, 1.571, 3.1]
"""


def test_the_table_is_one_fact_on_the_lowest_floor():
    from ethimon import _robot
    from ethimon.sim import _limits
    for name in ("RATED_Q_MIN", "RATED_Q_MAX", "RATED_DQ_MAX", "RATED_DDQ_MAX", "RATED_DDDQ_MAX",
                 "out_of_range", "safe_pose_problem"):
        assert getattr(_limits, name) is getattr(_robot, name)
    assert _robot.out_of_range(_robot.PANDA_HOME_JOINTS_RAD) == []


def _verify(tmp_path, text):
    pytest.importorskip("z3")
    from ethimon.verify import verify_spec
    p = tmp_path / "spec.yaml"
    p.write_text(text)
    rep = verify_spec(str(p))
    assert rep.error is None
    return rep, str(p)


@pytest.mark.slow
def test_verify_reports_a_safe_pose_outside_the_rated_range_naming_each_joint(tmp_path):
    rep, path = _verify(tmp_path, BAD)
    found = [f for f in rep.findings if f.name == "lint.safe_pose_range"]
    assert len(found) == 1 and found[0].status == "warning"
    msg = found[0].message
    assert msg.startswith(f"{path}:10:")                      # the joints_rad line of the file
    assert "joint 4 = 0.2 rad (rated -3.0718 .. -0.0698)" in msg
    assert "joint 7 = 3.1 rad (rated -2.8973 .. 2.8973)" in msg
    assert "joint 1 " not in msg


def test_verify_passes_the_default_and_the_shipped_safe_poses(tmp_path):
    rep, _ = _verify(tmp_path, BAD.replace("[0.0, -0.785, 0.0, 0.2, 0.0, 1.571, 3.1]",
                                           "[0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785]"))
    assert [f.status for f in rep.findings if f.name == "lint.safe_pose_range"] == ["ok"]


def test_lint_cli_reports_it_as_an_error(tmp_path, capsys):
    from ethimon.cli import main
    p = tmp_path / "spec.yaml"
    p.write_text(BAD)
    assert main(["lint", str(p)]) == 2
    err = capsys.readouterr().err
    assert "joint 4 = 0.2 rad" in err and f"{p}:10:" in err


@pytest.mark.slow
def test_verify_does_not_import_sim():
    import subprocess
    import sys
    code = ("import sys, ethimon.verify._verifier; "
            "print(any(m == 'ethimon.sim' or m.startswith('ethimon.sim.') for m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
