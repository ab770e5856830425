"""Issue 31 item 7: ``check`` and ``lint`` recognise each file's kind in a folder that holds a spec,
its scenarios and a replay mapping (both were an ERROR on the file of the other kind)."""

import shutil

from tests._cli import ROOT, call_cli


def _mixed(tmp_path):
    shutil.copy(ROOT / "specs" / "governor.yaml", tmp_path / "governor.yaml")
    (tmp_path / "knife.yaml").write_text(
        "ethimon: 1\nname: knife\nspec: governor.yaml\ntask: Hand the kitchen knife to the child blade first.\n"
        "cycles: 5\ninputs: {p_unsafe: 0.98}\nexpect: {override: true, override_by_cycle: 0}\n", encoding="utf-8")
    shutil.copy(ROOT / "examples" / "replay" / "mapping.yaml", tmp_path / "mapping.yaml")
    return tmp_path


def test_check_runs_the_scenarios_and_passes_over_the_spec_and_mapping(tmp_path):
    r = call_cli("check", str(_mixed(tmp_path)))
    assert r.returncode == 0, r.stdout + r.stderr
    assert "1 passed, 0 failed, 0 errors, 2 skipped" in r.stdout
    assert "a spec file, not a scenario: ethimon lint / verify reads it" in r.stderr + r.stdout
    assert "a mapping file, not a scenario" in r.stderr + r.stdout


def test_lint_lints_the_spec_and_passes_over_the_scenario_and_mapping(tmp_path):
    r = call_cli("lint", str(_mixed(tmp_path)))
    assert r.returncode == 0, r.stdout + r.stderr
    out = r.stdout + r.stderr
    assert "governor.yaml: ok (governor" in out
    assert "knife.yaml: skipped: a scenario file, not a spec: ethimon check reads it" in out
    assert "mapping.yaml: skipped: a mapping file, not a spec" in out


def test_a_file_named_explicitly_is_read_as_asked(tmp_path):
    """Only files found in a folder are passed over: a spec named to ``check`` is still an ERROR
    that says what is wrong (a located message), never silently skipped."""
    d = _mixed(tmp_path)
    r = call_cli("check", str(d / "governor.yaml"))
    assert r.returncode == 2
    assert "spec" in (r.stdout + r.stderr)
