"""``ethimon lint`` as a library (``ethimon._lint.lint_paths``): the CLI only prints its lines."""

from __future__ import annotations

import os

import pytest

from ethimon._lint import lint_paths
from ethimon.cli import main
from ethimon.errors import SpecError

SPECS = os.path.join(os.path.dirname(__file__), "..", "..", "specs")

GOOD = """\
ethimon: 1
name: lint-good
signals:
  x: {type: number, range: [0, 10]}
obligations:
  - id: small
    require: x < 5
    response: safe_pose
"""


def test_lint_paths_reports_each_spec_and_keeps_going_after_a_bad_one(tmp_path):
    (tmp_path / "a_good.yaml").write_text(GOOD)
    (tmp_path / "b_bad.yaml").write_text(GOOD.replace("x < 5", "y < 5"))
    (tmp_path / "c_good.yaml").write_text(GOOD.replace("lint-good", "lint-good-2"))
    rep = lint_paths([tmp_path])
    kinds = [(os.path.basename(ln.path), ln.kind) for ln in rep.lines]
    assert kinds == [("a_good.yaml", "ok"), ("b_bad.yaml", "error"), ("c_good.yaml", "ok")]
    assert rep.lines[0].text.endswith("ok (lint-good, 1 obligations)")
    bad = rep.lines[1].text
    assert bad.startswith(str(tmp_path / "b_bad.yaml") + ":7:") and "'y'" in bad, bad  # path:line:col
    assert not rep.ok and rep.exit_code == 2


def test_lint_paths_matches_the_cli_line_for_line(tmp_path, capsys):
    (tmp_path / "good.yaml").write_text(GOOD)
    (tmp_path / "bad.yaml").write_text(GOOD.replace("range: [0, 10]", "range: [10, 0]"))
    rep = lint_paths([tmp_path, os.path.join(SPECS, "governor.yaml")])
    rc = main(["lint", str(tmp_path), os.path.join(SPECS, "governor.yaml")])
    out, err = capsys.readouterr()
    assert rc == rep.exit_code == 2
    assert out.splitlines() == [ln.text for ln in rep.lines if ln.kind != "error"]
    assert err.splitlines() == [ln.text for ln in rep.lines if ln.kind == "error"]


def test_lint_paths_all_ok_and_a_missing_path_raises(tmp_path):
    (tmp_path / "good.yaml").write_text(GOOD)
    rep = lint_paths([tmp_path / "good.yaml"])
    assert rep.ok and rep.exit_code == 0 and [ln.kind for ln in rep.lines] == ["ok"]
    with pytest.raises(SpecError):
        lint_paths([tmp_path / "none.yaml"])


def test_a_safe_pose_outside_the_rated_range_is_a_located_error(tmp_path):
    (tmp_path / "pose.yaml").write_text(GOOD + "safe_pose:\n  joints_rad: [0, 0, 0, -2.0, 0, 9.0, 0.8]\n")
    rep = lint_paths([tmp_path / "pose.yaml"])
    (line,) = rep.lines
    assert line.kind == "error" and "rated" in line.text and ":" in line.text.split(" ")[0], line.text
