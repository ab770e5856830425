"""``ethimon verify``: proofs on the shipped specs, each lint on a broken fixture, counterexample replay."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys

import pytest

pytest.importorskip("z3")

import ethimon  # noqa: E402
from ethimon.cli import main  # noqa: E402
from ethimon.verify import format_table, verify_spec  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
FIX = os.path.join(ROOT, "tests", "verify_fixtures")
SPECS = os.path.join(ROOT, "specs")


def fixture(name: str) -> str:
    return os.path.join(FIX, name)


@pytest.fixture(scope="module")
def cobot():
    return verify_spec(os.path.join(SPECS, "cobot_cell.yaml"))


@pytest.mark.slow
def test_import_does_not_load_z3():
    code = "import sys, ethimon, ethimon.verify; print('z3' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_missing_z3_names_the_extra(monkeypatch):
    import builtins

    real_import = builtins.__import__

    def fake(name, *a, **kw):
        if name == "z3" or name.startswith("z3."):
            raise ImportError("no z3")
        return real_import(name, *a, **kw)
    monkeypatch.setattr(builtins, "__import__", fake)
    with pytest.raises(ethimon.DependencyNotInstalled, match=r'pip install "ethimon\[verify\]"'):
        verify_spec(os.path.join(SPECS, "governor.yaml"))


#: the one warning a shipped spec may carry: lint.retreat_uncapped (issue 32 item 5) is true of a spec whose
#: risk rule retreats to the safe pose but that has no ee_speed signal to cap the retreat near people
#: (the paper's text-only governor; ssm_measured, whose risk rule is unused in its cell). The lint's
#: message tells the integrator which rule to add; cobot_cell has it (slow_near_human).
#: lint.brakes (issue 32, BRAKE_SAFETY_FACTOR 1.5): the Panda's estimated 87 N·m brakes hold the rated
#: 3 kg at stretched poses with less than the factor, so a spec whose rules cut power (stop 0/1) warns.
EXPECTED_WARNINGS = {"governor.yaml": {"lint.retreat_uncapped"}, "cobot_cell.yaml": {"lint.brakes"},
                     "ssm_measured.yaml": {"lint.retreat_uncapped", "lint.brakes"}}


@pytest.mark.slow
@pytest.mark.parametrize("name", ["governor.yaml", "cobot_cell.yaml"])
def test_shipped_specs_prove_everything_without_warnings(name):
    rep = verify_spec(os.path.join(SPECS, name))
    assert rep.error is None
    agree = ("model.agrees", "tier.agrees")  # agreement checks against the Monitor: "ok", not proofs
    props = [f for f in rep.findings if f.kind == "property" and f.name not in agree]
    assert props and all(f.status == "proved" for f in props), format_table(rep)
    assert rep.finding("model.agrees").status == "ok"
    assert all(f.status == "ok" for f in rep.findings if f.name == "tier.agrees"), format_table(rep)
    assert {f.name for f in rep.warnings} == EXPECTED_WARNINGS[name], format_table(rep)
    assert rep.exit_code == 0


@pytest.mark.slow
def test_cobot_cell_has_one_proof_per_obligation(cobot):
    for oid in ("separation", "slow_near_human", "transient_contact", "clamping", "joint_speed"):
        assert cobot.finding(f"{oid}.response").status == "proved"
        assert cobot.finding(f"{oid}.defined").status == "proved"
    assert cobot.finding("risk.override").status == "proved"
    assert cobot.finding("risk.bounds").message.startswith("R_e in [0.1, 0.7]")
    assert cobot.unroll == 5  # held(…, 5): 4 cycles of look-back + the current one
    assert cobot.finding("model.agrees").status == "ok"


@pytest.mark.parametrize("file, lint", [
    ("tau_never.yaml", "lint.tau_range"),
    ("vacuous.yaml", "lint.vacuous.never_negative"),
    ("contradiction.yaml", "lint.contradiction.slow.fast"),
    ("contradiction.yaml", "lint.unsatisfiable.impossible_force"),
    ("release_unreachable.yaml", "lint.release"),
    ("unit_mismatch.yaml", "lint.unit_mismatch"),
    ("unbounded.yaml", "lint.unbounded.torque"),
    ("fault_gap.yaml", "lint.fault_gap.clamping"),
    ("risk_not_monotone.yaml", "lint.risk_monotone"),
])
@pytest.mark.slow
def test_each_lint_fires_on_its_fixture(file, lint):
    rep = verify_spec(fixture(file))
    f = rep.finding(lint)
    assert f is not None and f.status == "warning", format_table(rep)


def test_lints_stay_quiet_where_they_should():
    rep = verify_spec(fixture("contradiction.yaml"))
    # 'impossible_force' is unsatisfiable on its own, so it is not also reported in pairs
    assert not any(f.name.startswith("lint.contradiction.") and "impossible_force" in f.name for f in rep.findings)
    assert rep.finding("lint.tau_range").status == "ok"


def test_tau_always_fires_and_manual_release():
    spec = ethimon.load_spec_text("ethimon: 1\nname: t\nrisk: {threshold: 0.1, release: {mode: manual}}\n")
    rep = verify_spec(spec)
    assert "fires every cycle" in rep.finding("lint.tau_range").message
    assert "manual" in rep.finding("lint.release").message


def test_unit_mismatch_is_unusable_with_a_position():
    rep = verify_spec(fixture("unit_mismatch.yaml"))
    assert rep.exit_code == 2
    assert "unit_mismatch.yaml:9:14: unit mismatch" in rep.error


def test_refuted_property_replays_in_the_monitor(tmp_path):
    rep = verify_spec(fixture("refuted_division.yaml"), counterexamples=tmp_path)
    f = rep.finding("time_to_contact.defined")
    assert f.status == "refuted" and rep.exit_code == 1
    cex = f.counterexample
    assert cex.confirmed
    # replay the frames ourselves in a fresh Monitor: in-range input, yet a fail-closed fault
    spec = ethimon.load_spec(fixture("refuted_division.yaml"))
    m = ethimon.Monitor(spec)
    decisions = [m.step(fr) for fr in cex.frames]
    d = decisions[cex.cycle]
    assert all(0 <= fr["human_distance"] <= 10 and 0 <= fr["ee_speed"] <= 3 for fr in cex.frames)
    assert cex.frames[cex.cycle]["human_distance"] == 0.0
    assert d.override and any(x.kind == "internal" and "ZeroDivisionError" in x.message for x in d.faults)
    # the other properties of the same spec still hold
    assert rep.finding("time_to_contact.response").status == "proved"
    # the scenario file replays with the scenario runner and fails on the refuted property
    from ethimon.scenario import load_scenario, run_scenario
    assert f.scenario and os.path.exists(f.scenario)
    res = run_scenario(load_scenario(f.scenario))
    assert not res.passed and any("expected no fault" in x for x in res.failures)


@pytest.mark.slow
def test_multi_cycle_counterexample_inside_a_window(tmp_path):
    text = """
