"""An estimator in a child process (JSON lines over a pipe, no pickle): a hung child is killed."""

from __future__ import annotations

import os
import threading
import time
from collections.abc import Mapping
from typing import Any

from ..errors import EthimonError

__all__ = ["ProcessEstimator"]


class ProcessEstimator:
    """A :class:`~ethimon.risk.ProbsEstimator` that runs the real estimator in a child process.

    A thread stuck inside an estimator cannot be killed; a process can. Each
    :meth:`probs` sends the text to the child (JSON lines over a pipe, no
    pickle) and waits at most ``timeout_s``; a child that does not answer in
    time is killed and respawned on the next call, and the call raises
    :class:`EthimonError` (so :class:`~ethimon.loop.AsyncRiskSource` publishes a fault). Use
    it inside an :class:`~ethimon.loop.AsyncRiskSource`.

    Args:
        factory: ``"module:function"`` that builds the estimator in the child
            (default: ``"ethimon.risk:load_estimator"``), imported by name.
        kwargs: JSON-ready keyword arguments for the factory.
        timeout_s: longest wait for one answer (the first call also waits for
            the child to start and load its model: ``start_timeout_s``).
        start_timeout_s: longest wait for the child to load its model.
        python: interpreter for the child (default: this one).
        env: extra environment variables for the child (e.g. ``PYTHONPATH``).

    Example:
        >>> est = ProcessEstimator("ethimon.risk:load_estimator", {"quantize": "int8"})  # doctest: +SKIP
        >>> src = AsyncRiskSource(est, text="pour the water", rate_hz=20)               # doctest: +SKIP
    """

    #: runs outside this interpreter: it cannot freeze the control loop by holding the GIL
    isolated = True

    def __init__(self, factory: str = "ethimon.risk:load_estimator", kwargs: Mapping[str, Any] | None = None, *,
                 timeout_s: float = 1.0, start_timeout_s: float = 120.0, python: str | None = None,
                 env: Mapping[str, str] | None = None) -> None:
        import json
        import sys
        if not isinstance(factory, str) or factory.count(":") != 1:
            raise ValueError(f"factory={factory!r}; expected 'module:function'")
        self.factory = factory
        kw = dict(kwargs or {})
        if factory == "ethimon.risk:load_estimator":
            kw.setdefault("jit", True)  # trace while starting (start_timeout_s), never mid-run (timeout_s)
            from ..risk import default_threads
            kw.setdefault("num_threads", default_threads(1))  # one text per request: one thread
        self._kwargs_json = json.dumps(kw)
        self.timeout_s = float(timeout_s)
        self.start_timeout_s = float(start_timeout_s)
        self._python = python or sys.executable
        self._env = None if env is None else {**os.environ, **{str(k): str(v) for k, v in env.items()}}
        self._proc = None
        self._buf = b""
        self._lock = threading.Lock()
        self.model_id = f"process:{factory}"
        self.spawns = 0
        self.kills = 0

    def _spawn(self) -> None:
        import json
        import subprocess
        self._proc = subprocess.Popen(
            [self._python, "-c", "from ethimon.loop._process import _worker_main; _worker_main()", self.factory,
             self._kwargs_json], stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
            env=self._env)
        self._buf = b""
        self.spawns += 1
        hello = self._read(self.start_timeout_s)
        msg = json.loads(hello)
        if "error" in msg:
            self.close()
            raise EthimonError(f"estimator process failed to start: {msg['error']}")
        self.model_id = str(msg.get("model_id", self.model_id))

    def _read(self, timeout: float) -> bytes:
        import select
        proc = self._proc
        fd = proc.stdout.fileno()
        deadline = time.monotonic() + timeout
        while b"\n" not in self._buf:
            left = deadline - time.monotonic()
            if left <= 0:
                self._kill()
                raise EthimonError(f"estimator process did not answer within {timeout:g} s: killed")
            ready, _, _ = select.select([fd], [], [], left)
            if ready:
                chunk = os.read(fd, 65536)
                if not chunk:
                    code = proc.poll()
                    self._proc = None
                    raise EthimonError(f"estimator process exited (code {code})")
                self._buf += chunk
        line, _, self._buf = self._buf.partition(b"\n")
        return line

    def _kill(self) -> None:
        proc, self._proc = self._proc, None
        if proc is not None:
            self.kills += 1
            try:
                proc.kill()
                proc.wait(5.0)
            except Exception:  # noqa: BLE001
                pass

    def probs(self, text: str) -> tuple[float, ...]:
        """Class probabilities from the child (raises :class:`EthimonError` on timeout/crash)."""
        import json
        with self._lock:
            if self._proc is None or self._proc.poll() is not None:
                self._spawn()
            try:
                self._proc.stdin.write(json.dumps({"text": text}).encode() + b"\n")
                self._proc.stdin.flush()
            except (BrokenPipeError, OSError) as exc:
                self._kill()
                raise EthimonError(f"estimator process pipe broken: {exc}") from None
            msg = json.loads(self._read(self.timeout_s))
        if "error" in msg:
            raise EthimonError(f"estimator process: {msg['error']}")
        return tuple(msg["p"])

    def close(self) -> None:
        """Stop the child process."""
        proc, self._proc = self._proc, None
        if proc is not None:
            try:
                proc.stdin.close()
                proc.wait(2.0)
            except Exception:  # noqa: BLE001
                proc.kill()

    def __del__(self) -> None:  # pragma: no cover - best effort
        try:
            self._kill()
        except Exception:  # noqa: BLE001
            pass


def _worker_main() -> None:
    """Child side of :class:`ProcessEstimator`: JSON lines in, JSON lines out."""
    import importlib
    import json
    import sys
    out = sys.stdout.buffer

    def send(obj: dict) -> None:
        out.write(json.dumps(obj).encode() + b"\n")
        out.flush()

    try:
        mod, _, name = sys.argv[1].partition(":")
        est = getattr(importlib.import_module(mod), name)(**json.loads(sys.argv[2]))
    except Exception as exc:  # noqa: BLE001
        send({"error": f"{type(exc).__name__}: {exc}"[:500]})
        return
    send({"ready": True, "model_id": str(getattr(est, "model_id", type(est).__name__))})
    for line in sys.stdin.buffer:
        try:
            p = est.probs(json.loads(line)["text"])
            send({"p": [float(v) for v in p]})
        except Exception as exc:  # noqa: BLE001
            send({"error": f"{type(exc).__name__}: {exc}"[:500]})
