"""The CLI under hostile files (issue 11): one bad file is one failed row, never the whole run;
unknown scenario inputs are errors with a hint; FIFOs and /dev/stdin never make the CLI hang."""

import json
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import pytest
from tests._cli import ROOT, call_cli, run_cli

from ethimon.cli import main
from ethimon.errors import SpecError

GOVERNOR = ROOT / "specs" / "governor.yaml"

KETTLE_SPEC = """\
ethimon: 1
name: kettle
signals:
  vessel_temp: {unit: degC, range: [-50, 400]}
  human_distance: {unit: m, range: [0, 100]}
risk: {alpha: 0.6, beta: 0.2, gamma: 0.2, threshold: 0.27, response: safe_pose}
obligations:
  - id: hot_near_person
    require: not (vessel_temp > 60 and human_distance < 0.5)
    response: safe_pose
"""


def ok_scenario(path, name, spec=GOVERNOR):
    path.write_text(f"ethimon: 1\nname: {name}\nspec: {spec}\ncycles: 5\ninputs: {{risk: 0.2}}\n"
                    "expect: {override: false}\n")
    return path


def hostile_specs(folder):
    """A spec that must be refused (a 5,000-digit hex constant) and one that must load (a 2,000-term
    ``and`` chain: chains are balanced trees since issue 11)."""
    head = ("ethimon: 1\nname: {n}\nsignals:\n  x: {{unit: m, range: [0, 10]}}\n"
            "risk: {{alpha: 0.6, beta: 0.2, gamma: 0.2, threshold: 0.27, response: safe_pose}}\n")
    hexs = folder / "hex_spec.yaml"
    hexs.write_text(head.format(n="hex") + "constants:\n  big: 0x" + "f" * 5000 + "\n"
                    "obligations:\n  - {id: o, require: x < 5, response: safe_pose}\n")
    chain = folder / "chain_spec.yaml"
    chain.write_text(head.format(n="chain") + "obligations:\n  - id: o\n    require: "
                     + " and ".join(["x < 5"] * 2000) + "\n    response: safe_pose\n")
    return hexs, chain


def hostile_folder(tmp_path):
    specs = tmp_path / "specs"
    specs.mkdir()
    hexs, chain = hostile_specs(specs)
    d = tmp_path / "scenarios"
    d.mkdir()
    ok_scenario(d / "a_ok.yaml", "a_ok")
    for name, spec in (("b_hex", hexs), ("c_chain", chain)):
        (d / f"{name}.yaml").write_text(f"ethimon: 1\nname: {name}\nspec: {spec}\ncycles: 5\n"
                                        "inputs: {risk: 0.2, x: 1.0}\n")
    # a hostile scenario: a 5,000-digit hex cycle number
    (d / "d_hexat.yaml").write_text(f"ethimon: 1\nname: d_hexat\nspec: {GOVERNOR}\ncycles: 5\n"
                                    "inputs: {risk: 0.2}\ntimeline:\n  - {at: 0x" + "f" * 5000
                                    + ", set: {risk: 0.3}}\n")
    ok_scenario(d / "e_ok.yaml", "e_ok")
    return d


# -- (a) one bad file is one row ---------------------------------------------------------------------