ethimon: 1
name: windowed
signals:
  d: {unit: m, range: [0, 5]}
  v: {unit: m/s, range: [0, 2]}
obligations:
  - id: gap
    when: held(d < 1, 3)
    require: v / (d - prev(d)) < 10
"""
    path = tmp_path / "windowed.yaml"
    path.write_text(text)
    rep = verify_spec(str(path), counterexamples=tmp_path / "cex")
    f = rep.finding("gap.defined")
    assert f.status == "refuted" and f.counterexample.confirmed
    cex = f.counterexample
    assert cex.cycle >= 2  # the 'when' window must fill before 'require' is evaluated
    assert all(fr["d"] < 1 for fr in cex.frames[-3:])


@pytest.mark.slow
def test_cli_exit_codes_json_and_tables(tmp_path, capsys):
    out = tmp_path / "v.json"
    assert main(["verify", SPECS, "--json", str(out)]) == 0
    doc = json.loads(out.read_text())
    assert doc["exit_code"] == 0 and len(doc["specs"]) == 3  # cobot_cell, governor, ssm_measured
    for s in doc["specs"]:
        odd = {f["name"] for f in s["findings"] if f["status"] not in ("proved", "ok")}
        assert odd == EXPECTED_WARNINGS[os.path.basename(s["path"])], (s["path"], odd)
        assert {f["status"] for f in s["findings"] if f["name"] in odd} <= {"warning"}
    assert {f["name"] for s in doc["specs"] for f in s["findings"]} >= {"lint.brakes", "lint.retreat_uncapped"}
    assert "risk.override" in capsys.readouterr().out
    assert main(["verify", fixture("refuted_division.yaml"), "--counterexamples", str(tmp_path / "c")]) == 1
    assert os.listdir(tmp_path / "c") == ["refuted_division.time_to_contact.defined.yaml"]
    assert main(["verify", fixture("unit_mismatch.yaml")]) == 2
    capsys.readouterr()
    assert main(["verify", str(tmp_path / "missing.yaml")]) == 2
    err = capsys.readouterr().err
    assert "no such file" in err and "Traceback" not in err
    assert main(["verify", fixture("tau_never.yaml")]) == 0  # lint warnings alone do not fail


def test_counterexample_scenario_roundtrips_nan_free_values(tmp_path):
    rep = verify_spec(fixture("refuted_division.yaml"), counterexamples=tmp_path)
    cex = rep.finding("time_to_contact.defined").counterexample
    assert all(isinstance(v, (float, bool)) and not (isinstance(v, float) and math.isnan(v))
               for fr in cex.frames for v in fr.values())


@pytest.mark.slow
def test_three_classes_and_long_windows():
    spec = ethimon.load_spec_text("""
