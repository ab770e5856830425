"""Cheap full leave-one-writer-out table (issue 19): frozen MiniLM-L6 + logistic regression.

    python -m bench.risk.risk_writers_probe

For every writer w: a logistic-regression probe on frozen, mean-pooled MiniLM-L6 embeddings
(the pretrained base, 256 tokens) is fitted on (a) the hand-written corpus data/robot_train
only and (b) the corpus plus every *other* writer's train.csv; τ and τ_confirm come from
w's own train.csv plus data/robot_val_other (validation: never fitted on), by the rules of
bench/results/risk/writers/DECISIONS.md; w's frozen test slice is reported. The probe reads
each text flat, and with the step reading (every view embedded, the riskiest counts), so the
table also says whether reading the step pays when a model has seen other writers' registers.
C is fixed (1.0); nothing is tuned.

Writes bench/results/risk/risk_writers_probe.json with machine facts.
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

from bench import results_dir
from bench._machine import machine_facts
from bench.risk import risk_data as D
from bench.risk.risk_writers import choose_taus, outcomes


def embed_views(tok, enc, items: list[tuple[str, str]], max_length: int = 256) -> np.ndarray:
    import torch
    from ethimon.risk import _backend as B
    seqs = B.encode_views(tok, items, max_length, "head_tail")
    order = sorted(range(len(seqs)), key=lambda i: len(seqs[i]))
    out = np.zeros((len(seqs), enc.config.hidden_size), dtype=np.float32)
    with torch.inference_mode():
        for s in range(0, len(order), 64):
            idx = order[s:s + 64]
            ids, mask = B.collate([seqs[i] for i in idx], tok.pad_token_id or 0)
            h = enc(input_ids=ids, attention_mask=mask).last_hidden_state
            m = mask.unsqueeze(-1).float()
            out[idx] = ((h * m).sum(1) / m.sum(1)).numpy()
    return out


def main() -> None:
    argparse.ArgumentParser(description=__doc__.split("\n\n")[0]).parse_args()
    import torch
    from sklearn.linear_model import LogisticRegression
    from ethimon.risk import _backend as B
    from ethimon.risk import risk_from_p_unsafe
    from ethimon.risk._estimator import normalize_text
    from ethimon.risk._reading import View, views
    torch.set_num_threads(2)
    t0 = time.time()
    base = B.base_package_dir()
    tok, enc = B.load_tokenizer(base), B.load_encoder(base).eval()
    wids = D.writer_ids()
    tr_a, va_a = D.natural_train_splits()
    corpus = D.concat(tr_a, va_a)
    val_other = D.load_labelled_csv(D.ROOT / "data" / "robot_val_other" / "val_other.csv")
    sets = {"corpus": corpus, "val_other": val_other}
    for w in wids:
        sets[f"{w}/train"] = D.writers_train([w])
        sets[f"{w}/test"] = D.writer_test(w)
    # every text: its flat view, and its step views (flat view first, then the reading's own)
    items, spans = [], {}
    for name, rows in sets.items():
        sp = []
        for t in rows.texts:
            key = normalize_text(t)
            sv = views(key, "steps")
            start = len(items)
            items.append(View(key))
            own = [v for v in sv if v != View(key)] if sv != [View(key)] else []
            items += own
            sp.append((start, start + 1 if own else start, len(items)))
        spans[name] = sp
    X = embed_views(tok, enc, [(v.context, v.focus) for v in items])
    t_embed = time.time() - t0
    f = np.vectorize(risk_from_p_unsafe)

    def flat_X(name):
        return X[[a for a, _b, _c in spans[name]]]

    res = {"writers": wids, "C": 1.0, "rows": {}}
    for w in wids:
        row = {}
        for mix in ("corpus_only", "corpus_plus_other_writers"):
            names = ["corpus"] + ([f"{o}/train" for o in wids if o != w] if mix != "corpus_only" else [])
            Xtr = np.concatenate([flat_X(n) for n in names])
            ytr = np.concatenate([np.array(sets[n].labels) for n in names])
            clf = LogisticRegression(C=1.0, max_iter=2000).fit(Xtr, ytr)
            pu_all = clf.predict_proba(X)[:, 1]
            for reading in ("flat", "steps"):
                def r_of(name):
                    if reading == "flat":
                        return f(np.array([pu_all[a] for a, _b, _c in spans[name]]))
                    return f(np.array([pu_all[b:c].max() if c > b else pu_all[a] for a, b, c in spans[name]]))
                yv = np.concatenate([np.array(sets["val_other"].labels), np.array(sets[f"{w}/train"].labels)])
                rv = np.concatenate([r_of("val_other"), r_of(f"{w}/train")])
                taus = choose_taus(yv, rv)
                te = sets[f"{w}/test"]
                m = outcomes(np.array(te.labels), r_of(f"{w}/test"), taus["tau"], taus["tau_confirm"],
                             [e.get("pair", "") for e in te.extra])
                m["taus"] = taus
                row[f"{mix}|{reading}"] = m
        res["rows"][w] = row
    res["seconds_embed"] = round(t_embed, 1)
    res["seconds"] = round(time.time() - t0, 1)
    res["views_embedded"] = len(items)
    res["machine"] = machine_facts(threads=2)
    (results_dir("risk") / "risk_writers_probe.json").write_text(json.dumps(res, indent=1) + "\n")
    print(f"{'held-out writer':<16} {'train mix | reading':<36} {'n':>4} {'acc':>5} {'unseen':>6} {'held':>5} "
          f"{'stop':>5} {'AUC':>5} {'pairs':>5}")
    for w, row in res["rows"].items():
        for k, m in row.items():
            print(f"{w:<16} {k:<36} {m['n']:>4} {100 * m['accuracy']:5.1f} {100 * m['unsafe_executed_unseen']:6.1f} "
                  f"{100 * m['safe_held']:5.1f} {100 * m['safe_stopped']:5.1f} {m['roc_auc']:.3f} "
                  f"{100 * m['pairs_both_right'] if m['pairs'] else float('nan'):5.1f}")
    print(f"({len(items)} views embedded in {t_embed:.0f} s; total {res['seconds']} s)")


if __name__ == "__main__":
    main()
