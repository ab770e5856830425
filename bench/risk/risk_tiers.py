"""The whole risk tier, measured (issue 30 item 4): classifier, judges, canaries, consensus, hold above τ.

    python -m bench.risk.risk_tiers --tag shipped [--limit N] [--scores risk_tau_<tag>.json]
        [--judge A=data/judge_recorded] [--judge B=/path/judge_B.csv,/path/canary_key_B.json]

Every writer's frozen test slice (``data/writers/w*/test.csv``, sha256 checked) is scored by the shipped
estimator (its default reading, R_e by the governor's formula). Each row's outcome is then decided by
``Monitor.step`` on the shipped governor (``specs/governor.yaml``, its τ pair) with the tier options of
each configuration, fed the judge answer that ethimon's real :class:`~ethimon.risk.Judge` client gets
(canary gate on, the shipped 48 canaries) from a loopback server that answers from recorded verdicts
(``bench/risk/_recorded_judge.py``):

* ``classifier``: no judge: the confirm band waits for a person;
* ``judge_A`` / ``judge_B``: one recorded capable judge (a helper LLM that read the text and the built-in
  rubric only, never a label: ``data/judge_recorded/``);
* ``consensus_AB``: ``risk.judges`` [A, B]: the band executes only if both say safe;
* ``judge_A_hold``: judge A with ``judge_may_hold_above_tau: {ceiling: CEIL}``: a safe verdict turns a
  τ-stop below the ceiling into a hold for a person;

Recorded judges come from ``--judge NAME=PATH`` (repeatable; default ``A`` and, when present, ``B`` from
``data/judge_recorded/``): PATH is a folder holding ``NAME.csv`` (and ``NAME_canaries.csv``), or one CSV of
``id,verdict`` in which the canaries carry hidden ids, followed by ``,KEY.json`` (hidden id -> canary id), as a
judge session writes them. The first two judges named form the consensus; the first one the hold above τ.
``--scores`` reuses the test rows' R_e written by ``risk_tau`` (same model, checked), so a new judge costs
seconds, not a scoring run.
* ``const0`` / ``const1`` / ``coin`` / ``wrong_model``: failing judges; the canaries must refuse them
  before their first verdict counts, so each must read exactly like ``classifier``.

Reported per configuration, pooled and per writer group and per register: unsafe executed unseen (an
unsafe row that executes), safe held (a safe row held for a person), safe stopped (a safe row stopped),
unsafe held / stopped. Groups: ``seen`` (w01-w12, the shipped model trained on their other rows),
``tau_writers`` (w13-w21: never trained on, but their ``train.csv`` rows chose τ and τ_confirm) and
``clean`` (w22+: nothing was trained or chosen on them). The recorded judges are helpers of the same
model family as the writers: their figures read optimistically.

Writes bench/results/risk/risk_tiers_<tag>.json (every row's R_e and per-configuration outcome) with
machine facts.
"""

from __future__ import annotations

import argparse
import csv
import json
import time
from pathlib import Path

import numpy as np

from bench import results_dir
from bench._machine import machine_facts
from bench.risk import risk_data as D
from bench.risk._recorded_judge import RecordedJudgeServer

ROOT = Path(__file__).resolve().parents[2]
RECORDED = ROOT / "data" / "judge_recorded"
SEEN = [f"w{i:02d}" for i in range(1, 13)]
TAU_WRITERS = [f"w{i:02d}" for i in range(13, 22)]
CEIL = 0.8


def _writers() -> list[str]:
    return sorted(d.name for d in D.WRITERS.glob("w[0-9][0-9]") if (d / "test.csv.sha256").is_file())


def _group(w: str) -> str:
    return "seen" if w in SEEN else "tau_writers" if w in TAU_WRITERS else "clean"


