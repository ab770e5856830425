"""Average trained LoRA runs into one adapter (run by hand; never in CI).

    python -m bench.risk.risk_average --runs /work/runs/a,/work/runs/b,/work/runs/c --out /work/runs/avg3

The temperature of the average is fitted on the same validation rows the runs
were selected on (ETHICS 10% of the 80% + robot validation), never on a
hold-out. Writes bench/results/risk/risk_average_<tag>.json (validation loss and
accuracy of the average next to each run's). Then evaluate it like any run:
``python -m bench.risk.risk_eval --model OUT --tag TAG``.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

from bench import results_dir
from bench._machine import machine_facts
from bench.risk import risk_data as D


def component_val(run: str) -> dict:
    """The kept epoch's validation loss/accuracy of a run (its metrics.json)."""
    h = json.loads((Path(run) / "metrics.json").read_text())
    best = next(x for x in h["history"] if x["epoch"] == h["best_epoch"])
    return {"val_loss": best["val_loss"], "val_acc": best["val_acc"]}


def val_figures(model_dir, va, temperature: float) -> dict:
    import torch
    from ethimon.risk import load_estimator
    est = load_estimator(model_dir, cache_size=0, jit=False)
    lg = torch.as_tensor(np.array(est.logits_batch(va.texts)), dtype=torch.float32)
    y = torch.as_tensor(va.labels)
    from ethimon.risk._train import fit_temperature
    t_fit = fit_temperature(lg, va.labels)
    return {"val_loss": float(torch.nn.functional.cross_entropy(lg, y)),  # T = 1, as runs record it
            "val_loss_T": float(torch.nn.functional.cross_entropy(lg / temperature, y)),
            "val_loss_fitted_T": float(torch.nn.functional.cross_entropy(lg / t_fit, y)),
            "val_acc": float((lg.argmax(1) == y).float().mean())}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", required=True, help="comma list of run directories")
    ap.add_argument("--out", required=True)
    ap.add_argument("--max-length", type=int, default=None)
    ap.add_argument("--rank", type=int, default=None, help="truncated-SVD rank (default: exact)")
    ap.add_argument("--greedy", action="store_true",
                    help="greedy soup: runs in order of validation accuracy, each kept only if the "
                         "average's validation NLL (at a fitted temperature) does not rise")
    ap.add_argument("--tag", default=None, help="write bench/results/risk/risk_average_<tag>.json")
    a = ap.parse_args()
    import torch
    torch.set_num_threads(2)
    from ethimon.risk._average import average_runs

    _, e_va, _ = D.ethics_splits()
    _, s_va, _ = D.sab_splits()
    _, p_va, _, _ = D.pair_splits()
    va = D.concat(e_va, s_va, p_va)
    runs = a.runs.split(",")
    comp = {r: component_val(r) for r in runs}
    steps = []
    if a.greedy:
        # by validation NLL at a fitted temperature: smoother than accuracy on 463 rows,
        # which moves in steps of 0.2 points and is where the best single run was picked
        order = sorted(runs, key=lambda r: -comp[r]["val_acc"])
        runs = [order[0]]
        score = val_figures(order[0], va, 1.0)["val_loss_fitted_T"]
        tmp = Path(a.out).with_name(Path(a.out).name + ".greedy_tmp")
        for r in order[1:]:
            average_runs(runs + [r], tmp, temperature=1.0, max_length=a.max_length, rank=a.rank)
            f = val_figures(tmp, va, 1.0)
            keep = f["val_loss_fitted_T"] <= score
            steps.append({"run": Path(r).name, **f, "kept": keep})
            print(f"greedy: + {Path(r).name}: val NLL {f['val_loss_fitted_T']:.4f} vs {score:.4f} "
                  f"(acc {f['val_acc']:.4f}) -> {'keep' if keep else 'drop'}", flush=True)
            if keep:
                runs, score = runs + [r], f["val_loss_fitted_T"]
        if len(runs) < 2:
            raise SystemExit("greedy soup kept only one run; nothing to average")
    m = average_runs(runs, a.out, calibrate=(va.texts, va.labels), max_length=a.max_length,
                     rank=a.rank)
    # validation figures of the average (the rows its temperature was fitted on, the
    # rows runs are chosen by; never the hold-outs)
    res = {"runs": runs, "greedy_steps": steps,
           "manifest": {k: m[k] for k in ("name", "max_length", "temperature", "averaged_from")}
           | {"r": m["lora"]["r"], "svd_rel_error": m.get("svd_rel_error")},
           **val_figures(a.out, va, m["temperature"]), "n_val": len(va),
           "components_val": {Path(r).name: c for r, c in comp.items()}, "machine": machine_facts()}
    print(json.dumps({k: v for k, v in res.items() if k not in ("components_val", "machine")}, indent=1))
    if a.tag:
        out = results_dir("risk") / f"risk_average_{a.tag}.json"
        out.write_text(json.dumps(res, indent=1) + "\n")


if __name__ == "__main__":
    main()
