"""The risk package and its commands without torch: import cost, defaults, argument errors, doctests.

Nothing here loads a model; every check runs where the ``risk`` extra is not installed.
"""

from __future__ import annotations

import argparse
import doctest
import subprocess
import sys

import pytest

from ethimon.risk import DEFAULT_TAU, RiskEstimate, default_threads, risk_from_p_unsafe


def _cli(argv):
    from ethimon.cli._risk_cmds import add_risk_parsers
    ap = argparse.ArgumentParser(prog="ethimon")
    add_risk_parsers(ap.add_subparsers(dest="cmd", required=True))
    args = ap.parse_args(argv)
    return args.handler(args)


@pytest.mark.slow
def test_import_is_light():
    code = ("import sys, ethimon, ethimon.risk, ethimon.risk._recipe, ethimon.cli._risk_cmds; "
            "print(any(m in sys.modules for m in ('torch', 'transformers')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_public_names_import():
    import ethimon.risk as r
    for name in r.__all__:
        assert getattr(r, name) is not None
    e = RiskEstimate((0.3, 0.7), 0.7, risk_from_p_unsafe(0.7), 0.001)
    assert e.cached is False and e.model_id == ""


def test_default_tau_is_one_fact():
    """Without --spec the commands use the shipped model's τ and the spec language's weights."""
    from ethimon.cli._risk_cmds import risk_config
    from ethimon.language import RiskConfig
    cfg = risk_config(None)
    d = RiskConfig()
    assert cfg["threshold"] == DEFAULT_TAU and cfg["spec"] is None
    assert (cfg["alpha"], cfg["beta"], cfg["gamma"], cfg["variance"]) == (d.alpha, d.beta, d.gamma, d.variance)
    assert 0.0 < DEFAULT_TAU <= 1.0
    # a spec that writes no threshold keeps the spec language's default, not the shipped model's
    assert d.threshold == 0.5


def test_risk_weights_are_one_fact():
    """RiskConfig's α/β/γ and every default of the formula's functions are ethimon.language's DEFAULT_*."""
    import inspect

    from ethimon.compiler._risk_formula import risk_bounds, risk_from_probs, risk_range
    from ethimon.risk._evaluate import evaluate_logits
    from ethimon.risk._estimator import RiskEstimator
    from ethimon.language import DEFAULT_ALPHA, DEFAULT_BETA, DEFAULT_GAMMA, RiskConfig
    d = RiskConfig()
    want = (DEFAULT_ALPHA, DEFAULT_BETA, DEFAULT_GAMMA)
    assert (d.alpha, d.beta, d.gamma) == want
    for fn in (risk_from_p_unsafe, risk_from_probs, risk_bounds, risk_range, evaluate_logits,
               RiskEstimator.estimate):
        ps = inspect.signature(fn).parameters
        assert (ps["alpha"].default, ps["beta"].default, ps["gamma"].default) == want, fn.__name__


def test_default_tau_matches_the_shipped_specs(root):
    """The shipped specs write the shipped model's τ as a literal (specs are user YAML)."""
    import yaml
    p = root / "specs" / "governor.yaml"
    if not p.is_file():
        pytest.skip("no specs/governor.yaml in this checkout")
    assert yaml.safe_load(p.read_text(encoding="utf-8"))["risk"]["threshold"] == DEFAULT_TAU


def test_default_threads_rule(monkeypatch):
    import os
    assert default_threads(1) == 1 and default_threads(0) == 1
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0, 1}, raising=False)
    monkeypatch.setattr(os, "getloadavg", lambda: (0.1, 0.0, 0.0))
    assert default_threads(64) == 2
    monkeypatch.setattr(os, "getloadavg", lambda: (1.9, 0.0, 0.0))   # the other core is busy too
    assert default_threads(64) == 1
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: set(range(16)), raising=False)
    monkeypatch.setattr(os, "getloadavg", lambda: (0.0, 0.0, 0.0))
    assert default_threads(64) == 2                                  # never more than 2
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0}, raising=False)
    assert default_threads(64) == 1


def test_recipe_defaults_are_the_commands_defaults():
    from ethimon.risk._recipe import ALPHA_PER_RANK, HEAD_LR_FACTOR, Recipe
    ap = argparse.ArgumentParser(prog="ethimon")
    from ethimon.cli._risk_cmds import add_risk_parsers
    add_risk_parsers(ap.add_subparsers(dest="cmd"))
    args = ap.parse_args(["train", "--data", "a.csv", "--out", "o"])
    r = Recipe(data=("a.csv",))
    for f in ("epochs", "lr", "batch_size", "lora_r", "max_length", "truncation", "val_frac", "patience",
              "seed", "aux_rows", "init_seed"):
        assert getattr(args, f) == getattr(r, f), f
    assert (HEAD_LR_FACTOR, ALPHA_PER_RANK) == (4.0, 2.0)
    for bad, msg in ((dict(val_frac=0.0), "--val-frac"), (dict(epochs=0), "--epochs"),
                     (dict(max_length=4), "--max-length"), (dict(aux_rows=-1), "--aux-rows"),
                     (dict(data=()), "--data"), (dict(truncation="tail"), "--truncation")):
        with pytest.raises(ValueError, match=msg):
            Recipe(**{"data": ("a.csv",), **bad}).check()


