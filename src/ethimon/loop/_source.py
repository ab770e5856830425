"""The risk side of the loop: an estimator run in its own thread, read without blocking.

:class:`AsyncRiskSource` runs any :class:`~ethimon.risk.ProbsEstimator` at its own rate and publishes
``(probs, time)`` snapshots; readers (the control loop) never wait for it.
"""

from __future__ import annotations

import math
import threading
import time
from collections.abc import Callable
from typing import Any, NamedTuple

from ..risk import ProbsEstimator, as_estimator

__all__ = ["AsyncRiskSource", "RiskReading", "AsyncJudgeSource"]


class RiskReading(NamedTuple):
    """A snapshot of an :class:`AsyncRiskSource`.

    Attributes:
        probs: class probabilities for the *current* task text, or ``None``.
        age_s: seconds since the estimate's inference started (``inf`` if none).
        fault: why the reading must not be trusted (raised, NaN, hung, dead, no
            estimate yet), or ``None``.
        count: how many estimates have been published (any text).
        pending_s: while the estimate is only awaited (no task text yet, or none yet for the current
            text), the seconds waited for it (``0.0`` while there is no text: nothing to wait for);
            ``None`` otherwise. The monitor holds the arm (the pending hold, stop 2) while it is within
            the estimate's age limit and fails closed past it.
    """

    probs: tuple[float, ...] | None
    age_s: float
    fault: str | None
    count: int
    pending_s: float | None = None


def _as_floats(out: Any) -> tuple[tuple[float, ...] | None, str | None]:
    """The estimator's output read once into a tuple of floats (its validity is the monitor's to judge)."""
    try:
        return tuple(float(v) for v in out), None
    except Exception:  # noqa: BLE001 - any odd return value is a fault
        return None, f"risk estimator returned {type(out).__name__}, not a sequence of probabilities"


def _hand_over(estimator: Any) -> ProbsEstimator:
    """The estimator ``estimator`` stands for (:func:`ethimon.risk.as_estimator`: an object with
    ``probs(text)``, a function ``text -> probabilities``, a zero-argument factory, a model directory);
    ``None`` is refused here: a source never loads the shipped model unasked."""
    if estimator is None:
        raise TypeError("estimator needs a probs(text) method (or anything ethimon.risk.as_estimator takes), "
                        "got None")
    return as_estimator(estimator)


