"""The one place that talks to Ray: connect (or start a local instance) and map files over workers.

Every unit of work is one file (a scenario file, a bag). A worker returns plain
data (dicts, lists, str, int, float, bool, None); the driver puts the results back
in input order. A unit that raises inside the worker, or whose worker process
dies (after Ray's retries), becomes one failure for that file: the others still
run and are reported. Ray is imported only here, and only when called.
"""

from __future__ import annotations

import contextlib
import enum
import logging
import os
import re
import sys
from collections.abc import Callable, Sequence
from typing import Any

from ..errors import DependencyNotInstalled, EthimonError

__all__ = ["DEFAULT_LOCAL_CPUS", "Failure", "check_address", "map_files", "plain"]

#: the most CPUs a local instance started for one run gets by default (it shares the machine)
DEFAULT_LOCAL_CPUS = 4

_HOST_PORT = re.compile(r"^[A-Za-z0-9_.\-\[\]:]+:\d{1,5}$")

#: ``on_done(done, total, path)``: after each finished file (the progress bar of the CLI)
ProgressCallback = Callable[[int, int, str], None]


def check_address(address: str | None) -> str | None:
    """``None``/``"local"``: a new local instance; ``"auto"``, ``"ray://HOST:PORT"`` or ``"HOST:PORT"``:
    an existing cluster. Returns the address to pass to ``ray.init`` (``None`` for local).

    Raises:
        EthimonError: anything else (one line that says the accepted forms).
    """
    if address is None or address == "local":
        return None
    if address == "auto" or address.startswith("ray://") or _HOST_PORT.match(address):
        return address
    raise EthimonError(f"--ray: {address!r} is not a Ray address (use 'local', 'auto', 'ray://HOST:10001' or "
                       "HOST:PORT; put --ray after the paths, or write --ray=ADDRESS)")


class Failure:
    """A file whose unit did not return: ``what`` says why in one line (an exception in the worker,
    or the worker process died)."""

    __slots__ = ("what", "exc")

    def __init__(self, what: str, exc: BaseException | None = None) -> None:
        self.what, self.exc = what, exc

    def __repr__(self) -> str:
        return f"Failure({self.what!r})"