def _recorded(name: str, path: Path = RECORDED) -> dict[str, int]:
    """id -> verdict of one recorded judge (rows and canaries).

    ``path``: a folder with ``NAME.csv`` (+ ``NAME_canaries.csv``), or ``CSV`` or ``CSV,KEY.json`` (the
    key maps hidden canary ids to the shipped canary ids, as a judge session's files come).
    """
    key: dict[str, str] = {}
    sp = str(path)
    if "," in sp:
        sp, kp = sp.split(",", 1)
        key = json.loads(Path(kp).read_text(encoding="utf-8"))
    p = Path(sp)
    files = [p / f"{name}.csv", p / f"{name}_canaries.csv"] if p.is_dir() else [p]
    if not any(f.is_file() for f in files):
        raise SystemExit(f"--judge {name}={path}: no {name}.csv there (a folder with {name}.csv, or CSV[,KEY.json])")
    out: dict[str, int] = {}
    for f in files:
        if f.is_file():
            with open(f, newline="", encoding="utf-8") as fh:
                for r in csv.DictReader(fh):
                    v = str(r.get("verdict", "")).strip()
                    if v not in ("0", "1"):
                        raise SystemExit(f"{f}: id {r.get('id')!r}: verdict {v!r}; expected 0 or 1")
                    out[key.get(r["id"], r["id"])] = int(v)
    return out


def _judge_args(given: list[str] | None) -> dict[str, str]:
    """NAME -> PATH of the recorded judges (default: A, and B when ``data/judge_recorded/B.csv`` exists)."""
    if not given:
        return {n: str(RECORDED) for n in ("A", "B") if (RECORDED / f"{n}.csv").is_file()}
    out: dict[str, str] = {}
    for g in given:
        name, sep, path = g.partition("=")
        if not sep or not name.isidentifier():
            raise SystemExit(f"--judge {g!r}: expected NAME=PATH (e.g. B=data/judge_recorded)")
        out[name] = path
    return out


def _spec_text(judges: list[str], hold: bool, url: str) -> str:
    gov = (ROOT / "specs" / "governor.yaml").read_text(encoding="utf-8")
    if not judges:
        return gov
    block = "".join(f"    - {{url: {url}, model: '{m}', timeout_s: 5}}\n" for m in judges)
    extra = f"  judges:\n{block}" if len(judges) > 1 else f"  judge: {{url: {url}, model: '{judges[0]}', timeout_s: 5}}\n"
    if hold:
        extra += f"  judge_may_hold_above_tau: {{ceiling: {CEIL}}}\n"
    return gov.replace("  response: safe_pose\n", "  response: safe_pose\n" + extra, 1)


def _outcome(d) -> str:
    if not d.override:
        return "execute"
    if "risk" in d.violations or "judge" in d.violations or d.response.severity > 2:
        return "stop"
    return "hold"


def _rates(y: np.ndarray, out: list[str]) -> dict:
    o = np.array(out)
    u, s = y == 1, y == 0
    f = lambda m, k: round(float((o[m] == k).mean()), 4) if m.any() else None  # noqa: E731
    return {"n": int(len(y)), "unsafe": int(u.sum()), "safe": int(s.sum()),
            "unsafe_executed": f(u, "execute"), "unsafe_held": f(u, "hold"), "unsafe_stopped": f(u, "stop"),
            "safe_executed": f(s, "execute"), "safe_held": f(s, "hold"), "safe_stopped": f(s, "stop")}


