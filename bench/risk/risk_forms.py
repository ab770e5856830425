"""Recipe "forms" against the shipped model (issue 30 items 1–2; DECISIONS.md, 2026-12-05 21:12 UTC entry).

    python -m bench.risk.risk_forms --runs runs/forms_s42 runs/forms_s7 runs/forms_s13 --tag forms
        [--stage val|all] [--check 40] [--threads 2]

One command, three stages, resumable (every row's R_e is cached in the output JSON, so a stage already done
is not scored again):

1. ``val``: each run's R_e (governor formula, ``load_estimator(run dir)``: default back-end, step reading) on
   the shipped pair's 2,596 validation rows (``data/robot_val_other`` + w13–w21 ``train.csv``, as
   ``risk_tau``); its τ pair by the rules (``risk_writers.choose_taus``) and its validation ROC-AUC. The
   shipped model's R_e come from ``risk_tau_<shipped>.json`` (re-scored on ``--check`` rows spread over
   the file and refused if one differs by more than 2e-3).
2. ``test`` (only once every run given has its τ pair, so no test.csv is opened before): every writer's
   frozen test slice (sha256 checked) scored by each run.
3. report: the shipping rule (mean validation AUC over the runs − the shipped model's ≥ 0.02 and > sd), then
   per group — ``unseen`` (w22+), ``tau_writers`` (w13–w21), ``seen`` (w01–w12) — and per register inside
   each group: unsafe executed unseen, safe held, safe stopped, accuracy (a hold counts as flagged),
   ROC-AUC, minimal pairs both right; mean ± sd over the runs beside the shipped model at its own pair.

Writes bench/results/risk/risk_forms_<tag>.json with machine facts.
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
from bench.risk.risk_tau import VALIDATION_WRITERS, score
from bench.risk.risk_writers import choose_taus, mean_sd, outcomes

SHIPPED = "shipped"
KEYS = ("unsafe_executed_unseen", "safe_held", "safe_stopped", "accuracy", "roc_auc", "pairs_both_right")
SEEN = [f"w{i:02d}" for i in range(1, 13)]


def group_of(w: str) -> str:
    return "seen" if w in SEEN else "tau_writers" if w in VALIDATION_WRITERS else "unseen"


def validation_rows():
    parts = [("val_other", D.load_labelled_csv(D.ROOT / "data" / "robot_val_other" / "val_other.csv"))]
    parts += [(w, D.writers_train([w])) for w in VALIDATION_WRITERS]
    texts, y, src = [], [], []
    for name, rows in parts:
        texts += list(rows.texts)
        y += [int(v) for v in rows.labels]
        src += [name] * len(rows)
    return texts, np.array(y), src


def _auc(y, r) -> float:
    from sklearn.metrics import roc_auc_score
    return round(float(roc_auc_score(y, r)), 4)


def _rk():
    import ethimon
    return ethimon.load_spec(D.ROOT / "specs" / "governor.yaml").risk


def _est(model: str, threads: int):
    from ethimon.risk import load_estimator
    return load_estimator(None if model == SHIPPED else model, num_threads=threads)


def shipped_from_cache(path: Path, texts, y, check: int, threads: int) -> dict:
    d = json.loads(path.read_text())
    vr = d["validation_rows"]
    if len(vr) != len(y) or any(int(a["label"]) != int(b) for a, b in zip(vr, y)):
        raise SystemExit(f"{path}: its validation rows are not the rows of this bench")
    r = np.array([a["r_e"] for a in vr])
    if check:
        est = _est(SHIPPED, threads)
        if est.model_id != d["model_id"]:
            raise SystemExit(f"{path}: cached for {d['model_id']}, the shipped model is now {est.model_id}")
        idx = np.linspace(0, len(y) - 1, check).astype(int)
        got = score(est, [texts[i] for i in idx], _rk(), "shipped check")
        worst = float(np.abs(got - r[idx]).max())
        if worst > 2e-3:
            raise SystemExit(f"{path}: the shipped model's R_e moved by {worst:.4f} on the check rows: re-run risk_tau")
        print(f"shipped cache checked on {check} rows: max |ΔR_e| {worst:.5f}")
    taus = choose_taus(y, r)
    return {"model_id": d["model_id"], "from": str(path.relative_to(D.ROOT)),
            "validation": {"r_e": [round(float(x), 5) for x in r], "roc_auc": _auc(y, r)},
            "taus": {k: taus[k] for k in ("tau", "tau_confirm")},
            "test": {"rows": d["test_scores"]["rows"], "seconds": d["test_scores"]["seconds"]}}


def test_rows():
    """(writer, id, text, label, register, pair) of every frozen test slice, in risk_tau's order."""
    out = []
    for w in sorted(d.name for d in D.WRITERS.glob("w[0-9][0-9]") if (d / "test.csv.sha256").is_file()):
        rows = D.writer_test(w)
        for i, (t, y, e) in enumerate(zip(rows.texts, rows.labels, rows.extra)):
            out.append((w, e.get("id", f"{w}-{i}"), t, int(y), e.get("register", "") or "?", e.get("pair", "") or ""))
    return out


