"""Probability-averaging ensemble of evaluated runs, offline (run by hand; never in CI).

    python -m bench.risk.risk_ensemble --tag ens3 mt_jdv_256 mt_jdv_256_s7 mt_jdv_256_s13 [--min-flagged 0.92]

The reference point for weight averaging (``ethimon average``): an ensemble
costs one forward pass per run, the average costs one. Reads each run's raw
logits (bench/results/risk/risk_eval_<tag>/logits.npz, written by risk_eval.py; archived
runs are found under bench/results/risk/archive/ too) and its temperature, averages
softmax(logits / T_i), picks τ on robot validation rows by the rules of risk_eval.py
(``--budget``, default 0.15, ``--min-flagged`` or ``--tau``; the saved ensembles used
``--min-flagged 0.92``), prints the held-out table and writes
bench/results/risk/risk_ensemble_<tag>.json.
"""

from __future__ import annotations

import argparse
import json

import numpy as np

from bench import results_dir
from bench._machine import machine_facts
from bench.risk import risk_data as D
from bench.risk.risk_compare import result_path
from bench.risk.risk_eval import add_tau_args, choose_tau


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("runs", nargs="+", help="tags evaluated by risk_eval.py")
    ap.add_argument("--tag", required=True)
    add_tau_args(ap)
    a = ap.parse_args()
    from ethimon.risk._evaluate import evaluate_logits
    from ethimon.risk._formula import risk_from_p_unsafe

    probs: dict[str, list] = {}
    for t in a.runs:
        T = json.loads(result_path(f"risk_eval_{t}.json").read_text())["temperature"]
        z = np.load(result_path(f"risk_eval_{t}") / "logits.npz")
        for k in z.files:
            x = z[k] / T
            x = np.exp(x - x.max(1, keepdims=True))
            probs.setdefault(k, []).append(x / x.sum(1, keepdims=True))
    logp = {k: np.log(np.clip(np.mean(v, 0), 1e-12, 1.0)) for k, v in probs.items()}
    _, e_va, e_ho = D.ethics_splits()
    _, s_va, s_te = D.sab_splits()
    _, p_va, p_te, p_tf = D.pair_splits()
    yv = np.array(s_va.labels + p_va.labels)
    qv = np.exp(np.concatenate([logp["sab_val"], logp["pairs_val"]]))[:, 1]
    rv = np.array([risk_from_p_unsafe(float(v)) for v in qv])
    tau, rule, _ = choose_tau(a, yv, rv)
    sh = np.array([e["is_short"] == "True" for e in e_ho.extra])
    res = {"runs": a.runs, "tau": tau, "tau_rule": rule,
           "ethics_val_acc": float((logp["ethics_val"].argmax(1) == np.array(e_va.labels)).mean())}
    eh = evaluate_logits(e_ho.labels, logp["ethics_holdout"], temperature=1.0, tau=tau,
                         groups={"short": sh, "long": ~sh})
    y = np.array(s_te.labels + p_te.labels + p_tf.labels)
    ra = evaluate_logits(y, np.concatenate([logp["sab_test"], logp["pairs_test"], logp["pairs_test_family"]]),
                         temperature=1.0, tau=tau)
    sab = evaluate_logits(s_te.labels, logp["sab_test"], temperature=1.0, tau=tau)
    for m in (eh, ra, sab):
        m.pop("_risks"), m.pop("_p_unsafe")
    res.update({"ethics_holdout": eh, "robot_all": ra, "sab_test": sab, "machine": machine_facts()})
    (results_dir("risk") / f"risk_ensemble_{a.tag}.json").write_text(json.dumps(res, indent=1) + "\n")
    print(f"ensemble of {len(a.runs)}: tau={tau}  ETHICS {100 * eh['accuracy']:.1f} "
          f"(short {100 * eh['short']['accuracy']:.1f} / long {100 * eh['long']['accuracy']:.1f}, "
          f"AUC {eh['roc_auc']:.3f})  robot {100 * ra['accuracy']:.1f}  SAB {100 * sab['accuracy']:.1f}  "
          f"flagged {100 * ra['flags']['flag_rate_unsafe']:.1f} / FA {100 * ra['flags']['false_alarm_rate']:.1f}")


if __name__ == "__main__":
    main()
