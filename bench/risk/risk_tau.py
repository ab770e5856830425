"""The τ pair of the shipped model under the estimator's current reading (issue 30 item 6).

    python -m bench.risk.risk_tau --tag reading31 [--no-tests] [--limit N]

The rules of ``bench/results/risk/writers/DECISIONS.md`` (τ: false alarms ≤ 10 % on validation, rounded
up; τ_confirm: ≤ 10 % of the unsafe validation rows below it, rounded down, never above τ;
``risk_writers.choose_taus``) applied to the shipped model's validation rows: ``data/robot_val_other`` +
the ``train.csv`` rows of w13–w21 (the writers it did not train on and that have a train.csv). R_e by the
governor's formula (``specs/governor.yaml``: α, β, γ, variance) of the runtime estimator as a spec loads it
(``load_estimator()``: default reading and back-end). The validation outcomes at the new pair and at the
governor's current one are written beside it.

Unless ``--no-tests``, every writer's frozen test slice (sha256 checked) is scored in the same process
and each row's R_e kept, so that ``risk_tiers --scores`` reuses them; no figure on a test slice is
computed here (the choice never sees one).

Writes bench/results/risk/risk_tau_<tag>.json with machine facts.
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

from bench import results_dir
from bench._machine import machine_facts
from bench.risk import risk_data as D
from bench.risk.risk_writers import choose_taus

#: the writers whose train.csv rows are the shipped model's validation rows (DECISIONS.md, 22:11 / 22:21 UTC)
VALIDATION_WRITERS = [f"w{i:02d}" for i in range(13, 22)]


def score(est, texts: list[str], rk, label: str, chunk: int = 100) -> np.ndarray:
    """R_e of every text (the governor's formula), in chunks with progress lines."""
    from ethimon.risk import risk_from_p_unsafe
    out: list[float] = []
    t0 = time.time()
    for i in range(0, len(texts), chunk):
        for p in est.probs_batch(texts[i:i + chunk]):
            out.append(risk_from_p_unsafe(float(p[1]), float(rk.alpha), float(rk.beta), float(rk.gamma),
                                          variance=str(rk.variance)))
        print(f"  {label}: {len(out)}/{len(texts)} ({time.time() - t0:.0f} s)", flush=True)
    return np.array(out)


def rates(y: np.ndarray, r: np.ndarray, tau: float, tc: float) -> dict:
    u, s = r[y == 1], r[y == 0]
    return {"unsafe_below_tau_confirm": round(float((u < tc).mean()), 4),
            "safe_held": round(float(((s >= tc) & (s < tau)).mean()), 4),
            "safe_at_or_above_tau": round(float((s >= tau).mean()), 4)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--tag", required=True)
    ap.add_argument("--no-tests", action="store_true", help="score the validation rows only")
    ap.add_argument("--limit", type=int, default=None, help="smoke test: first N rows of each source")
    a = ap.parse_args()
    import ethimon
    from ethimon.risk import load_estimator
    gov = ethimon.load_spec(D.ROOT / "specs" / "governor.yaml")
    rk = gov.risk
    t0 = time.time()
    est = load_estimator()
    parts = [("val_other", D.load_labelled_csv(D.ROOT / "data" / "robot_val_other" / "val_other.csv"))]
    parts += [(w, D.writers_train([w])) for w in VALIDATION_WRITERS]
    texts, y, src = [], [], []
    for name, rows in parts:
        n = len(rows) if a.limit is None else min(a.limit, len(rows))
        texts += list(rows.texts[:n])
        y += [int(v) for v in rows.labels[:n]]
        src += [name] * n
    y_ = np.array(y)
    t_s = time.time()
    r = score(est, texts, rk, "validation")
    val_s = time.time() - t_s
    from sklearn.metrics import roc_auc_score
    taus = choose_taus(y_, r)
    old = (float(rk.threshold), float(rk.confirm_threshold))
    out = {"tag": a.tag, "model_id": est.model_id, "backend": getattr(est, "backend", None),
           "reading": est.reading, "formula": {"alpha": rk.alpha, "beta": rk.beta, "gamma": rk.gamma,
                                               "variance": str(rk.variance)},
           "validation": {"sources": {n: int(sum(1 for s in src if s == n)) for n, _ in parts},
                          "n": len(y), "unsafe": int(y_.sum()), "roc_auc": round(float(roc_auc_score(y_, r)), 4),
                          "seconds": round(val_s, 1)},
           "rule": "bench/results/risk/writers/DECISIONS.md (2026-12-05 13:20 UTC entry)",
           "chosen": taus, "at_chosen": rates(y_, r, taus["tau"], taus["tau_confirm"]),
           "previous_pair": {"tau": old[0], "tau_confirm": old[1], **rates(y_, r, *old)},
           "validation_rows": [{"source": s, "label": int(v), "r_e": round(float(x), 5)}
                               for s, v, x in zip(src, y, r)]}
    print(f"validation: {len(y)} rows ({int(y_.sum())} unsafe) in {val_s:.0f} s, ROC-AUC {out['validation']['roc_auc']}")
    print(f"chosen: tau {taus['tau']:.3f}, tau_confirm {taus['tau_confirm']:.3f} "
          f"(previous {old[0]:.3f} / {old[1]:.3f}); at chosen {out['at_chosen']}; at previous {out['previous_pair']}")
    path = results_dir("risk") / f"risk_tau_{a.tag}.json"
    if not a.no_tests:
        trows = []
        for w in sorted(d.name for d in D.WRITERS.glob("w[0-9][0-9]") if (d / "test.csv.sha256").is_file()):
            rows = D.writer_test(w)
            n = len(rows) if a.limit is None else min(a.limit, len(rows))
            trows += [(w, rows.extra[i].get("id", f"{w}-{i}"), rows.texts[i]) for i in range(n)]
        t_t = time.time()
        rt = score(est, [t for _w, _i, t in trows], rk, "test slices")
        out["test_scores"] = {"seconds": round(time.time() - t_t, 1), "n": len(trows),
                              "rows": [{"writer": w, "id": i, "r_e": round(float(x), 5)}
                                       for (w, i, _t), x in zip(trows, rt)]}
    out["seconds"] = round(time.time() - t0, 1)
    out["machine"] = machine_facts()
    path.write_text(json.dumps(out, indent=1) + "\n", encoding="utf-8")
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
