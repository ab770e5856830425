"""Deterministic stand-in risk estimators for loop and fault-injection tests.

Real small objects with the estimator interface (``probs(text)``, ``model_id``),
each misbehaving in one scripted way.
"""

from __future__ import annotations

import threading


class ScriptedEstimator:
    """Returns ``probs`` (or does ``mode``) on every call; counts calls.

    Modes: ``ok``, ``raise``, ``nan``, ``inf``, ``badsum``, ``wronglen``, ``notseq``,
    ``hang`` (blocks until :meth:`release`), ``die`` (raises SystemExit, which
    ends the worker thread).
    """

    model_id = "scripted-fake@0"

    def __init__(self, probs: tuple[float, float] = (0.95, 0.05), mode: str = "ok") -> None:
        self.p = probs
        self.mode = mode
        self.calls = 0
        self.entered = threading.Event()
        self._release = threading.Event()

    def release(self) -> None:
        self._release.set()

    def probs(self, text: str):
        self.calls += 1
        self.entered.set()
        mode = self.mode
        if mode == "ok":
            return self.p
        if mode == "raise":
            raise RuntimeError("CUDA error: device-side assert")
        if mode == "nan":
            return (float("nan"), 0.5)
        if mode == "inf":
            return (float("inf"), 0.0)
        if mode == "badsum":
            return (0.7, 0.7)
        if mode == "wronglen":
            return (1.0,)
        if mode == "notseq":
            return 0.3
        if mode == "hang":
            self._release.wait(30.0)
            return self.p
        if mode == "die":
            raise SystemExit(3)
        raise AssertionError(mode)


class FakeClock:
    """A clock that only moves when told to."""

    def __init__(self, t: float = 100.0) -> None:
        self.t = t

    def __call__(self) -> float:
        return self.t

    def advance(self, dt: float) -> None:
        self.t += dt


def wait_for(cond, timeout: float = 5.0, poll: float = 0.005) -> bool:
    """Poll ``cond()`` until true or ``timeout`` (generous: the machine is shared)."""
    import time
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if cond():
            return True
        time.sleep(poll)
    return bool(cond())


def run_in_thread(fn, timeout: float = 5.0) -> tuple[bool, dict]:
    """Run ``fn`` in a daemon thread for at most ``timeout`` s: ``(still_running, out)`` where
    ``out`` holds ``"value"`` or ``"exc"`` (any exception, even BaseException) once it returned."""
    out: dict = {}

    def work():
        try:
            out["value"] = fn()
        except BaseException as exc:  # noqa: BLE001
            out["exc"] = exc

    t = threading.Thread(target=work, daemon=True)
    t.start()
    t.join(timeout)
    return t.is_alive(), out
