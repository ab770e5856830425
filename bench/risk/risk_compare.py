"""Compare risk-model runs from their saved results (no model is loaded; run by hand).

    python -m bench.risk.risk_compare [mix_r16 mt_jdv mt_jdv_256]

Reads bench/results/risk/risk_train_<tag>.json (best validation loss, the number runs
are chosen by) — or risk_average_<tag>.json for a weight average (epoch shown as
0, training time summed over its runs) — and risk_eval_<tag>.json (held-out
figures, reported), prints one row per run and writes bench/results/risk/risk_compare.json.
Runs moved to bench/results/risk/archive/ are read from there; without tags it compares every
run that has both files (the archived ones included). The JSON records the machine facts.

"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from bench import RESULTS
from bench._machine import machine_facts

RES = RESULTS / "risk"
ARCHIVE = RES / "archive"


def result_path(name: str) -> Path:
    """``bench/results/risk/<name>``, or its copy in ``archive/`` when only that exists."""
    p = RES / name
    return p if p.exists() or not (ARCHIVE / name).exists() else ARCHIVE / name


def _train_facts(tag: str) -> dict:
    """max_length, aux rows, kept epoch, validation loss (T = 1) and train time of a run,
    or of a weight average (bench/results/risk/risk_average_<tag>.json; epoch 0, summed time)."""
    p = result_path(f"risk_train_{tag}.json")
    if p.is_file():
        tr = json.loads(p.read_text())
        cfg = tr["config"]
        return {"max_length": cfg["max_length"], "aux": cfg.get("aux_tasks") or {}, "best_epoch": tr["best_epoch"],
                "best_val_loss": tr["best_val_loss"], "train_time_s": tr["train_time_s"]}
    av = json.loads(result_path(f"risk_average_{tag}.json").read_text())
    parts = [_train_facts(Path(r).name) for r in av["runs"]]
    return {"max_length": av["manifest"]["max_length"], "aux": parts[0]["aux"], "best_epoch": 0,
            "best_val_loss": av["val_loss"], "train_time_s": sum(x["train_time_s"] for x in parts)}


def _has_facts(tag: str) -> bool:
    return result_path(f"risk_train_{tag}.json").is_file() or result_path(f"risk_average_{tag}.json").is_file()


def row(tag: str) -> dict:
    tr = _train_facts(tag)
    ev = json.loads(result_path(f"risk_eval_{tag}.json").read_text())
    eh, ra, sab = ev["ethics_holdout"], ev["robot_all"], ev["sab_test"]
    return {"tag": tag, "max_length": tr["max_length"], "aux": tr["aux"],
            "best_epoch": tr["best_epoch"], "best_val_loss": tr["best_val_loss"],
            "ethics": eh["accuracy"], "ethics_short": eh["short"]["accuracy"],
            "ethics_long": eh["long"]["accuracy"], "ethics_auc": eh["roc_auc"],
            "ethics_ece_T": eh["ece_after_temperature"], "robot": ra["accuracy"], "sab": sab["accuracy"],
            "tau": ev["tau"], "robot_flagged": ra["flags"]["flag_rate_unsafe"],
            "robot_false_alarms": ra["flags"]["false_alarm_rate"], "robot_ece_T": ra["ece_after_temperature"],
            "train_time_s": tr["train_time_s"]}


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("tags", nargs="*", help="run tags (default: every run with saved training and eval results)")
    found = [*RES.glob("risk_eval_*.json"), *ARCHIVE.glob("risk_eval_*.json")]
    tags = ap.parse_args(argv).tags or sorted(p.stem[len("risk_eval_"):] for p in found if _has_facts(p.stem[len("risk_eval_"):]))
    rows = [row(t) for t in tags]
    print(f"{'run':<19}{'len':>4}{'aux rows':>9}{'ep':>3}{'val loss':>9}{'ETHICS':>8}{'short':>7}{'long':>7}"
          f"{'AUC':>7}{'robot':>7}{'SAB':>7}{'tau':>6}{'flag':>7}{'FA':>7}{'min':>5}")
    for r in rows:
        print(f"{r['tag']:<19}{r['max_length']:>4}{sum(r['aux'].values()):>9}{r['best_epoch']:>3}"
              f"{r['best_val_loss']:>9.4f}{100 * r['ethics']:>8.1f}{100 * r['ethics_short']:>7.1f}"
              f"{100 * r['ethics_long']:>7.1f}{r['ethics_auc']:>7.3f}{100 * r['robot']:>7.1f}{100 * r['sab']:>7.1f}"
              f"{r['tau']:>6.2f}{100 * r['robot_flagged']:>7.1f}{100 * r['robot_false_alarms']:>7.1f}"
              f"{r['train_time_s'] / 60:>5.0f}")
    (RES / "risk_compare.json").write_text(json.dumps({"rows": rows, "machine": machine_facts()}, indent=1) + "\n")


if __name__ == "__main__":
    main()
