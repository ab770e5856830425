"""The one place that talks to Ray: connect (or start a local instance) and map files over workers.

Every unit of work is one file (a scenario file, a bag). A worker returns plain
data (dicts, lists, str, int, float, bool, None); the driver puts the results back
in input order. A unit that raises inside the worker, or whose worker process
dies (after Ray's retries), or that has not returned within the per-file timeout
(its task is then cancelled), becomes one failure for that file: the others still
run and are reported. Ray is imported only here, and only when called.
"""

from __future__ import annotations

import contextlib
import logging
import math
import os
import re
import sys
import time
from collections.abc import Callable, Sequence
from typing import Any

from .._batch import plain  # noqa: F401 - served as ethimon.fleet.plain
from ..errors import DependencyNotInstalled, EthimonError

__all__ = ["DEFAULT_LOCAL_CPUS", "Failure", "check_address", "check_file_timeout", "map_files", "plain"]

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


def check_file_timeout(seconds: float | None, on_ray: bool = True) -> float | None:
    """The ``--file-timeout-s`` of a run: ``None`` (no timeout) or a finite number of seconds above 0.

    Raises:
        EthimonError: a value that is not above 0 or not finite, or a timeout for a run without Ray
            (a serial run checks each file in its own process, where a hung parser cannot be stopped;
            that would need a subprocess per file).
    """
    if seconds is None:
        return None
    if not on_ray:
        raise EthimonError("--file-timeout-s needs --ray (a serial run checks the files in this process, where a "
                           "hung file cannot be stopped; add --ray to run each file as a Ray task)")
    if not isinstance(seconds, (int, float)) or isinstance(seconds, bool) or not math.isfinite(seconds) \
            or seconds <= 0:
        raise EthimonError(f"--file-timeout-s must be a number of seconds above 0, got {seconds!r}")
    return float(seconds)


class Failure:
    """A file whose unit did not return: ``what`` says why in one line (an exception in the worker,
    the worker process died, or it ran past the per-file timeout)."""

    __slots__ = ("what", "exc")

    def __init__(self, what: str, exc: BaseException | None = None) -> None:
        self.what, self.exc = what, exc

    def __repr__(self) -> str:
        return f"Failure({self.what!r})"


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
              on_done: ProgressCallback | None = None, max_retries: int = 1,
              file_timeout: float | None = None) -> list[Any]:
    """Run ``fn(*calls[i])`` on Ray workers, one task per file; the results in input order.

    Args:
        fn: a module-level function (workers import it by name) that returns plain data.
        calls: the arguments of each call; ``labels[i]`` names its file (for the progress bar).
        address: ``None`` a new local instance of ``num_cpus`` CPUs (default at most
            :data:`DEFAULT_LOCAL_CPUS`); else an address for ``ray.init`` (see :func:`check_address`).
            When this process is already connected (``ray.is_initialized()``), that connection is used.
        on_done: ``on_done(done, total, label)`` once before the first result (``done == 0``) and after each.
        max_retries: how often Ray re-runs a file whose worker process died.
        file_timeout: ``None`` no limit; else seconds a file's task may take, counted from when the
            driver hands it to Ray (a worker's start-up and Ray's retries count too). A task past it is
            cancelled (``ray.cancel(force=True)``: its worker process is killed) and the file is a
            :class:`Failure` ("timed out after S s"). So that a file's clock does not run while it waits
            for a CPU, at most as many tasks as the cluster has CPUs (``ray.cluster_resources()``, read
            once at the start) are in flight at a time; on a cluster busy with other jobs a task may still
            wait for a CPU on its clock.

    Returns:
        one entry per call: ``fn``'s result, or a :class:`Failure` (the worker raised, died, or timed out).

    Raises:
        DependencyNotInstalled: Ray is not installed.
        EthimonError: no local instance could start, the cluster cannot be reached, or a bad ``file_timeout``.
    """
    file_timeout = check_file_timeout(file_timeout)
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
        return _map(ray, fn, calls, labels, out, address, num_cpus, on_done, max_retries, file_timeout)


def _timed_out(seconds: float) -> str:
    return f"timed out after {seconds:g} s; its Ray task was cancelled"


def _map(ray: Any, fn: Callable[..., Any], calls: Sequence[tuple], labels: Sequence[str], out: list[Any],
         address: str | None, num_cpus: int | None, on_done: ProgressCallback | None, max_retries: int,
         file_timeout: float | None) -> list[Any]:
    total = len(calls)
    started = _connect(ray, address, num_cpus)
    done = 0

    def finish(i: int, result: Any) -> None:
        nonlocal done
        out[i] = result
        done += 1
        if on_done is not None:
            on_done(done, total, labels[i])

    try:
        task = ray.remote(num_cpus=1, max_retries=max_retries)(fn)
        if file_timeout is None:
            window = total  # every task at once: Ray queues them
        else:  # a task's clock starts when it is submitted: submit no more than can run
            window = max(1, int(ray.cluster_resources().get("CPU", 1)))
        inflight: dict[Any, tuple[int, float]] = {}  # ref -> (index, deadline)
        nxt = 0
        while nxt < total or inflight:
            try:
                while nxt < total and len(inflight) < window:
                    deadline = math.inf if file_timeout is None else time.monotonic() + file_timeout
                    inflight[task.remote(*calls[nxt])] = (nxt, deadline)
                    nxt += 1
                wait_s = 0.25
                if file_timeout is not None:
                    wait_s = min(wait_s, max(0.0, min(d for _, d in inflight.values()) - time.monotonic()))
                refs = list(inflight)
                ready, _ = ray.wait(refs, num_returns=1, timeout=wait_s)
                if ready:  # all that are ready now, not only the first
                    ready, _ = ray.wait(refs, num_returns=len(refs), timeout=0)
            except Exception as exc:  # noqa: BLE001 - the cluster went away: keep what finished
                lost = Failure(f"the Ray cluster stopped answering ({type(exc).__name__}: {str(exc)[:200]})", exc)
                for i in sorted([i for i, _ in inflight.values()] + list(range(nxt, total))):
                    finish(i, lost)
                break
            for ref in ready:
                i, _ = inflight.pop(ref)
                try:
                    res = ray.get(ref)
                except Exception as exc:  # noqa: BLE001 - this file's failure; the others still report
                    res = Failure(_why(exc, ray), exc)
                finish(i, res)
            if file_timeout is not None:
                now = time.monotonic()
                for ref in [r for r, (_, d) in inflight.items() if d <= now]:
                    i, _ = inflight.pop(ref)
                    with contextlib.suppress(Exception):  # a task that ended meanwhile: nothing to cancel
                        ray.cancel(ref, force=True)
                    finish(i, Failure(_timed_out(file_timeout)))
    finally:
        if started:
            ray.shutdown()
    return out
