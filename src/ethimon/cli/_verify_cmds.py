"""``ethimon verify``: prove each spec's invariants with z3, lint it, write counterexamples."""

from __future__ import annotations

import argparse
import json
import sys

__all__ = ["add_verify_parsers"]


def add_verify_parsers(sub) -> None:
    """Add the ``verify`` sub-command to an argparse sub-parser group."""
    p = sub.add_parser(
        "verify", help="prove spec invariants with an SMT solver and lint specs",
        description="Prove every spec's decision-logic invariants over all in-range inputs (z3, bounded "
                    "unrolling of the temporal windows), lint the spec, and replay counterexamples in the "
                    "monitor. Exit 0 all proved, 1 a property refuted or unproved, 2 bad input.")
    p.add_argument("paths", nargs="+", metavar="PATH", help="spec files or folders")
    p.add_argument("--json", metavar="FILE", help="write the report as JSON ('-' for stdout)")
    p.add_argument("--counterexamples", metavar="DIR",
                   help="write each counterexample as a scenario file that 'ethimon check' replays")
    p.add_argument("--timeout-s", type=float, default=None, metavar="S",
                   help="z3 time limit per check in seconds (default 20)")
    p.add_argument("--max-unroll", type=int, default=None, metavar="N",
                   help="most cycles of symbolic state to unroll (default 32)")
    p.add_argument("--no-lint", action="store_true", help="prove only, skip the lints")
    p.set_defaults(handler=cmd_verify)


def cmd_verify(args: argparse.Namespace) -> int:
    from ..errors import SpecError
    from ..verify import (DEFAULT_MAX_UNROLL, DEFAULT_TIMEOUT_S, exit_code, find_specs, format_table,
                          reports_to_json, require_z3, verify_spec)

    require_z3()  # DependencyNotInstalled -> one line, exit 2
    timeout = args.timeout_s if args.timeout_s is not None else DEFAULT_TIMEOUT_S
    unroll = args.max_unroll if args.max_unroll is not None else DEFAULT_MAX_UNROLL
    if timeout <= 0 or unroll < 1:
        raise SpecError("--timeout-s must be > 0 and --max-unroll >= 1", path="<command line>")
    paths = find_specs(args.paths)
    to_stdout = args.json == "-"
    out = sys.stderr if to_stdout else sys.stdout
    reports = []
    for path in paths:
        rep = verify_spec(path, timeout_s=timeout, max_unroll=unroll, lints=not args.no_lint,
                          counterexamples=args.counterexamples)
        reports.append(rep)
        print(format_table(rep), file=out)
        print(file=out)
    n_ref = sum(len(r.refuted) for r in reports)
    n_warn = sum(len(r.warnings) for r in reports)
    n_err = sum(r.error is not None for r in reports)
    n_prop = sum(1 for r in reports for f in r.findings if f.kind == "property" and f.status == "proved")
    print(f"{len(reports)} spec(s): {n_prop} properties proved, {n_ref} refuted, {n_warn} lint warnings, "
          f"{n_err} unusable", file=out)
    if args.json:
        import z3

        from .. import __version__
        doc = reports_to_json(reports, {"ethimon": __version__, "z3": z3.get_version_string(),
                                        "timeout_s": timeout, "max_unroll": unroll})
        text = json.dumps(doc, indent=2)
        if to_stdout:
            print(text)
        else:
            try:
                with open(args.json, "w", encoding="utf-8") as fh:
                    fh.write(text + "\n")
            except OSError as exc:
                raise SpecError(f"cannot write JSON report: {exc.strerror or exc}", path=args.json) from None
    return exit_code(reports)