def plain(obj: Any) -> Any:
    """``obj`` as plain data, the way the CLI's JSON writer (``json.dumps(..., default=str)``) sees it:
    dicts, lists (tuples too), str, int, float, bool and None are kept (subclasses such as numpy
    floats or enums become the base type's value); anything else becomes ``str(obj)``."""
    if obj is None or type(obj) in (str, int, float, bool):
        return obj
    if isinstance(obj, dict):
        return {(k if k is None or type(k) in (str, int, float, bool) else _plain_key(k)): plain(v)
                for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [plain(v) for v in obj]
    if isinstance(obj, bool):
        return bool(obj)
    if isinstance(obj, str):
        return str.__str__(obj)
    if isinstance(obj, int) and not isinstance(obj, enum.Flag):
        return int(obj)
    if isinstance(obj, float):
        return float(obj)
    return str(obj)


def _plain_key(k: Any) -> Any:
    if isinstance(k, str):
        return str.__str__(k)
    if isinstance(k, (int, float)):
        return int(k) if isinstance(k, int) else float(k)
    return str(k)


def _import_ray():
    try:
        import ray
    except ImportError as exc:
        raise DependencyNotInstalled(f"--ray needs Ray: pip install 'ethimon[fleet]' ({exc})") from None
    return ray


def _connect(ray: Any, address: str | None, num_cpus: int | None) -> bool:
    """Join ``address`` or start a local instance (unless this process is connected already).
    Returns True when this call started the connection (and must shut it down)."""
    if ray.is_initialized():
        return False
    logging.getLogger("ray").setLevel(logging.ERROR)  # Ray's start-up chatter; errors still show
    kw: dict[str, Any] = {"logging_level": logging.ERROR, "log_to_driver": False}
    if address is None:
        cpus = num_cpus if num_cpus is not None else max(1, min(os.cpu_count() or 1, DEFAULT_LOCAL_CPUS))
        kw.update(num_cpus=int(cpus), include_dashboard=False)
    elif num_cpus is not None:
        raise EthimonError("the number of workers is set only for a local Ray instance (a cluster has its own)")
    try:  # "local": a new instance even where RAY_ADDRESS names a cluster
        ray.init(address=address if address is not None else "local", **kw)
    except Exception as exc:  # noqa: BLE001 - cannot reach the cluster: one line, no traceback
        where = "start a local Ray instance" if address is None else f"connect to the Ray cluster at {address}"
        hint = "" if address is None else (" (is the cluster running? 'ray start --head' starts one here; "
                                           "--ray without an address runs on a local instance of its own)")
        first = str(exc).strip().split(". ")[0][:300]
        raise EthimonError(f"cannot {where}: {type(exc).__name__}: {first}{hint}") from None
    return True


def _why(exc: BaseException, ray: Any) -> str:
    died = (getattr(ray.exceptions, "WorkerCrashedError", ()), getattr(ray.exceptions, "NodeDiedError", ()),
            getattr(ray.exceptions, "OutOfMemoryError", ()), getattr(ray.exceptions, "ActorDiedError", ()))
    died = tuple(t for t in died if isinstance(t, type))
    if died and isinstance(exc, died):
        return f"the Ray worker checking this file died ({type(exc).__name__})"
    cause = getattr(exc, "cause", None)  # a RayTaskError: the worker's own exception
    if isinstance(cause, BaseException):
        exc = cause
    text = str(exc).strip().splitlines()[-1] if str(exc).strip() else ""
    text = text if len(text) <= 300 else text[:297] + "..."
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__


def map_files(fn: Callable[..., Any], calls: Sequence[tuple], labels: Sequence[str], *,
              address: str | None = None, num_cpus: int | None = None,
              on_done: ProgressCallback | None = None, max_retries: int = 1) -> list[Any]:
    """Run ``fn(*calls[i])`` on Ray workers, one task per file; the results in input order.

    Args:
        fn: a module-level function (workers import it by name) that returns plain data.
        calls: the arguments of each call; ``labels[i]`` names its file (for the progress bar).
        address: ``None`` a new local instance of ``num_cpus`` CPUs (default at most
            :data:`DEFAULT_LOCAL_CPUS`); else an address for ``ray.init`` (see :func:`check_address`).
            When this process is already connected (``ray.is_initialized()``), that connection is used.
        on_done: ``on_done(done, total, label)`` once before the first result (``done == 0``) and after each.
        max_retries: how often Ray re-runs a file whose worker process died.

    Returns:
        one entry per call: ``fn``'s result, or a :class:`Failure` (the worker raised, or died).

    Raises:
        DependencyNotInstalled: Ray is not installed.
        EthimonError: no local instance could start, or the cluster cannot be reached.
    """
    ray = _import_ray()
    total = len(calls)
    out: list[Any] = [None] * total
    if on_done is not None:
        on_done(0, total, labels[0] if total else "")
    if not total:
        return out
    # Ray's driver prints cluster errors (a worker that died, ...) to sys.stdout from a thread: during the
    # run they go to stderr, so that stdout holds only what the command writes there (e.g. --json -)
    with contextlib.redirect_stdout(sys.stderr):
        return _map(ray, fn, calls, labels, out, address, num_cpus, on_done, max_retries)


def _map(ray: Any, fn: Callable[..., Any], calls: Sequence[tuple], labels: Sequence[str], out: list[Any],
         address: str | None, num_cpus: int | None, on_done: ProgressCallback | None, max_retries: int) -> list[Any]:
    total = len(calls)
    started = _connect(ray, address, num_cpus)
    try:
        task = ray.remote(num_cpus=1, max_retries=max_retries)(fn)
        refs = [task.remote(*args) for args in calls]
        index = {ref: i for i, ref in enumerate(refs)}
        pending, done = list(refs), 0
        while pending:
            try:
                ready, pending = ray.wait(pending, num_returns=len(pending), timeout=0.25)
            except Exception as exc:  # noqa: BLE001 - the cluster went away: keep what finished
                lost = Failure(f"the Ray cluster stopped answering ({type(exc).__name__}: {str(exc)[:200]})", exc)
                for ref in pending:
                    out[index[ref]] = lost
                    done += 1
                    if on_done is not None:
                        on_done(done, total, labels[index[ref]])
                break
            for ref in ready:
                i = index[ref]
                try:
                    out[i] = ray.get(ref)
                except Exception as exc:  # noqa: BLE001 - this file's failure; the others still report
                    out[i] = Failure(_why(exc, ray), exc)
                done += 1
                if on_done is not None:
                    on_done(done, total, labels[i])
    finally:
        if started:
            ray.shutdown()
    return out
