"""Issue 19 on two CPU cores: the shipped MiniLM's top k layers trained on other writers' rows.

    python -m bench.risk.risk_writers_top --top 2 --epochs 2 --rotations 0 1 2 --tag top2
    python -m bench.risk.risk_writers_top --top 2 --epochs 2 --final runs/top2_all --tag top2_all

The recipe and every rule are in bench/results/risk/writers/DECISIONS.md (22:11 UTC entry):
the shipped model's LoRA is merged into the encoder; the hidden states entering layer
``6 - k`` are computed once for every text and view (the lower layers stay frozen, so one
cache serves every run); each run trains a fresh LoRA (r 16, α 32) on every matrix of the top
``k`` layers and the head (warm-started from the shipped head) on the shipped recipe's rows plus
the ``train.csv`` rows of its trained writers. Early stopping and the temperature use the
corpus validation split only.

Rotation k (seed 42, 7, 13) holds out the writers w01–w12 at positions i % 3 == k: their
``train.csv`` + data/robot_val_other choose τ and τ_confirm (step reading, R_e by the spec
formula), their frozen test slices are reported per writer and per register, and so are the
test slices of the writers w13+ that no run trains on. The shipped model is scored on each
rotation's validation rows for the shipping rule. ``--final OUT`` trains on all of w01–w12
and saves an ethimon model directory (the shipped factors and the new ones in one r-32
adapter, exactly what the runtime loads); its τ pair comes from val_other + w13+ train.csv.

Writes bench/results/risk/risk_writers_top_<tag>.json (per run: history, taus, figures, every
held-out row's R_e) with machine facts.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import random
import statistics
import time
from pathlib import Path

import numpy as np

from bench import results_dir
from bench._machine import machine_facts
from bench.risk import risk_data as D
from bench.risk.risk_mpnet_top import batch_of
from bench.risk.risk_writers import choose_taus, mean_sd, outcomes, pooled

ROTATED = [f"w{i:02d}" for i in range(1, 13)]
SEEDS = (42, 7, 13)


def _external() -> list[str]:
    return [w for w in D.writer_ids() if w not in ROTATED]


def main() -> None:  # noqa: C901 - one experiment, read top to bottom
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--top", type=int, default=2)
    ap.add_argument("--epochs", type=int, default=2)
    ap.add_argument("--rotations", type=int, nargs="*", default=[0, 1, 2])
    ap.add_argument("--final", default=None, help="train on all of w01-w12 (seed 42) and save a model dir here")
    ap.add_argument("--lr", type=float, default=3e-4)
    ap.add_argument("--head-lr", type=float, default=1e-3)
    ap.add_argument("--pair-weight", type=float, default=1.0)
    ap.add_argument("--limit", type=int, default=None, help="smoke test: first N rows per set")
    ap.add_argument("--max-steps", type=int, default=None, help="smoke test: steps per epoch")
    ap.add_argument("--save-runs", default=None, help="save each rotation's model dir under this folder")
    ap.add_argument("--external", nargs="*", default=None,
                    help="never-trained writers to report (default: every complete writer after w12)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--tag", required=True)
    a = ap.parse_args()
    import torch
    from torch import nn
    torch.set_num_threads(a.threads)
    from ethimon.risk import _backend as B
    from ethimon.risk._estimator import normalize_text
    from ethimon.risk._formula import risk_from_p_unsafe
    from ethimon.risk._reading import views
    from ethimon.risk._train import fit_temperature

    t0 = time.time()
    ship = Path(__file__).resolve().parents[2] / "src" / "ethimon" / "risk" / "default_model"
    manifest = B.read_manifest(ship)
    adapter, _ = B.checked_adapter(ship, manifest)
    ship_t = {k: v.float() for k, v in B.load_adapter_tensors(adapter).items()}
    max_len, trunc = int(manifest["max_length"]), manifest["truncation"]
    base = B.base_package_dir()
    tok = B.load_tokenizer(base)
    enc = B.load_encoder(base).eval()
    ship_scale = float(manifest["lora"]["alpha"]) / float(manifest["lora"]["r"])
    B.merge_lora(enc, ship_t, ship_scale)
    n_layers = len(enc.encoder.layer)
    cut = n_layers - a.top
    pad = tok.pad_token_id or 0

    # ---------------------------------------------------------------- rows
    e_tr, _e_va, e_ho = D.ethics_splits()
    e_tr = e_tr.sample(1000, 42)
    s_tr, _s_va, _ = D.sab_splits()
    p_tr, _p_va, _, _ = D.pair_splits()
    n_tr, n_va = D.natural_train_splits()
    common = D.concat(e_tr, s_tr, p_tr, n_tr)
    common_w = ([1.0] * len(e_tr) + [0.5 if e.get("source_file") == "abstract_1009.jsonl" else 1.0 for e in s_tr.extra]
                + [1.0] * (len(p_tr) + len(n_tr)))
    common_pairs = D.pair_index(n_tr, offset=len(e_tr) + len(s_tr) + len(p_tr))
    ext = _external() if a.external is None else list(a.external)
    wtrain = {w: D.writers_train([w]) for w in ROTATED + ext}
    wtest = {w: D.writer_test(w) for w in ROTATED + ext}
    val_other = D.load_labelled_csv(D.ROOT / "data" / "robot_val_other" / "val_other.csv")
    natural = D.natural_test()
    if a.limit:
        cut_ = lambda r: r.subset(list(range(min(a.limit, len(r)))))  # noqa: E731
        common, common_w = cut_(common), common_w[:a.limit]
        common_pairs = [(u, s) for u, s in common_pairs if u < a.limit and s < a.limit]
        n_va, e_ho, val_other, natural = cut_(n_va), cut_(e_ho), cut_(val_other), cut_(natural)
        wtrain = {w: cut_(r) for w, r in wtrain.items()}
        wtest = {w: cut_(r) for w, r in wtest.items()}
    print(f"common training rows {len(common)} ({len(common_pairs)} pairs); writers {ROTATED} rotated, "
          f"{ext} never trained on; top {a.top} of {n_layers} layers", flush=True)

    # ---------------------------------------------------------------- one cache of lower-layer states
    seq_of: dict[tuple[str, str], int] = {}     # (context, focus) -> item index
    seqs_src: list[tuple[str, str]] = []

    def item(ctx: str, focus: str) -> int:
        k = (ctx, focus)
        if k not in seq_of:
            seq_of[k] = len(seqs_src)
            seqs_src.append(k)
        return seq_of[k]

    # training rows and the corpus validation split: read flat, encoded as training encodes them
    flat_train: dict[str, int] = {}
    flat_items: list[str] = []

    def flat(t: str) -> int:
        if t not in flat_train:
            flat_train[t] = len(flat_items)
            flat_items.append(t)
        return flat_train[t]

    # evaluated texts: every view of the step reading (and the flat view), as the estimator reads them
    def spans_of(rows) -> list[tuple[int, list[int]]]:
        out = []
        for t in rows.texts:
            key = normalize_text(t)
            sv = views(key, "steps")
            out.append((item("", key), [item(v.context, v.focus) for v in sv]))
        return out

    train_of_w = {w: [flat(t) for t in r.texts] for w, r in wtrain.items()}
    common_idx = [flat(t) for t in common.texts]
    nva_idx = [flat(t) for t in n_va.texts]
    ev = {"val_other": spans_of(val_other), "natural": spans_of(natural)}
    for w in ROTATED + ext:
        ev[f"{w}/train"] = spans_of(wtrain[w])
        ev[f"{w}/test"] = spans_of(wtest[w])
    eth_idx = [flat(t) for t in e_ho.texts]

    with torch.inference_mode():
        tr_seqs = B.encode(tok, flat_items, max_len, trunc)
        ev_seqs = B.encode_views(tok, seqs_src, max_len, trunc)

        def lower_all(seqs):
            items = [None] * len(seqs)
            order = np.argsort([len(s) for s in seqs])
            for i in range(0, len(order), 64):
                idx = order[i:i + 64]
                ids, mask = B.collate([seqs[j] for j in idx], pad)
                h = enc(input_ids=ids, attention_mask=mask, output_hidden_states=True).hidden_states[cut]
                for r, j in enumerate(idx):
                    items[j] = h[r, :int(mask[r].sum())].clone()
            return items

        tr_cache = lower_all(tr_seqs)
        ev_cache = lower_all(ev_seqs)
    n_tok = sum(x.shape[0] for x in tr_cache) + sum(x.shape[0] for x in ev_cache)
    cache_s = time.time() - t0
    print(f"cached layer-{cut} states: {len(tr_cache)} training texts, {len(ev_cache)} views, "
          f"{n_tok} tokens ({n_tok * enc.config.hidden_size * 4 / 2**30:.2f} GiB) in {cache_s:.0f} s", flush=True)

    def upper(h, mask):
        ext_mask, _ = enc._create_attention_masks(attention_mask=mask, encoder_attention_mask=None,
                                                  embedding_output=h, encoder_hidden_states=None, cache=None)
        for layer in enc.encoder.layer[cut:]:
            out = layer(h, ext_mask)
            h = out[0] if isinstance(out, tuple) else out
        m = mask.unsqueeze(-1).to(h.dtype)
        return (h * m).sum(1) / m.sum(1).clamp(min=1.0)

    head = nn.Linear(enc.config.hidden_size, 2)

    def load_ship_head():
        with torch.no_grad():
            head.weight.copy_(ship_t["head.weight"])
            head.bias.copy_(ship_t["head.bias"])

    load_ship_head()
    with torch.inference_mode():           # the cached path must equal the full forward pass
        probe = [seqs_src[i] for i in range(min(6, len(seqs_src)))]
        sq = B.encode_views(tok, probe, max_len, trunc)
        ids, mask = B.collate(sq, pad)
        full = enc(input_ids=ids, attention_mask=mask).last_hidden_state
        m = mask.unsqueeze(-1).to(full.dtype)
        want = (full * m).sum(1) / m.sum(1)
        got = upper(*batch_of(ev_cache, list(range(len(sq)))))
        err = float((want - got).abs().max())
    if err > 1e-4:
        raise SystemExit(f"cached path differs from the full forward pass by {err}")
    print(f"cached path == full forward (max abs diff {err:.1e})", flush=True)

    def logits(cache, idx_list):
        enc.eval()
        out = []
        with torch.inference_mode():
            for i in range(0, len(idx_list), 64):
                out.append(head(upper(*batch_of(cache, idx_list[i:i + 64]))))
        return torch.cat(out) if out else torch.zeros(0, 2)

    f_r = np.vectorize(risk_from_p_unsafe)

    def score_all(T: float) -> tuple[dict, np.ndarray]:
        """R_e (step reading, flat reading) of every evaluated text; ETHICS hold-out p_unsafe."""
        pu = torch.softmax(logits(ev_cache, list(range(len(ev_cache)))) / T, -1)[:, 1].numpy()
        out = {}
        for name, sp in ev.items():
            steps = np.array([pu[v].max() for _f, v in sp])
            flat_ = np.array([pu[f] for f, _v in sp])
            out[name] = {"steps": f_r(steps), "flat": f_r(flat_)}
        pe = torch.softmax(logits(tr_cache, eth_idx) / T, -1)[:, 1].numpy()
        return out, pe

    def rows_of(name):
        w, _, part = name.partition("/")
        return {"val_other": val_other, "natural": natural}.get(name) or (wtrain if part == "train" else wtest)[w]

    def report(R, pe, held: list[str], never: list[str], val_names: list[str], reading="steps") -> dict:
        yv = np.concatenate([np.array(rows_of(n).labels) for n in val_names])
        rv = np.concatenate([R[n][reading] for n in val_names])
        from sklearn.metrics import roc_auc_score
        taus = choose_taus(yv, rv)
        taus["val_roc_auc"] = float(roc_auc_score(yv, rv))
        tau, tc = taus["tau"], taus["tau_confirm"]

        def block(names):
            return pooled({n: (rows_of(n), R[n][reading]) for n in names}, tau, tc)
        out = {"taus": taus,
               "held_out_pooled": block([f"{w}/test" for w in held]) if held else None,
               "per_writer": {w: {**outcomes(np.array(wtest[w].labels), R[f"{w}/test"][reading], tau, tc,
                                             [e.get("pair", "") for e in wtest[w].extra]),
                                  "status": "held_out" if w in held else ("never_trained" if w in never else "seen"),
                                  "risks": [round(float(x), 5) for x in R[f"{w}/test"][reading]]}
                              for w in ROTATED + ext},
               "never_trained_pooled": block([f"{w}/test" for w in never]) if never else None,
               "natural_test": outcomes(np.array(natural.labels), R["natural"][reading], tau, tc,
                                        [e.get("pair", "") for e in natural.extra]),
               "ethics_holdout_accuracy": float(((pe >= 0.5) == (np.array(e_ho.labels) == 1)).mean()) if len(pe) else None}
        return out

    # ---------------------------------------------------------------- the shipped model, same cache
    ship_R, ship_pe = score_all(float(manifest["temperature"]))
    ytr_common = list(common.labels)
    ship_state = {k: v.clone() for k, v in enc.state_dict().items()}

    def strip_lora():
        for layer in enc.encoder.layer:
            for name, mod in list(layer.named_modules()):
                if isinstance(mod, B.LoRALinear):
                    parent, _, child = name.rpartition(".")
                    setattr(layer.get_submodule(parent) if parent else layer, child, mod.base)

    def train_run(trained: list[str], seed: int) -> dict:
        strip_lora()
        enc.load_state_dict(ship_state, strict=True)
        load_ship_head()
        torch.manual_seed(seed)
        rng = random.Random(seed)
        for p in enc.parameters():
            p.requires_grad_(False)
        targets = []
        for li in range(cut, n_layers):
            layer = enc.encoder.layer[li]
            for name, mod in list(layer.named_modules()):
                if isinstance(mod, nn.Linear):
                    parent, _, child = name.rpartition(".")
                    setattr(layer.get_submodule(parent) if parent else layer, child, B.LoRALinear(mod, 16, 32.0, 0.05))
                    targets.append(f"encoder.layer.{li}.{name}")
        idx = list(common_idx)
        y = list(ytr_common)
        wts = list(common_w)
        pairs = list(common_pairs)
        for w in trained:
            off = len(idx)
            idx += train_of_w[w]
            y += list(wtrain[w].labels)
            wts += [1.0] * len(wtrain[w])
            pairs += D.pair_index(wtrain[w], offset=off)
        yt = torch.tensor(y, dtype=torch.long)
        wt = torch.tensor(wts, dtype=torch.float32)
        lora_params = [p for n_, p in enc.named_parameters() if "lora_" in n_]
        for p in head.parameters():
            p.requires_grad_(True)
        opt = torch.optim.AdamW([{"params": lora_params, "lr": a.lr},
                                 {"params": list(head.parameters()), "lr": a.head_lr}], weight_decay=0.01)
        n = len(idx)
        spe = math.ceil(n / 32) if a.max_steps is None else min(a.max_steps, math.ceil(n / 32))
        total = spe * a.epochs
        wu = max(1, int(0.06 * total))
        sched = torch.optim.lr_scheduler.LambdaLR(
            opt, lambda s: min(1.0, (s + 1) / wu) * max(0.0, (total - s) / max(1, total - wu)))
        drop = nn.Dropout(0.1)
        lengths = [tr_cache[i].shape[0] for i in idx]
        yva = torch.tensor(n_va.labels, dtype=torch.long)
        history, best = [], (math.inf, None, 0)
        t_run = time.time()
        print(f"run seed {seed}: {n} rows ({len(pairs)} pairs), trained writers {trained}, {spe} steps/epoch", flush=True)
        for ep in range(a.epochs):
            enc.train()
            order = sorted(range(n), key=lambda i: (lengths[i], rng.random()))
            batches = [order[i:i + 32] for i in range(0, n, 32)]
            rng.shuffle(batches)
            batches = batches[:spe]
            run_loss = 0.0
            for bi, b in enumerate(batches):
                z = head(drop(upper(*batch_of(tr_cache, [idx[i] for i in b]))))
                loss = (nn.functional.cross_entropy(z, yt[b], reduction="none") * wt[b]).sum() / wt[b].sum()
                if pairs and a.pair_weight > 0:
                    ch = [pairs[rng.randrange(len(pairs))] for _ in range(8)]
                    pl = head(drop(upper(*batch_of(tr_cache, [idx[u] for u, _ in ch] + [idx[s] for _, s in ch]))))
                    d = pl[:, 1] - pl[:, 0]
                    loss = loss + a.pair_weight * nn.functional.relu(1.0 - (d[:8] - d[8:])).mean()
                opt.zero_grad(set_to_none=True)
                loss.backward()
                torch.nn.utils.clip_grad_norm_(lora_params + list(head.parameters()), 1.0)
                opt.step()
                sched.step()
                run_loss += float(loss.detach()) * len(b)
                if bi % 50 == 0:
                    print(f"  ep {ep + 1} step {bi}/{len(batches)} loss {float(loss.detach()):.3f} {time.time() - t_run:.0f}s",
                          flush=True)
            # the adapter is saved in fp16: evaluate exactly what would be saved
            with torch.no_grad():
                for p in lora_params:
                    p.copy_(p.half().float())
            vl = logits(tr_cache, nva_idx)
            vloss = float(nn.functional.cross_entropy(vl, yva))
            rec = {"epoch": ep + 1, "train_loss": run_loss / max(1, sum(len(b) for b in batches)), "val_loss": vloss,
                   "val_acc": float((vl.argmax(-1) == yva).float().mean()), "elapsed_s": round(time.time() - t_run, 1)}
            history.append(rec)
            print(f"  {json.dumps(rec)}", flush=True)
            if vloss < best[0]:
                best = (vloss, {"lora": {n_: p.detach().clone() for n_, p in enc.named_parameters() if "lora_" in n_},
                                "head": {k: v.detach().clone() for k, v in head.state_dict().items()}}, ep + 1)
        with torch.no_grad():
            params = dict(enc.named_parameters())
            for n_, v in best[1]["lora"].items():
                params[n_].copy_(v)
            head.load_state_dict(best[1]["head"])
        T = fit_temperature(logits(tr_cache, nva_idx), list(n_va.labels))
        R, pe = score_all(T)
        return {"seed": seed, "trained_writers": trained, "best_epoch": best[2], "temperature": T,
                "history": history, "train_seconds": round(time.time() - t_run, 1), "targets": targets,
                "R": R, "pe": pe}

    def save_model(run: dict, out: Path, taus: dict) -> None:
        """Shipped factors + this run's top-layer factors in one r-32 adapter (exact: 2·(B₁A₁ + B₂A₂))."""
        out.mkdir(parents=True, exist_ok=True)
        r1 = int(manifest["lora"]["r"])
        if ship_scale != 2.0 or r1 != 16:
            raise SystemExit("the shipped adapter is not r 16, α 32: the combined adapter would not be exact")
        tensors = {}
        mods = dict(enc.named_modules())
        for name in manifest["lora"]["targets"]:
            a1, b1 = ship_t[f"lora.{name}.A"], ship_t[f"lora.{name}.B"]
            mod = mods[name]
            if isinstance(mod, B.LoRALinear):
                a2, b2 = mod.lora_A.detach().float(), mod.lora_B.detach().float()
            else:
                a2, b2 = torch.zeros_like(a1), torch.zeros_like(b1)
            tensors[f"lora.{name}.A"] = torch.cat([a1, a2], 0).half().contiguous()
            tensors[f"lora.{name}.B"] = torch.cat([b1, b2], 1).half().contiguous()
        tensors["head.weight"] = head.weight.detach().float().contiguous()
        tensors["head.bias"] = head.bias.detach().float().contiguous()
        B.save_adapter(tensors, out / "adapter.safetensors")
        m = dict(manifest)
        m["name"] = f"ethimon-minilm-l6-lora-top{a.top}-writers"
        m["adapter_sha256"] = B.sha256_file(out / "adapter.safetensors")
        m["lora"] = {"r": 32, "alpha": 64.0, "targets": list(manifest["lora"]["targets"])}
        m["temperature"] = round(float(run["temperature"]), 6)
        (out / B.MANIFEST).write_text(json.dumps(m, indent=2) + "\n", encoding="utf-8")
        (out / "metrics.json").write_text(json.dumps({
            "config": {"recipe": f"top{a.top}", "writers": run["trained_writers"], "seed": run["seed"],
                       "epochs": a.epochs, "lr": a.lr, "head_lr": a.head_lr, "pair_weight": a.pair_weight,
                       "init_from": "src/ethimon/risk/default_model", "max_length": max_len},
            "history": run["history"], "best_epoch": run["best_epoch"], "temperature": run["temperature"],
            "taus": taus}, indent=1) + "\n", encoding="utf-8")

    def save() -> None:
        results["seconds"] = round(time.time() - t0, 1)
        results["machine"] = machine_facts(threads=a.threads)
        results["load"] = os.getloadavg()
        (results_dir("risk") / f"risk_writers_top_{a.tag}.json").write_text(json.dumps(results, indent=1) + "\n")

    results = {"recipe": f"top{a.top}", "args": vars(a), "cache_seconds": round(cache_s, 1), "rotated": ROTATED,
               "never_trained": ext, "runs": [], "shipped": []}
    if a.final:
        run = train_run(list(ROTATED), 42)
        val_names = ["val_other"] + [f"{w}/train" for w in ext]
        rep = report(run["R"], run["pe"], [], ext, val_names)
        rep_flat = report(run["R"], run["pe"], [], ext, val_names, "flat")
        save_model(run, Path(a.final), rep["taus"])
        ship_rep = report(ship_R, ship_pe, [], ext, val_names)
        results["runs"].append({k: v for k, v in run.items() if k not in ("R", "pe")} | {"steps": rep, "flat": rep_flat})
        results["shipped"].append({"val_names": val_names, "steps": ship_rep})
        _print(f"final (all of w01-w12), τ pair on val_other + {ext} train", rep, ext)
        _print("shipped, same rows", ship_rep, ext)
    for k in a.rotations:
        held = [w for i, w in enumerate(ROTATED) if i % 3 == k]
        trained = [w for w in ROTATED if w not in held]
        run = train_run(trained, SEEDS[k])
        val_names = ["val_other"] + [f"{w}/train" for w in held]
        rep = report(run["R"], run["pe"], held, ext, val_names)
        rep_flat = report(run["R"], run["pe"], held, ext, val_names, "flat")
        ship_rep = report(ship_R, ship_pe, held, ext, val_names)
        results["runs"].append({k_: v for k_, v in run.items() if k_ not in ("R", "pe")}
                               | {"rotation": k, "held_out": held, "steps": rep, "flat": rep_flat})
        results["shipped"].append({"rotation": k, "held_out": held, "steps": ship_rep})
        if a.save_runs:
            save_model(run, Path(a.save_runs) / f"{a.tag}_k{k}", rep["taus"])
        _print(f"rotation {k} (held out {held})", rep, held)
        _print(f"shipped on rotation {k}'s rows", ship_rep, held)
        save()   # after each rotation, so a cut-short session keeps what ran
    rot = [r for r in results["runs"] if "rotation" in r]
    if len(rot) >= 2:
        results["summary"] = summarise(rot, [s for s in results["shipped"] if "rotation" in s])
        print(json.dumps(results["summary"], indent=1))
    save()


