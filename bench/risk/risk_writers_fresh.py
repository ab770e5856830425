"""Models of bench/risk/risk_writers_top.py read through the runtime on writers no run trained on.

    python -m bench.risk.risk_writers_fresh --top-json bench/results/risk/risk_writers_top_top2.json \
        --run-dirs runs/top2_k0 runs/top2_k1 runs/top2_k2 --writers w13 w14 ... --tag top2

For every rotation k: the saved model dir of run k and the model they started from (``--baseline``: the shipped model when they ran), each loaded as a user
loads it (``load_estimator``, step reading, torch backend as every issue-19 figure) and each at
its own τ pair from that rotation's validation rows (stored in the top-k JSON), score the frozen
test slices of ``--writers`` (sha256 checked; writers that no run trained on and no rule chose
anything on). Also checks that the runtime reproduces the cached path: run k's R_e on its
held-out writers' test slices (max abs difference reported; the run fails above 1e-3).

Prints per writer and pooled figures (mean ± sd over the rotations) and writes
bench/results/risk/risk_writers_fresh_<tag>.json with machine facts.
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

from bench import results_dir
from bench._machine import machine_facts
from bench.risk import risk_data as D
from bench.risk.risk_writers import load, mean_sd, outcomes, pooled, risks_both
from bench.risk.risk_writers_top import KEYS


def block(rows_by_w: dict, risks_by_w: dict, tau: float, tc: float) -> dict:
    out = pooled({w: (rows_by_w[w], risks_by_w[w]) for w in rows_by_w}, tau, tc)
    out["per_writer"] = {w: outcomes(np.array(rows_by_w[w].labels), risks_by_w[w], tau, tc,
                                     [e.get("pair", "") for e in rows_by_w[w].extra]) for w in rows_by_w}
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--top-json", required=True)
    ap.add_argument("--run-dirs", nargs="+", required=True, help="one model dir per rotation, in the JSON's order")
    ap.add_argument("--writers", nargs="+", required=True)
    ap.add_argument("--baseline", default="default",
                    help="the model the rotations started from (its τ pairs are in the JSON as 'shipped'); once "
                         "the default has been replaced, the previous default's directory (git show it out)")
    ap.add_argument("--tag", required=True)
    a = ap.parse_args()
    t0 = time.time()
    top = json.loads(open(a.top_json).read())
    rot = [r for r in top["runs"] if "rotation" in r]
    ship = [s for s in top["shipped"] if "rotation" in s]
    if len(rot) != len(a.run_dirs):
        raise SystemExit(f"{len(rot)} rotations in {a.top_json}, {len(a.run_dirs)} --run-dirs")
    trained = set().union(*[set(r["trained_writers"]) for r in rot])
    if trained & set(a.writers):
        raise SystemExit(f"writers {sorted(trained & set(a.writers))} were trained on")
    tests = {w: D.writer_test(w) for w in a.writers}
    est_ship = load(a.baseline)
    ship_r = {w: risks_both(est_ship, tests[w].texts)["steps"] for w in a.writers}
    out = {"writers": a.writers, "top_json": a.top_json, "baseline": a.baseline,
           "baseline_model_id": est_ship.model_id, "rotations": []}
    for r, s, d in zip(rot, ship, a.run_dirs):
        est = load(d)
        rr = {w: risks_both(est, tests[w].texts)["steps"] for w in a.writers}
        # the runtime must reproduce the cached path on the run's held-out writers
        diffs = []
        for w in r["held_out"]:
            got = risks_both(est, D.writer_test(w).texts)["steps"]
            want = np.array(r["steps"]["per_writer"][w]["risks"])
            diffs.append(float(np.abs(got - want).max()))
        if max(diffs) > 1e-3:
            raise SystemExit(f"{d}: the runtime's R_e differs from the cached path by {max(diffs)}")
        tr, ts = r["steps"]["taus"], s["steps"]["taus"]
        out["rotations"].append({
            "rotation": r["rotation"], "model_dir": d, "runtime_vs_cache_max_abs": max(diffs),
            "recipe": {"taus": tr, **block(tests, rr, tr["tau"], tr["tau_confirm"])},
            "shipped": {"taus": ts, **block(tests, ship_r, ts["tau"], ts["tau_confirm"])}})
        print(f"rotation {r['rotation']}: runtime == cache within {max(diffs):.1e}", flush=True)
    summ = {}
    for who in ("recipe", "shipped"):
        bs = [x[who] for x in out["rotations"]]
        summ[who] = {k: mean_sd([b[k] for b in bs]) for k in KEYS}
        summ[who]["per_register_auc"] = {g: mean_sd([b["per_register"][g]["roc_auc"] for b in bs])
                                         for g in bs[0]["per_register"]}
        summ[who]["per_writer_auc"] = {w: mean_sd([b["per_writer"][w]["roc_auc"] for b in bs]) for w in a.writers}
    out["summary"] = summ
    out["seconds"] = round(time.time() - t0, 1)
    out["machine"] = machine_facts(threads=2)
    (results_dir("risk") / f"risk_writers_fresh_{a.tag}.json").write_text(json.dumps(out, indent=1) + "\n")
    f = lambda m: f"{100 * m['mean']:5.1f} ± {100 * (m['sd'] or 0):4.1f}"  # noqa: E731
    print(f"\n{len(a.writers)} writers no run trained on, {len(rot)} rotations (mean ± sd, %; AUC × 100)")
    print(f"{'':10} " + " ".join(f"{k[:14]:>15}" for k in KEYS))
    for who in ("recipe", "shipped"):
        print(f"{who:10} " + " ".join(f"{f(summ[who][k]):>15}" for k in KEYS))
    for g in summ["recipe"]["per_register_auc"]:
        print(f"  AUC {g:<18} recipe {f(summ['recipe']['per_register_auc'][g])}  shipped "
              f"{f(summ['shipped']['per_register_auc'][g])}")
    for w in a.writers:
        print(f"  AUC {w:<18} recipe {f(summ['recipe']['per_writer_auc'][w])}  shipped "
              f"{f(summ['shipped']['per_writer_auc'][w])}")


if __name__ == "__main__":
    main()
