"""Running a shipped sim scenario the way several sim tests do (not a test module)."""

from __future__ import annotations

from pathlib import Path

import yaml

import ethimon

ROOT = Path(__file__).resolve().parents[2]
SPEC = ROOT / "specs" / "cobot_cell.yaml"


def run_scenario(name: str, sim_over: dict | None = None, **run_kw):
    """``scenarios/sim/<name>.yaml`` under ``specs/cobot_cell.yaml``: ``(block, result)``.

    ``sim_over`` replaces keys of its ``sim:`` block; its ``inputs.p_unsafe`` (else 0.9: the
    scenarios without one are unsafe texts) stands in for the risk model; ``run_kw`` go to ``run_sim``.
    """
    from ethimon.sim import SimBlock, run_sim
    doc = yaml.safe_load((ROOT / "scenarios" / "sim" / f"{name}.yaml").read_text())
    doc["sim"].update(sim_over or {})
    block = SimBlock.model_validate(doc["sim"])
    res = run_sim(block, ethimon.Monitor(ethimon.load_spec(str(SPEC))),
                  p_unsafe=doc["inputs"].get("p_unsafe", 0.9), **run_kw)
    return block, res