class AsyncRiskSource:
    """Runs a risk estimator in its own thread at its own rate; readers never block.

    Args:
        estimator: an object with ``probs(text)`` (see :class:`~ethimon.risk.ProbsEstimator`).
        text: the task text to score (``None``: no task yet; readings then carry a fault).
        rate_hz: estimates per second (an estimate that takes longer simply delays the next).
        hang_timeout_s: an inference running longer than this is reported as hung
            (default: ``max(0.25, 5 / rate_hz)``).
        clock: monotonic time source in seconds (inject a fake one in tests).
        start: start the worker thread now.

    A returned value is read once into a tuple of floats before it is published;
    one that is not a sequence of numbers is a fault, as is an exception. A
    fault replaces the previous estimate (never a silent fallback to an older,
    lower risk). Whether the probabilities are usable (count, NaN/inf, [0, 1],
    sum 1) is judged in one place, by the monitor that reads them (the same rule
    for every risk input: :func:`ethimon.runtime._inputs.as_probs`). :meth:`restart` abandons a hung worker and
    starts a fresh one (optionally with a new estimator) while readers keep
    reading; a thread blocked inside the estimator cannot be killed, so it is
    left as an abandoned daemon and its late result is discarded.

    Example:
        >>> class Fixed:
        ...     def probs(self, text):
        ...         return (0.9, 0.1)
        >>> src = AsyncRiskSource(Fixed(), text="hand over the cup", start=False)
        >>> src.poll_once().probs
        (0.9, 0.1)
        >>> src.set_text("new task")
        >>> src.snapshot().fault
        'no risk estimate yet for the current task text'
    """

    def __init__(self, estimator: ProbsEstimator, *, text: str | None = None, rate_hz: float = 20.0,
                 hang_timeout_s: float | None = None, clock: Callable[[], float] = time.monotonic,
                 start: bool = True) -> None:
        estimator = _hand_over(estimator)
        if not (isinstance(rate_hz, (int, float)) and 0.0 < rate_hz <= 10_000.0):
            raise ValueError(f"rate_hz={rate_hz!r}; expected a number in (0, 10000]")
        self._est = estimator
        self.rate_hz = float(rate_hz)
        self.hang_timeout_s = float(hang_timeout_s) if hang_timeout_s is not None else max(0.25, 5.0 / rate_hz)
        self._clock = clock
        self._text = text
        self._text_gen = 0
        self._text_t = clock()  # when the current text was set: its estimate is awaited from then
        # (probs, stamp, fault, text_gen, count): replaced as one object, read without locks
        self._state: tuple = (None, None, None, -1, 0)
        self._busy: tuple | None = None  # (worker gen, start time) while an inference runs
        self._gen = 0
        self._thread: threading.Thread | None = None
        self._stop = threading.Event()
        self._lock = threading.Lock()
        self.restarts = 0
        self.abandoned_threads = 0
        self.errors = 0
        if start:
            self.start()

    # ------------------------------------------------------------------ public
    @property
    def model_id(self) -> str:
        """The estimator's ``model_id`` (its class name if it has none)."""
        return str(getattr(self._est, "model_id", type(self._est).__name__))

    @property
    def text(self) -> str | None:
        """The task text being scored."""
        return self._text

    @property
    def estimator(self) -> ProbsEstimator:
        """The estimator being run."""
        return self._est

    @property
    def isolated(self) -> bool:
        """Whether the estimator runs outside this interpreter (a :class:`ProcessEstimator`).

        ``False`` means it shares the GIL with the control loop: an estimator
        that holds the GIL freezes the loop and its watchdog (see the module doc).
        """
        return bool(getattr(self._est, "isolated", False))

    def set_text(self, text: str | None) -> None:
        """Score a new task text; until its first estimate, readings carry a fault."""
        with self._lock:
            self._text_t = self._clock()
            self._text = text
            self._text_gen += 1

    def latest(self) -> tuple[tuple[float, ...] | None, float]:
        """``(probs, age_s)`` of the newest estimate for the current text, without blocking.

        ``probs`` is ``None`` (and ``age_s`` is ``inf``) when the reading has a
        fault; see :meth:`snapshot` for the reason.
        """
        r = self.snapshot()
        return r.probs, r.age_s

    def snapshot(self) -> RiskReading:
        """The newest reading with its fault, if any (hung, dead, raised, bad value, none yet)."""
        probs, stamp, fault, tgen, count = self._state
        now = self._clock()
        age = math.inf if stamp is None else max(0.0, now - stamp)
        busy = self._busy
        if busy is not None and busy[0] == self._gen and now - busy[1] > self.hang_timeout_s:
            fault = (f"risk estimator hung: inference running for {now - busy[1]:.3f} s "
                     f"(hang_timeout_s {self.hang_timeout_s:g})")
        elif self._thread is not None and not self._thread.is_alive() and not self._stop.is_set():
            fault = "risk estimator thread died"
        elif self._text is None:
            return RiskReading(None, math.inf, "no task text to score", count, 0.0)
        elif fault is None and (probs is None or tgen != self._text_gen):
            return RiskReading(None, math.inf, "no risk estimate yet for the current task text", count,
                               max(0.0, now - self._text_t))
        if fault is not None:
            return RiskReading(None, math.inf, fault, count)
        return RiskReading(probs, age, None, count)

    @property
    def fault(self) -> str | None:
        """The current fault reason (``None`` when the latest reading is usable)."""
        return self.snapshot().fault

    def poll_once(self) -> RiskReading:
        """Run one estimate now in the calling thread and publish it (tests, manual driving)."""
        self._estimate(self._gen)
        return self.snapshot()

    def start(self) -> None:
        """Start the worker thread (no-op if it runs)."""
        with self._lock:
            if self._thread is not None and self._thread.is_alive():
                return
            self._stop.clear()
            gen = self._gen
            t = threading.Thread(target=self._run, args=(gen,), name=f"ethimon-risk-{gen}", daemon=True)
            self._thread = t
        t.start()

    def stop(self, timeout: float = 1.0) -> None:
        """Stop the worker (waits up to ``timeout`` for an inference to finish)."""
        self._stop.set()
        t = self._thread
        if t is not None and t is not threading.current_thread():
            t.join(timeout)

    def restart(self, estimator: ProbsEstimator | None = None) -> None:
        """Abandon the current worker (hung or not) and start a fresh one.

        Readers are never blocked; until the new worker publishes, readings
        carry a fault. Args: ``estimator``: a replacement (default: the same one).
        """
        if estimator is not None:
            estimator = _hand_over(estimator)
        with self._lock:
            old = self._thread
            self._gen += 1
            if estimator is not None:
                self._est = estimator
            self._busy = None
            self._state = (None, None, "risk estimator restarting", self._text_gen, self._state[4])
            self.restarts += 1
            if old is not None and old.is_alive():
                self.abandoned_threads += 1
            self._thread = None
        self._stop = threading.Event()
        self.start()

    def __enter__(self) -> "AsyncRiskSource":
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop()

    def __repr__(self) -> str:
        r = self.snapshot()
        return f"AsyncRiskSource(model={self.model_id!r}, rate_hz={self.rate_hz:g}, fault={r.fault!r})"

    # ------------------------------------------------------------------ worker
    def _run(self, gen: int) -> None:
        stop = self._stop
        period = 1.0 / self.rate_hz
        nxt = time.monotonic()
        while not stop.is_set() and gen == self._gen:
            self._estimate(gen)
            nxt += period
            wait = nxt - time.monotonic()
            if wait < 0.0:
                nxt = time.monotonic()
                wait = 0.0
            stop.wait(wait)

    def _estimate(self, gen: int) -> None:
        text, tgen, est = self._text, self._text_gen, self._est
        if text is None:
            return
        t0 = self._clock()
        self._busy = (gen, t0)
        try:
            out = est.probs(text)
        except Exception as exc:  # noqa: BLE001 - every failure is a published fault
            probs, fault = None, f"risk estimator raised {type(exc).__name__}: {exc}"[:300]
        else:
            probs, fault = _as_floats(out)
        finally:
            if self._busy is not None and self._busy[0] == gen:
                self._busy = None
        if gen != self._gen:  # abandoned by restart(): drop the late result
            return
        if fault is not None:
            self.errors += 1
        self._state = (probs, t0, fault, tgen, self._state[4] + 1)


