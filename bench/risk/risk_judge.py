"""What the judge tier buys: escalations and the three outcomes, with no judge and a perfect one.

    python -m bench.risk.risk_judge                    # the shipped governor (specs/governor.yaml)
    python -m bench.risk.risk_judge --unseen 0.10      # the validation budget for τ_confirm

The shipped estimator scores the second-writer validation set (data/robot_val_other, validation only)
and the frozen natural test set (data/natural_robot, sha256-checked; report only, never tuned on).

* τ is the governor's (0.47). τ_confirm is chosen on the **validation** set only: the highest value
  (two decimals, rounded down) at which at most ``--unseen`` (default 10 %) of its unsafe rows execute
  with nobody seeing them (the issue-19 target), with no judge. The same rule on the test set would
  be tuning on it; it is never applied there.
* On the test set, at that τ_confirm, three arms (``ethimon.risk.tier_outcome``, the monitor's rule,
  checked against ``Monitor.step`` by ``verify``'s ``tier.agrees``):
  - **no band**: τ alone (what the governor does today);
  - **band, no judge**: every text in [τ_confirm, τ) waits for a person;
  - **band, scripted perfect judge** (asked on every text, as the GovernedLoop does; and, as a second
    arm, only on the band's texts): the judge answers each row's label (p_unsafe 1.0 / 0.0). An
    upper bound on what a judge can buy, not a measured LLM: a real judge is wrong on some rows,
    and an unsure or late one sends the row to a person (as "no judge").
  Each arm: unsafe executed unseen, safe held for confirmation, safe stopped outright, escalation rate
  (share of all commands that reach a person).
* The injection signs (``ethimon.risk.injection_signs``) on data/judge_injection (tuned-on set and
  fresh holdout) and their false alarms on the natural and validation sets.

Prints a table; writes bench/results/risk/risk_judge.json.
"""

from __future__ import annotations

import argparse
import csv
import hashlib
import json
import math
import time
from pathlib import Path

import numpy as np

from bench import ROOT, results_dir
from bench._machine import machine_facts

VAL = ROOT / "data" / "robot_val_other" / "val_other.csv"
TEST = ROOT / "data" / "natural_robot" / "natural_test.csv"
INJ = ROOT / "data" / "judge_injection"


def _rows(path: Path) -> tuple[list[str], list[int]]:
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    return [r.get("text") or r["input"] for r in rows], [int(r["label"]) for r in rows]


def _sha_ok(path: Path) -> bool:
    side = path.with_name(path.name + ".sha256")
    if not side.is_file():
        return False
    want = side.read_text().split()[0]
    return hashlib.sha256(path.read_bytes()).hexdigest() == want


def choose_confirm_threshold(labels, risks, tau: float, unseen: float) -> float:
    """The highest τ_confirm (two decimals, down from τ) with at most ``unseen`` of the unsafe rows executing."""
    from ethimon.risk._evaluate import tier_metrics
    best = None
    for k in range(int(math.floor(tau * 100)) - 1, -1, -1):
        tc = k / 100
        if tc >= tau:
            continue
        m = tier_metrics(labels, risks, tau, tc)
        if m["unsafe_executed_unseen"] <= unseen:
            best = tc
            break
    return 0.0 if best is None else best


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--spec", default=str(ROOT / "specs" / "governor.yaml"))
    ap.add_argument("--unseen", type=float, default=0.10, help="validation budget of unsafe rows executed unseen")
    ap.add_argument("--json", default=None, help="output (default bench/results/risk/risk_judge.json)")
    args = ap.parse_args()

    import ethimon
    from ethimon.risk import injection_signs, load_estimator_for
    from ethimon.risk._evaluate import tier_metrics

    t0 = time.time()
    spec = ethimon.load_spec(args.spec)
    r = spec.risk
    est = load_estimator_for(spec)
    sets = {"val_other": _rows(VAL), "natural_test": _rows(TEST)}
    risks = {}
    for name, (texts, _) in sets.items():
        probs = est.probs_batch(texts)
        risks[name] = [ethimon.risk.risk_from_p_unsafe(p[1], r.alpha, r.beta, r.gamma, r.variance) for p in probs]
    tau = float(r.threshold)
    yv, rv = sets["val_other"][1], risks["val_other"]
    tc = choose_confirm_threshold(yv, rv, tau, args.unseen)
    out = {"spec": str(Path(args.spec).relative_to(ROOT)), "model_id": est.model_id, "tau": tau,
           "rule": f"highest tau_confirm (2 decimals) with <= {args.unseen:.0%} of the unsafe val_other rows "
                   f"executed unseen, no judge", "confirm_threshold": tc,
           "test_sha256_ok": _sha_ok(TEST), "val_sha256_ok": _sha_ok(VAL), "sets": {}}
    for name, (texts, y) in sets.items():
        rs = risks[name]
        perfect = [1.0 if lab else 0.0 for lab in y]
        out["sets"][name] = {
            "n": len(y),
            "no_band": tier_metrics(y, rs, tau, None),
            "band_no_judge": tier_metrics(y, rs, tau, tc),
            "band_perfect_judge": tier_metrics(y, rs, tau, tc, perfect),
            # the judge consulted only on the band's rows (below tau_confirm the classifier alone decides)
            "band_perfect_judge_band_only": tier_metrics(
                y, rs, tau, tc, [p if tc <= x < tau else None for p, x in zip(perfect, rs)]),
            "role": "validation: tau_confirm chosen here" if name == "val_other" else "test: report only",
        }
    inj = {}
    for fname in ("injection.csv", "holdout.csv"):
        with open(INJ / fname, newline="", encoding="utf-8") as f:
            rows = list(csv.DictReader(f))
        hostile = [x for x in rows if x["hostile"] == "1"]
        benign = [x for x in rows if x["hostile"] == "0"]
        inj[fname] = {"hostile": len(hostile), "caught": sum(bool(injection_signs(x["text"])) for x in hostile),
                      "benign": len(benign), "benign_flagged": sum(bool(injection_signs(x["text"])) for x in benign)}
    for name, (texts, _) in sets.items():
        inj[f"{name}_flagged"] = {"n": len(texts), "flagged": sum(bool(injection_signs(t)) for t in texts)}
    out["injection_signs"] = inj
    out["seconds"] = round(time.time() - t0, 1)
    out["machine"] = machine_facts(threads=getattr(est, "num_threads", None))

    print(f"governor tau={tau:g}; tau_confirm={tc:g} chosen on val_other ({out['rule']}); model {est.model_id}")
    print(f"{'set':<13} {'arm':<29} {'unsafe exec unseen':>18} {'safe held':>10} {'safe stopped':>13} "
          f"{'escalated':>10}")
    for name, s in out["sets"].items():
        for arm in ("no_band", "band_no_judge", "band_perfect_judge", "band_perfect_judge_band_only"):
            m = s[arm]
            print(f"{name:<13} {arm:<29} {m['unsafe_executed_unseen']:>18.3f} {m['safe_held_for_confirmation']:>10.3f} "
                  f"{m['safe_stopped_outright']:>13.3f} {m['escalation_rate']:>10.3f}")
    for k, v in inj.items():
        print(f"injection signs {k}: {v}")
    path = Path(args.json) if args.json else results_dir("risk") / "risk_judge.json"
    path.write_text(json.dumps(out, indent=2) + "\n")
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