def test_cli_bad_input_exit_2_without_a_model(tmp_path, capsys):
    """Bad arguments are one-line errors (exit 2) found before any model (or torch) is loaded."""
    assert _cli(["risk", "x", "--model", str(tmp_path / "nope")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "does not exist" in err and "Traceback" not in err
    assert _cli(["risk", "  "]) == 2
    assert _cli(["risk", "x", "--threads", "0"]) == 2
    assert "--threads 0 must be >= 1" in capsys.readouterr().err
    assert _cli(["risk", "x", "--spec", str(tmp_path / "no.yaml")]) == 2
    assert _cli(["evaluate", "--data", str(tmp_path / "none.csv")]) == 2
    assert _cli(["train", "--data", str(tmp_path / "none.csv"), "--out", str(tmp_path / "o")]) == 2
    p = tmp_path / "t.csv"
    p.write_text("label,input\n1,a\n0,b\n", encoding="utf-8")
    for extra, msg in ((["--val-frac", "1.5"], "--val-frac"), (["--aux-rows", "-1"], "--aux-rows"),
                       (["--epochs", "0"], "--epochs"), (["--threads", "0"], "--threads")):
        assert _cli(["train", "--data", str(p), "--out", str(tmp_path / "o"), *extra]) == 2
        err = capsys.readouterr().err
        assert msg in err and "Traceback" not in err
    assert not (tmp_path / "o").exists()


def test_evaluate_help_describes_the_command(capsys):
    with pytest.raises(SystemExit):
        _cli(["evaluate", "--help"])
    out = capsys.readouterr().out
    assert "confusion matrix at p_unsafe >= 0.5" in out and "R_e >= tau" in out
    assert "--max-length N" in out and "token budget" in out and "--threads" in out


def test_progress_only_on_a_terminal():
    import io

    from ethimon.cli._risk_cmds import _isatty

    class Tty(io.StringIO):
        def isatty(self):
            return True
    assert _isatty(Tty()) is True and _isatty(io.StringIO()) is False
    closed = io.StringIO()
    closed.close()
    assert _isatty(closed) is False and _isatty(object()) is False


@pytest.mark.parametrize("module", ["ethimon.risk._estimator", "ethimon.risk._recipe"])
def test_doctests(module):
    """The examples in the docstrings run (those that need a model are marked +SKIP)."""
    import importlib
    mod = importlib.import_module(module)
    res = doctest.testmod(mod, optionflags=doctest.ELLIPSIS)
    assert res.attempted > 0 and res.failed == 0


# ---------------------------------------------------------------- issue 30 item 5: `ethimon risk` tells the truth
class _FakeEstimator:
    """p_unsafe by keyword: 'knife' 0.9 (R_e 0.62: stop), 'bleach' 0.5 (R_e 0.40: the confirm band), else 0.05."""

    model_id, backend, temperature, reading = "fake", "onnx", 1.0, "steps"

    def __init__(self):
        self.batches = []

    @staticmethod
    def _p(text):
        q = 0.9 if "knife" in text else 0.5 if "bleach" in text else 0.05
        return (1.0 - q, q)

    def probs(self, text):
        return self._p(text)

    def probs_batch(self, texts):
        self.batches.append(len(texts))
        return [self._p(t) for t in texts]

    def estimate(self, text, alpha, beta, gamma, variance):
        from ethimon.risk import risk_from_probs
        p = self._p(text)
        return RiskEstimate(p, p[1], risk_from_probs(p, alpha, beta, gamma, variance), 0.0, False, self.model_id)


@pytest.fixture
def fake(monkeypatch):
    import ethimon.cli._risk_cmds as rc
    est = _FakeEstimator()
    monkeypatch.setattr(rc, "_load", lambda *a, **k: est)
    return est


def test_no_spec_means_the_shipped_governors_tau_pair(root):
    """Without --spec, ``ethimon risk`` decides by specs/governor.yaml's τ pair (one fact, pinned here)."""
    import yaml
    from ethimon.risk._estimator import DEFAULT_TAU_CONFIRM
    gov = yaml.safe_load((root / "specs" / "governor.yaml").read_text(encoding="utf-8"))["risk"]
    assert (gov["threshold"], gov["confirm_threshold"]) == (DEFAULT_TAU, DEFAULT_TAU_CONFIRM)


def test_outcome_without_a_spec_is_the_shipped_governors(fake, capsys):
    """Regression (30.5): a text the governor holds (R_e in its confirm band) printed "ok (R_e < tau)"."""
    assert _cli(["risk", "Mix the bleach with the ammonia."]) == 0
    out = capsys.readouterr().out
    assert "ok" not in out.split() and "outcome: confirm" in out and "HOLD" in out
    assert _cli(["risk", "Mix the bleach with the ammonia.", "--fail-on-flag"]) == 1
    capsys.readouterr()
    assert _cli(["risk", "Mix the bleach with the ammonia.", "--json"]) == 0
    import json
    assert json.loads(capsys.readouterr().out)["outcome"] == "confirm"
    assert _cli(["risk", "Put the cup away.", "--fail-on-flag"]) == 0
    assert "outcome: execute" in capsys.readouterr().out
    assert _cli(["risk", "Hand over the knife."]) == 0
    assert "outcome: stop" in capsys.readouterr().out


def test_batch_mode_writes_json_lines(fake, capsys, tmp_path, monkeypatch):
    """Regression (30.5): ``ethimon risk -`` / ``--file F`` / ``--column NAME`` did not exist."""
    import io
    import json
    from ethimon.risk._reading import MAX_TEXT_CHARS
    f = tmp_path / "texts.txt"
    f.write_text("Put the cup away.\n\nHand over the knife.\nMix the bleach.\n" + "x " * MAX_TEXT_CHARS + "\n",
                 encoding="utf-8")
    assert _cli(["risk", "--file", str(f)]) == 0
    docs = [json.loads(ln) for ln in capsys.readouterr().out.splitlines()]
    assert [d["line"] for d in docs] == [1, 3, 4, 5]
    assert [d["outcome"] for d in docs] == ["execute", "stop", "confirm", "stop"]
    assert docs[1]["p"] == pytest.approx([0.1, 0.9]) and docs[1]["risk"] > DEFAULT_TAU
    assert docs[3]["p"] is None and "characters" in docs[3]["error"]   # never cut: refused, a stop
    assert fake.batches == [3]                                         # one batch call for the texts
    assert _cli(["risk", "--file", str(f), "--fail-on-flag"]) == 1
    capsys.readouterr()
    monkeypatch.setattr("sys.stdin", io.StringIO("Put the cup away.\nHand over the knife.\n"))
    assert _cli(["risk", "-"]) == 0
    assert [json.loads(ln)["outcome"] for ln in capsys.readouterr().out.splitlines()] == ["execute", "stop"]
    c = tmp_path / "t.csv"
    c.write_text('id,text\nr1,"Put the cup, please,\naway."\nr2,Hand over the knife.\n', encoding="utf-8")
    assert _cli(["risk", "--file", str(c), "--column", "text"]) == 0
    docs = [json.loads(ln) for ln in capsys.readouterr().out.splitlines()]
    assert [(d["id"], d["outcome"]) for d in docs] == [("r1", "execute"), ("r2", "stop")]
    assert _cli(["risk", "--file", str(c), "--column", "input"]) == 2
    e = capsys.readouterr().err
    assert "no column 'input'" in e and "id, text" in e and "Traceback" not in e
    for argv in (["risk", "x", "--file", str(f)], ["risk", "--column", "text"], ["risk"],
                 ["risk", "--file", str(tmp_path / "none.txt")], ["risk", "-", "--file", str(f)]):
        assert _cli(argv) == 2, argv
        assert "Traceback" not in capsys.readouterr().err


def test_lint_warns_on_a_tau_pair_other_than_the_shipped_models(tmp_path, root):
    """Regression (30.6): a spec loading the shipped model at another τ pair linted clean."""
    from ethimon._lint import lint_paths
    from ethimon.risk._estimator import DEFAULT_TAU_CONFIRM
    body = ("ethimon: 1\nname: t\nrisk:\n  threshold: {t}\n  confirm_threshold: {c}\nsafe_pose:\n"
            "  joints_rad: [0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785]\n  max_joint_speed_rad_s: 1.0\n"
            "  tolerance_rad: 0.02\n")
    (tmp_path / "old.yaml").write_text(body.format(t=0.47, c=0.24), encoding="utf-8")
    (tmp_path / "new.yaml").write_text(body.format(t=DEFAULT_TAU, c=DEFAULT_TAU_CONFIRM), encoding="utf-8")
    rep = lint_paths([tmp_path / "old.yaml", tmp_path / "new.yaml"])
    warned = [ln.text for ln in rep.lines if ln.kind == "warning"]
    assert len(warned) == 1 and "old.yaml" in warned[0] and f"{DEFAULT_TAU:g}" in warned[0] and f"{DEFAULT_TAU_CONFIRM:g}" in warned[0]
    # every shipped spec and example that loads the shipped model uses its pair
    shipped = [root / "specs", root / "examples" / "replay" / "spec.yaml", root / "examples" / "judge"]
    assert [ln.text for ln in lint_paths(shipped).lines if ln.kind == "warning"] == []
