"""What every sub-command prints the same way: errors, JSON reports, report files, progress bars."""

from __future__ import annotations

import json
import sys
from typing import Any

from ..errors import SpecError

__all__ = ["err", "ERROR_PREFIX", "write_report", "emit_report", "emit_json", "Progress"]

#: the one prefix of a CLI error that is not located in a file (located ones read ``path:line:col: ...``)
ERROR_PREFIX = "ethimon: error: "


def err(msg: str) -> int:
    """Print ``ethimon: error: msg`` to stderr; returns exit code 2 (bad input)."""
    print(f"{ERROR_PREFIX}{msg}", file=sys.stderr)
    return 2


def write_report(path: str, text: str, what: str) -> None:
    """Write a report file without ever blocking on a FIFO that has no reader
    (:func:`ethimon._files.open_regular`; a FIFO with a reader or ``/dev/null`` is accepted).

    Raises:
        SpecError: the file cannot be written (one line, names the path).
    """
    from .._files import open_regular
    with open_regular(path, "w", what=what, error=SpecError, special_ok=True) as fh:
        try:
            fh.write(text)
        except OSError as exc:
            raise SpecError(f"cannot write the {what}: {exc.strerror or exc}", path=path) from None


def emit_report(target: str, text: str, what: str, *, dash_is_stdout: bool = True) -> bool:
    """Write ``text`` to the file ``target`` (``-``: stdout, unless ``dash_is_stdout`` is false);
    on failure print one line and return False."""
    if target == "-" and dash_is_stdout:
        sys.stdout.write(text)
        sys.stdout.flush()
        return True
    try:
        write_report(target, text, what)
        return True
    except SpecError as exc:
        print(str(exc), file=sys.stderr)
        return False


def emit_json(target: str, doc: Any, what: str = "JSON report") -> bool:
    """The one JSON writer of the CLI: ``doc`` indented to ``target`` (``-``: stdout, nothing else there)."""
    return emit_report(target, json.dumps(doc, indent=2, default=str) + "\n", what)


class Progress:
    """A progress bar on stderr while files are worked through, only when stdout is a terminal.

    Off when stdout is not a TTY (pipes, CI logs, ``--json -``) or when ``tqdm`` is not installed
    (it ships with the ``risk`` extra); imported only when shown. Use as a context manager and call
    it as ``on_file(done, total, path)`` (before each file, and at the end).
    """

    def __init__(self, desc: str, *, enabled: bool = True, stream=None) -> None:
        self.desc = desc
        self.stream = stream if stream is not None else sys.stderr
        self.enabled = bool(enabled) and _isatty(sys.stdout)
        self.bar = None

    def __enter__(self) -> Progress:
        return self

    def __call__(self, done: int, total: int, path: str) -> None:
        if not self.enabled:
            return
        if self.bar is None:
            try:
                from tqdm import tqdm
            except ImportError:
                self.enabled = False
                return
            self.bar = tqdm(total=total, desc=self.desc, unit="file", file=self.stream, leave=False,
                            dynamic_ncols=True)
        self.bar.set_postfix_str(_short(path), refresh=False)
        self.bar.update(done - self.bar.n)
        self.bar.refresh()

    def __exit__(self, *exc) -> None:
        if self.bar is not None:
            self.bar.close()
            self.bar = None


def _isatty(stream) -> bool:
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):
        return False


def _short(path: str, width: int = 40) -> str:
    return path if len(path) <= width else "…" + path[-(width - 1):]
