"""Does a larger encoder pay? Frozen-encoder linear probes, MiniLM-L6 vs MPNet (issue 12, item 5).

    python -m bench.risk.risk_probe --mpnet DIR [--seeds 42 7 13] [--tag probe]

Fine-tuning MPNet (110 M) with LoRA on 2 CPU cores takes hours per seed, so this asks the cheaper
question first: with both encoders *frozen* (mean pooling, as both were pre-trained for sentence
embeddings), how well does a logistic-regression head trained on the same rows read robot
commands? If MPNet's probe does not clearly beat MiniLM's probe, fine-tuning it (or distilling it)
is unlikely to pay either.

Rows: training = the hand-written corpus's training split (data/robot_train) + N ETHICS cm
training rows (drawn per seed); the L2 strength C is chosen on the corpus's validation split;
τ is chosen on that validation split for a false-alarm budget (15 %), as in bench/risk/risk_natural.py;
the frozen natural test set (data/natural_robot) is only reported on. Seeds vary the ETHICS draw.
Writes bench/results/risk/risk_probe_<tag>.json; prints a table (mean ± sd over seeds).
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from bench import results_dir
from bench._machine import machine_facts
from bench.risk import risk_data as D

MPNET_SHA256 = "78c0197b6159d92658e319bc1d72e4c73a9a03dd03815e70e555c5ef05615658"


def embed(model_dir: Path, texts: list[str], max_length: int = 128, batch: int = 32) -> np.ndarray:
    import torch
    from ethimon.risk import _backend as B
    tok = B.load_tokenizer(model_dir)
    enc = B.load_encoder(model_dir).eval()
    seqs = B.encode(tok, texts, max_length)
    order = np.argsort([len(s) for s in seqs])
    out = np.zeros((len(texts), enc.config.hidden_size), dtype=np.float32)
    pad = tok.pad_token_id or 0
    with torch.inference_mode():
        for i in range(0, len(order), batch):
            idx = order[i:i + batch]
            ids, mask = B.collate([seqs[j] for j in idx], pad)
            h = enc(input_ids=ids, attention_mask=mask).last_hidden_state
            m = mask.unsqueeze(-1).to(h.dtype)
            v = (h * m).sum(1) / m.sum(1).clamp(min=1.0)
            out[idx] = torch.nn.functional.normalize(v, dim=-1).numpy()
    return out


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--mpnet", required=True, help="unpacked all-mpnet-base-v2 directory (sha256-pinned)")
    ap.add_argument("--seeds", type=int, nargs="+", default=[42, 7, 13])
    ap.add_argument("--ethics-n", type=int, default=1000)
    ap.add_argument("--budget", type=float, default=0.15)
    ap.add_argument("--tag", default="probe")
    a = ap.parse_args()
    import torch
    torch.set_num_threads(2)
    from sklearn.linear_model import LogisticRegression
    from ethimon.risk import _backend as B
    from ethimon.risk._evaluate import (classification_metrics, flag_stats, pair_metrics,
                                        tau_for_false_alarm_budget, type_metrics)
    from ethimon.risk._formula import risk_from_p_unsafe

    mp = Path(a.mpnet)
    got = B.sha256_file(mp / "model.safetensors")
    if got != MPNET_SHA256:
        raise SystemExit(f"{mp}/model.safetensors: sha256 {got} is not the pinned {MPNET_SHA256}")
    n_tr, n_va = D.natural_train_splits()
    test = D.natural_test()
    e_tr, _, e_ho = D.ethics_splits()
    sets = {"n_tr": n_tr, "n_va": n_va, "test": test, "e_tr": e_tr, "e_ho": e_ho}
    encoders = {"minilm_l6": B.base_package_dir(), "mpnet_base": mp}
    emb: dict[str, dict[str, np.ndarray]] = {}
    enc_s = {}
    for name, d in encoders.items():
        t0 = time.time()
        emb[name] = {k: embed(d, rows.texts) for k, rows in sets.items()}
        enc_s[name] = round(time.time() - t0, 1)
        print(f"{name}: embedded {sum(len(r) for r in sets.values())} rows in {enc_s[name]} s", flush=True)

    y_te, y_va = np.array(test.labels), np.array(n_va.labels)
    pair_ids, types = [e.get("pair") for e in test.extra], [e.get("type") for e in test.extra]
    results: dict[str, list[dict]] = {k: [] for k in encoders}
    for name in encoders:
        E = emb[name]
        for seed in a.seeds:
            rng = np.random.default_rng(seed)
            pick = rng.choice(len(e_tr), size=min(a.ethics_n, len(e_tr)), replace=False)
            X = np.vstack([E["n_tr"], E["e_tr"][pick]])
            y = np.concatenate([n_tr.labels, np.array(e_tr.labels)[pick]])
            best = None
            for C in (0.1, 0.3, 1.0, 3.0, 10.0, 30.0):
                clf = LogisticRegression(C=C, max_iter=3000, random_state=seed).fit(X, y)
                acc = float((clf.predict(E["n_va"]) == y_va).mean())
                if best is None or acc > best[0]:
                    best = (acc, C, clf)
            _, C, clf = best
            q = {k: clf.predict_proba(E[k])[:, 1] for k in ("n_va", "test", "e_ho")}
            r = {k: np.array([risk_from_p_unsafe(float(v)) for v in q[k]]) for k in q}
            tau = tau_for_false_alarm_budget(y_va, r["n_va"], a.budget)["tau"]
            results[name].append({
                "seed": seed, "C": C, "tau": tau, "val_accuracy": best[0],
                "natural": {**classification_metrics(y_te, q["test"]), "at_tau": flag_stats(y_te, r["test"], tau),
                            "pairs": pair_metrics(y_te, q["test"], r["test"], pair_ids, tau),
                            "by_type": type_metrics(y_te, q["test"], r["test"], types, tau)},
                "ethics_holdout": classification_metrics(e_ho.labels, q["e_ho"])})

    def ms(vals):
        v = np.array(vals, dtype=float)
        return f"{100 * v.mean():5.1f} ± {100 * v.std(ddof=1):3.1f}" if len(v) > 1 else f"{100 * v[0]:5.1f}"
    rows = [("natural accuracy (p>=0.5)", lambda m: m["natural"]["accuracy"]),
            ("natural ROC-AUC", lambda m: m["natural"]["roc_auc"]),
            ("natural unsafe flagged at tau", lambda m: m["natural"]["at_tau"]["flag_rate_unsafe"]),
            ("natural false alarms at tau", lambda m: m["natural"]["at_tau"]["false_alarm_rate"]),
            ("pairs: unsafe ranked higher", lambda m: m["natural"]["pairs"]["ranked"]),
            ("pairs: both right at tau", lambda m: m["natural"]["pairs"]["both_right_at_tau"]),
            ("validation accuracy (selection)", lambda m: m["val_accuracy"]),
            ("ETHICS hold-out accuracy", lambda m: m["ethics_holdout"]["accuracy"])]
    print(f"\nfrozen encoder + logistic regression, {len(a.seeds)} seeds (mean ± sd, %)")
    print(f"{'measure':36} " + " ".join(f"{k:>16}" for k in encoders))
    for label, f in rows:
        print(f"{label:36} " + " ".join(f"{ms([f(m) for m in results[k]]):>16}" for k in encoders))
    out = {"what": "frozen-encoder linear probes (issue 12 item 5)", "seeds": a.seeds, "ethics_n": a.ethics_n,
           "budget": a.budget, "mpnet_sha256": MPNET_SHA256, "embed_seconds": enc_s,
           "results": results, "machine": machine_facts()}
    (results_dir("risk") / f"risk_probe_{a.tag}.json").write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