@pytest.mark.slow
@pytest.mark.parametrize("sim", [False, True])
def test_hostile_files_are_one_error_row_each_and_reports_are_written(tmp_path, sim):
    d = hostile_folder(tmp_path)
    out, junit = tmp_path / "r.json", tmp_path / "r.xml"
    r = call_cli("check", str(d), "--json", str(out), "--junit", str(junit), *(["--sim"] if sim else []),
                timeout=120)
    assert r.returncode == 2, r.stdout + r.stderr
    assert "Traceback" not in r.stderr
    doc = json.loads(out.read_text())
    by_path = {os.path.basename(x["path"]): x for x in doc["results"]}
    assert sorted(by_path) == ["a_ok.yaml", "b_hex.yaml", "c_chain.yaml", "d_hexat.yaml", "e_ok.yaml"]
    assert by_path["a_ok.yaml"]["passed"] is True and by_path["e_ok.yaml"]["passed"] is True
    # the huge literals are ERROR rows, refused by the parser (a SpecError naming the file, not an
    # internal error); the 2,000-term chain loads and its scenario passes
    for bad in ("b_hex.yaml", "d_hexat.yaml"):
        assert by_path[bad]["passed"] is False and "too long" in by_path[bad]["error"]
        assert "internal error" not in by_path[bad]["error"]
    assert by_path["c_chain.yaml"]["passed"] is True and "error" not in by_path["c_chain.yaml"]
    assert "3 passed, 0 failed, 2 errors" in r.stdout, r.stdout
    suite = ET.parse(junit).getroot()
    assert suite.get("tests") == "5" and suite.get("errors") == "2" and suite.get("failures") == "0"


@pytest.mark.parametrize("exc", [RecursionError("maximum recursion depth exceeded"),
                                 OverflowError("int too large to convert to float"),
                                 ValueError("Exceeds the limit (4300 digits)"),
                                 MemoryError(), ZeroDivisionError("float division by zero")])
def test_unexpected_exception_in_one_file_is_one_error_row(tmp_path, monkeypatch, capsys, exc):
    import ethimon.scenario as scenario_pkg
    real = scenario_pkg.load_scenario

    def load(path):
        if os.path.basename(path) == "b.yaml":
            raise exc
        return real(path)
    monkeypatch.setattr(scenario_pkg, "load_scenario", load)
    for n in ("a", "b", "c"):
        ok_scenario(tmp_path / f"{n}.yaml", n)
    junit = tmp_path / "r.xml"
    rc = main(["check", str(tmp_path), "--junit", str(junit)])
    cap = capsys.readouterr()
    assert rc == 2
    assert "2 passed, 0 failed, 1 errors" in cap.out
    assert f"{tmp_path / 'b.yaml'}: internal error: {type(exc).__name__}" in cap.err
    assert "please report" in cap.err and "Traceback" not in cap.err
    suite = ET.parse(junit).getroot()
    assert suite.get("tests") == "3" and suite.get("errors") == "1"


def test_a_bad_spec_shared_by_scenarios_is_read_once(tmp_path, monkeypatch, capsys):
    import ethimon._api as api
    calls = []
    real = api.load_spec

    def load_spec(path):
        calls.append(path)
        if "bad" in os.fspath(path):
            raise RecursionError("maximum recursion depth exceeded")
        return real(path)
    monkeypatch.setattr(api, "load_spec", load_spec)
    bad = tmp_path / "bad_spec.yaml"
    bad.write_text(GOVERNOR.read_text())
    for n in ("a", "b"):
        ok_scenario(tmp_path / f"{n}.yaml", n, spec=bad)
    ok_scenario(tmp_path / "c.yaml", "c")
    rc = main(["check", str(tmp_path / "a.yaml"), str(tmp_path / "b.yaml"), str(tmp_path / "c.yaml")])
    cap = capsys.readouterr()
    assert rc == 2 and "1 passed, 0 failed, 2 errors" in cap.out
    assert sum("bad" in os.fspath(c) for c in calls) == 1



@pytest.mark.parametrize("exc", [RecursionError("maximum recursion depth exceeded"),
                                 SpecError("bad spec", path="x.yaml", line=3, column=1, hint="fix it")])
