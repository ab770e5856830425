"""MPNet with LoRA on its top layers only, lower layers frozen and cached (issue 12, item 5).

    python -m bench.risk.risk_mpnet_top --mpnet DIR [--top 3] [--seeds 42 7 13] [--tag mpnet_top3]

Full LoRA fine-tuning of all-mpnet-base-v2 (110 M) takes hours per seed on 2 CPU cores. With
adapters on the top ``k`` of 12 layers only, the hidden states entering layer ``12 - k`` never
change during training, so they are computed once (one forward pass over every row) and each
training step runs only the top ``k`` layers. The adapter is an ordinary ethimon LoRA adapter
that names only top-layer modules (``merge_lora`` folds any subset), so a winning run can be
saved as a model directory the runtime loads.

Rows and rules as in bench/results/risk/risk_natural_decisions.md (19:20): training = the
hand-written corpus's training split + 1,000 ETHICS cm training rows (seed-42 draw); best epoch
and temperature on natural_val (the corpus's validation split); τ for a 15 % false-alarm budget
on natural_val; the frozen natural test set only reported. Prints mean ± sd over seeds, writes
bench/results/risk/risk_mpnet_top_<tag>.json (per seed: history, metrics) with machine facts.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import random
import time
from pathlib import Path

import numpy as np

from bench import results_dir
from bench._machine import machine_facts
from bench.risk import risk_data as D
from bench.risk.risk_probe import MPNET_SHA256


def batch_of(items, idx):
    """Cached hidden states ``items[j]`` (tokens × hidden) of rows ``idx``, zero-padded: ``(h, mask)``."""
    import torch
    n = max(items[j].shape[0] for j in idx)
    h = torch.zeros(len(idx), n, items[idx[0]].shape[1])
    mask = torch.zeros(len(idx), n, dtype=torch.long)
    for r, j in enumerate(idx):
        m = items[j].shape[0]
        h[r, :m] = items[j]
        mask[r, :m] = 1
    return h, mask


def main() -> None:  # noqa: C901 - one experiment, read top to bottom
    ap = argparse.ArgumentParser()
    ap.add_argument("--mpnet", required=True)
    ap.add_argument("--top", type=int, default=3)
    ap.add_argument("--seeds", type=int, nargs="+", default=[42, 7, 13])
    ap.add_argument("--epochs", type=int, default=3)
    ap.add_argument("--lr", type=float, default=3e-4)
    ap.add_argument("--head-lr", type=float, default=2e-3)
    ap.add_argument("--ethics-n", type=int, default=1000)
    ap.add_argument("--pair-weight", type=float, default=1.0)
    ap.add_argument("--budget", type=float, default=0.15)
    ap.add_argument("--max-length", type=int, default=128)
    ap.add_argument("--limit", type=int, default=None, help="smoke test: first N rows per set")
    ap.add_argument("--tag", default=None)
    a = ap.parse_args()
    import torch
    from torch import nn
    torch.set_num_threads(2)
    from ethimon.risk import _backend as B
    from ethimon.risk._evaluate import (classification_metrics, flag_stats, pair_metrics,
                                        tau_for_false_alarm_budget, type_metrics)
    from ethimon.risk._formula import risk_from_p_unsafe
    from ethimon.risk._train import fit_temperature
    from transformers.masking_utils import create_bidirectional_mask

    mp = Path(a.mpnet)
    if B.sha256_file(mp / "model.safetensors") != MPNET_SHA256:
        raise SystemExit(f"{mp}: not the pinned all-mpnet-base-v2 (sha256 {MPNET_SHA256})")
    n_tr, n_va = D.natural_train_splits()
    test = D.natural_test()
    e_tr, _, e_ho = D.ethics_splits()
    pick = np.random.default_rng(42).choice(len(e_tr), size=min(a.ethics_n, len(e_tr)), replace=False)
    e_sub = e_tr.subset([int(i) for i in pick])
    tr_rows = D.concat(n_tr, e_sub)
    pairs = D.pair_index(n_tr)  # corpus rows come first in tr_rows
    sets = {"train": tr_rows, "val": n_va, "test": test, "ethics_holdout": e_ho}
    if a.limit:
        sets = {k: v.subset(list(range(min(a.limit, len(v))))) for k, v in sets.items()}
        pairs = [(u, s) for u, s in pairs if u < a.limit and s < a.limit]

    tok = B.load_tokenizer(mp)
    enc = B.load_encoder(mp).eval()
    n_layers = len(enc.encoder.layer)
    cut = n_layers - a.top
    pad = tok.pad_token_id or 0

    # ---- cache the hidden states entering layer `cut` (one forward pass over every row)
    def lower(ids, mask):
        out = enc(input_ids=ids, attention_mask=mask, output_hidden_states=True)
        return out.hidden_states[cut], out.last_hidden_state

    cache: dict[str, list] = {}
    t0 = time.time()
    with torch.inference_mode():
        for name, rows in sets.items():
            seqs = B.encode(tok, rows.texts, a.max_length)
            items = [None] * len(seqs)
            order = np.argsort([len(s) for s in seqs])
            for i in range(0, len(order), 32):
                idx = order[i:i + 32]
                ids, mask = B.collate([seqs[j] for j in idx], pad)
                h, _ = lower(ids, mask)
                for r, j in enumerate(idx):
                    n = int(mask[r].sum())
                    items[j] = h[r, :n].clone()
            cache[name] = items
    cache_s = time.time() - t0
    print(f"cached layer-{cut} states of {sum(len(v) for v in cache.values())} rows in {cache_s:.0f} s", flush=True)

    def upper(h, mask):
        ext = create_bidirectional_mask(config=enc.config, inputs_embeds=h, attention_mask=mask)
        pb = enc.encoder.compute_position_bias(h)
        for layer in enc.encoder.layer[cut:]:
            h = layer(h, ext, pb)[0]
        m = mask.unsqueeze(-1).to(h.dtype)
        return (h * m).sum(1) / m.sum(1).clamp(min=1.0)

    # the cached path must equal the full forward pass (checked on a few rows)
    with torch.inference_mode():
        seqs = B.encode(tok, sets["val"].texts[:4], a.max_length)
        ids, mask = B.collate(seqs, pad)
        full = enc(input_ids=ids, attention_mask=mask).last_hidden_state
        m = mask.unsqueeze(-1).to(full.dtype)
        want = (full * m).sum(1) / m.sum(1)
        got = upper(*batch_of(cache["val"], list(range(len(seqs)))))
        err = float((want - got).abs().max())
        if err > 1e-4:
            raise SystemExit(f"cached path differs from the full forward pass by {err}")
    print(f"cached path == full forward (max abs diff {err:.1e})", flush=True)

    base_state = {k: v.clone() for k, v in enc.state_dict().items()}
    ytr = torch.tensor(sets["train"].labels, dtype=torch.long)
    y_va, y_te = np.array(sets["val"].labels), np.array(sets["test"].labels)
    results = []
    for seed in a.seeds:
        enc.load_state_dict(base_state, strict=False)
        # fresh LoRA on the top layers only
        for layer in enc.encoder.layer:
            for name, mod in list(layer.named_modules()):
                if isinstance(mod, B.LoRALinear):
                    parent_name, _, child = name.rpartition(".")
                    setattr(layer.get_submodule(parent_name) if parent_name else layer, child, mod.base)
        torch.manual_seed(seed)
        random.seed(seed)
        rng = random.Random(seed)
        for p in enc.parameters():
            p.requires_grad_(False)
        targets = []
        for li in range(cut, n_layers):
            layer = enc.encoder.layer[li]
            for name, mod in list(layer.named_modules()):
                if isinstance(mod, nn.Linear):
                    parent_name, _, child = name.rpartition(".")
                    parent = layer.get_submodule(parent_name) if parent_name else layer
                    setattr(parent, child, B.LoRALinear(mod, 16, 32.0, 0.05))
                    targets.append(f"encoder.layer.{li}.{name}")
        head = nn.Linear(enc.config.hidden_size, 2)
        drop = nn.Dropout(0.1)
        lora_params = [p for n_, p in enc.named_parameters() if "lora_" in n_]
        opt = torch.optim.AdamW([{"params": lora_params, "lr": a.lr},
                                 {"params": list(head.parameters()), "lr": a.head_lr}], weight_decay=0.01)
        n_train = len(cache["train"])
        steps_per_epoch = math.ceil(n_train / 32)
        total = steps_per_epoch * a.epochs
        wu = max(1, int(0.06 * total))
        sched = torch.optim.lr_scheduler.LambdaLR(
            opt, lambda s: min(1.0, (s + 1) / wu) * max(0.0, (total - s) / max(1, total - wu)))

        def logits_of(name):
            enc.eval()
            out = []
            with torch.inference_mode():
                items = cache[name]
                for i in range(0, len(items), 64):
                    idx = list(range(i, min(i + 64, len(items))))
                    out.append(head(upper(*batch_of(items, idx))))
            enc.train()
            return torch.cat(out)

        history, best = [], (math.inf, None, 0)
        t_seed = time.time()
        lengths = [x.shape[0] for x in cache["train"]]
        for ep in range(a.epochs):
            enc.train()
            # length-bucketed shuffled batches
            order = sorted(range(n_train), key=lambda i: (lengths[i], rng.random()))
            batches = [order[i:i + 32] for i in range(0, n_train, 32)]
            rng.shuffle(batches)
            run = 0.0
            for bidx in batches:
                logits = head(drop(upper(*batch_of(cache["train"], bidx))))
                loss = nn.functional.cross_entropy(logits, ytr[bidx])
                if pairs and a.pair_weight > 0:
                    chosen = [pairs[rng.randrange(len(pairs))] for _ in range(8)]
                    idx = [u for u, _ in chosen] + [s for _, s in chosen]
                    pl = head(drop(upper(*batch_of(cache["train"], idx))))
                    z = pl[:, 1] - pl[:, 0]
                    loss = loss + a.pair_weight * nn.functional.relu(1.0 - (z[:8] - z[8:])).mean()
                opt.zero_grad(set_to_none=True)
                loss.backward()
                torch.nn.utils.clip_grad_norm_(lora_params + list(head.parameters()), 1.0)
                opt.step()
                sched.step()
                run += float(loss.detach()) * len(bidx)
            vlog = logits_of("val")
            yv = torch.tensor(y_va, dtype=torch.long)
            vloss = float(nn.functional.cross_entropy(vlog, yv))
            rec = {"epoch": ep + 1, "train_loss": run / n_train, "val_loss": vloss,
                   "val_acc": float((vlog.argmax(-1) == yv).float().mean()),
                   "elapsed_s": round(time.time() - t_seed, 1)}
            history.append(rec)
            print(f"seed {seed} {json.dumps(rec)}", flush=True)
            if vloss < best[0]:
                best = (vloss, {"lora": {n_: p.detach().clone() for n_, p in enc.named_parameters() if "lora_" in n_},
                                "head": {k: v.clone() for k, v in head.state_dict().items()}}, ep + 1)
        with torch.no_grad():
            params = dict(enc.named_parameters())
            for n_, v in best[1]["lora"].items():
                params[n_].copy_(v)
            head.load_state_dict(best[1]["head"])
        vlog = logits_of("val")
        T = fit_temperature(vlog, list(y_va))
        q = {k: torch.softmax(logits_of(k) / T, -1)[:, 1].numpy() for k in ("val", "test", "ethics_holdout")}
        r = {k: np.array([risk_from_p_unsafe(float(v)) for v in q[k]]) for k in q}
        tau = tau_for_false_alarm_budget(y_va, r["val"], a.budget)["tau"]
        te = sets["test"]
        res = {"seed": seed, "best_epoch": best[2], "temperature": T, "tau": tau, "history": history,
               "val_at_tau": flag_stats(y_va, r["val"], tau),
               "natural": {**classification_metrics(y_te, q["test"]), "at_tau": flag_stats(y_te, r["test"], tau),
                           "pairs": pair_metrics(y_te, q["test"], r["test"], [e.get("pair") for e in te.extra], tau),
                           "by_type": type_metrics(y_te, q["test"], r["test"], [e.get("type") for e in te.extra], tau)},
               "ethics_holdout": classification_metrics(sets["ethics_holdout"].labels, q["ethics_holdout"]),
               "train_seconds": round(time.time() - t_seed, 1), "lora_targets": len(targets)}
        results.append(res)
        print(f"seed {seed}: val flagged@15%FA {res['val_at_tau']['flag_rate_unsafe']:.3f}, "
              f"test acc {res['natural']['accuracy']:.3f}, pairs both {res['natural']['pairs']['both_right_at_tau']:.3f}",
              flush=True)

    def ms(vals):
        v = np.array(vals, dtype=float)
        return f"{100 * v.mean():5.1f} ± {100 * v.std(ddof=1):3.1f}" if len(v) > 1 else f"{100 * v[0]:5.1f}"
    rows = [("validation unsafe flagged at tau (selection)", lambda m: m["val_at_tau"]["flag_rate_unsafe"]),
            ("validation false alarms at tau", lambda m: m["val_at_tau"]["false_alarm_rate"]),
            ("natural accuracy (p>=0.5)", lambda m: m["natural"]["accuracy"]),
            ("natural ROC-AUC", lambda m: m["natural"]["roc_auc"]),
            ("natural unsafe flagged at tau", lambda m: m["natural"]["at_tau"]["flag_rate_unsafe"]),
            ("natural false alarms at tau", lambda m: m["natural"]["at_tau"]["false_alarm_rate"]),
            ("pairs: unsafe ranked higher", lambda m: m["natural"]["pairs"]["ranked"]),
            ("pairs: both right at tau", lambda m: m["natural"]["pairs"]["both_right_at_tau"]),
            ("ETHICS hold-out accuracy", lambda m: m["ethics_holdout"]["accuracy"])]
    print(f"\nMPNet, LoRA on the top {a.top} layers, {len(a.seeds)} seeds (mean ± sd, %)")
    for label, f in rows:
        print(f"{label:46} {ms([f(m) for m in results]):>14}")
    tag = a.tag or f"mpnet_top{a.top}"
    out = {"what": "MPNet LoRA on the top layers, lower layers cached (issue 12 item 5)", "args": vars(a),
           "mpnet_sha256": MPNET_SHA256, "cache_seconds": round(cache_s, 1), "results": results,
           "machine": machine_facts(), "load": os.getloadavg()}
    (results_dir("risk") / f"risk_mpnet_top_{tag}.json").write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
