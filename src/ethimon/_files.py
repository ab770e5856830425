"""Opening user-named files without ever blocking: the one "regular files only" rule.

A FIFO (or ``/dev/stdin`` on a pipe or terminal) blocks ``open()`` until a
writer appears and ``read()`` until it writes; a device never ends. ethimon
reads only regular files: every path a user names is opened here with
``O_NONBLOCK`` (so a FIFO swapped in after any earlier check cannot block the
open) and checked with ``fstat`` on the open descriptor (no check-then-open
race), then switched back to blocking I/O.

Errors are built by the caller's ``error`` factory, called as
``error(message, path=path, hint=hint)`` (:class:`~ethimon.errors.SpecError`
takes exactly that), so each caller raises its own error type with the same words.
"""

from __future__ import annotations

import errno
import os
import re
import stat
from collections.abc import Callable, Iterable
from typing import IO, Any

from .errors import SpecError

__all__ = ["NOT_REGULAR_HINT", "file_kind", "find_yaml_files", "open_regular", "require_regular", "scan_yaml_files",
           "yaml_kind"]

#: the hint of every "not a regular file" refusal
NOT_REGULAR_HINT = "ethimon reads files only, not pipes, devices or standard input; save it to a file first"

ErrorFactory = Callable[..., BaseException]

_READ = os.O_RDONLY
_WRITE = os.O_WRONLY | os.O_CREAT | os.O_TRUNC
_COMMON = (getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0) | getattr(os, "O_CLOEXEC", 0)
           | getattr(os, "O_BINARY", 0))


def file_kind(target: str | os.PathLike | os.stat_result) -> str | None:
    """``None`` for a regular file, else what it is (``"a directory"``, ``"a named pipe (FIFO)"``, ...).

    ``target`` is a stat result or a path (``os.stat``, following links; ``OSError`` passes through).
    """
    st = target if isinstance(target, os.stat_result) else os.stat(target)
    mode = st.st_mode
    if stat.S_ISREG(mode):
        return None
    return ("a directory" if stat.S_ISDIR(mode) else "a named pipe (FIFO)" if stat.S_ISFIFO(mode)
            else "a socket" if stat.S_ISSOCK(mode) else "a character device" if stat.S_ISCHR(mode)
            else "a block device" if stat.S_ISBLK(mode) else "a special file")


def _a(what: str) -> str:
    return f"{'an' if what[:1].lower() in 'aeiou' else 'a'} {what}"


def not_regular_error(kind: str, path: str, what: str, error: ErrorFactory = SpecError) -> BaseException:
    """The one refusal of a path that is ``kind`` (from :func:`file_kind`) instead of a regular file."""
    if kind == "a directory":
        return error(f"expected {_a(what)}, found a directory", path=path, hint=None)
    return error(f"expected {_a(what)}, found {kind}, not a regular file", path=path, hint=NOT_REGULAR_HINT)


def require_regular(path: str | os.PathLike, what: str = "file", *, error: ErrorFactory = SpecError) -> None:
    """Refuse, without opening it, a path that is missing or not a regular file.

    For paths that are only listed now and opened later (with :func:`open_regular`).
    """
    spath = os.fspath(path)
    try:
        kind = file_kind(spath)
    except FileNotFoundError:
        raise error("no such file or folder", path=spath, hint=None) from None
    except OSError as exc:
        raise error(f"cannot read this {what}: {exc.strerror or exc}", path=spath, hint=None) from None
    if kind is not None:
        raise not_regular_error(kind, spath, what, error)


def open_regular(path: str | os.PathLike, mode: str = "rb", *, what: str = "file",
                 error: ErrorFactory = SpecError, special_ok: bool = False,
                 encoding: str | None = None) -> IO[Any]:
    """Open ``path`` without ever blocking; only a regular file is accepted.

    Args:
        path: the file.
        mode: ``"rb"``/``"r"`` to read, ``"wb"``/``"w"`` to create or truncate and write.
        what: what the file is, for the messages (``"spec"``, ``"audit log"``, ``"JSON report"``).
        error: builds the exception, ``error(message, path=..., hint=...)``.
        special_ok: also accept a FIFO that already has its other end open, or a device
            (a report to ``/dev/null``); the open still never blocks.
        encoding: for text modes (default UTF-8).

    Raises:
        whatever ``error`` builds: missing, unreadable, a directory, a FIFO, socket or device.
    """
    spath = os.fspath(path)
    writing = mode[:1] in ("w", "a")
    verb = "write" if writing else "read"
    try:
        fd = os.open(spath, (_WRITE if writing else _READ) | _COMMON, 0o666)
    except FileNotFoundError:
        if writing:
            raise error(f"cannot write the {what}: no such folder", path=spath, hint=None) from None
        raise error(f"{what} not found", path=spath, hint="check the path") from None
    except PermissionError:
        raise error(f"cannot {verb} the {what} (permission denied)", path=spath, hint=None) from None
    except IsADirectoryError:
        raise not_regular_error("a directory", spath, what, error) from None
    except OSError as exc:
        if writing and exc.errno == errno.ENXIO:  # a FIFO nobody reads: a blocking open would hang
            raise error(f"cannot write the {what}: a named pipe (FIFO) with no reader", path=spath,
                        hint="start the reader first, or write it to a regular file") from None
        raise error(f"cannot {verb} the {what}: {exc.strerror or exc}", path=spath, hint=None) from None
    try:
        kind = file_kind(os.fstat(fd))  # what we opened is what we use
        if kind is not None and not (special_ok and kind != "a directory"):
            raise not_regular_error(kind, spath, what, error)
        if hasattr(os, "set_blocking"):
            os.set_blocking(fd, True)
        if "b" in mode:
            return os.fdopen(fd, mode)
        return os.fdopen(fd, mode, encoding=encoding or "utf-8")
    except BaseException:
        os.close(fd)
        raise


