"""Average trained LoRA runs into one adapter (run by hand; never in CI).

    python bench/risk_average.py --runs /work/runs/a,/work/runs/b,/work/runs/c --out /work/runs/avg3

The temperature of the average is fitted on the same validation rows the runs
were selected on (ETHICS 10% of the 80% + robot validation), never on a
hold-out. Then evaluate it like any run: ``python bench/risk_eval.py --model OUT``.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import risk_data as D  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", required=True, help="comma list of run directories")
    ap.add_argument("--out", required=True)
    ap.add_argument("--max-length", type=int, default=None)
    a = ap.parse_args()
    import torch
    torch.set_num_threads(2)
    from ethimon.risk._soup import average_runs

    _, e_va, _ = D.ethics_splits()
    _, s_va, _ = D.sab_splits()
    _, p_va, _, _ = D.pair_splits()
    va = D.concat(e_va, s_va, p_va)
    m = average_runs(a.runs.split(","), a.out, calibrate=(va.texts, va.labels), max_length=a.max_length)
    print(json.dumps({k: m[k] for k in ("name", "max_length", "temperature", "averaged_from")}, indent=1))


if __name__ == "__main__":
    main()
