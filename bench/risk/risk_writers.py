"""Risk models on other writers' text (issue 19): leave-writer-out, per register, three outcomes.

    python -m bench.risk.risk_writers --models default [runs/a runs/b runs/c] --tag NAME [--ethics]

For every model: the writers it was trained on are read from its ``metrics.json``
(``config.writers``; ``SHIPPED_WRITERS`` for the shipped model). Its validation rows are
``data/robot_val_other`` plus the ``train.csv`` rows of every writer it was *not* trained on;
τ and τ_confirm come from them by the rules of ``bench/results/risk/writers/DECISIONS.md``
(τ: false alarms ≤ 10 %; τ_confirm: ≤ 10 % of unsafe rows below it). Then each writer's frozen
test slice (sha256 checked) is scored and reported, per writer and per register, as

* executed unseen (unsafe, R_e < τ_confirm), safe held (τ_confirm ≤ R_e < τ), safe stopped (R_e ≥ τ),
* accuracy (a hold counts as flagged), ROC-AUC of R_e, minimal pairs both right,

labelled ``held_out`` (a writer the model never trained on) or ``seen``. Both readings of the
estimator come from one pass (the step reading's first view is the whole text, the flat
reading). ``natural_test`` (frozen) is reported too, ``--ethics`` adds the ETHICS hold-out.
Over several models, the held-out figures are summarised as mean ± sd.

Writes bench/results/risk/risk_writers_<tag>.json (every row's R_e too) with machine facts.
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from pathlib import Path

import numpy as np

from bench import results_dir
from bench._machine import machine_facts
from bench.risk import risk_data as D

BUDGET = 0.10      # safe stopped outright on validation
MISS = 0.10        # unsafe below tau_confirm on validation
READINGS = ("steps", "flat")


def risks_both(est, texts: list[str]) -> dict[str, np.ndarray]:
    """R_e (spec defaults) of every text under the step reading and the flat one, one forward pass."""
    from ethimon.risk import risk_from_p_unsafe
    from ethimon.risk._estimator import normalize_text
    from ethimon.risk._reading import View, views
    allv, own = [], []
    for t in texts:
        key = normalize_text(t)
        sv = views(key, "steps")
        if sv == [View(key)]:          # one sentence: both readings are the text itself
            own.append((len(allv), len(allv), len(allv) + 1))
            allv += sv
        else:                          # the flat view, then the step reading's own views
            own.append((len(allv), len(allv) + 1, len(allv) + 1 + len(sv)))
            allv += [View(key)] + sv
    p = est._forward_views(allv, raw=False)
    pu = np.array([q[1] for q in p])
    steps = np.array([pu[s0:e].max() for _f, s0, e in own])
    flat = np.array([pu[f] for f, _s0, _e in own])
    f = np.vectorize(risk_from_p_unsafe)
    return {"steps": f(steps), "flat": f(flat), "views": len(allv)}


def choose_taus(y: np.ndarray, r: np.ndarray) -> dict:
    from ethimon.risk._evaluate import tau_for_false_alarm_budget
    fs = tau_for_false_alarm_budget(y, r, BUDGET)
    tau = float(np.ceil(fs["tau"] * 1000) / 1000)
    ru = np.sort(r[y == 1])
    # largest tau_c <= tau with share(unsafe R < tau_c) <= MISS
    k = int(np.floor(MISS * len(ru)))          # at most k unsafe rows below
    tc = float(ru[k]) if k < len(ru) else tau  # every candidate <= ru[k] leaves <= k below
    tc = min(tau, float(np.floor(tc * 1000) / 1000))
    return {"tau": tau, "tau_confirm": tc, "val_false_alarms": fs["false_alarm_rate"],
            "val_unsafe_below_tc": float((ru < tc).mean()) if len(ru) else 0.0,
            "val_n": int(len(y))}


def outcomes(y: np.ndarray, r: np.ndarray, tau: float, tc: float, pairs: list[str] | None = None) -> dict:
    from sklearn.metrics import roc_auc_score
    y = np.asarray(y)
    flagged = r >= tc
    res = {"n": int(len(y)), "n_unsafe": int(y.sum()),
           "accuracy": float((flagged == (y == 1)).mean()) if len(y) else float("nan"),
           "unsafe_executed_unseen": float((r[y == 1] < tc).mean()) if (y == 1).any() else float("nan"),
           "unsafe_flagged": float((r[y == 1] >= tc).mean()) if (y == 1).any() else float("nan"),
           "safe_held": float(((r[y == 0] >= tc) & (r[y == 0] < tau)).mean()) if (y == 0).any() else float("nan"),
           "safe_stopped": float((r[y == 0] >= tau).mean()) if (y == 0).any() else float("nan"),
           "accuracy_at_tau_only": float(((r >= tau) == (y == 1)).mean()) if len(y) else float("nan"),
           "roc_auc": float(roc_auc_score(y, r)) if 0 < y.sum() < len(y) else float("nan")}
    if pairs is not None:
        by: dict[str, dict[int, int]] = {}
        for i, pid in enumerate(pairs):
            if pid:
                by.setdefault(pid, {})[int(y[i])] = i
        full = [d for d in by.values() if len(d) == 2]
        res["pairs"] = len(full)
        res["pairs_both_right"] = (float(np.mean([flagged[d[1]] and not flagged[d[0]] for d in full]))
                                   if full else float("nan"))
        res["pairs_ranked"] = (float(np.mean([r[d[1]] > r[d[0]] for d in full])) if full else float("nan"))
    return res


#: the writers whose train.csv rows the shipped default model trained on (issue 19:
#: bench/risk/risk_writers_top.py --final, MODEL_CARD.md); the model before it trained on none
SHIPPED_WRITERS = [f"w{i:02d}" for i in range(1, 13)]


def mean_sd(values) -> dict:
    """``{"mean", "sd", "runs"}`` of the numbers in ``values`` (None and NaN left out; sd needs 2)."""
    xs = [x for x in values if x is not None and x == x]
    return {"mean": statistics.fmean(xs) if xs else None, "sd": statistics.stdev(xs) if len(xs) > 1 else None,
            "runs": len(xs)}


def pooled(parts: dict, tau: float, tc: float) -> dict:
    """:func:`outcomes` of several slices pooled (``parts``: name -> (rows, R_e)), plus per register.

    Pair ids are prefixed by the slice's name, so two writers' ``p001`` stay two pairs.
    """
    ys = np.concatenate([np.array(rows.labels) for rows, _r in parts.values()])
    rs = np.concatenate([np.asarray(r) for _rows, r in parts.values()])
    ps = [f"{n}:{e['pair']}" if e.get("pair") else "" for n, (rows, _r) in parts.items() for e in rows.extra]
    regs = [e.get("register", "") for rows, _r in parts.values() for e in rows.extra]
    res = outcomes(ys, rs, tau, tc, ps)
    res["per_register"] = {g: outcomes(ys[[i for i, x in enumerate(regs) if x == g]],
                                       rs[[i for i, x in enumerate(regs) if x == g]], tau, tc)
                           for g in sorted(set(regs))}
    return res


def trained_writers(model: str) -> list[str]:
    if model == "default":
        return list(SHIPPED_WRITERS)
    m = Path(model) / "metrics.json"
    if not m.is_file():
        return []
    return list(json.loads(m.read_text()).get("config", {}).get("writers") or [])


def load(model: str):
    from ethimon.risk import load_estimator
    # torch, as every figure of issue 19 was measured (ONNX Runtime agrees within 2e-3: test_risk_onnx)
    return load_estimator(None if model == "default" else model, cache_size=0, batch_size=32, jit=True,
                          backend="torch")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--models", nargs="+", default=["default"], help="model dirs, or 'default' (the shipped one)")
    ap.add_argument("--tag", required=True)
    ap.add_argument("--writers", nargs="*", default=None, help="writers to use (default: every complete one)")
    ap.add_argument("--ethics", action="store_true", help="also the ETHICS cm hold-out (about 800 stories)")
    ap.add_argument("--threads", type=int, default=2)
    a = ap.parse_args()
    import torch
    torch.set_num_threads(a.threads)
    wids = a.writers if a.writers is not None else D.writer_ids()
    tests = {w: D.writer_test(w) for w in wids}            # sha256-checked
    trains = {w: D.writers_train([w]) for w in wids}
    val_other = D.load_labelled_csv(D.ROOT / "data" / "robot_val_other" / "val_other.csv")
    nat = D.natural_test()
    eth = D.ethics_splits()[2] if a.ethics else None
    out = {"writers": wids, "rules": {"budget": BUDGET, "miss": MISS}, "models": {}}
    t_all = time.time()
    for model in a.models:
        t0 = time.time()
        seen = trained_writers(model)
        est = load(model)
        val_ids = [w for w in wids if w not in seen]
        val_texts = list(val_other.texts) + [t for w in val_ids for t in trains[w].texts]
        val_y = np.array(list(val_other.labels) + [y for w in val_ids for y in trains[w].labels])
        rv = risks_both(est, val_texts)
        rec = {"model_id": est.model_id, "trained_writers": seen, "validation_writers": val_ids, "readings": {}}
        scored = {w: risks_both(est, tests[w].texts) for w in wids}
        rn = risks_both(est, nat.texts)
        re_ = risks_both(est, eth.texts) if eth is not None else None
        for rd in READINGS:
            taus = choose_taus(val_y, rv[rd])
            from sklearn.metrics import roc_auc_score
            taus["val_roc_auc"] = float(roc_auc_score(val_y, rv[rd]))
            per_w, per_reg = {}, {}
            for w in wids:
                rows = tests[w]
                y = np.array(rows.labels)
                r = scored[w][rd]
                res = outcomes(y, r, taus["tau"], taus["tau_confirm"], [e.get("pair", "") for e in rows.extra])
                res["status"] = "seen" if w in seen else "held_out"
                res["risks"] = [round(float(x), 5) for x in r]
                per_w[w] = res
                regs = [e.get("register", "") or "?" for e in rows.extra]
                for g in sorted(set(regs)):
                    idx = [i for i, x in enumerate(regs) if x == g]
                    key = f"{g}|{'seen' if w in seen else 'held_out'}"
                    per_reg.setdefault(key, {"y": [], "r": [], "pairs": []})
                    per_reg[key]["y"] += [int(y[i]) for i in idx]
                    per_reg[key]["r"] += [float(r[i]) for i in idx]
                    per_reg[key]["pairs"] += [f"{w}:{rows.extra[i].get('pair', '')}" if rows.extra[i].get("pair")
                                              else "" for i in idx]
            regs_out = {k: outcomes(np.array(v["y"]), np.array(v["r"]), taus["tau"], taus["tau_confirm"], v["pairs"])
                        for k, v in sorted(per_reg.items())}
            held = [w for w in wids if w not in seen]
            if held:
                ys = np.concatenate([np.array(tests[w].labels) for w in held])
                rs = np.concatenate([scored[w][rd] for w in held])
                pp = [f"{w}:{e.get('pair', '')}" if e.get("pair") else "" for w in held for e in tests[w].extra]
                pooled = outcomes(ys, rs, taus["tau"], taus["tau_confirm"], pp)
            else:
                pooled = None
            nat_res = outcomes(np.array(nat.labels), rn[rd], taus["tau"], taus["tau_confirm"],
                               [e.get("pair", "") for e in nat.extra])
            eth_res = (outcomes(np.array(eth.labels), re_[rd], taus["tau"], taus["tau_confirm"])
                       if re_ is not None else None)
            rec["readings"][rd] = {"taus": taus, "held_out_pooled": pooled, "per_writer": per_w,
                                   "per_register": regs_out, "natural_test": nat_res, "ethics_holdout": eth_res}
        rec["seconds"] = round(time.time() - t0, 1)
        out["models"][model] = rec
        _print(model, rec, wids)
    out["summary"] = summarise(out)
    out["seconds"] = round(time.time() - t_all, 1)
    out["machine"] = machine_facts(threads=a.threads)
    p = results_dir("risk") / f"risk_writers_{a.tag}.json"
    p.write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {p}")


def _pct(x) -> str:
    return "  –  " if x is None or x != x else f"{100 * x:5.1f}"


def _print(model: str, rec: dict, wids: list[str]) -> None:
    print(f"\n== {model} [{rec['model_id']}] trained on writers {rec['trained_writers'] or 'none'} ({rec['seconds']} s)")
    for rd, R in rec["readings"].items():
        t = R["taus"]
        print(f"-- reading {rd}: tau {t['tau']:.3f}, tau_confirm {t['tau_confirm']:.3f} (validation n {t['val_n']}, "
              f"AUC {t['val_roc_auc']:.3f})")
        print(f"{'slice':<34} {'n':>5} {'acc':>5} {'unseen':>6} {'held':>5} {'stop':>5} {'AUC':>5} {'pairs':>5}")
        rows = [(f"{w} ({R['per_writer'][w]['status']})", R["per_writer"][w]) for w in wids]
        rows += [(k, v) for k, v in R["per_register"].items()]
        if R["held_out_pooled"]:
            rows.append(("held-out writers pooled", R["held_out_pooled"]))
        rows.append(("natural_test", R["natural_test"]))
        if R["ethics_holdout"]:
            rows.append(("ETHICS hold-out", R["ethics_holdout"]))
        for name, m in rows:
            auc = m["roc_auc"]
            print(f"{name:<34} {m['n']:>5} {_pct(m['accuracy'])} {_pct(m['unsafe_executed_unseen']):>6} "
                  f"{_pct(m['safe_held'])} {_pct(m['safe_stopped'])} {'  –  ' if auc != auc else f'{auc:.3f}'} "
                  f"{_pct(m.get('pairs_both_right'))}")


def summarise(out: dict) -> dict:
    """mean ± sd over models of the held-out pooled figures (and each register, held out), per reading."""
    res = {}
    keys = ("accuracy", "unsafe_executed_unseen", "safe_held", "safe_stopped", "roc_auc", "pairs_both_right")
    for rd in READINGS:
        pools = [m["readings"][rd]["held_out_pooled"] for m in out["models"].values()
                 if m["readings"][rd]["held_out_pooled"]]
        s = {}
        for k in keys:
            s[k] = mean_sd(p.get(k) for p in pools)
        regs: dict[str, list[float]] = {}
        for m in out["models"].values():
            for k, v in m["readings"][rd]["per_register"].items():
                if k.endswith("|held_out"):
                    regs.setdefault(k.split("|")[0], []).append(v["accuracy"])
        s["register_accuracy_held_out"] = {g: mean_sd(v) for g, v in sorted(regs.items())}
        res[rd] = s
    return res


if __name__ == "__main__":
    main()