def test_a_cached_spec_failure_is_raised_fresh_for_each_scenario(tmp_path, monkeypatch, exc):
    import ethimon._api as api
    from ethimon.scenario import ScenarioSession, load_scenario
    from ethimon.scenario._session import _SpecLoadError

    def load_spec(path):
        raise exc
    monkeypatch.setattr(api, "load_spec", load_spec)
    (tmp_path / "bad_spec.yaml").write_text("")  # exists: the failure is the loader's, not "not found"
    session, raised = ScenarioSession(), []
    for n in ("a", "b", "c"):
        sc = load_scenario(ok_scenario(tmp_path / f"{n}.yaml", n, spec=tmp_path / "bad_spec.yaml"))
        # a SpecError is raised as itself; anything else wrapped, naming the spec (the row blames it)
        with pytest.raises(SpecError if isinstance(exc, SpecError) else _SpecLoadError) as info:
            session.spec_for(sc)
        got = info.value
        if isinstance(got, _SpecLoadError):
            assert got.spec_path == str(tmp_path / "bad_spec.yaml")
            got = got.exc
        assert isinstance(got, type(exc))
        raised.append(got)
    assert len({id(e) for e in raised}) == 3 and all(e is not exc for e in raised)
    assert all(str(e) == str(exc) and type(e) is type(exc) for e in raised)
    assert all(e.__context__ is None and e.__cause__ is None for e in raised)
    # no traceback accumulates across scenarios: each carries only its own raise
    depths = []
    for e in raised:
        tb, n = e.__traceback__, 0
        while tb is not None:
            tb, n = tb.tb_next, n + 1
        depths.append(n)
    assert len(set(depths)) == 1, depths

@pytest.mark.slow
def test_lint_reports_every_file_despite_a_hostile_one(tmp_path):
    hexs, chain = hostile_specs(tmp_path)
    good = tmp_path / "good.yaml"
    good.write_text(GOVERNOR.read_text())
    r = call_cli("lint", str(tmp_path), timeout=120)
    assert r.returncode == 2, r.stdout + r.stderr
    assert "Traceback" not in r.stderr
    assert f"{good}: ok (governor" in r.stdout
    assert f"{hexs}:" in r.stderr and "too long" in r.stderr and f"{hexs}: ok" not in r.stdout
    assert f"{chain}: ok" in r.stdout and f"{chain}:" not in r.stderr


def test_lint_unexpected_exception_is_one_line(tmp_path, monkeypatch, capsys):
    import ethimon._api as api
    real = api.load_spec

    def load_spec(path):
        if os.path.basename(path) == "a.yaml":
            raise OverflowError("cannot convert float infinity to integer")
        return real(path)
    monkeypatch.setattr(api, "load_spec", load_spec)
    for n in ("a", "b"):
        (tmp_path / f"{n}.yaml").write_text(GOVERNOR.read_text())
    rc = main(["lint", str(tmp_path)])
    cap = capsys.readouterr()
    assert rc == 2
    assert f"{tmp_path / 'a.yaml'}: internal error: OverflowError" in cap.err
    assert f"{tmp_path / 'b.yaml'}: ok" in cap.out


@pytest.mark.slow
def test_lint_empty_folder_message_is_about_specs(tmp_path):
    r = run_cli("lint", str(tmp_path))
    assert r.returncode == 2
    assert "no spec files" in r.stderr and "ethimon lint" in r.stderr
    assert "ethimon check" not in r.stderr and "scenario" not in r.stderr


def test_verify_unexpected_exception_in_one_spec_is_one_report(tmp_path, monkeypatch, capsys):
    pytest.importorskip("z3")
    import ethimon.verify as verify_pkg
    from ethimon.verify import SpecReport
    (tmp_path / "a.yaml").write_text(GOVERNOR.read_text())
    (tmp_path / "b.yaml").write_text(GOVERNOR.read_text())

    def verify_spec(path, **kw):
        if os.path.basename(path) == "a.yaml":
            raise RecursionError("maximum recursion depth exceeded")
        return SpecReport(path=path, name="governor")
    monkeypatch.setattr(verify_pkg, "verify_spec", verify_spec)
    out = tmp_path / "r.json"
    rc = main(["verify", str(tmp_path), "--json", str(out)])
    cap = capsys.readouterr()
    assert rc == 2
    assert "internal error: RecursionError" in cap.out
    doc = json.loads(out.read_text())
    assert len(doc["specs"]) == 2


# -- (b) unknown scenario inputs --------------------------------------------------------------------

