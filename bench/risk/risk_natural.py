"""Headline robot figures: the frozen natural robot-command test set (run by hand; never in CI).

    python -m bench.risk.risk_natural --models runs/a_s42 runs/a_s7 runs/a_s13 --tag recipe_a
    python -m bench.risk.risk_natural --models src/ethimon/risk/default_model --tag shipped

For each model (one per seed), with the spec's R_e formula (α, β, γ = 0.6, 0.2, 0.2, sample variance):

* τ is chosen on validation rows only — the validation split of the hand-written robot
  training corpus (data/robot_train, crc32 of the pair id) — as the most sensitive τ whose
  false-alarm rate there is ≤ ``--budget`` (default 15 %); ``--tau`` fixes it instead
  (e.g. to report a shipped model at its shipped τ);
* the natural test set (data/natural_robot, sha256-checked; only reported on) gives accuracy at
  p_unsafe ≥ 0.5, ROC-AUC, unsafe flagged / safe flagged at τ, minimal pairs (ranked, both
  right at τ) and per-type rows (negations, polite/justified harmful requests, ...);
* the same on the test rows that the leakage audit found far from every training row
  (bench/risk/risk_leakage.py; the two sets were written by separate writers, but common hazards
  make some sentences converge);
* secondary rows: the ETHICS cm 20 % hold-out and the templated pairs' test split.

Then mean ± sd over the models. Prints a table; writes bench/results/risk/risk_natural_<tag>.json and
bench/results/risk/risk_natural_<tag>/flag_curves.png (unsafe flagged vs false alarms as τ moves).
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from bench import RESULTS, results_dir
from bench._machine import machine_facts
from bench.risk import risk_data as D

TYPES = ("negation", "condition", "polite_harmful", "justified_harmful", "safe_mentions_danger",
         "safe_mentions_vulnerable", "multi_step", "first_person", "deception", "privacy", "property")


FAR_RULE = "nearest training row: cosine < 0.80, word-3-gram Jaccard < 0.30, not an exact duplicate"


def _far_rows(test) -> np.ndarray:
    """Mask of test rows the leakage audit (bench/risk/risk_leakage.py) found far from all training rows."""
    audit = json.loads((RESULTS / "risk" / "risk_leakage.json").read_text())
    near = {r["test_id"] for r in audit["rows"]
            if r["exact"] or r["cosine"] >= 0.80 or r["ngram_jaccard"] >= 0.30}
    return np.array([e["id"] not in near for e in test.extra])


def _curve(y, r) -> list[dict]:
    from ethimon.risk._evaluate import flag_stats
    out = []
    for t in np.round(np.arange(0.10, 0.701, 0.01), 2):
        f = flag_stats(y, r, float(t))
        out.append({"tau": float(t), "flag_rate_unsafe": f["flag_rate_unsafe"], "false_alarm_rate": f["false_alarm_rate"]})
    return out


def evaluate_model(path: str | None, *, budget: float, tau_fixed: float | None, skip_ethics: bool) -> dict:
    from ethimon.risk import load_estimator
    from ethimon.risk._evaluate import (classification_metrics, flag_stats, pair_metrics, softmax_unsafe,
                                        tau_for_false_alarm_budget, type_metrics)
    from ethimon.risk._formula import risk_from_p_unsafe

    est = load_estimator(path, cache_size=0)
    T = est.temperature
    _, n_va = D.natural_train_splits()
    test = D.natural_test()
    _, _, p_te, _ = D.pair_splits()
    sets = {"natural_val": n_va, "natural_test": test, "templated_test": p_te}
    if not skip_ethics:
        sets["ethics_holdout"] = D.ethics_splits()[2]
    q, r = {}, {}
    for name, rows in sets.items():
        q[name] = softmax_unsafe(np.array(est.logits_batch(rows.texts)), T)
        r[name] = np.array([risk_from_p_unsafe(float(v)) for v in q[name]])
    yv = np.array(n_va.labels)
    choice = tau_for_false_alarm_budget(yv, r["natural_val"], budget)
    tau = tau_fixed if tau_fixed is not None else choice["tau"]
    y = np.array(test.labels)
    far = _far_rows(test)  # test rows with no near-duplicate in the training corpus (leakage audit)
    out = {"model": path or "default", "model_id": est.model_id, "temperature": T, "tau": tau,
           "tau_rule": (f"fixed {tau_fixed}" if tau_fixed is not None
                        else f"most sensitive tau with false alarms <= {budget:g} on natural_val"),
           "val_at_tau": flag_stats(yv, r["natural_val"], tau),
           "natural": {**classification_metrics(y, q["natural_test"]), "at_tau": flag_stats(y, r["natural_test"], tau),
                       "pairs": pair_metrics(y, q["natural_test"], r["natural_test"],
                                             [e.get("pair") for e in test.extra], tau),
                       "by_type": type_metrics(y, q["natural_test"], r["natural_test"],
                                               [e.get("type") for e in test.extra], tau)},
           "natural_far": {**classification_metrics(y[far], q["natural_test"][far]),
                           "at_tau": flag_stats(y[far], r["natural_test"][far], tau),
                           "rule": FAR_RULE},
           "templated_test": {**classification_metrics(p_te.labels, q["templated_test"]),
                              "at_tau": flag_stats(p_te.labels, r["templated_test"], tau)},
           "curves": {"natural_val": _curve(yv, r["natural_val"]), "natural_test": _curve(y, r["natural_test"])}}
    if not skip_ethics:
        out["ethics_holdout"] = classification_metrics(sets["ethics_holdout"].labels, q["ethics_holdout"])
    return out


def _ms(vals) -> tuple[float, float]:
    v = np.array([x for x in vals if x == x], dtype=np.float64)
    return (float(v.mean()), float(v.std(ddof=1)) if len(v) > 1 else 0.0) if len(v) else (float("nan"), 0.0)


def summary_rows(results: list[dict]) -> list[tuple[str, float, float]]:
    get = {
        "natural accuracy (p>=0.5)": lambda m: m["natural"]["accuracy"],
        "natural, far from training rows: accuracy": lambda m: m["natural_far"]["accuracy"],
        "natural, far from training rows: flagged at tau": lambda m: m["natural_far"]["at_tau"]["flag_rate_unsafe"],
        "natural, far from training rows: false alarms at tau": lambda m: m["natural_far"]["at_tau"]["false_alarm_rate"],
        "natural ROC-AUC": lambda m: m["natural"]["roc_auc"],
        "natural unsafe flagged at tau": lambda m: m["natural"]["at_tau"]["flag_rate_unsafe"],
        "natural false alarms at tau": lambda m: m["natural"]["at_tau"]["false_alarm_rate"],
        "pairs: unsafe ranked higher": lambda m: m["natural"]["pairs"]["ranked"],
        "pairs: both right at tau": lambda m: m["natural"]["pairs"]["both_right_at_tau"],
        "tau (chosen on validation)": lambda m: m["tau"],
        "validation false alarms at tau": lambda m: m["val_at_tau"]["false_alarm_rate"],
        "templated test accuracy": lambda m: m["templated_test"]["accuracy"],
    }
    if all("ethics_holdout" in m for m in results):
        get["ETHICS hold-out accuracy"] = lambda m: m["ethics_holdout"]["accuracy"]
    rows = [(k, *_ms([f(m) for m in results])) for k, f in get.items()]
    for t in TYPES:
        if all(t in m["natural"]["by_type"] for m in results):
            b = results[0]["natural"]["by_type"][t]
            key = "flagged_unsafe" if b["unsafe"] == b["n"] else "flagged_safe" if b["unsafe"] == 0 else "accuracy"
            rows.append((f"type {t} ({b['n']} rows): {key.replace('_', ' ')}{' at tau' if key != 'accuracy' else ''}",
                         *_ms([m["natural"]["by_type"][t][key] for m in results])))
    return rows


def plot_curves(results: list[dict], path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
    for ax, key, title in ((axes[0], "natural_val", "validation (τ chosen here)"),
                           (axes[1], "natural_test", "natural test set (reported only)")):
        for m in results:
            c = m["curves"][key]
            ax.plot([p["false_alarm_rate"] for p in c], [p["flag_rate_unsafe"] for p in c], "-", lw=1,
                    label=Path(m["model"]).name)
            at = m["val_at_tau"] if key == "natural_val" else m["natural"]["at_tau"]
            ax.plot([at["false_alarm_rate"]], [at["flag_rate_unsafe"]], "o", ms=4)
        ax.axvline(0.15, ls=":", c="k")
        ax.set_xlabel("safe commands flagged (false alarms)")
        ax.set_title(title)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("unsafe commands flagged")
    axes[1].legend(fontsize=7)
    fig.suptitle("R_e ≥ τ as τ moves from 0.70 (left) to 0.10 (right); dots: the chosen τ")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--models", nargs="+", default=[None], help="model dirs, one per seed (default: shipped)")
    ap.add_argument("--tag", required=True)
    ap.add_argument("--budget", type=float, default=0.15, help="false-alarm budget on validation rows")
    ap.add_argument("--tau", type=float, default=None, help="fix τ instead of choosing it")
    ap.add_argument("--skip-ethics", action="store_true")
    a = ap.parse_args()
    import torch
    torch.set_num_threads(2)
    t0 = time.time()
    results = [evaluate_model(m, budget=a.budget, tau_fixed=a.tau, skip_ethics=a.skip_ethics) for m in a.models]
    rows = summary_rows(results)
    out = results_dir("risk")
    (out / f"risk_natural_{a.tag}").mkdir(parents=True, exist_ok=True)
    plot_curves(results, out / f"risk_natural_{a.tag}" / "flag_curves.png")
    doc = {"tag": a.tag, "models": a.models, "budget": a.budget, "n_models": len(results),
           "summary": {k: {"mean": m, "sd": s} for k, m, s in rows}, "runs": results,
           "machine": machine_facts(), "eval_time_s": round(time.time() - t0, 1)}
    (out / f"risk_natural_{a.tag}.json").write_text(json.dumps(doc, indent=1) + "\n", encoding="utf-8")
    n = len(results)
    print(f"\n{a.tag}: {n} model(s); mean ± sd over them" + ("" if n > 1 else " (a single run: no spread)"))
    for k, m, s in rows:
        print(f"  {k:<62} {m:7.4f} ± {s:.4f}")


if __name__ == "__main__":
    main()
