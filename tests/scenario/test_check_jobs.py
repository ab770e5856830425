"""``check --sim -j N`` (issue 32, speed): the sim rows run in worker processes, and the report is
the serial run's (rows, order, figures); a file that cannot be simulated is the same ERROR row."""

from __future__ import annotations

from pathlib import Path

import pytest

from ethimon.cli import main
from ethimon.scenario import check_paths

ROOT = Path(__file__).resolve().parents[2]
SIM = ROOT / "scenarios" / "sim"


def _rows(report):
    out = []
    for o in report.outcomes:
        rec = {k: v for k, v in o.record.items() if k != "realtime_factor"}  # wall clock
        out.append((o.name, o.status, o.expected, o.got, o.first_override_cycle, o.messages, rec))
    return out


def test_jobs_below_one_is_refused(capsys):
    assert main(["check", str(ROOT / "scenarios" / "bleach_in_drink.yaml"), "--sim", "-j", "0"]) == 2
    assert "--jobs must be at least 1" in capsys.readouterr().err


@pytest.mark.slow
@pytest.mark.sim
def test_pool_gives_the_serial_report(tmp_path):
    pytest.importorskip("pybullet")
    # a short scenario with a timeline and a sim row, and one whose start pose is inside a fixed
    # box (its sim row raises at run time: serially the file's one row is that ERROR)
    text = (SIM / "fast_motion_fault.yaml").read_text().replace("../../specs/", f"{ROOT}/specs/")
    text = text.replace("  duration_s: 3.0\n", "  duration_s: 1.0\n")  # short: the stop is at 0.42 s
    (tmp_path / "b_sim.yaml").write_text(text)
    bad = text.replace("name: fast_motion_fault", "name: starts_inside_a_box").replace(
        "  duration_s: 1.0\n", "  duration_s: 0.1\n  start_xyz_m: [0.5, 0.0, 0.3]\n  objects:\n"
        "    - {name: block, shape: box, xyz_m: [0.5, 0.0, 0.3], half_extents_m: [0.1, 0.1, 0.1], fixed: true}\n", 1)
    assert bad != text
    (tmp_path / "c_bad.yaml").write_text(bad)
    serial = check_paths([str(tmp_path)], sim=True)
    pooled = check_paths([str(tmp_path)], sim=True, jobs=2)
    assert [o.status for o in serial.outcomes] == ["PASS", "PASS", "ERROR"], serial.outcomes
    assert _rows(pooled) == _rows(serial)
    assert "starts" in pooled.outcomes[-1].messages[0]
