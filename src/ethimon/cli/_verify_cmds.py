"""``ethimon verify``: prove each spec's invariants with z3, lint it, write counterexamples."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from ..errors import SpecError
from ._common import Progress, emit_json

__all__ = ["add_verify_parsers"]


def add_verify_parsers(sub) -> None:
    """Add the ``verify`` sub-command to an argparse sub-parser group."""
    p = sub.add_parser(
        "verify", help="prove spec invariants with an SMT solver and lint specs",
        description="Prove every spec's decision-logic invariants over all in-range inputs (z3, bounded "
                    "unrolling of the temporal windows), lint the spec, and replay counterexamples in the "
                    "monitor. Each spec has a total time budget (--budget-s); checks it does not reach are "
                    "reported as 'unknown (budget)'. Exit 0 every property proved and every check run; 1 a "
                    "property refuted or unproved (solver or unrolling limit), or checks cut by the budget; "
                    "2 bad input. Lint warnings alone do not change the exit code.")
    p.add_argument("paths", nargs="+", metavar="PATH", help="spec files or folders")
    p.add_argument("--json", metavar="FILE", help="write the report as JSON ('-' for stdout: then stdout holds "
                   "only the JSON, the tables go to stderr)")
    p.add_argument("--counterexamples", metavar="DIR",
                   help="write each counterexample as a scenario file that 'ethimon check' replays")
    p.add_argument("--timeout-s", type=float, default=None, metavar="S",
                   help="z3 time limit per check in seconds (default 20)")
    p.add_argument("--budget-s", type=float, default=None, metavar="S",
                   help="total time for all checks of one spec in seconds (default 120); what is not "
                        "reached is reported as unknown and the exit code is 1")
    p.add_argument("--max-unroll", type=int, default=None, metavar="N",
                   help="most cycles of symbolic state to unroll (default 32)")
    p.add_argument("--no-lint", action="store_true", help="prove only, skip the lints")
    p.set_defaults(handler=cmd_verify)


def verify_unit(path: str, skipped: str | None, timeout_s: float, max_unroll: int, lints: bool,
                counterexamples: str | None, budget_s: float) -> Any:
    """The unit of ``ethimon verify`` (one unit of :func:`ethimon.run`): one spec's ``SpecReport`` (an
    unusable spec is a report carrying its error line), ``None`` for a file passed over (``skipped``)."""
    from .. import verify
    from ..errors import DependencyNotInstalled
    from ..scenario import error_line
    if skipped is not None:  # a FIFO, socket or device in a folder: never opened
        return None
    try:
        return verify.verify_spec(path, timeout_s=timeout_s, max_unroll=max_unroll, lints=lints,
                                  counterexamples=counterexamples, budget_s=budget_s)
    except DependencyNotInstalled:
        raise
    except Exception as exc:  # noqa: BLE001 - one unusable spec is one report; the others still run
        return verify.SpecReport(path=path, error=error_line(path, exc))


def cmd_verify(args: argparse.Namespace) -> int:
    from .._batch import Unit, run
    from .._files import scan_yaml_files
    from ..verify import DEFAULT_BUDGET_S, DEFAULT_MAX_UNROLL, DEFAULT_TIMEOUT_S, exit_code, format_table, require_z3

    require_z3()  # DependencyNotInstalled -> one line, exit 2
    timeout = args.timeout_s if args.timeout_s is not None else DEFAULT_TIMEOUT_S
    unroll = args.max_unroll if args.max_unroll is not None else DEFAULT_MAX_UNROLL
    budget = args.budget_s if args.budget_s is not None else DEFAULT_BUDGET_S
    if not timeout > 0 or unroll < 1 or not budget > 0:
        raise SpecError("--timeout-s and --budget-s must be > 0 and --max-unroll >= 1", path="<command line>")
    scanned = scan_yaml_files(args.paths, what="spec", command="ethimon verify")
    out = sys.stderr if args.json == "-" else sys.stdout

    def one(path: str, skipped: str | None) -> Any:  # each table printed as its spec is done
        rep = verify_unit(path, skipped, timeout, unroll, not args.no_lint, args.counterexamples, budget)
        if rep is None:
            print(f"{path}: skipped: {skipped}", file=out)
        else:
            if progress.bar is not None:
                progress.bar.clear()
            print(format_table(rep), file=out, end="\n\n")
        return rep

    with Progress("verify", enabled=args.json != "-") as progress:
        done = run([Unit(one, (path, skipped), path) for path, skipped in scanned], None, progress)
    reports = [r for r in done.values() if r is not None]
    print(_summary(reports, budget), file=out)
    if args.json and not emit_json(args.json, _json(reports, timeout, unroll, budget)):
        return 2
    return exit_code(reports)


def _summary(reports: list, budget: float) -> str:
    """The last line of ``ethimon verify``: what was proved, refuted, unknown, warned, unusable, cut short."""
    n_ref = sum(len(r.refuted) for r in reports)
    n_warn = sum(len(r.warnings) for r in reports)
    n_err = sum(r.error is not None for r in reports)
    props = [f.status for r in reports for f in r.findings if f.kind == "property"]
    n_prop, n_real, n_unk = (props.count(s) for s in ("proved", "proved (real arithmetic)", "unknown"))
    n_cut = sum(r.not_reached for r in reports)
    return (f"{len(reports)} spec(s): {n_prop} properties proved"
            + (f" ({n_real} more in real arithmetic only)" if n_real else "") + f", {n_ref} refuted, {n_unk} "
            f"unknown, {n_warn} lint warnings, {n_err} unusable" + (f"; {n_cut} check(s) cut short or not reached "
                                                                    f"by the budget (--budget-s {budget:g} per spec)"
                                                                    if n_cut else ""))


def _json(reports: list, timeout: float, unroll: int, budget: float) -> dict:
    import z3

    from .. import __version__
    from ..verify import reports_to_json
    return reports_to_json(reports, {"ethimon": __version__, "z3": z3.get_version_string(),
                                     "timeout_s": timeout, "max_unroll": unroll, "budget_s": budget})
