"""``ethimon check PATH...``: run scenarios, print a table, exit 0 / 1 / 2.

Thin: parses, calls :func:`ethimon.scenario.check_paths`, prints the table, the
problems and the summary, and writes the JSON / JUnit reports.
"""

from __future__ import annotations

import argparse
import sys

from ._common import Progress, add_ray_options, emit_json, emit_report, err, executor_of

__all__ = ["add_check_parser", "cmd_check"]


def add_check_parser(sub) -> None:
    p = sub.add_parser("check", help="run scenario files against their specs",
                       description="Run every scenario; exit 0 all pass, 1 an expectation failed, 2 bad input.")
    # nargs="*" (checked in cmd_check): so that 'check --ray scenarios/' takes the folder back from --ray
    p.add_argument("paths", nargs="*", metavar="PATH", help="scenario files or folders")
    p.add_argument("--json", metavar="FILE", help="write results as JSON ('-' for stdout: then stdout holds "
                   "only the JSON, the table and summary go to stderr)")
    p.add_argument("--junit", metavar="FILE", help="write a JUnit XML report")
    p.add_argument("--sim", action="store_true", help="also run scenarios with a 'sim:' block in PyBullet")
    p.add_argument("--jobs", "-j", type=int, metavar="N", default=None,
                   help="with --sim: run the sim blocks in N worker processes (default: the CPU cores this "
                        "process may use; 1: serial). Results and their order are the serial run's")
    p.add_argument("--model", metavar="DIR", help="risk model directory for every scenario "
                   "(default: each spec's risk.estimator.model, else the shipped model)")
    p.add_argument("--quiet", "-q", action="store_true", help="print only problems and the summary")
    add_ray_options(p, "scenario files")
    p.set_defaults(handler=cmd_check)


def cmd_check(args: argparse.Namespace) -> int:
    from ..errors import EthimonError
    from ..scenario import check_paths

    json_to_stdout = args.json == "-"
    out = sys.stderr if json_to_stdout else sys.stdout  # stdout is the JSON's alone
    try:
        executor = executor_of(args, "paths")  # Serial(), or fleet.Ray(...) with --ray
    except EthimonError as exc:
        return err(str(exc))
    if not args.paths:
        return err("ethimon check: give at least one PATH (scenario files or folders)")
    if args.jobs is not None and args.jobs < 1:
        return err(f"ethimon check: --jobs must be at least 1, got {args.jobs}")
    jobs = args.jobs if args.jobs is not None else default_jobs()
    with Progress("check", enabled=not json_to_stdout) as progress:
        report = check_paths(args.paths, sim=args.sim, model_dir=args.model, on_progress=progress, jobs=jobs,
                             executor=executor)
    if not args.quiet:
        print_table([(o.name, o.expected, o.got, "-" if o.first_override_cycle is None
                      else str(o.first_override_cycle), o.status) for o in report.outcomes], out)
    for o in report.outcomes:
        for msg in o.messages:
            print(msg, file=sys.stderr)
    print(report.summary(), file=out)
    rc = report.exit_code
    if args.json and not emit_json(args.json, report.as_dict()):
        rc = 2
    if args.junit and not emit_report(args.junit, report.junit_xml(), "JUnit report", dash_is_stdout=False):
        rc = 2
    return rc


def default_jobs() -> int:
    """The CPU cores this process may use: the default ``--jobs`` of ``check --sim``."""
    import os
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):  # pragma: no cover - not Linux
        return max(1, os.cpu_count() or 1)


def print_table(rows, out=None) -> None:
    out = out if out is not None else sys.stdout
    header = ("scenario", "expected", "got", "first override", "result")
    table = [header] + [tuple(str(c) for c in r) for r in rows]
    widths = [min(max(len(r[i]) for r in table), 44) for i in range(len(header))]

    def fmt(r):
        cells = []
        for c, w in zip(r, widths):
            c = c if len(c) <= w else c[: w - 1] + "…"
            cells.append(c.ljust(w))
        return "  ".join(cells).rstrip()
    print(fmt(header), file=out)
    print("  ".join("-" * w for w in widths), file=out)
    for r in table[1:]:
        print(fmt(r), file=out)