ethimon: 1
name: k3
signals: {x: {range: [0, 10]}}
risk: {classes: 3, threshold: 0.7}
obligations:
  - {id: slow, when: "once(x > 5, 3)", require: x < 8, within_cycles: 40}
""")
    rep = verify_spec(spec, max_unroll=8)
    assert rep.finding("risk.bounds").status == "skipped"
    # K = 3, paper weights: R_e in [0.2/3, 0.6 + 0.2/3]; tau = 0.7 is above it
    tau = rep.finding("lint.tau_range")
    assert tau.status == "warning" and "never fire" in tau.message
    # a bounded response longer than the unrolling is not claimed as proved
    assert rep.finding("slow.response").status == "unknown" and rep.exit_code == 1
    assert rep.finding("risk.override").status == "proved"


@pytest.mark.slow
def test_sqrt_is_encoded_exactly():
    spec = ethimon.load_spec_text("""
ethimon: 1
name: roots
signals: {x: {range: [0, 10]}}
obligations:
  - {id: guarded, require: "x <= 0 or x / sqrt(x) < 3"}
  - {id: unguarded, require: "sqrt(x - 1) < 2", response: stop_2}
""")
    rep = verify_spec(spec)
    assert rep.finding("guarded.defined").status == "proved"
    assert rep.finding("lint.vacuous").status == "ok"  # x >= 9 violates 'guarded': sqrt(x) >= 3
    f = rep.finding("unguarded.defined")
    assert f.status == "refuted" and f.counterexample.confirmed
    assert f.counterexample.frames[-1]["x"] < 1
    assert "ValueError" in " ".join(f.counterexample.replay[-1]["faults"])


def test_a_wrong_model_is_caught_by_the_replay(monkeypatch):
    """If the z3 model of the decision logic were wrong, its counterexample would not replay."""
    from ethimon.verify import _encode, _unrolling

    real_trace = _encode.decision_trace

    def broken(enc, **kw):  # a model that forgets the risk rule
        dt = real_trace(enc, **kw)
        dt.override = [z3.And(o, z3.Not(f)) for o, f in zip(dt.override, dt.risk_fires)]
        return dt
    import z3
    monkeypatch.setattr(_unrolling, "decision_trace", broken)
    rep = verify_spec(os.path.join(SPECS, "governor.yaml"))
    f = rep.finding("risk.override")
    assert f.status == "refuted"
    assert not f.counterexample.confirmed  # the real Monitor overrides: the model, not the spec, is wrong
    assert "NOT confirmed" in format_table(rep)
    # and the sampled comparison of model and Monitor flags the model itself
    agree = rep.finding("model.agrees")
    assert agree.status == "refuted" and "disagrees with the Monitor" in agree.message
