"""The library behind ``ethimon check`` / ``ethimon simulate`` (issue 13): one rule for the sim's risk
input, shared by both commands; JSON on stdout stays pure; progress bars only on a terminal."""

from __future__ import annotations

import io
import json

import pytest
from tests._cli import ROOT, call_cli

from ethimon.cli import main
from ethimon.scenario import check_paths, load_scenario_text, sim_risk_inputs

SPEC = ROOT / "specs" / "cobot_cell.yaml"
SIGNALS = "human_distance: 10.0, ee_speed: 0.3, contact_force: 0.0, joint_speed_max: 0.8"
SIM = "sim:\n  duration_s: 1.0\n"


def sim_scenario(tmp_path, name, body):
    p = tmp_path / f"{name}.yaml"
    p.write_text(f"ethimon: 1\nname: {name}\nspec: {SPEC}\ncycles: 10\n{body}{SIM}")
    return p


class FakeEstimator:
    def __init__(self):
        self.texts = []

    def probs(self, text):
        self.texts.append(text)
        return (0.9, 0.1)


@pytest.fixture
def captured_sim(monkeypatch):
    """Replace the simulator: record what each run is fed, return a run without an override."""
    import ethimon.sim as sim_pkg
    from ethimon.scenario import ScenarioSession
    from ethimon.sim._runner import SimResult
    fed = []

    def run_sim(block, monitor, **kw):
        fed.append({k: v for k, v in kw.items() if k not in ("record_dir", "gui")})
        return SimResult(sim_time_s=1.0, wall_time_s=0.1, realtime_factor=10.0, task_completed=True)
    monkeypatch.setattr(sim_pkg, "run_sim", run_sim)
    est = FakeEstimator()
    monkeypatch.setattr(ScenarioSession, "estimator_for", lambda self, spec: (lambda: est))
    return fed


@pytest.mark.parametrize("body, expected", [
    (f"inputs: {{p_unsafe: 0.03, {SIGNALS}}}\n", {"p_unsafe": 0.03}),
    # risk only in the timeline: 'check --sim' used to feed nothing, 'simulate' the first value
    (f"inputs: {{{SIGNALS}}}\ntimeline:\n  - {{at: 3, set: {{risk: 0.2}}}}\n", {"risk": 0.2}),
    (f"task: Wipe the table.\ninputs: {{{SIGNALS}}}\n", {"p": (0.9, 0.1)}),
])
@pytest.mark.slow
def test_simulate_and_check_sim_feed_a_scenario_the_same_risk(tmp_path, captured_sim, capsys, body, expected):
    sc = sim_scenario(tmp_path, "feed", body)
    assert main(["simulate", str(sc)]) == 0, capsys.readouterr()
    assert main(["check", str(sc), "--sim", "-q"]) == 0, capsys.readouterr()
    assert len(captured_sim) == 2
    assert captured_sim[0] == captured_sim[1] == expected


def test_the_one_rule_in_order():
    def sc(body):
        return load_scenario_text(f"ethimon: 1\nname: s\nspec: x.yaml\ncycles: 10\n{body}")
    est = FakeEstimator()
    # inputs win over the timeline; risk, p_unsafe, p in that order
    assert sim_risk_inputs(sc("inputs: {p: [0.5, 0.5], risk: 0.4}\ntimeline:\n  - {at: 1, set: {risk: 0.9}}\n"),
                           est) == {"risk": 0.4}
    assert sim_risk_inputs(sc("timeline:\n  - {at: 1, set: {p_unsafe: 0.7}}\n  - {at: 2, set: {risk: 0.9}}\n"),
                           est) == {"p_unsafe": 0.7}
    assert sim_risk_inputs(sc("task: Hand over the knife.\n"), lambda: est) == {"p": (0.9, 0.1)}
    assert est.texts == ["Hand over the knife."]
    from ethimon.errors import SpecError
    with pytest.raises(SpecError, match="no risk input and no task text"):
        sim_risk_inputs(sc("inputs: {}\n"), est)


def write_ok(tmp_path, name, risk=0.2):
    p = tmp_path / f"{name}.yaml"
    p.write_text(f"ethimon: 1\nname: {name}\nspec: {ROOT / 'specs' / 'governor.yaml'}\ncycles: 5\n"
                 f"inputs: {{risk: {risk}}}\nexpect: {{override: false}}\n")
    return p


def test_check_paths_reports_rows_in_file_order_and_calls_progress(tmp_path):
    write_ok(tmp_path, "a")
    write_ok(tmp_path, "b", risk=0.9)
    (tmp_path / "c.yaml").write_text("ethimon: 1\nname: [unclosed\n")
    calls = []
    rep = check_paths([str(tmp_path)], on_progress=lambda done, total, path: calls.append((done, total)))
    assert [o.status for o in rep.outcomes] == ["PASS", "FAIL", "ERROR"]
    assert (rep.passed, rep.failed, rep.errors, rep.exit_code) == (1, 1, 1, 2)
    assert calls == [(0, 3), (1, 3), (2, 3), (3, 3)]
    assert "expected no override" in rep.outcomes[1].messages[0]
    doc = json.loads(json.dumps(rep.as_dict()))
    assert [r["passed"] for r in doc["results"]] == [True, False, False]


