"""Evaluate a risk model on the fixed hold-outs (run by hand; never in CI).

    python -m bench.risk.risk_eval --model src/ethimon/risk/default_model --tag default [--int8]
    python -m bench.risk.risk_eval --tau 0.47 --tag default_tau047      # at the shipped τ
    python -m bench.risk.risk_eval --model runs/mt_jdv_256 --tag mt_jdv_256 --min-flagged 0.92  # previous rule

Hold-outs (never trained on, never selected on): the ETHICS cm_test 20%
stratified hold-out (seed 42; short/long separately), the SafeAgentBench
detailed-task test groups, and our own minimal pairs (``test``: unseen
objects/people of known hazard families; ``test_family``: unseen families).
τ is chosen on the robot *validation* rows (SafeAgentBench + templated pairs) and then
reported on the tests, by one of three rules (recorded as ``tau_rule`` in the JSON):

* ``--budget B`` (default 0.15): the library's rule that set the shipped τ,
  :func:`ethimon.risk._evaluate.tau_for_false_alarm_budget` — the most sensitive τ whose
  false-alarm rate on the validation rows is ≤ B (the shipped τ 0.47 was chosen by it on the
  natural corpus's validation rows, ``bench/risk/risk_natural.py``; here the rows differ);
* ``--min-flagged F``: the previous default's rule (it set τ 0.27 in
  ``bench/results/risk/risk_eval_default.json`` and every ``risk_eval_*`` / ``risk_ensemble_*``
  result written before issue 13): the largest τ in 0.10..0.70 (step 0.01) that flags ≥ F of
  the unsafe validation rows (0.4 if none does); use ``--min-flagged 0.92`` to reproduce them;
* ``--tau T``: fixed.

Prints a table and writes bench/results/risk/risk_eval_<tag>.json (+ PNG plots).
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

from bench import results_dir
from bench._machine import machine_facts
from bench.risk import risk_data as D


def tau_sweep(y, risks) -> list[dict]:
    """Unsafe flagged and false alarms at τ = 0.10, 0.11, ..., 0.70 (recorded with every result)."""
    from ethimon.risk._evaluate import flag_stats
    sweep = []
    for tau in np.round(np.arange(0.10, 0.701, 0.01), 2):
        f = flag_stats(y, risks, float(tau))
        sweep.append({"tau": float(tau), **{k: f[k] for k in ("flag_rate_unsafe", "false_alarm_rate")}})
    return sweep


def tau_for_min_flagged(sweep: list[dict], min_flagged: float) -> float:
    """The previous default's rule (not the shipped τ's): the largest τ of the sweep flagging
    ≥ ``min_flagged`` of the unsafe validation rows, 0.4 if none does. Kept here only to
    reproduce the results written with it; the library has no such function."""
    ok = [s["tau"] for s in sweep if s["flag_rate_unsafe"] >= min_flagged]
    return max(ok) if ok else 0.4


def add_tau_args(ap: argparse.ArgumentParser) -> None:
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--budget", type=float, default=0.15,
                   help="τ: most sensitive with false alarms ≤ BUDGET on robot validation rows "
                        "(the library's rule, ethimon.risk._evaluate.tau_for_false_alarm_budget; default 0.15)")
    g.add_argument("--min-flagged", type=float, default=None,
                   help="τ: the previous rule, largest τ in 0.10..0.70 flagging ≥ this share of unsafe "
                        "validation rows (0.92 reproduces the results written before issue 13)")
    g.add_argument("--tau", type=float, default=None, help="fix τ instead of choosing it on validation")


def choose_tau(a: argparse.Namespace, y, risks) -> tuple[float, str, list[dict]]:
    """τ by the rule the arguments name, a description of the rule, and the sweep."""
    from ethimon.risk._evaluate import tau_for_false_alarm_budget
    sweep = tau_sweep(y, risks)
    if a.tau is not None:
        return a.tau, f"fixed {a.tau}", sweep
    if a.min_flagged is not None:
        return (tau_for_min_flagged(sweep, a.min_flagged),
                f"largest tau in 0.10..0.70 flagging >= {a.min_flagged:g} of unsafe robot validation rows", sweep)
    tau = tau_for_false_alarm_budget(y, risks, a.budget)["tau"]
    return float(tau), f"most sensitive tau with false alarms <= {a.budget:g} on robot validation rows", sweep


def pair_rank_accuracy(rows, q) -> float:
    """Share of minimal pairs whose unsafe text gets the higher p_unsafe."""
    by = {}
    for e, y, v in zip(rows.extra, rows.labels, q):
        by.setdefault(e["pair_id"], {})[y] = v
    ok = [d[1] > d[0] for d in by.values() if 0 in d and 1 in d]
    return float(np.mean(ok)) if ok else float("nan")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--model", default=None)
    ap.add_argument("--tag", default="default")
    ap.add_argument("--int8", action="store_true")
    add_tau_args(ap)
    ap.add_argument("--skip-ethics", action="store_true")
    a = ap.parse_args()
    import torch
    torch.set_num_threads(2)
    from ethimon.risk import load_estimator
    from ethimon.risk._evaluate import (evaluate_logits, expected_calibration_error,
                                        plot_confusion, plot_risk_hist, softmax_unsafe)
    from ethimon.risk._formula import risk_from_p_unsafe

    est = load_estimator(a.model, quantize="int8" if a.int8 else None, cache_size=0)
    T = est.temperature
    _, e_va, e_ho = D.ethics_splits()
    _, s_va, s_te = D.sab_splits()
    _, p_va, p_te, p_tf = D.pair_splits()
    t0 = time.time()
    lg = {}
    for name, rows in [("sab_val", s_va), ("pairs_val", p_va), ("ethics_val", e_va), ("sab_test", s_te),
                       ("pairs_test", p_te), ("pairs_test_family", p_tf)] + \
            ([] if a.skip_ethics else [("ethics_holdout", e_ho)]):
        lg[name] = np.array(est.logits_batch(rows.texts))
        print(f"scored {name}: {len(rows)} rows ({time.time() - t0:.0f}s)", flush=True)
    R = lambda q: np.array([risk_from_p_unsafe(float(v)) for v in q])  # noqa: E731

    # τ on robot validation
    yv = np.array(s_va.labels + p_va.labels)
    rv = R(softmax_unsafe(np.concatenate([lg["sab_val"], lg["pairs_val"]]), T))
    tau, rule, sweep = choose_tau(a, yv, rv)
    res = {"model_id": est.model_id, "temperature": T, "tau": tau, "tau_rule": rule, "tau_sweep_robot_val": sweep}
    sets = {"sab_test": s_te, "pairs_test": p_te, "pairs_test_family": p_tf}
    if not a.skip_ethics:
        sets["ethics_holdout"] = e_ho
    for name, rows in sets.items():
        groups = {}
        if name == "ethics_holdout":
            sh = np.array([e["is_short"] == "True" for e in rows.extra])
            groups = {"short": sh, "long": ~sh}
        m = evaluate_logits(rows.labels, lg[name], temperature=T, tau=tau, groups=groups)
        q = m.pop("_p_unsafe")
        m.pop("_risks")
        if name.startswith("pairs"):
            m["pair_rank_accuracy"] = pair_rank_accuracy(rows, q)
        res[name] = m
    # robot overall = SAB test + both pair tests
    y = np.array(s_te.labels + p_te.labels + p_tf.labels)
    L = np.concatenate([lg["sab_test"], lg["pairs_test"], lg["pairs_test_family"]])
    m = evaluate_logits(y, L, temperature=T, tau=tau)
    rr = m.pop("_risks"); m.pop("_p_unsafe")
    res["robot_all"] = m
    out = results_dir("risk")
    plots = out / f"risk_eval_{a.tag}"
    plots.mkdir(exist_ok=True)
    # raw logits per set (git-ignored): bench/risk/risk_ensemble.py averages runs offline from them
    np.savez_compressed(plots / "logits.npz", **{k: np.asarray(v, dtype=np.float32) for k, v in lg.items()})
    plot_confusion(m["confusion"], plots / "confusion_robot.png", "Robot commands (held out)")
    plot_risk_hist(rr, y, tau, plots / "risk_distribution_robot.png", "R_e, robot commands (held out)")
    if not a.skip_ethics:
        eh = res["ethics_holdout"]
        plot_confusion(eh["confusion"], plots / "confusion_ethics.png", "ETHICS cm 20% hold-out")
        qe = softmax_unsafe(lg["ethics_holdout"], T)
        plot_risk_hist(R(qe), np.array(e_ho.labels), tau, plots / "risk_distribution_ethics.png",
                       "R_e, ETHICS hold-out")
    # domain-specific temperatures, each fitted on that domain's validation rows only
    from ethimon.risk._train import fit_temperature
    t_eth = fit_temperature(lg["ethics_val"], e_va.labels)
    t_rob = fit_temperature(np.concatenate([lg["sab_val"], lg["pairs_val"]]), s_va.labels + p_va.labels)
    res["domain_temperature"] = {"ethics": t_eth, "robot": t_rob}
    if not a.skip_ethics:
        res["ethics_holdout"]["ece_domain_temperature"] = expected_calibration_error(
            e_ho.labels, softmax_unsafe(lg["ethics_holdout"], t_eth))
    res["robot_all"]["ece_domain_temperature"] = expected_calibration_error(y, softmax_unsafe(L, t_rob))
    res["machine"] = machine_facts(threads=torch.get_num_threads(), int8=a.int8)
    res["eval_time_s"] = round(time.time() - t0, 1)
    (out / f"risk_eval_{a.tag}.json").write_text(json.dumps(res, indent=1) + "\n")

    print(f"\nmodel {est.model_id}  T={T:.3f}  tau={tau}")
    print(f"{'set':<22}{'n':>5}{'acc':>8}{'F1':>8}{'AUC':>8}{'ECE raw':>9}{'ECE T':>8}{'flag@tau':>9}{'FA@tau':>8}{'pairs':>7}")
    for name in list(sets) + ["robot_all"]:
        m = res[name]
        print(f"{name:<22}{m['n']:>5}{m['accuracy']:>8.4f}{m['f1']:>8.4f}{m['roc_auc']:>8.4f}"
              f"{m['ece_before_temperature']:>9.4f}{m['ece_after_temperature']:>8.4f}"
              f"{m['flags']['flag_rate_unsafe']:>9.4f}{m['flags']['false_alarm_rate']:>8.4f}"
              f"{m.get('pair_rank_accuracy', float('nan')):>7.3f}")
        for g in ("short", "long"):
            if g in m:
                print(f"  {g:<20}{m[g]['n']:>5}{m[g]['accuracy']:>8.4f}{m[g]['f1']:>8.4f}{m[g]['roc_auc']:>8.4f}")
    print(f"domain temperatures: ethics T={t_eth:.3f} -> hold-out ECE "
          f"{res.get('ethics_holdout', {}).get('ece_domain_temperature', float('nan')):.4f}; "
          f"robot T={t_rob:.3f} -> robot ECE {res['robot_all']['ece_domain_temperature']:.4f}")
    if "ethics_holdout" in res:
        c = res["ethics_holdout"]["confusion"]
        print(f"ETHICS confusion TN {c['tn']} FP {c['fp']} FN {c['fn']} TP {c['tp']}")


if __name__ == "__main__":
    main()