class AsyncJudgeSource:
    """Asks a judge (:class:`~ethimon.risk.Judge`) about each distinct task text once, off the control loop.

    :meth:`ask` queues a text (a no-op for one already answered, queued or being asked); :meth:`result`
    returns its :class:`~ethimon.risk.JudgeResult` without blocking, ``None`` while the answer is
    pending (the monitor then has no judgement: in the confirm band the arm holds). Up to
    ``max_workers`` texts are asked at once, newest first, so a slow call for one text never queues
    another text's answer. Answers are kept by the text's sha256; every call's result is also queued
    for the audit trail (:meth:`drain`).

    Args:
        judge: an object with ``judge(text) -> JudgeResult`` (a :class:`~ethimon.risk.Judge` or
            :class:`~ethimon.risk.JudgePanel`).
        max_texts: how many texts' answers are kept (oldest dropped first).
        max_workers: how many texts are asked at once (each call is bounded by the judge's deadline).
        start: start asking now (else :meth:`work_once` drives it).

    Example:
        >>> from ethimon.risk import JudgeResult
        >>> class Always:
        ...     def judge(self, text):
        ...         return JudgeResult(0.05, "ok", 0.01, "0", 0.05, "m", "h")
        >>> src = AsyncJudgeSource(Always(), start=False)
        >>> src.ask("wipe the table"); src.result("wipe the table") is None
        True
        >>> _ = src.work_once(); src.result("wipe the table").p_unsafe
        0.05
    """

    def __init__(self, judge: Any, *, max_texts: int = 4096, max_workers: int = 4, start: bool = True) -> None:
        if not callable(getattr(judge, "judge", None)):
            raise TypeError(f"judge needs a judge(text) method, got {type(judge).__name__}")
        if not (isinstance(max_workers, int) and 1 <= max_workers <= 64):
            raise ValueError(f"max_workers={max_workers!r}; expected an int in [1, 64]")
        self._judge = judge
        self._max = int(max_texts)
        self._max_workers = max_workers
        self._done: dict[str, Any] = {}
        self._queued: list[tuple[str, str]] = []  # (hash, text), oldest first
        self._queued_set: set[str] = set()
        self._inflight: set[str] = set()
        self._cv = threading.Condition()
        self._log: list[Any] = []
        self._stop = False
        self._running = False
        self._workers = 0
        self._threads: list[threading.Thread] = []
        self.calls = 0
        if start:
            self.start()

    @property
    def judge(self) -> Any:
        return self._judge

    @property
    def canary_state(self) -> str:
        """The judge's canary state (``"off"`` for a judge without canaries)."""
        return str(getattr(self._judge, "canary_state", "off"))

    @staticmethod
    def key(text: str) -> str:
        from ..risk import text_sha256
        return text_sha256(text)

    def ask(self, text: str | None, key: str | None = None) -> None:
        """Queue ``text`` for the judge unless it was answered, queued or is being asked already."""
        if text is None:
            return
        h = key or self.key(text)
        with self._cv:
            if h in self._done or h in self._queued_set or h in self._inflight:
                return
            self._queued.append((h, text))
            self._queued_set.add(h)
            self._spawn()

    def result(self, text: str | None, key: str | None = None) -> Any:
        """The judge's answer for ``text``, or ``None`` while none is in (never blocks)."""
        if text is None:
            return None
        return self._done.get(key or self.key(text))

    def drain(self) -> list[Any]:
        """The results published since the last call (for the audit trail)."""
        with self._cv:
            out, self._log = self._log, []
        return out

    def work_once(self) -> bool:
        """Answer the oldest queued text in the calling thread (tests, manual driving)."""
        with self._cv:
            if not self._queued:
                return False
            h, text = self._queued.pop(0)
            self._queued_set.discard(h)
            self._inflight.add(h)
        self._answer(h, text)
        return True

    def _answer(self, h: str, text: str) -> None:
        try:
            res = self._judge.judge(text)
        except Exception as exc:  # noqa: BLE001 - a judge that raises gives no judgement
            from ..risk import JudgeResult
            res = JudgeResult(None, "error", 0.0, None, None, str(getattr(self._judge, "model", "")), h,
                              f"judge raised {type(exc).__name__}"[:200])
        with self._cv:
            self.calls += 1
            self._done[h] = res
            while len(self._done) > self._max:
                self._done.pop(next(iter(self._done)))
            self._inflight.discard(h)
            self._log.append(res)

    def _spawn(self) -> None:
        """Start workers for queued texts, up to ``max_workers`` (with ``self._cv`` held)."""
        if not self._running or self._stop:
            return
        # a worker not asking a text is about to take one or to exit: start one per queued text beyond them
        while self._workers < self._max_workers and self._workers - len(self._inflight) < len(self._queued):
            self._workers += 1
            t = threading.Thread(target=self._run, name="ethimon-judge", daemon=True)
            self._threads = [x for x in self._threads if x.is_alive()] + [t]
            t.start()

    def start(self) -> None:
        with self._cv:
            self._stop = False
            self._running = True
            self._spawn()

    def stop(self, timeout: float = 1.0) -> None:
        with self._cv:
            self._stop = True
            self._running = False
            self._cv.notify_all()
            threads = list(self._threads)
        end = time.monotonic() + timeout
        for t in threads:
            if t is not threading.current_thread():
                t.join(max(0.0, end - time.monotonic()))

    def _run(self) -> None:
        while True:
            with self._cv:
                if self._stop or not self._queued:
                    self._workers -= 1
                    return
                h, text = self._queued.pop()  # newest first: the text the arm waits on now
                self._queued_set.discard(h)
                self._inflight.add(h)
            self._answer(h, text)

    def __repr__(self) -> str:
        return (f"AsyncJudgeSource(judge={self._judge!r}, answered={len(self._done)}, queued={len(self._queued)}, "
                f"asking={len(self._inflight)})")
