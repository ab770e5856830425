"""The ``ethimon`` command line: a thin layer over the library.

Exit codes: 0 success, 1 an expectation/property failed, 2 bad input, 3 an internal error
(a bug: the message asks for a report), 130 interrupted (Ctrl-C).
Errors print as ``path:line:column: message (hint)``, never as a traceback.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Sequence

from ..errors import EthimonError, SpecError
from ._common import ERROR_PREFIX, emit_json

__all__ = ["main"]

#: optional sub-command modules: (module, function that adds its parsers)
_PLUGINS = (("_risk_cmds", "add_risk_parsers"), ("_sim_cmds", "add_sim_parsers"),
            ("_verify_cmds", "add_verify_parsers"), ("_audit_cmds", "add_audit_parsers"),
            ("_replay_cmds", "add_replay_parsers"), ("_ros2_cmds", "add_ros2_parsers"))


def _build_parser() -> argparse.ArgumentParser:
    from .. import __version__
    from ._check_cmds import add_check_parser

    p = argparse.ArgumentParser(prog="ethimon", description="Formal-spec-checked runtime safety monitor.")
    p.add_argument("--version", action="version", version=f"ethimon {__version__}")
    sub = p.add_subparsers(dest="command", metavar="COMMAND")
    add_check_parser(sub)
    sp = sub.add_parser("schema", help="print the JSON Schema of spec or scenario files")
    sp.add_argument("kind", nargs="?", choices=("spec", "scenario"), default="spec")
    sp.set_defaults(handler=_cmd_schema)
    lp = sub.add_parser("lint", help="load and compile specs, report errors (no proofs)",
                        description="Load and compile every spec file (files or folders of *.yaml/*.yml): one "
                                    "'ok' line per spec, or its errors as path:line:column: message (hint). "
                                    "No proofs ('ethimon verify' proves). Exit 0 all ok, 2 an error.")
    lp.add_argument("paths", nargs="+", metavar="SPEC", help="spec files or folders")
    lp.add_argument("--map", dest="mapping", metavar="MAP", help="also lint a replay mapping against each spec "
                    "(prev() of a zero-order-held input, unmapped signals)")
    lp.set_defaults(handler=_cmd_lint)
    for mod, fn in _PLUGINS:
        try:
            module = importlib.import_module(f"{__name__}.{mod}")
        except ModuleNotFoundError as exc:
            if exc.name and exc.name.endswith(mod):
                continue
            raise
        getattr(module, fn)(sub)
    _whole_flags_only(p)
    return p


def _whole_flags_only(p: argparse.ArgumentParser) -> None:
    """No prefix abbreviations (``--duration`` is not ``--duration-s``): a flag is spelt out or unknown."""
    p.allow_abbrev = False
    for a in p._actions:
        if isinstance(a, argparse._SubParsersAction):
            for child in a.choices.values():
                _whole_flags_only(child)


def _cmd_schema(args: argparse.Namespace) -> int:
    if args.kind == "spec":
        from ..language import Spec as model
    else:
        from ..scenario import Scenario as model
    schema = model.model_json_schema()
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    schema["title"] = f"ethimon {args.kind} (format 1)"
    emit_json("-", schema, "JSON Schema")
    return 0


def _cmd_lint(args: argparse.Namespace) -> int:
    from .._batch import run
    from .._lint import LintLine, lint_units
    rc = 0
    for o in run(lint_units(args.paths, mapping=getattr(args, "mapping", None))).outcomes:
        for line in o.value if o.ok else [LintLine(o.label, "error", o.lines()[0])]:
            print(line.text, file=sys.stderr if line.kind == "error" else sys.stdout)
            rc = 2 if line.kind == "error" else rc
    return rc


def main(argv: Sequence[str] | None = None) -> int:
    """Run the CLI; returns the exit code (also used as the console-script entry)."""
    try:
        parser = _build_parser()
        args = parser.parse_args(argv)
        handler = getattr(args, "handler", None)
        if handler is None:
            parser.print_help(sys.stderr)
            return 2
        return int(handler(args) or 0)
    except SpecError as exc:
        print(str(exc), file=sys.stderr)
        return 2
    except EthimonError as exc:
        print(f"{ERROR_PREFIX}{exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 0
    except SystemExit as exc:  # argparse usage errors
        return int(exc.code) if isinstance(exc.code, int) else 2
    except Exception as exc:  # never a traceback for the user
        print(f"{ERROR_PREFIX}internal error: {type(exc).__name__}: {exc} (please report this)", file=sys.stderr)
        return 3


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
