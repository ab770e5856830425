"""A watchdog thread that fires when the control loop stops kicking it."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

__all__ = ["Watchdog"]


class Watchdog:
    """Calls ``on_timeout(reason)`` from its own thread when :meth:`kick` stops coming.

    The control loop kicks it every cycle; if the loop itself stalls (a blocked
    driver call, a GC pause, a stuck signal source) nothing steps the monitor,
    so the watchdog is the only place left to trigger a stop (e.g. the robot's
    hardware stop). It fires once per stall.

    The watchdog thread shares the interpreter: if another thread holds the GIL
    (an in-process estimator stuck in C code), it is frozen too and cannot fire
    while the stall lasts. :meth:`kick` therefore checks the gap itself: a
    stall the thread did not report fires ``on_timeout`` when the loop resumes
    (late, but never lost).

    Args:
        timeout_s: longest allowed gap between kicks.
        on_timeout: called with a one-line reason; it must be quick and must not raise.
        clock: monotonic time source.
    """

    def __init__(self, timeout_s: float, on_timeout: Callable[[str], None], *,
                 clock: Callable[[], float] = time.monotonic) -> None:
        if not timeout_s > 0:
            raise ValueError(f"timeout_s={timeout_s!r}; expected > 0")
        self.timeout_s = float(timeout_s)
        self._on_timeout = on_timeout
        self._clock = clock
        self._last = clock()
        self._fired = False
        self.fired_count = 0
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None

    def kick(self) -> str | None:
        """The loop is alive. Fires now (and returns the reason) for a stall the thread could not report."""
        now = self._clock()
        gap = now - self._last
        reason = None
        if gap > self.timeout_s and not self._fired:
            self._fired = True
            self.fired_count += 1
            reason = (f"control loop stalled: no cycle for {gap * 1e3:.1f} ms (watchdog {self.timeout_s * 1e3:g} ms; "
                      "detected after it ended: the watchdog thread could not run either, e.g. another "
                      "thread held the GIL)")
            try:
                self._on_timeout(reason)
            except Exception:  # noqa: BLE001
                pass
        self._last = now
        self._fired = False
        return reason

    def check(self) -> str | None:
        """Fire if overdue; returns the reason when it fired now (also used by the thread)."""
        gap = self._clock() - self._last
        if gap > self.timeout_s and not self._fired:
            self._fired = True
            self.fired_count += 1
            reason = f"control loop stalled: no cycle for {gap * 1e3:.1f} ms (watchdog {self.timeout_s * 1e3:g} ms)"
            try:
                self._on_timeout(reason)
            except Exception:  # noqa: BLE001 - the watchdog itself must keep running
                pass
            return reason
        return None

    def start(self) -> "Watchdog":
        self._last = self._clock()  # the time before start() is not a stall (the loop was not running)
        self._fired = False
        self._stop.clear()
        self._thread = threading.Thread(target=self._run, name="ethimon-watchdog", daemon=True)
        self._thread.start()
        return self

    def stop(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(1.0)

    def _run(self) -> None:
        poll = min(self.timeout_s / 4.0, 0.01)
        while not self._stop.wait(poll):
            self.check()