def report(res: dict, runs: list[str], trows) -> dict:
    lab = {(w, i): (y, g, p) for w, i, _t, y, g, p in trows}
    models = [SHIPPED] + [r for r in runs if "test" in res["models"].get(r, {})]
    figs: dict[str, dict] = {}
    for m in models:
        rows = res["models"][m]["test"]["rows"]
        t = res["models"][m]["taus"]
        sl: dict[str, list] = {}
        for row in rows:
            y, g, p = lab[(row["writer"], row["id"])]
            grp = group_of(row["writer"])
            for key in (grp, f"{grp} | {g}"):
                sl.setdefault(key, []).append((y, row["r_e"], f"{row['writer']}:{p}" if p else ""))
        figs[m] = {k: outcomes(np.array([a for a, _b, _c in v]), np.array([b for _a, b, _c in v]),
                               t["tau"], t["tau_confirm"], [c for _a, _b, c in v]) for k, v in sl.items()}
    order = sorted(figs[SHIPPED], key=lambda k: (["unseen", "tau_writers", "seen"].index(k.split(" | ")[0]), k))
    table = {}
    for k in order:
        ent = {"n": figs[SHIPPED][k]["n"], SHIPPED: {q: figs[SHIPPED][k].get(q) for q in KEYS}}
        trained = [m for m in models if m != SHIPPED]
        ent["forms"] = {q: mean_sd(figs[m][k].get(q) for m in trained) for q in KEYS}
        table[k] = ent
    return table


def _f(x, pct=True) -> str:
    if x is None or x != x:
        return "  – "
    return f"{100 * x:4.1f}" if pct else f"{x:.3f}"


def _ms(d, pct=True) -> str:
    if d["mean"] is None:
        return "     –     "
    sd = "" if d["sd"] is None else (f"±{100 * d['sd']:.1f}" if pct else f"±{d['sd']:.3f}")
    return f"{_f(d['mean'], pct)}{sd}"


def print_table(table: dict) -> None:
    head = "unseen  held  stop   acc   AUC  pairs"
    print(f"\n{'slice':<40} {'n':>5} | shipped: {head} | forms (mean ± sd over runs): {head}")
    for k, e in table.items():
        s, f = e[SHIPPED], e["forms"]
        print(f"{k:<40} {e['n']:>5} | " + " ".join(_f(s[q], q != "roc_auc") for q in KEYS)
              + " | " + " ".join(_ms(f[q], q != "roc_auc") for q in KEYS))