#: which command reads each kind of ethimon YAML file (named when a folder's file is passed over)
_READER = {"spec": "ethimon lint / verify", "scenario": "ethimon check", "mapping": "ethimon replay --map"}
_TOP_KEY = re.compile(rb"^([A-Za-z_][A-Za-z0-9_-]*)[ \t]*:", re.M)
_KIND_PEEK = 256 * 1024  # a spec's, scenario's or mapping's top-level keys are near its start


def yaml_kind(path: str | os.PathLike) -> str | None:
    """What an ethimon YAML file is, from its top-level keys (no YAML parse, nothing run):
    ``"scenario"`` (it names a ``spec:``), ``"mapping"`` (a ``rate_hz:`` and no obligations,
    risk or safe pose), ``"spec"`` (``obligations:``, ``risk:``, ``safe_pose:`` or ``on_fault:``),
    or ``None`` when it cannot be told (unreadable, or none of those keys): the caller then reads
    it as the kind it expects, and that reader gives the located error."""
    try:
        with open_regular(path, "rb", what="file") as fh:
            head = fh.read(_KIND_PEEK)
    except (OSError, SpecError):
        return None
    keys = {m.group(1).decode("ascii") for m in _TOP_KEY.finditer(head)}
    if "spec" in keys:
        return "scenario"
    spec_keys = {"obligations", "risk", "safe_pose", "on_fault"} & keys
    if "rate_hz" in keys and not spec_keys:
        return "mapping"
    if spec_keys:
        return "spec"
    return None


def scan_yaml_files(paths: Iterable[str], *, what: str = "scenario",
                    command: str = "ethimon check") -> list[tuple[str, str | None]]:
    """Expand files and folders into ``(path, reason)`` pairs, in order, without opening any file: the one
    discovery rule of ``ethimon check``, ``simulate``, ``lint``, ``verify`` (and ``--ray``).

    ``reason`` is ``None`` for a file to read; for a FIFO, socket or device
    found in a folder (never opened: a FIFO would block) it says why it is
    passed over, and so for a file in a folder that is plainly another kind of
    ethimon file (:func:`yaml_kind`: a spec in a folder of scenarios, a scenario or
    a mapping among specs), which is named with the command that reads it. A path
    named in ``paths`` must be a regular file or a folder, and is always read as ``what``.

    Raises:
        SpecError: a path that does not exist or is not a regular file or folder,
            or a folder with no ``*.yaml``/``*.yml`` at all.
    """
    out: list[tuple[str, str | None]] = []
    for p in paths:
        if os.path.isdir(p):
            found: list[tuple[str, str | None]] = []
            for root, dirs, files in os.walk(p):
                dirs.sort()
                for f in sorted(files):
                    if not f.endswith((".yaml", ".yml")):
                        continue
                    full = os.path.join(root, f)
                    try:
                        kind = file_kind(full)
                    except OSError:  # a broken link or no permission: reading it gives the clean error
                        kind = None
                    if kind is not None:
                        found.append((full, f"{kind}, not a regular file: not read"))
                        continue
                    other = yaml_kind(full) if what in _READER else None
                    if other is not None and other != what:
                        found.append((full, f"{_a(other)} file, not {_a(what)}: {_READER[other]} reads it"))
                    else:
                        found.append((full, None))
            if not found:
                raise SpecError(f"no {what} files (*.yaml, *.yml) in this folder", path=p,
                                hint=f"point {command} at {what} files or a folder that holds them")
            out.extend(found)
        else:
            require_regular(p, what)
            out.append((p, None))
    return out


def find_yaml_files(paths: Iterable[str], *, what: str = "scenario", command: str = "ethimon check",
                    skipped: list[tuple[str, str]] | None = None) -> list[str]:
    """The files of :func:`scan_yaml_files` to read; the passed-over ones go to ``skipped``."""
    out = []
    for path, reason in scan_yaml_files(paths, what=what, command=command):
        if reason is None:
            out.append(path)
        elif skipped is not None:
            skipped.append((path, reason))
    return out
