"""What every sub-command prints the same way: errors, JSON reports, report files, progress bars."""

from __future__ import annotations

import json
import sys
from typing import Any

from ..errors import SpecError

__all__ = ["err", "ERROR_PREFIX", "write_report", "emit_report", "emit_json", "Progress", "add_ray_options",
           "ray_options", "ray_target", "executor_of"]

#: the one prefix of a CLI error that is not located in a file (located ones read ``path:line:col: ...``)
ERROR_PREFIX = "ethimon: error: "


def err(msg: str) -> int:
    """Print ``ethimon: error: msg`` to stderr; returns exit code 2 (bad input)."""
    print(f"{ERROR_PREFIX}{msg}", file=sys.stderr)
    return 2


def open_audit_log(path: str, compiled_spec: Any, /, **meta: Any) -> tuple[Any, int | None]:
    """A new audit log for a command (``--audit PATH``), its meta with ``compiled_spec``'s sha256.

    Returns ``(log, None)``, or ``(None, 2)`` after printing why (the file exists: a log is never
    appended to; it cannot be written; the key named by ``ETHIMON_AUDIT_KEY_FILE``/``_ENV`` cannot be
    read). The log is HMAC-keyed when the operator names a key; on close it prints its head.
    """
    from ..audit import AuditLog, key_from_env, spec_hash
    try:
        key, _ = key_from_env()
    except ValueError as exc:
        return None, err(f"{path}: {exc}")
    try:
        return AuditLog(path, fsync="interval", meta={**meta, "spec_sha256": spec_hash(compiled_spec)}, key=key,
                        on_close=lambda log: print(log.head_summary(), file=sys.stderr)), None
    except FileExistsError:
        return None, err(f"{path}: the audit log exists already (a log is never appended to; pick a new name)")
    except OSError as exc:
        return None, err(f"{path}: cannot write the audit log: {exc.strerror or exc}")


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


def add_ray_options(p, what: str) -> None:
    """``--ray [ADDRESS]``, ``--ray-workers N`` and ``--file-timeout-s S`` of a command that works
    through many files (read back with :func:`ray_options`)."""
    p.add_argument("--ray", nargs="?", const="local", default=None, metavar="ADDRESS",
                   help=f"spread the {what} over a Ray cluster (needs ethimon[fleet]); no ADDRESS: a local "
                        "instance; 'auto': the cluster of 'ray start' on this machine; 'ray://HOST:10001': a "
                        "remote one. The results are the serial run's, in the same order")
    p.add_argument("--ray-workers", type=int, metavar="N", default=None,
                   help="CPUs (parallel workers) of the local Ray instance (default: up to 4)")
    p.add_argument("--file-timeout-s", type=float, metavar="S", default=None,
                   help="with --ray: a file whose task has not finished after S seconds is an ERROR row and its "
                        "task is cancelled (default: no limit)")


def ray_options(args, paths_attr: str) -> tuple[tuple[str | None, int | None] | None, float | None]:
    """``(ray_target(args, paths_attr), file timeout)`` from the options of :func:`add_ray_options`.

    Raises:
        EthimonError: a bad ``--ray``/``--ray-workers`` value, or ``--file-timeout-s`` that is not a
            positive finite number or is given without ``--ray``.
    """
    from ..fleet import check_file_timeout
    ray = ray_target(args, paths_attr)
    return ray, check_file_timeout(args.file_timeout_s, on_ray=ray is not None)


def executor_of(args, paths_attr: str) -> Any:
    """The executor of :func:`ethimon.run` the options of :func:`add_ray_options` ask for: ``Serial()``
    without ``--ray``, else ``fleet.Ray(address, num_cpus=workers, file_timeout=...)``.

    Raises:
        EthimonError: as :func:`ray_options`.
    """
    ray, file_timeout = ray_options(args, paths_attr)
    if ray is None:
        from .._batch import Serial
        return Serial()
    from ..fleet import Ray
    return Ray(ray[0], num_cpus=ray[1], file_timeout=file_timeout)


def ray_target(args, paths_attr: str) -> tuple[str | None, int | None] | None:
    """``None`` without ``--ray``; else ``(address or None for local, workers)``.

    ``--ray PATH`` (argparse took a path given after ``--ray`` as its ADDRESS): the path goes back
    in front of the others and the run is local.

    Raises:
        EthimonError: a value that is neither a Ray address nor an existing path, or a bad ``--ray-workers``.
    """
    import os

    from ..errors import EthimonError
    from ..fleet import check_address
    workers = getattr(args, "ray_workers", None)
    if args.ray is None:
        if workers is not None:
            raise EthimonError("--ray-workers needs --ray")
        return None
    if workers is not None and workers < 1:
        raise EthimonError(f"--ray-workers must be at least 1, got {workers}")
    value = args.ray
    try:
        address = check_address(value)
    except EthimonError:
        if not os.path.exists(value):
            raise
        setattr(args, paths_attr, [value] + list(getattr(args, paths_attr) or []))
        address = None
    if address is not None and workers is not None:
        raise EthimonError("--ray-workers sets the size of a local Ray instance; a cluster has its own")
    return address, workers