KEYS = ("accuracy", "unsafe_executed_unseen", "safe_held", "safe_stopped", "roc_auc", "pairs_both_right", "pairs_ranked")


def summarise(runs: list[dict], shipped: list[dict]) -> dict:
    out = {}
    for label, rs in (("recipe", runs), ("shipped", shipped)):
        s = {"val_roc_auc": mean_sd([r["steps"]["taus"]["val_roc_auc"] for r in rs])}
        for part in ("held_out_pooled", "never_trained_pooled"):
            blocks = [r["steps"][part] for r in rs if r["steps"].get(part)]
            s[part] = {k: mean_sd([b[k] for b in blocks]) for k in KEYS}
            regs = sorted({g for b in blocks for g in b["per_register"]})
            s[part]["per_register_auc"] = {g: mean_sd([b["per_register"][g]["roc_auc"] for b in blocks
                                                   if g in b["per_register"]]) for g in regs}
            s[part]["per_register_accuracy"] = {g: mean_sd([b["per_register"][g]["accuracy"] for b in blocks
                                                        if g in b["per_register"]]) for g in regs}
        s["natural_test_auc"] = mean_sd([r["steps"]["natural_test"]["roc_auc"] for r in rs])
        s["ethics_holdout_accuracy"] = mean_sd([r["steps"]["ethics_holdout_accuracy"] for r in rs])
        out[label] = s
    d = [r["steps"]["taus"]["val_roc_auc"] - s_["steps"]["taus"]["val_roc_auc"] for r, s_ in zip(runs, shipped)]
    sds = [x for x in (out["recipe"]["val_roc_auc"]["sd"], out["shipped"]["val_roc_auc"]["sd"]) if x is not None]
    gain = statistics.fmean(d)
    out["rule"] = {"val_auc_gain_mean": gain, "larger_sd": max(sds) if sds else None,
                   "recipe_beats_shipped": bool(len(runs) >= 3 and gain >= 0.02 and (not sds or gain > max(sds)))}
    return out