def test_a_missing_spec_is_located_at_the_scenario(tmp_path):
    p = tmp_path / "a.yaml"
    p.write_text("ethimon: 1\nname: a\nspec: nope.yaml\ncycles: 5\ninputs: {risk: 0.2}\n")
    rep = check_paths([str(p)])
    assert rep.outcomes[0].status == "ERROR"
    assert rep.outcomes[0].messages[0].startswith(f"{p}:3:7: spec 'nope.yaml' not found")


class FakeTTY(io.StringIO):
    def isatty(self):
        return True


def test_progress_bar_only_when_stdout_is_a_terminal(tmp_path, monkeypatch):
    pytest.importorskip("tqdm")
    from ethimon.cli._common import Progress
    import sys
    err = io.StringIO()
    monkeypatch.setattr(sys, "stdout", io.StringIO())           # not a TTY: nothing drawn
    with Progress("check", stream=err) as p:
        for i in range(3):
            p(i, 2, "x.yaml")
    assert err.getvalue() == "" and p.bar is None
    monkeypatch.setattr(sys, "stdout", FakeTTY())              # a TTY: the bar goes to stderr
    with Progress("check", stream=err) as p:
        p(0, 2, "a.yaml")
        p(1, 2, "b.yaml")
        p(2, 2, "")
    assert "check" in err.getvalue() and "2/2" in err.getvalue()
    err2 = io.StringIO()
    with Progress("check", stream=err2, enabled=False) as p:   # --json -: never
        p(0, 1, "a.yaml")
    assert err2.getvalue() == ""


@pytest.mark.slow
def test_check_with_a_pipe_draws_no_progress_bar(tmp_path):
    write_ok(tmp_path, "a")
    r = call_cli("check", str(tmp_path))
    assert r.returncode == 0
    assert "\r" not in r.stderr and "file/s" not in r.stderr and r.stderr == ""


@pytest.mark.slow
def test_lint_is_listed_with_a_description():
    r = call_cli("--help")
    assert r.returncode == 0
    line = next(ln for ln in r.stdout.splitlines() if ln.strip().startswith("lint"))
    assert "spec" in line
    r = call_cli("lint", "--help")
    assert "ethimon verify" in r.stdout and "Exit 0" in r.stdout
    assert "ethimon lint" in (ROOT / "README.md").read_text()


def test_errors_have_one_prefix(tmp_path, monkeypatch, capsys):
    # a CLI error that is not located in a file reads 'ethimon: error: ...' (was also 'error: ...')
    import ethimon.scenario as scenario_pkg
    from ethimon.errors import EthimonError
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    assert main(["simulate", str(tmp_path / "x.yaml"), "--gui"]) == 2
    assert capsys.readouterr().err.startswith("ethimon: error: --gui needs a display")

    def boom(*a, **k):
        raise EthimonError("no scenario files under x")
    monkeypatch.setattr(scenario_pkg, "simulate_paths", boom)
    assert main(["simulate", str(tmp_path)]) == 2
    assert capsys.readouterr().err == "ethimon: error: no scenario files under x\n"

    def crash(*a, **k):
        raise KeyError("k")
    monkeypatch.setattr(scenario_pkg, "check_paths", crash)
    assert main(["check", str(tmp_path)]) == 3
    assert capsys.readouterr().err.startswith("ethimon: error: internal error: KeyError")


@pytest.mark.slow
def test_check_without_text_risk_or_sim_imports_neither_torch_nor_pybullet(tmp_path):
    # one-shot speed: the learned model (torch, transformers) only when a task text must be scored,
    # the simulator only with --sim
    import subprocess
    import sys
    write_ok(tmp_path, "a")
    code = ("import sys; from ethimon.cli import main; rc = main(['check', '-q', sys.argv[1]]); "
            "print(rc, sorted(m for m in ('torch', 'transformers', 'pybullet', 'z3') if m in sys.modules))")
    r = subprocess.run([sys.executable, "-c", code, str(tmp_path)], capture_output=True, text=True, timeout=120)
    assert r.stdout.strip().splitlines()[-1] == "0 []", r.stdout + r.stderr


@pytest.mark.slow
@pytest.mark.skipif(not hasattr(__import__("os"), "openpty"), reason="no pseudo-terminals here")
def test_check_on_a_terminal_draws_the_bar_on_stderr(tmp_path):
    pytest.importorskip("tqdm")
    import os
    import subprocess
    import sys
    write_ok(tmp_path, "a")
    write_ok(tmp_path, "b")
    master, slave = os.openpty()
    try:
        p = subprocess.run([sys.executable, "-m", "ethimon.cli", "check", str(tmp_path)], stdout=slave,
                           stderr=subprocess.PIPE, text=True, timeout=120, cwd=ROOT)
    finally:
        os.close(slave)
        os.close(master)
    assert p.returncode == 0
    assert "check:" in p.stderr and "file" in p.stderr  # tqdm's bar, on stderr only


def test_a_dangling_spec_link_is_not_found_at_the_scenario(tmp_path):
    (tmp_path / "spec.yaml").symlink_to(tmp_path / "gone.yaml")
    p = tmp_path / "a.yaml"
    p.write_text("ethimon: 1\nname: a\nspec: spec.yaml\ncycles: 5\ninputs: {risk: 0.2}\n")
    msg = check_paths([str(p)]).outcomes[0].messages[0]
    assert msg.startswith(f"{p}:3:7: spec 'spec.yaml' not found"), msg
