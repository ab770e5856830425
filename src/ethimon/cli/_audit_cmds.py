"""``ethimon audit ...`` subcommands (wired into ``ethimon.cli:main``).

``ethimon audit verify LOG`` exits 0 if the hash chain is intact, 1 if it is
tampered (edited, removed, reordered records; with ``--require-closed`` or
``--head`` also a truncated tail or a chain rebuilt after a record was dropped), 2 for bad
input (missing file, not an audit log, unreadable or wrong key). It prints one line and never a
traceback; the line says whether the log is keyed (HMAC) or unkeyed.
"""

from __future__ import annotations

import argparse
import sys

from ._common import err

__all__ = ["add_audit_parsers", "cmd_audit_verify", "main"]


def add_audit_parsers(subparsers: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Add ``audit`` (with ``verify``) to an argparse subparsers object.

    Each leaf parser sets ``handler``: call ``args.handler(args)`` and exit with its return value.
    """
    audit = subparsers.add_parser("audit", help="audit-trail tools",
                                  description="Tools for ethimon audit logs (hash-chained JSONL).")
    sub = audit.add_subparsers(dest="audit_command", metavar="COMMAND")
    sub.required = True
    v = sub.add_parser("verify", help="check a log's hash chain (exit 0 ok, 1 tampered, 2 bad input)",
                       description="Check an audit log's hash chain: exit 0 ok, 1 tampered or truncated, "
                                   "2 bad input.")
    v.add_argument("log", metavar="LOG", help="the audit log (JSONL)")
    v.add_argument("--require-closed", action="store_true",
                   help="fail if the log has no 'close' record (truncated tail or killed writer)")
    v.add_argument("--head", metavar="COUNT:HASH",
                   help="the head printed when the log was closed (or a bare hash of the last record), kept "
                        "elsewhere; the log must end exactly there")
    key = v.add_mutually_exclusive_group()
    key.add_argument("--key-file", metavar="FILE", help="HMAC key file, for logs written with a key")
    key.add_argument("--key-env", metavar="NAME", help="environment variable holding the HMAC key")
    v.set_defaults(handler=cmd_audit_verify)
    return audit


def cmd_audit_verify(args: argparse.Namespace) -> int:
    """Run ``audit verify``; returns the exit code (0/1/2)."""
    from .._files import open_regular
    from ..audit import AuditFormatError, verify_log
    from ..errors import SpecError
    key = None
    if getattr(args, "key_file", None):
        try:  # regular files only: a FIFO or /dev/stdin would block the read
            with open_regular(args.key_file, "rb", what="key file") as fh:
                key = fh.read().strip()
        except SpecError as exc:
            print(str(exc), file=sys.stderr)
            return 2
        except OSError as exc:
            print(f"{args.key_file}: cannot read key: {exc.strerror or exc}", file=sys.stderr)
            return 2
        if not key:
            print(f"{args.key_file}: empty key file", file=sys.stderr)
            return 2
    elif getattr(args, "key_env", None):
        import os
        from ..audit import KEY_ENV, key_from_env
        try:
            key, _ = key_from_env({KEY_ENV: args.key_env, **{args.key_env: os.environ[args.key_env]}}
                                  if args.key_env in os.environ else {KEY_ENV: args.key_env})
        except ValueError as exc:
            return err(f"--key-env: {exc}")
    try:
        rep = verify_log(args.log, key=key, require_closed=args.require_closed, expect_head=args.head)
    except AuditFormatError as exc:
        print(str(exc), file=sys.stderr)
        return 2
    except Exception as exc:  # noqa: BLE001 - one line, no traceback
        print(f"{args.log}: cannot verify: {type(exc).__name__}: {exc}", file=sys.stderr)
        return 2
    if rep.ok:
        print(f"{args.log}: {rep.summary()}")
        return 0
    print(f"{args.log}: {rep.summary()}")
    return 1


def main(argv: list[str] | None = None) -> int:
    """Standalone entry (``python -m ethimon.cli._audit_cmds audit verify LOG``)."""
    parser = argparse.ArgumentParser(prog="ethimon")
    subs = parser.add_subparsers(dest="command", metavar="COMMAND")
    subs.required = True
    add_audit_parsers(subs)
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:
        return int(exc.code or 0) if exc.code in (0, None) else 2
    return int(args.handler(args))


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
