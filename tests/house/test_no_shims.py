"""Issue 33 item 5: 0.1.0 was never released, so its deprecation shims go: ``ethimon.spec``, the keyword
form of ``train_lora``, ``run_sim(probs=)``, ``Plan.fault_release``, the CLI's hidden old flag spellings
(``--duration``, ``--expect-head``, ``--file-timeout``). Nothing in the source warns ``DeprecationWarning``."""

from __future__ import annotations

import importlib
from pathlib import Path

import pytest

from ethimon.cli import main

SRC = Path(__file__).resolve().parents[2] / "src" / "ethimon"


def test_no_module_warns_a_deprecation():
    found = [f"{p.relative_to(SRC)}" for p in sorted(SRC.rglob("*.py"))
             if "DeprecationWarning" in p.read_text(encoding="utf-8")
             or "add_deprecated_alias" in p.read_text(encoding="utf-8")]
    assert found == [], f"deprecation shims left: {found}"


def test_the_old_spec_module_is_gone():
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module("ethimon.spec")


def test_run_sim_takes_p_only():
    from ethimon.sim import run_sim
    with pytest.raises(TypeError, match="probs"):
        run_sim({}, object(), probs=(0.9, 0.1))


def test_plan_has_no_fault_release():
    import ethimon
    from ethimon.compiler import plan_of
    plan = plan_of(ethimon.load_spec("specs/cobot_cell.yaml"))
    assert not hasattr(type(plan), "fault_release")


@pytest.mark.parametrize("argv", [
    ["ros2", "--spec", "s", "--map", "m", "--duration", "0"],
    ["audit", "verify", "log.jsonl", "--expect-head", "abc"],
    ["check", "scenarios", "--file-timeout", "5"],
    ["replay", "x.bag", "--spec", "s", "--map", "m", "--file-timeout", "5"],
])
def test_old_flag_spellings_are_unknown(argv, capsys):
    assert main(argv) == 2
    assert "unrecognized arguments" in capsys.readouterr().err


@pytest.mark.slow
def test_train_lora_takes_a_recipe_only():
    pytest.importorskip("torch")
    import inspect
    from ethimon.risk import _train
    params = inspect.signature(_train.train_lora).parameters
    assert params["recipe"].default is inspect.Parameter.empty
    assert not any(p.kind is inspect.Parameter.VAR_KEYWORD for p in params.values())
    assert not hasattr(_train, "recipe_from_keywords")