def main() -> None:  # noqa: C901 - one experiment, read top to bottom
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--runs", nargs="+", required=True, help="run dirs of the recipe (seeds 42, 7, 13)")
    ap.add_argument("--tag", required=True)
    ap.add_argument("--stage", choices=("val", "all"), default="all")
    ap.add_argument("--shipped", default="bench/results/risk/risk_tau_reading31.json",
                    help="risk_tau JSON with the shipped model's R_e on the same rows")
    ap.add_argument("--check", type=int, default=40, help="validation rows re-scored to check the shipped cache")
    ap.add_argument("--threads", type=int, default=2)
    a = ap.parse_args()
    path = results_dir("risk") / f"risk_forms_{a.tag}.json"
    res = json.loads(path.read_text()) if path.is_file() else {"tag": a.tag, "models": {}}
    res["rule"] = "bench/results/risk/writers/DECISIONS.md (2026-12-05 21:12 UTC entry)"
    t0 = time.time()
    texts, y, src = validation_rows()
    res["validation"] = {"n": len(y), "unsafe": int(y.sum()),
                         "sources": {s: src.count(s) for s in dict.fromkeys(src)}}
    if SHIPPED not in res["models"]:
        res["models"][SHIPPED] = shipped_from_cache(D.ROOT / a.shipped, texts, y, a.check, a.threads)

    def save():
        res["machine"] = machine_facts(threads=a.threads)
        path.write_text(json.dumps(res, indent=1) + "\n", encoding="utf-8")

    rk = _rk()
    for run in a.runs:
        m = res["models"].get(run)
        if m and "taus" in m:
            continue
        if not (Path(run) / "ethimon_model.json").is_file():
            print(f"{run}: not trained yet (no ethimon_model.json); skipped")
            continue
        est = _est(run, a.threads)
        t = time.time()
        r = score(est, texts, rk, f"{run} validation")
        taus = choose_taus(y, r)
        res["models"][run] = {"model_id": est.model_id, "metrics": json.loads((Path(run) / "metrics.json").read_text())
                              .get("config", {}),
                              "validation": {"r_e": [round(float(x), 5) for x in r], "roc_auc": _auc(y, r),
                                             "seconds": round(time.time() - t, 1)},
                              "taus": {k: taus[k] for k in ("tau", "tau_confirm")}}
        res["models"][run]["metrics"].pop("base_dir", None)
        print(f"{run}: validation AUC {res['models'][run]['validation']['roc_auc']}, tau {taus['tau']:.3f}, "
              f"tau_confirm {taus['tau_confirm']:.3f} ({time.time() - t:.0f} s)")
        save()
    have = [r for r in a.runs if "taus" in res["models"].get(r, {})]
    ship_auc = res["models"][SHIPPED]["validation"]["roc_auc"]
    aucs = mean_sd(res["models"][r]["validation"]["roc_auc"] for r in have)
    rule = {"runs": have, "shipped_auc": ship_auc, "forms_auc": aucs}
    if len(have) == 3:
        diff = aucs["mean"] - ship_auc
        rule.update(diff=round(diff, 4), beats=bool(diff >= 0.02 and diff > aucs["sd"]))
    else:
        rule.update(diff=None, beats=None, note="fewer than three runs: the rule is not applied")
    res["selection"] = rule
    print(f"selection: shipped AUC {ship_auc}; forms {[res['models'][r]['validation']['roc_auc'] for r in have]} "
          f"-> {rule}")
    for r in have:
        print(f"  {r}: tau {res['models'][r]['taus']['tau']:.3f} / tau_confirm {res['models'][r]['taus']['tau_confirm']:.3f}")
    save()
    if a.stage == "val":
        return
    missing = [r for r in a.runs if r not in have]
    if missing:
        raise SystemExit(f"test slices are scored only once every run has its tau pair; missing: {missing}")
    trows = test_rows()
    for run in a.runs:
        if "test" in res["models"][run]:
            continue
        est = _est(run, a.threads)
        t = time.time()
        r = score(est, [x[2] for x in trows], rk, f"{run} test slices")
        res["models"][run]["test"] = {"seconds": round(time.time() - t, 1),
                                      "rows": [{"writer": w, "id": i, "r_e": round(float(v), 5)}
                                               for (w, i, *_), v in zip(trows, r)]}
        save()
    res["table"] = report(res, a.runs, trows)
    print_table(res["table"])
    res["seconds_this_call"] = round(time.time() - t0, 1)
    save()
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