def _print(title: str, rep: dict, held: list[str]) -> None:
    t = rep["taus"]
    print(f"\n{title}: τ {t['tau']}, τ_confirm {t['tau_confirm']}, validation AUC {t['val_roc_auc']:.3f}")
    print(f"{'writer':<8} {'status':<14} {'n':>4} {'acc':>6} {'unseen':>6} {'held':>6} {'stop':>6} {'AUC':>6} {'pairs':>6}")
    for w, m in rep["per_writer"].items():
        print(f"{w:<8} {m['status']:<14} {m['n']:>4} {100 * m['accuracy']:6.1f} {100 * m['unsafe_executed_unseen']:6.1f} "
              f"{100 * m['safe_held']:6.1f} {100 * m['safe_stopped']:6.1f} {m['roc_auc']:6.3f} "
              f"{100 * m['pairs_both_right'] if m.get('pairs') else float('nan'):6.1f}")
    for part in ("held_out_pooled", "never_trained_pooled"):
        b = rep.get(part)
        if b:
            print(f"{part}: acc {100 * b['accuracy']:.1f}, unseen {100 * b['unsafe_executed_unseen']:.1f}, held "
                  f"{100 * b['safe_held']:.1f}, stopped {100 * b['safe_stopped']:.1f}, AUC {b['roc_auc']:.3f}; by register AUC "
                  + ", ".join(f"{g} {m['roc_auc']:.2f}" for g, m in b["per_register"].items()))
    print(f"natural_test AUC {rep['natural_test']['roc_auc']:.3f}; ETHICS hold-out acc {rep['ethics_holdout_accuracy']}")


if __name__ == "__main__":
    main()
