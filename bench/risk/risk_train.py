"""Train the shipped risk model by hand (never in CI). Writes a run dir + JSON.

    python -m bench.risk.risk_train --out runs/main [--ethics-only] [--epochs 4]
    python -m bench.risk.risk_train --out runs/mt --aux justice,deontology,virtue --aux-n 2000
    python -m bench.risk.risk_train --out runs/forms_s42 --natural --ethics-n 1000 --writers w01,...,w12 \
        --forms f01,f02 --full --init-from src/ethimon/risk/default_model --epochs 1 --max-steps S --lr 3e-5 \
        --max-length 256 --pair-weight 1.0 --seed 42      (issue 30: DECISIONS.md, 21:12 UTC entry)

Prints the per-epoch table and writes bench/results/risk/risk_train_<tag>.json.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

from bench import results_dir
from bench._machine import machine_facts
from bench.risk import risk_data as D


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", required=True)
    ap.add_argument("--tag", default=None)
    ap.add_argument("--ethics-only", action="store_true")
    ap.add_argument("--robot-only", action="store_true")
    ap.add_argument("--epochs", type=int, default=4)
    ap.add_argument("--lr", type=float, default=5e-4)
    ap.add_argument("--r", type=int, default=16)
    ap.add_argument("--max-length", type=int, default=128)
    ap.add_argument("--truncation", default="head_tail")
    ap.add_argument("--seed", type=int, default=42)
    ap.add_argument("--init-seed", type=int, default=None,
                    help="seed of the initial LoRA factors and heads only (runs to be averaged)")
    ap.add_argument("--robot-weight", type=float, default=1.0)
    ap.add_argument("--max-steps", type=int, default=None)
    ap.add_argument("--aux", default="", help="comma list of ETHICS subsets as auxiliary "
                    "tasks (justice,deontology,virtue)")
    ap.add_argument("--aux-n", type=int, default=2000, help="rows drawn per auxiliary task")
    ap.add_argument("--aux-weight", type=float, default=1.0)
    ap.add_argument("--limit", type=int, default=None, help="smoke test: first N rows per set")
    ap.add_argument("--natural", action="store_true",
                    help="add the hand-written robot corpus data/robot_train (its validation split too)")
    ap.add_argument("--natural-weight", type=float, default=1.0)
    ap.add_argument("--ethics-n", type=int, default=None, help="draw this many ETHICS cm training rows")
    ap.add_argument("--no-templated", action="store_true", help="leave out the templated robot_pairs.csv")
    ap.add_argument("--init-from", default=None, help="warm start from this ethimon LoRA model dir")
    ap.add_argument("--pair-weight", type=float, default=0.0, help="weight of the minimal-pair margin loss")
    ap.add_argument("--pair-margin", type=float, default=1.0)
    ap.add_argument("--pairs-per-step", type=int, default=8)
    ap.add_argument("--full", action="store_true", help="full fine-tuning (every weight matrix of the layers) at --lr")
    ap.add_argument("--writers", default="", help="comma list of writer ids (data/writers/wNN) whose train.csv "
                    "rows are added to training (their test.csv never)")
    ap.add_argument("--val-writers", default="", help="comma list of writers NOT trained on whose train.csv rows "
                    "are the validation rows (early stopping, temperature) instead of the corpus split")
    ap.add_argument("--forms", default="", help="comma list of data/forms sets (f01,f02) whose rows (sources "
                    "w01-w12 and robot_train only, checked; rewrites of corpus-validation rows left out) are added "
                    "to training, their minimal pairs to the pair loss")
    a = ap.parse_args()
    import torch
    torch.set_num_threads(2)
    from ethimon.risk import _backend as B
    from ethimon.risk._recipe import Recipe
    from ethimon.risk._train import train_lora

    e_tr, e_va, _ = D.ethics_splits()
    if a.ethics_n:
        e_tr = e_tr.sample(a.ethics_n, a.seed)
    s_tr, s_va, _ = D.sab_splits()
    p_tr, p_va, _, _ = D.pair_splits()
    if a.no_templated:
        p_tr, p_va = p_tr.subset([]), p_va.subset([])
    parts_tr, parts_va, w = [], [], []
    if not a.robot_only:
        parts_tr.append(e_tr); parts_va.append(e_va); w += [1.0] * len(e_tr)
    if not a.ethics_only:
        parts_tr += [s_tr, p_tr]; parts_va += [s_va, p_va]
        w += [a.robot_weight * (0.5 if e.get("source_file") == "abstract_1009.jsonl" else 1.0)
              for e in s_tr.extra] + [a.robot_weight] * len(p_tr)
    pairs = []
    if a.natural:
        n_tr, n_va = D.natural_train_splits()
        pairs = D.pair_index(n_tr, offset=sum(len(p) for p in parts_tr))
        parts_tr.append(n_tr); parts_va.append(n_va); w += [a.natural_weight] * len(n_tr)
    wids = [w.strip() for w in a.writers.split(",") if w.strip()]
    vids = [w.strip() for w in a.val_writers.split(",") if w.strip()]
    if set(wids) & set(vids):
        raise SystemExit(f"--writers and --val-writers overlap: {sorted(set(wids) & set(vids))}")
    if wids:
        wr = D.writers_train(wids)
        pairs += D.pair_index(wr, offset=sum(len(p) for p in parts_tr))
        parts_tr.append(wr); w += [a.natural_weight] * len(wr)
    fids = [f.strip() for f in a.forms.split(",") if f.strip()]
    if fids:
        fr = D.forms_train(fids)
        pairs += D.pair_index(fr, offset=sum(len(p) for p in parts_tr))
        parts_tr.append(fr); w += [a.natural_weight] * len(fr)
        print(f"forms {fids}: {len(fr)} rows", flush=True)
    if vids:
        parts_va = [D.writers_train(vids)]
    tr, va = D.concat(*parts_tr), D.concat(*parts_va)
    if a.limit:
        tr, va, w = tr.subset(list(range(a.limit))), va.subset(list(range(a.limit))), w[:a.limit]
    aux = []
    for name in filter(None, (x.strip() for x in a.aux.split(","))):
        texts, labels = D.ethics_aux(name, a.limit or a.aux_n, a.seed)
        aux.append((name, texts, labels))
    print(f"train {len(tr)} rows ({len(pairs)} minimal pairs), val {len(va)} rows, "
          f"aux {[(n, len(t)) for n, t, _ in aux]}", flush=True)
    base = B.base_package_dir()
    t0 = time.time()
    # lr as given (no FULL_LR_FACTOR under --full) and head_lr 2e-3: what this script always trained with
    recipe = Recipe(epochs=a.epochs, lr=a.lr, encoder_lr=a.lr, head_lr=2e-3, lora_r=a.r, lora_alpha=2.0 * a.r,
                    max_length=a.max_length, truncation=a.truncation, seed=a.seed, init_seed=a.init_seed,
                    max_steps=a.max_steps, aux_weight=a.aux_weight, pair_weight=a.pair_weight,
                    pair_margin=a.pair_margin, pairs_per_step=a.pairs_per_step, full_finetune=a.full)
    s = train_lora(tr.texts, tr.labels, va.texts, va.labels, recipe, base_dir=base, out_dir=a.out,
                   base_ref={"package": B.BASE_PACKAGE}, train_weights=w, name="ethimon-minilm-l6-lora",
                   num_threads=2, progress=False,
                   log=lambda m: print(m, flush=True), aux_tasks=aux, init_from=a.init_from, pairs=pairs,
                   extra_meta={"writers": wids, "forms": fids, "val_writers": vids, "ethics_only": a.ethics_only, "robot_only": a.robot_only,
                               "robot_weight": a.robot_weight, "aux": a.aux, "aux_n": a.aux_n,
                               "natural": a.natural, "natural_weight": a.natural_weight, "ethics_n": a.ethics_n,
                               "no_templated": a.no_templated})
    print(f"{'epoch':>5} {'train_loss':>10} {'val_loss':>9} {'val_acc':>8} {'elapsed_s':>9}")
    for h in s["history"]:
        print(f"{h['epoch']:>5} {h['train_loss']:>10.4f} {h['val_loss']:>9.4f} {h['val_acc']:>8.4f} {h['elapsed_s']:>9}")
    print(f"best epoch {s['best_epoch']}, T={s['temperature']:.3f}, {time.time() - t0:.0f}s")
    tag = a.tag or Path(a.out).name
    res = {k: v for k, v in s.items() if k != "train_loss_curve"}
    res["machine"] = machine_facts(threads=torch.get_num_threads())
    res["out_dir"] = a.out
    (results_dir("risk") / f"risk_train_{tag}.json").write_text(json.dumps(res, indent=1) + "\n")


if __name__ == "__main__":
    main()
