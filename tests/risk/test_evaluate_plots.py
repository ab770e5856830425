"""``ethimon evaluate --plots`` agrees with the monitor (issue 34 item 6): the confusion matrix and the
three outcomes at the spec's τ and τ_confirm (the shipped governor's without a spec), τ_confirm drawn,
y axes in whole rows. Asserted on what the plot functions return and on the files, never on pixels."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from ethimon.risk._evaluate import plot_outcomes, plot_risk_hist  # noqa: E402

LABELS = [0, 0, 0, 1, 1, 1, 0]
RISKS = [0.10, 0.35, 0.60, 0.20, 0.40, 0.59, 0.25]


@pytest.mark.slow
def test_histogram_draws_tau_and_tau_confirm_with_whole_rows(tmp_path: Path) -> None:
    p = plot_risk_hist(RISKS, LABELS, 0.576, tmp_path / "h.png", confirm_threshold=0.299)
    assert Path(p).is_file() and p.ylabel == "rows"
    assert {v for v, _ in p.lines} == {0.576, 0.299}
    assert any("τ_confirm = 0.299" in lab for _, lab in p.lines) and any("τ = 0.576" in lab for _, lab in p.lines)
    assert p.yticks and all(float(t).is_integer() for t in p.yticks)  # 3 rows at most: no 0.5, 1.5


@pytest.mark.slow
def test_three_outcomes_at_the_real_thresholds(tmp_path: Path) -> None:
    p = plot_outcomes(LABELS, RISKS, 0.576, 0.299, tmp_path / "o.png")
    assert Path(p).is_file()
    assert "τ = 0.576" in p.title and "τ_confirm = 0.299" in p.title and "0.5" not in p.title.replace("0.576", "")
    assert p.xticklabels == ["execute", "hold (confirm)", "stop"] and p.yticklabels == ["safe", "unsafe"]
    # safe: 0.10, 0.25 execute; 0.35 held; 0.60 stops. unsafe: 0.20 executes; 0.40 held; 0.59 stops
    assert p.matrix == [[2, 1, 1], [1, 1, 1]]
    q = plot_outcomes(LABELS, RISKS, 0.576, None, tmp_path / "o2.png")  # no band: two outcomes
    assert q.xticklabels == ["execute", "stop"] and q.matrix == [[3, 1], [2, 1]] and "τ_confirm" not in q.title


class _Stub:
    model_id, temperature = "stub", 1.0

    def logits_batch(self, texts, progress=False, desc=""):
        # p_unsafe of each row: its text is the number
        p = np.array([float(t) for t in texts])
        return np.log(np.stack([1 - p, p], axis=1))


@pytest.mark.slow
def test_cli_plots_at_the_spec_tau_pair_and_the_governors_without_one(tmp_path: Path, monkeypatch) -> None:
    from ethimon.cli import _risk_cmds, main
    monkeypatch.setattr(_risk_cmds, "_load", lambda *a, **k: _Stub())
    data = tmp_path / "rows.csv"
    data.write_text("label,input\n" + "".join(f"{y},{q}\n" for y, q in
                                              [(0, 0.05), (0, 0.5), (0, 0.97), (1, 0.3), (1, 0.6), (1, 0.99)]))
    spec = tmp_path / "spec.yaml"
    spec.write_text("ethimon: 1\nname: t\nrisk: {threshold: 0.5, confirm_threshold: 0.3}\n")
    out = tmp_path / "m.json"
    assert main(["evaluate", "--data", str(data), "--spec", str(spec), "--plots", str(tmp_path / "p"),
                 "--json", str(out)]) == 0
    m = json.loads(out.read_text())
    names = sorted(Path(p).name for p in m["plots"])
    assert names == ["confusion_matrix.png", "outcomes.png", "risk_distribution.png"]
    assert all(Path(p).is_file() for p in m["plots"])
    assert m["plot_titles"]["confusion_matrix.png"].endswith("(R_e ≥ τ = 0.5: stop)")
    assert "τ_confirm = 0.3" in m["plot_titles"]["outcomes.png"]
    assert main(["evaluate", "--data", str(data), "--plots", str(tmp_path / "g"), "--json", str(out)]) == 0
    m = json.loads(out.read_text())
    from ethimon.risk import DEFAULT_TAU
    from ethimon.risk._estimator import DEFAULT_TAU_CONFIRM
    assert f"τ = {DEFAULT_TAU:g}" in m["plot_titles"]["outcomes.png"]
    assert f"τ_confirm = {DEFAULT_TAU_CONFIRM:g}" in m["plot_titles"]["outcomes.png"]
    assert m["tiers"]["confirm_threshold"] == DEFAULT_TAU_CONFIRM