def kettle(tmp_path, body):
    spec = tmp_path / "kettle.yaml"
    spec.write_text(KETTLE_SPEC)
    sc = tmp_path / "sc.yaml"
    sc.write_text(f"ethimon: 1\nname: sc\nspec: kettle.yaml\ncycles: 10\n{body}")
    return sc


@pytest.mark.slow
def test_timeline_typo_is_an_error_with_a_hint(tmp_path):
    sc = kettle(tmp_path, "inputs: {risk: 0.1, vessel_temp: 20, human_distance: 0.2}\n"
                          "timeline:\n  - {at: 5, set: {vesel_temp: 90}}\n"
                          "expect: {override: false}\n")
    r = call_cli("check", str(sc))
    assert r.returncode == 2, r.stdout + r.stderr
    assert f"{sc}:7:" in r.stderr  # file:line:column of the key
    assert "'vesel_temp'" in r.stderr and "did you mean 'vessel_temp'?" in r.stderr
    assert "Traceback" not in r.stderr and "PASS" not in r.stdout


@pytest.mark.slow
def test_inputs_typo_is_an_error_not_a_missing_signal(tmp_path):
    sc = kettle(tmp_path, "inputs: {risk: 0.1, vessel_temp: 20, human_distnce: 3.0}\n"
                          "expect: {override: true}\n")
    r = run_cli("check", str(sc))
    assert r.returncode == 2, r.stdout + r.stderr
    line = next(ln for ln in r.stderr.splitlines() if "human_distnce" in ln)
    assert line.startswith(f"{sc}:5:")
    assert "did you mean 'human_distance'?" in line
    assert "is missing" not in r.stderr


def test_unknown_input_without_close_match_lists_known_inputs(tmp_path):
    from ethimon.scenario import load_scenario, run_scenario
    sc = kettle(tmp_path, "inputs: {risk: 0.1, vessel_temp: 20, human_distance: 3.0, zzz: 1}\n")
    with pytest.raises(SpecError) as ei:
        run_scenario(load_scenario(sc))
    e = ei.value
    assert e.line == 5 and e.column is not None
    assert "human_distance" in str(e) and "vessel_temp" in str(e) and "risk" in str(e)


@pytest.mark.parametrize("risk", ["risk: 0.1", "p_unsafe: 0.05", "p: [0.95, 0.05]"])
def test_builtin_inputs_stay_valid(tmp_path, risk):
    from ethimon.scenario import load_scenario, run_scenario
    sc = kettle(tmp_path, f"inputs: {{{risk}, vessel_temp: 20, human_distance: 3.0, risk_age_s: 0.0}}\n"
                          "timeline:\n  - {at: 3, set: {risk_age_s: 0.1, " + risk + "}}\n"
                          "expect: {override: false, fault: false}\n")
    res = run_scenario(load_scenario(sc))
    assert res.passed, res.failures


@pytest.mark.slow
def test_counterexample_style_scenario_stays_valid(tmp_path):
    # what 'ethimon verify --counterexamples' writes: signals, risk, risk_age_s, nulls in the timeline
    sc = kettle(tmp_path, "inputs: {vessel_temp: 20.0, human_distance: 3.0, risk: 0.1, risk_age_s: 0.0}\n"
                          "timeline:\n  - {at: 2, set: {vessel_temp: null}}\n"
                          "expect: {fault: true}\n")
    r = run_cli("check", str(sc))
    assert r.returncode == 0, r.stdout + r.stderr


# -- (c) FIFOs and /dev/stdin never hang --------------------------------------------------------------

needs_fifo = pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs on this platform")


@pytest.mark.slow
@needs_fifo
def test_fifo_in_a_folder_is_a_skipped_row(tmp_path):
    ok_scenario(tmp_path / "a.yaml", "a")
    os.mkfifo(tmp_path / "b.yaml")
    junit = tmp_path / "r.xml"
    r = run_cli("check", str(tmp_path), "--junit", str(junit), timeout=30)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "1 passed, 0 failed, 0 errors, 1 skipped" in r.stdout
    assert "regular file" in r.stdout + r.stderr
    assert ET.parse(junit).getroot().get("skipped") == "1"


