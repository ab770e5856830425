"""The risk rule is resolved once, in the frozen Plan (issue 33 item 2): the accepted R_e range is
written in one place (``RiskPlan.accepted``) and the consumers read ``plan.risk_plan``, never the
spec's ``risk`` block, for τ, the weights, K, the variance or the age limit."""

from __future__ import annotations

import re
from pathlib import Path

import ethimon
from ethimon.compiler import plan_of

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "src" / "ethimon"
CONSUMERS = ("runtime", "verify", "loop", "scenario", "replay", "offline", "testing")
_RANGE_CALL = re.compile(r"(?<![\w.])risk_range\(")
_ACCEPTED = re.compile(r"min\(0\.0, *lo\), *max\(1\.0, *hi\)")
_RULE_READ = re.compile(r"(spec|plan)\.risk\.(alpha|beta|gamma|variance|classes|unsafe_index|max_age_s|threshold)\b")


def _lines(pkgs):
    for pkg in pkgs:
        for path in sorted((SRC / pkg).glob("*.py")):
            for i, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                yield f"{path.relative_to(ROOT)}:{i}: {line.strip()}", line.split("#")[0]


def test_the_accepted_range_is_written_once():
    where = [at for at, code in _lines(CONSUMERS + ("compiler",))
             if (_RANGE_CALL.search(code) and "def risk_range" not in code and ">>>" not in code)
             or _ACCEPTED.search(code)]
    assert where == [l for l in where if l.startswith("src/ethimon/compiler/_plan.py")], "\n".join(where)
    assert len(where) == 2  # RiskPlan.reachable and RiskPlan.accepted


def test_no_consumer_reads_the_spec_for_the_risk_rule():
    where = [at for at, code in _lines(CONSUMERS) if _RULE_READ.search(code)]
    assert not where, "\n".join(where)


def test_the_monitor_reference_and_verify_share_the_plans_range():
    spec = ethimon.load_spec_text(
        "ethimon: 1\nname: k3\nsignals: {d: {unit: m}}\nrisk: {classes: 3, gamma: 2.0}\n"
        "obligations:\n  - {id: far, require: \"d > 0.5\"}\n")
    plan = plan_of(spec)
    lo, hi = plan.risk_plan.accepted
    assert (lo, hi) == (min(0.0, plan.risk_plan.reachable[0]), max(1.0, plan.risk_plan.reachable[1]))
    m = ethimon.Monitor(spec)
    assert not m.step({"d": 1.0, "risk": hi}).faults  # at the edge: accepted
    assert m.step({"d": 1.0, "risk": hi + 1e-9}).faults[0].kind == "range"
