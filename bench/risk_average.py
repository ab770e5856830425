"""Average trained LoRA runs into one adapter (run by hand; never in CI).

    python bench/risk_average.py --runs /work/runs/a,/work/runs/b,/work/runs/c --out /work/runs/avg3

The temperature of the average is fitted on the same validation rows the runs
were selected on (ETHICS 10% of the 80% + robot validation), never on a
hold-out. Writes bench/results/risk_average_<tag>.json (validation loss and
accuracy of the average next to each run's). Then evaluate it like any run:
``python bench/risk_eval.py --model OUT --tag TAG``.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import numpy as np  # noqa: E402
import risk_data as D  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", required=True, help="comma list of run directories")
    ap.add_argument("--out", required=True)
    ap.add_argument("--max-length", type=int, default=None)
    ap.add_argument("--rank", type=int, default=None, help="truncated-SVD rank (default: exact)")
    ap.add_argument("--tag", default=None, help="write bench/results/risk_average_<tag>.json")
    a = ap.parse_args()
    import torch
    torch.set_num_threads(2)
    from ethimon.risk._soup import average_runs

    _, e_va, _ = D.ethics_splits()
    _, s_va, _ = D.sab_splits()
    _, p_va, _, _ = D.pair_splits()
    va = D.concat(e_va, s_va, p_va)
    runs = a.runs.split(",")
    m = average_runs(runs, a.out, calibrate=(va.texts, va.labels), max_length=a.max_length,
                     rank=a.rank)
    # validation figures of the average (the rows its temperature was fitted on, the
    # rows runs are chosen by; never the hold-outs)
    from ethimon.risk import load_estimator
    est = load_estimator(a.out, cache_size=0)
    lg = torch.as_tensor(np.array(est.logits_batch(va.texts)), dtype=torch.float32)
    y = torch.as_tensor(va.labels)
    res = {"runs": runs, "manifest": {k: m[k] for k in ("name", "max_length", "temperature", "averaged_from", "lora")
                                          if k != "lora"} | {"r": m["lora"]["r"],
                                                             "svd_rel_error": m.get("svd_rel_error")},
           "val_loss": float(torch.nn.functional.cross_entropy(lg, y)),  # T = 1, as runs record it
           "val_loss_T": float(torch.nn.functional.cross_entropy(lg / m["temperature"], y)),
           "val_acc": float((lg.argmax(1) == y).float().mean()), "n_val": len(va),
           "components_val": {}}
    for r in runs:
        t = Path(r) / "metrics.json"
        if t.is_file():
            h = json.loads(t.read_text())
            best = next(x for x in h["history"] if x["epoch"] == h["best_epoch"])
            res["components_val"][Path(r).name] = {"val_loss": best["val_loss"], "val_acc": best["val_acc"]}
    print(json.dumps(res, indent=1))
    if a.tag:
        out = Path(__file__).resolve().parent / "results" / f"risk_average_{a.tag}.json"
        out.write_text(json.dumps(res, indent=1) + "\n")


if __name__ == "__main__":
    main()
