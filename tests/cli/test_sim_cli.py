"""``ethimon simulate`` and ``ethimon check --sim`` as a user runs them."""

from __future__ import annotations

import json

import pytest

from ethimon.cli import main

pytest.importorskip("pybullet")
pytestmark = pytest.mark.sim


@pytest.mark.slow
def test_simulate_records_and_passes(tmp_path, capsys, root):
    rc = main(["simulate", str(root / "scenarios/sim/knife_handover_child.yaml"),
               "--record", str(tmp_path), "--json", str(tmp_path / "out.json")])
    out = capsys.readouterr().out
    assert rc == 0, out
    assert "knife_handover_child" in out and "PASS" in out
    rec = tmp_path / "knife_handover_child"
    assert (rec / "trace.csv").is_file() and (rec / "plot.png").is_file()
    assert any(p.name.endswith("_safe_pose.png") for p in rec.iterdir())
    doc = json.loads((tmp_path / "out.json").read_text())
    r = doc["results"][0]
    # within the scenario's own expectation (the retreat near the child keeps 0.25 m/s)
    assert r["override_reaction_cycles"] == 0 and r["time_to_safe_pose_s"] <= 3.5


def test_simulate_bad_input_is_one_line(tmp_path, capsys, root):
    assert main(["simulate", str(tmp_path / "nope.yaml")]) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1
    bad = tmp_path / "bad.yaml"
    bad.write_text((root / "scenarios/sim/routine_wipe.yaml").read_text()
                   .replace("../../specs/cobot_cell.yaml", str(root / "specs/cobot_cell.yaml"))
                   .replace("passes: 3", "passes: 3, speeed: 2"))
    assert main(["simulate", str(bad)]) == 2
    err = capsys.readouterr().err
    assert "speeed" in err and "Traceback" not in err


def test_simulate_needs_a_display_for_gui(monkeypatch, capsys, root):
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    assert main(["simulate", str(root / "scenarios/sim/routine_wipe.yaml"), "--gui"]) == 2
    assert "display" in capsys.readouterr().err


def test_simulate_unknown_input_is_an_error_with_a_hint(tmp_path, capsys, root):
    bad = tmp_path / "typo.yaml"
    bad.write_text((root / "scenarios/sim/sensor_dropout.yaml").read_text()
                   .replace("../../specs/cobot_cell.yaml", str(root / "specs/cobot_cell.yaml"))
                   .replace("set: {human_distance: null}", "set: {human_distanse: null}"))
    assert main(["simulate", str(bad)]) == 2
    err = capsys.readouterr().err
    assert f"{bad}:10:21:" in err and "did you mean 'human_distance'?" in err and "Traceback" not in err
    assert main(["check", str(bad), "--sim"]) == 2
    assert "did you mean 'human_distance'?" in capsys.readouterr().err


@pytest.mark.slow
def test_simulate_unexpected_exception_in_one_file_is_one_line(tmp_path, capsys, root, monkeypatch):
    import ethimon.scenario as scenario_pkg
    real = scenario_pkg.load_scenario

    def load(path):
        if str(path).endswith("a_bad.yaml"):
            raise RecursionError("maximum recursion depth exceeded")
        return real(path)
    monkeypatch.setattr(scenario_pkg, "load_scenario", load)
    (tmp_path / "a_bad.yaml").write_text("ethimon: 1\n")
    good = tmp_path / "b_good.yaml"
    good.write_text((root / "scenarios/sim/routine_wipe.yaml").read_text()
                    .replace("../../specs/cobot_cell.yaml", str(root / "specs/cobot_cell.yaml")))
    assert main(["simulate", str(tmp_path)]) == 2
    cap = capsys.readouterr()
    assert f"{tmp_path / 'a_bad.yaml'}: internal error: RecursionError" in cap.err
    assert "routine_wipe" in cap.out and "PASS" in cap.out and "Traceback" not in cap.err


@pytest.mark.slow
def test_simulate_json_to_stdout_is_pure_json(capsys, root):
    # regression (issue 13): the table and summary were printed to stdout before the JSON
    rc = main(["simulate", str(root / "scenarios/sim/routine_wipe.yaml"), "--json", "-"])
    cap = capsys.readouterr()
    assert rc == 0, cap.out + cap.err
    doc = json.loads(cap.out)
    assert [r["name"] for r in doc["results"]] == ["routine_wipe"] and doc["results"][0]["passed"] is True
    assert "PASS" in cap.err and "1 passed, 0 failed" in cap.err


@pytest.mark.slow
def test_recorded_summary_has_the_wall_time_and_every_file(tmp_path, root):
    # regression (issue 13): summary.json had wall_time_s 0.0 (written before it was set) and
    # listed the frames only, not the trace, summary and plot files
    assert main(["simulate", str(root / "scenarios/sim/routine_wipe.yaml"), "--record", str(tmp_path)]) == 0
    rec = tmp_path / "routine_wipe"
    summary = json.loads((rec / "summary.json").read_text())
    assert summary["wall_time_s"] > 0
    assert summary["realtime_factor"] > 0
    listed = sorted(summary["files"])
    assert listed == sorted(str(p) for p in rec.iterdir())
    assert {"trace.jsonl", "trace.csv", "summary.json", "plot.png"} <= {p.rsplit("/", 1)[-1] for p in listed}