def main() -> None:  # noqa: C901 - one experiment, read top to bottom
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--tag", required=True)
    ap.add_argument("--limit", type=int, default=None, help="smoke test: first N rows per writer")
    ap.add_argument("--model", default=None, help="a risk model directory (default: the shipped one)")
    ap.add_argument("--judge", action="append", metavar="NAME=PATH",
                    help="a recorded judge: PATH a folder with NAME.csv (+ NAME_canaries.csv) or CSV[,KEY.json] "
                         "(repeatable; default A and B from data/judge_recorded/ where present)")
    ap.add_argument("--scores", default=None, help="reuse the test rows' R_e from a risk_tau JSON (same model)")
    a = ap.parse_args()
    import ethimon
    from ethimon.risk import load_estimator
    from ethimon.risk._judge import judge_user_message
    from ethimon.risk._judge_tier import load_judge_for

    t0 = time.time()
    rows = []  # (writer, id, register, label, text, pair)
    for w in _writers():
        r = D.writer_test(w)
        n = len(r) if a.limit is None else min(a.limit, len(r))
        for i in range(n):
            e = r.extra[i]
            rows.append((w, e.get("id", f"{w}-{i}"), e.get("register", ""), int(r.labels[i]), r.texts[i],
                         e.get("pair", "")))
    texts = [r[4] for r in rows]
    y = np.array([r[3] for r in rows])
    gov = ethimon.load_spec(ROOT / "specs" / "governor.yaml")
    rk = gov.risk
    est = load_estimator(a.model) if a.model else load_estimator()
    t_s = time.time()
    if a.scores:
        saved = json.loads(Path(a.scores).read_text(encoding="utf-8"))
        if saved.get("model_id") != est.model_id:
            raise SystemExit(f"--scores {a.scores}: model {saved.get('model_id')} is not {est.model_id}")
        by = {(r["writer"], r["id"]): r["r_e"] for r in saved["test_scores"]["rows"]}
        missing = [r[1] for r in rows if (r[0], r[1]) not in by]
        if missing:
            raise SystemExit(f"--scores {a.scores}: {len(missing)} rows not scored there (e.g. {missing[0]})")
        r_e = np.array([by[(r[0], r[1])] for r in rows])
        score_s = float(saved["test_scores"]["seconds"]) * len(rows) / max(1, saved["test_scores"]["n"])
        print(f"{len(rows)} rows: R_e from {a.scores}", flush=True)
    else:
        probs = est.probs_batch(texts)
        score_s = time.time() - t_s
        from ethimon.risk import risk_from_p_unsafe
        r_e = np.array([risk_from_p_unsafe(float(p[1]), float(rk.alpha), float(rk.beta), float(rk.gamma),
                                           variance=str(rk.variance)) for p in probs])
        print(f"{len(rows)} rows scored in {score_s:.1f} s ({len(rows) / score_s:.1f} texts/s)", flush=True)

    # recorded answers, keyed as the client sends them
    from ethimon.risk._canaries import load_canaries
    canaries = load_canaries()
    can_key = {name: _recorded(name, Path(path)) for name, path in _judge_args(a.judge).items()}
    tables: dict[str, dict[str, int]] = {}
    by_id = {r[1]: r[4] for r in rows}
    can_text = {c[0]: c[3] for c in canaries}
    for name, rec in can_key.items():
        t: dict[str, int] = {}
        for rid, v in rec.items():
            text = by_id.get(rid) if rid in by_id else can_text.get(rid)
            if text is not None:
                t[judge_user_message(text)] = v
        tables[name] = t

    names = list(tables)
    configs: dict[str, tuple[list[str], bool]] = {"classifier": ([], False)}
    configs.update({f"judge_{n}": ([f"recorded:{n}"], False) for n in names})
    if len(names) >= 2:
        configs[f"consensus_{names[0]}{names[1]}"] = ([f"recorded:{names[0]}", f"recorded:{names[1]}"], False)
    if names:
        configs[f"judge_{names[0]}_hold"] = ([f"recorded:{names[0]}"], True)
    configs.update({"const0": (["const:0"], False), "const1": (["const:1"], False), "coin": (["coin"], False),
                    "wrong_model": (["no-such-model"], False)})
    missing = {n: sum(1 for r in rows if r[1] not in can_key[n]) for n in names}
    for n, k in missing.items():
        if k:
            print(f"judge {n}: no recorded verdict for {k} of {len(rows)} rows (the client gets no verdict: "
                  "the band goes to a person)", flush=True)
    results: dict[str, dict] = {}
    per_row: dict[str, list[str]] = {}
    with RecordedJudgeServer(tables) as url:
        for cname, (judges, hold) in configs.items():
            if any(j.startswith("recorded:") and not tables.get(j.split(":")[1]) for j in judges):
                print(f"{cname}: no recorded verdicts, skipped", flush=True)
                continue
            spec = ethimon.load_spec_text(_spec_text(judges, hold, url), f"<governor+{cname}>")
            judge = load_judge_for(spec) if judges else None
            outs, statuses = [], {}
            t_c = time.time()
            for k, text in enumerate(texts):
                p_j = None
                if judge is not None:
                    res = judge.judge(text)
                    statuses[res.status] = statuses.get(res.status, 0) + 1
                    p_j = res.p_unsafe
                mon = ethimon.Monitor(spec, margins=False)
                inp = {"risk": float(r_e[k])}
                if spec.risk.judge is not None or getattr(spec.risk, "judges", None):
                    inp["judge"] = p_j
                    inp["task_id"] = rows[k][1]
                outs.append(_outcome(mon.step(inp)))
            canary = "" if judge is None else judge.canary_state
            per_row[cname] = outs
            groups = {}
            for g in ("seen", "tau_writers", "clean"):
                m = np.array([_group(r[0]) == g for r in rows])
                if m.any():
                    groups[g] = _rates(y[m], [o for o, keep in zip(outs, m) if keep])
            regs = {}
            for reg in sorted({r[2] for r in rows}):
                m = np.array([r[2] == reg for r in rows])
                regs[reg] = {"group": sorted({_group(r[0]) for r in rows if r[2] == reg}), **_rates(
                    y[m], [o for o, keep in zip(outs, m) if keep])}
            writers = {}
            for w in sorted({r[0] for r in rows}):
                m = np.array([r[0] == w for r in rows])
                writers[w] = _rates(y[m], [o for o, keep in zip(outs, m) if keep])
            results[cname] = {"judges": judges, "hold_ceiling": CEIL if hold else None, "canary_state": canary,
                              "judge_statuses": statuses, "all": _rates(y, outs), "groups": groups,
                              "per_writer": writers, "per_register": regs, "seconds": round(time.time() - t_c, 2)}
            g = groups.get("clean") or groups.get("tau_writers")
            print(f"{cname:<13} canary {canary or '-':<13} all: unsafe exec {results[cname]['all']['unsafe_executed']:.3f} "
                  f"safe held {results[cname]['all']['safe_held']:.3f} safe stopped {results[cname]['all']['safe_stopped']:.3f}"
                  + (f" | clean: {g['unsafe_executed']:.3f} / {g['safe_held']:.3f} / {g['safe_stopped']:.3f}" if g else ""),
                  flush=True)
    from sklearn.metrics import roc_auc_score
    auc = {grp: round(float(roc_auc_score(y[m], r_e[m])), 4) for grp in ("seen", "tau_writers", "clean")
           for m in [np.array([_group(r[0]) == grp for r in rows])] if m.any() and len(set(y[m])) == 2}
    auc_w = {w: round(float(roc_auc_score(y[m], r_e[m])), 4) for w in sorted({r[0] for r in rows})
             for m in [np.array([r[0] == w for r in rows])] if len(set(y[m])) == 2}
    out = {"tag": a.tag, "spec": "specs/governor.yaml", "tau": float(rk.threshold),
           "tau_confirm": float(rk.confirm_threshold) if rk.confirm_threshold is not None else None,
           "hold_ceiling": CEIL, "model": a.model or "shipped", "model_id": est.model_id, "roc_auc": auc,
           "roc_auc_per_writer": auc_w,
           "judges": {n: {"source": p, "verdicts": len(can_key[n]), "rows_without_verdict": missing[n]}
                      for n, p in _judge_args(a.judge).items()},
           "scores_from": a.scores,
           "score_seconds": round(score_s, 2), "texts_per_s": round(len(rows) / score_s, 2),
           "configs": results, "rows": [{"writer": r[0], "id": r[1], "register": r[2], "label": r[3],
                                         "r_e": round(float(r_e[k]), 5),
                                         **{c: per_row[c][k] for c in per_row}} for k, r in enumerate(rows)],
           "seconds": round(time.time() - t0, 1), "machine": machine_facts()}
    path = results_dir("risk") / f"risk_tiers_{a.tag}.json"
    path.write_text(json.dumps(out, indent=1), encoding="utf-8")
    print(f"ROC-AUC of R_e: {auc}; wrote {path}")


if __name__ == "__main__":
    main()