@pytest.mark.slow
@needs_fifo
@pytest.mark.parametrize("cmd", ["check", "lint", "simulate"])
def test_fifo_on_the_command_line_is_refused(tmp_path, cmd):
    fifo = tmp_path / "x.yaml"
    os.mkfifo(fifo)
    r = run_cli(cmd, str(fifo), timeout=30)
    assert r.returncode == 2, r.stdout + r.stderr
    assert f"{fifo}" in r.stderr and "regular file" in r.stderr and "FIFO" in r.stderr
    assert "Traceback" not in r.stderr


@pytest.mark.slow
@needs_fifo
def test_fifo_in_a_folder_is_skipped_by_lint(tmp_path):
    (tmp_path / "a.yaml").write_text(GOVERNOR.read_text())
    os.mkfifo(tmp_path / "b.yaml")
    r = run_cli("lint", str(tmp_path), timeout=30)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "skipped" in r.stdout and "regular file" in r.stdout


@pytest.mark.slow
@needs_fifo
def test_scenario_whose_spec_is_a_fifo_is_one_error_row(tmp_path):
    os.mkfifo(tmp_path / "spec.yaml")
    ok_scenario(tmp_path / "a.yaml", "a", spec="spec.yaml")
    ok_scenario(tmp_path / "b.yaml", "b")
    r = run_cli("check", str(tmp_path / "a.yaml"), str(tmp_path / "b.yaml"), timeout=30)
    assert r.returncode == 2, r.stdout + r.stderr
    assert "1 passed, 0 failed, 1 errors" in r.stdout
    assert "regular file" in r.stderr and "FIFO" in r.stderr


@pytest.mark.slow
@needs_fifo
def test_fifo_key_file_is_refused(tmp_path):
    fifo = tmp_path / "key"
    os.mkfifo(fifo)
    log = tmp_path / "log.jsonl"
    log.write_text("")
    r = run_cli("audit", "verify", str(log), "--key-file", str(fifo), timeout=30)
    assert r.returncode == 2 and "regular file" in r.stderr


@pytest.mark.slow
@pytest.mark.skipif(not os.path.exists("/dev/stdin"), reason="no /dev/stdin")
@pytest.mark.parametrize("cmd", ["check", "lint"])
def test_dev_stdin_as_a_pipe_does_not_hang(cmd):
    rfd, wfd = os.pipe()  # the writer stays open: reading the pipe would block forever
    try:
        p = subprocess.run([sys.executable, "-m", "ethimon.cli", cmd, "/dev/stdin"], stdin=rfd,
                           capture_output=True, text=True, timeout=30, cwd=ROOT)
    finally:
        os.close(rfd)
        os.close(wfd)
    assert p.returncode == 2, p.stdout + p.stderr
    assert "regular file" in p.stderr and "Traceback" not in p.stderr


@pytest.mark.slow
@needs_fifo
def test_report_to_a_fifo_without_reader_does_not_hang(tmp_path):
    ok_scenario(tmp_path / "a.yaml", "a")
    fifo = tmp_path / "report.json"
    os.mkfifo(fifo)
    junit = tmp_path / "r.xml"
    r = run_cli("check", str(tmp_path / "a.yaml"), "--json", str(fifo), "--junit", str(junit), timeout=30)
    assert r.returncode == 2, r.stdout + r.stderr
    assert f"{fifo}: cannot write the JSON report: a named pipe (FIFO) with no reader" in r.stderr
    assert ET.parse(junit).getroot().get("tests") == "1"  # the other report is still written


@pytest.mark.slow
def test_unwritable_report_is_one_line(tmp_path):
    ok_scenario(tmp_path / "a.yaml", "a")
    junit = tmp_path / "no" / "such" / "r.xml"
    r = call_cli("check", str(tmp_path / "a.yaml"), "--junit", str(junit))
    assert r.returncode == 2, r.stdout + r.stderr
    assert f"{junit}: cannot write the JUnit report" in r.stderr and "Traceback" not in r.stderr
    assert "1 passed" in r.stdout
