"""``ethimon simulate SCENARIO... [--gui] [--record DIR]``: run scenarios' ``sim:`` blocks.

Thin: parses, calls :func:`ethimon.sim.run_sim` and
:func:`ethimon.sim.check_sim_expectations`, prints one row per scenario.
Exit codes: 0 every run met its ``sim.expect``, 1 one did not, 2 bad input
(one-line message, no traceback).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time

from ..errors import DependencyNotInstalled, EthimonError, SpecError

__all__ = ["add_sim_parsers", "cmd_simulate"]


def add_sim_parsers(subparsers) -> None:
    """Add the ``simulate`` sub-command."""
    p = subparsers.add_parser(
        "simulate", help="run scenarios' sim: blocks in PyBullet with the monitor in the loop",
        description="Run each scenario's 'sim:' block (Franka Panda, 240 Hz) with the monitor "
                    "in the loop; exit 0 all sim expectations met, 1 one failed, 2 bad input.")
    p.add_argument("paths", nargs="+", metavar="SCENARIO", help="scenario files or folders")
    p.add_argument("--gui", action="store_true", help="show the PyBullet GUI, in real time (needs a display)")
    p.add_argument("--record", metavar="DIR",
                   help="write PNG frames (start, override, safe pose, end), trace.jsonl/.csv, "
                        "summary.json and plot.png to DIR/<scenario name>/")
    p.add_argument("--model", metavar="DIR", help="risk model directory (default: the spec's "
                   "risk.estimator.model, else the shipped model)")
    p.add_argument("--json", metavar="FILE", help="write the results as JSON ('-' for stdout)")
    p.set_defaults(handler=cmd_simulate)


def _err(msg: str) -> int:
    print(f"ethimon: error: {msg}", file=sys.stderr)
    return 2


def _has_display() -> bool:
    if sys.platform != "linux":
        return True
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def _risk_kwargs(sc, spec, model_dir: str | None) -> dict:
    """The constant risk input of a sim run: the scenario's own, else the task text's."""
    from ..scenario._run import needs_text_risk

    if not needs_text_risk(sc):
        for key in ("risk", "p_unsafe", "p"):
            if key in sc.inputs:
                return {key: sc.inputs[key]}
        for entry in sc.timeline:  # risk given only in the timeline: use its first value
            for key in ("risk", "p_unsafe", "p"):
                if key in entry.set:
                    return {key: entry.set[key]}
        return {}
    if not sc.task:
        raise SpecError("the scenario gives no risk input and no task text to score",
                        path=sc.path, hint="add 'inputs: {p_unsafe: ...}' or 'task: ...'")
    from ..risk import load_estimator_for

    return {"probs": tuple(load_estimator_for(spec, model_dir=model_dir).probs(sc.task))}


def _fmt(v, unit: str = "", nd: int = 2) -> str:
    if v is None or v == float("inf"):
        return "-"
    return f"{v:.{nd}f}{unit}"


def cmd_simulate(args: argparse.Namespace) -> int:
    """Handler of ``ethimon simulate``."""
    if args.gui and not _has_display():
        return _err("--gui needs a display (DISPLAY is not set); use --record DIR for frames instead")
    try:
        from .. import Monitor, load_spec
        from ..scenario import check_input_names, load_scenario
        from ..scenario._run import scan_yaml_files
        from ..sim import SimBlock, check_sim_expectations, run_sim
    except ImportError as exc:  # pragma: no cover - packaging problem
        return _err(f"cannot load the simulator: {exc}")
    try:
        scanned = scan_yaml_files(args.paths, what="scenario", command="ethimon simulate")
    except (SpecError, EthimonError) as exc:
        return _err(str(exc))
    for path, reason in scanned:
        if reason is not None:  # a FIFO, socket or device in a folder: never opened
            print(f"{path}: skipped: {reason}", file=sys.stderr)
    files = [path for path, reason in scanned if reason is None]
    if not files:
        return _err(f"no scenario files under {' '.join(args.paths)}")
    rows, results = [], []
    failed = bad = False
    specs: dict[str, object] = {}
    t0 = time.perf_counter()
    for path in files:
        try:
            sc = load_scenario(path)
            if sc.sim is None:
                if len(files) == 1:
                    return _err(f"{path}: the scenario has no 'sim:' block")
                continue
            spec = specs.get(sc.spec_path)
            if spec is None:
                spec = specs[sc.spec_path] = load_spec(sc.spec_path)  # regular files only: never blocks
            check_input_names(sc, spec)
            block = SimBlock.model_validate(sc.sim)  # already validated with positions by the loader
            rec = os.path.join(args.record, sc.name) if args.record else None
            res = run_sim(block, Monitor(spec), record_dir=rec, gui=args.gui,
                          **_risk_kwargs(sc, spec, args.model))
        except SpecError as exc:
            print(str(exc), file=sys.stderr)
            bad = True
            continue
        except DependencyNotInstalled as exc:
            return _err(str(exc))
        except (EthimonError, OSError) as exc:
            print(f"{path}: {exc}", file=sys.stderr)
            bad = True
            continue
        except Exception as exc:  # noqa: BLE001 - one unusable file is one line; the others still run
            from ._check import internal_error
            print(internal_error(path, exc), file=sys.stderr)
            bad = True
            continue
        problems = check_sim_expectations(block, res)
        failed = failed or bool(problems)
        for pr in problems:
            print(f"{path}: {sc.name}: {pr}", file=sys.stderr)
        rows.append((sc.name, "-" if res.first_override_cycle is None else str(res.first_override_cycle),
                     "-" if res.override_reaction_cycles is None else str(res.override_reaction_cycles),
                     res.executed_response, _fmt(res.time_to_safe_pose_s, " s"),
                     _fmt(res.max_joint_speed_safe_pose_rad_s, "", 3), _fmt(res.min_separation_m, " m"),
                     "yes" if res.task_completed else "no", f"{res.realtime_factor:.0f}x",
                     "FAIL" if problems else "PASS"))
        results.append({"name": sc.name, "path": path, "passed": not problems, "problems": problems,
                        **res.summary()})
        if rec:
            print(f"{sc.name}: recorded {len(res.files)} files in {rec}")
    head = ("scenario", "override@", "react", "response", "to safe pose", "max qd", "min sep",
            "task done", "speed", "result")
    if rows:
        widths = [max(len(str(r[i])) for r in (head, *rows)) for i in range(len(head))]
        for r in (head, tuple("-" * w for w in widths), *rows):
            print("  ".join(str(c).ljust(w) for c, w in zip(r, widths)).rstrip())
    n_pass = sum(r[-1] == "PASS" for r in rows)
    print(f"{n_pass} passed, {len(rows) - n_pass} failed in {time.perf_counter() - t0:.2f}s")
    if args.json:
        doc = json.dumps({"results": results}, indent=2, default=str)
        if args.json == "-":
            print(doc)
        else:
            from ._check import write_report
            try:
                write_report(args.json, doc + "\n", "JSON report")
            except SpecError as exc:
                print(str(exc), file=sys.stderr)
                bad = True
    return 2 if bad else (1 if failed else 0)
