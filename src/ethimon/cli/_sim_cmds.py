"""``ethimon simulate SCENARIO... [--gui] [--record DIR]``: run scenarios' ``sim:`` blocks.

Thin: parses, calls :func:`ethimon.scenario.simulate_paths`, prints one row per scenario.
Exit codes: 0 every run met its ``sim.expect``, 1 one did not, 2 bad input
(one-line message, no traceback).
"""

from __future__ import annotations

import argparse
import os
import sys

from ._common import Progress, emit_json, err

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
                   help="write PNG frames with an overlay (start, end and every event: violation, "
                        "override, escalation, closest approach, peak force, standstill, safe pose, "
                        "release), trace.jsonl/.csv, summary.json and plot.png to DIR/<scenario name>/")
    p.add_argument("--model", metavar="DIR", help="risk model directory (default: the spec's "
                   "risk.estimator.model, else the shipped model)")
    p.add_argument("--json", metavar="FILE", help="write the results as JSON ('-' for stdout: then stdout "
                   "holds only the JSON, the table and summary go to stderr)")
    p.set_defaults(handler=cmd_simulate)


def _has_display() -> bool:
    if sys.platform != "linux":
        return True
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def _fmt(v, unit: str = "", nd: int = 2) -> str:
    if v is None or v == float("inf"):
        return "-"
    return f"{v:.{nd}f}{unit}"


def cmd_simulate(args: argparse.Namespace) -> int:
    """Handler of ``ethimon simulate``."""
    from ..errors import DependencyNotInstalled
    from ..scenario import simulate_paths

    if args.gui and not _has_display():
        return err("--gui needs a display (DISPLAY is not set); use --record DIR for frames instead")
    json_to_stdout = args.json == "-"
    out = sys.stderr if json_to_stdout else sys.stdout  # stdout is the JSON's alone
    try:
        with Progress("simulate", enabled=not (json_to_stdout or args.gui)) as progress:
            report = simulate_paths(args.paths, model_dir=args.model, record_dir=args.record, gui=args.gui,
                                    on_progress=progress)
    except DependencyNotInstalled as exc:
        return err(str(exc))
    runs = [o for o in report.outcomes if o.status in ("PASS", "FAIL")]
    for o in report.outcomes:
        for msg in o.messages:
            print(msg, file=sys.stderr)
    for o in runs if args.record else ():
        print(f"{o.name}: recorded {len(o.result.files)} files in {os.path.join(args.record, o.name)}", file=out)
    _print_table(runs, out)
    print(f"{report.passed} passed, {report.failed} failed in {report.seconds:.2f}s", file=out)
    rc = report.exit_code
    if args.json and not emit_json(args.json, {"results": [o.record for o in runs]}):
        rc = 2
    return rc


def _print_table(runs, out) -> None:
    """The table of ``ethimon simulate``: one row per run (nothing without runs)."""
    rows = []
    for o in runs:
        res = o.result
        rows.append((o.name, "-" if res.first_override_cycle is None else str(res.first_override_cycle),
                     "-" if res.override_reaction_cycles is None else str(res.override_reaction_cycles),
                     res.executed_response, _fmt(res.time_to_safe_pose_s, " s"),
                     _fmt(res.max_joint_speed_safe_pose_rad_s, "", 3), _fmt(res.min_separation_m, " m"),
                     "yes" if res.task_completed else "no", f"{res.realtime_factor:.0f}x", o.status))
    head = ("scenario", "override@", "react", "response", "to safe pose", "max qd", "min sep",
            "task done", "speed", "result")
    if rows:
        widths = [max(len(str(r[i])) for r in (head, *rows)) for i in range(len(head))]
        for r in (head, tuple("-" * w for w in widths), *rows):
            print("  ".join(str(c).ljust(w) for c, w in zip(r, widths)).rstrip(), file=out)
