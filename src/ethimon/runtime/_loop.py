"""Multi-rate governed control loop: async risk estimator, watchdog, hot spec reload.

The risk estimator is slow (10–50 Hz) and the monitor fast (up to 1 kHz), so
they run apart: :class:`AsyncRiskSource` runs the estimator in its own thread
on the current task text and publishes ``(probs, time)`` snapshots;
:class:`GovernedLoop` steps the monitor every cycle with the latest snapshot
(``p`` and ``risk_age_s``) and never waits for the estimator.

Everything that can go wrong around the monitor ends in an override with the
reason in ``Decision.faults``: an estimator that raises, returns NaN/inf or
probabilities that do not sum to 1, hangs or dies; a stale estimate; a control
cycle that misses its deadline; a loop that stalled between two cycles (found
when it resumes, even if the whole interpreter was frozen); a signal source that
raises; an audit log that is closed, broken, full or behind its lag bounds.
The one loop::

    loop = GovernedLoop(Monitor(load_spec("specs/governor.yaml")), signals=read_sensors,
                        risk=AsyncRiskSource(load_estimator(), text=task), period_s=0.001,
                        audit=AuditLog("run.jsonl"))
    loop.run(duration_s=60)      # or call loop.cycle() from your own timer

A spec is reloaded with :meth:`GovernedLoop.reload`: compiled (and optionally
verified) in the caller's thread, swapped in between two cycles; an invalid
spec is rejected and the running one stays, and so is a spec that *weakens*
monitoring (see :func:`weakenings`) unless ``allow_weaker=True`` is passed.

Estimator isolation. An estimator running in a thread of this interpreter
(any plain object given to :class:`AsyncRiskSource`) shares the GIL with the
loop and its watchdog: an estimator that holds the GIL (a C extension that
does not release it, a catastrophic regular expression) freezes the loop, the
watchdog *and* the hang detection until it returns. Nothing in the same
interpreter can interrupt that; the loop only finds the stall afterwards and
overrides then (``LoopStats.stalls``). Run the estimator in a child process
(:class:`ProcessEstimator`: ``GovernedLoop(..., risk="ethimon.risk:load_estimator")``
does that) so that the loop keeps its rate and a stuck child is killed. In-process
estimators stay supported because a child process needs an importable
``module:function`` factory with JSON arguments (no pickled objects cross the
boundary), loads its own copy of the model and costs a process start.
"""

from __future__ import annotations

import math
import os
import re
import threading
import time
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import Future
from dataclasses import dataclass, field
from typing import Any, NamedTuple, Protocol, runtime_checkable

from ..errors import EthimonError
from ..risk._formula import release_bound
from ..spec._model import Spec
from ._decision import Decision
from ._monitor import Monitor

__all__ = ["AsyncRiskSource", "GovernedLoop", "LoopStats", "ProbEstimator", "ProcessEstimator", "ReloadResult",
           "RiskReading", "Watchdog", "weakenings"]


@runtime_checkable
class ProbEstimator(Protocol):
    """Anything with ``probs(text) -> (p_0, ..., p_{K-1})``, e.g. :func:`ethimon.risk.load_estimator`."""

    def probs(self, text: str) -> Sequence[float]: ...


class RiskReading(NamedTuple):
    """A snapshot of an :class:`AsyncRiskSource`.

    Attributes:
        probs: class probabilities for the *current* task text, or ``None``.
        age_s: seconds since the estimate's inference started (``inf`` if none).
        fault: why the reading must not be trusted (raised, NaN, hung, dead, no
            estimate yet), or ``None``.
        count: how many estimates have been published (any text).
    """

    probs: tuple[float, ...] | None
    age_s: float
    fault: str | None
    count: int


def _check_probs(out: Any, classes: int | None, tol: float) -> tuple[tuple[float, ...] | None, str | None]:
    try:
        p = tuple(float(v) for v in out)
    except Exception:  # noqa: BLE001 - any odd return value is a fault
        return None, f"risk estimator returned {type(out).__name__}, not a sequence of probabilities"
    if len(p) < 2 or (classes is not None and len(p) != classes):
        want = classes if classes is not None else "at least 2"
        return None, f"risk estimator returned {len(p)} probabilities, expected {want}"
    for v in p:
        if not (0.0 <= v <= 1.0):
            return None, f"risk estimator returned {_short(p)}: NaN/inf or outside [0, 1]"
    s = math.fsum(p)
    if abs(s - 1.0) > tol:
        return None, f"risk estimator returned {_short(p)}, which sums to {s:.6g}, not 1"
    return p, None


def _short(p: tuple[float, ...]) -> str:
    text = "(" + ", ".join(f"{v:.4g}" for v in p[:6]) + (", ..." if len(p) > 6 else "") + ")"
    return text


class AsyncRiskSource:
    """Runs a risk estimator in its own thread at its own rate; readers never block.

    Args:
        estimator: an object with ``probs(text)`` (see :class:`ProbEstimator`).
        text: the task text to score (``None``: no task yet; readings then carry a fault).
        rate_hz: estimates per second (an estimate that takes longer simply delays the next).
        hang_timeout_s: an inference running longer than this is reported as hung
            (default: ``max(0.25, 5 / rate_hz)``).
        classes: expected number of probabilities (``None``: any ``>= 2``).
        sum_tol: allowed ``|sum(p) - 1|``.
        clock: monotonic time source in seconds (inject a fake one in tests).
        start: start the worker thread now.

    A returned value is checked before it is published: not a sequence of
    numbers, NaN/inf, outside [0, 1] or not summing to 1 is a fault, as is an
    exception. A fault replaces the previous estimate (never a silent fallback
    to an older, lower risk). :meth:`restart` abandons a hung worker and
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

    def __init__(self, estimator: ProbEstimator, *, text: str | None = None, rate_hz: float = 20.0,
                 hang_timeout_s: float | None = None, classes: int | None = None, sum_tol: float = 1e-3,
                 clock: Callable[[], float] = time.monotonic, start: bool = True) -> None:
        if not callable(getattr(estimator, "probs", None)):
            raise TypeError(f"estimator needs a probs(text) method, got {type(estimator).__name__}")
        if not (isinstance(rate_hz, (int, float)) and 0.0 < rate_hz <= 10_000.0):
            raise ValueError(f"rate_hz={rate_hz!r}; expected a number in (0, 10000]")
        self._est = estimator
        self.rate_hz = float(rate_hz)
        self.hang_timeout_s = float(hang_timeout_s) if hang_timeout_s is not None else max(0.25, 5.0 / rate_hz)
        self.classes = classes
        self.sum_tol = float(sum_tol)
        self._clock = clock
        self._text = text
        self._text_gen = 0
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
    def estimator(self) -> ProbEstimator:
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
            fault = "no task text to score"
        elif fault is None and (probs is None or tgen != self._text_gen):
            fault = "no risk estimate yet for the current task text"
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

    def restart(self, estimator: ProbEstimator | None = None) -> None:
        """Abandon the current worker (hung or not) and start a fresh one.

        Readers are never blocked; until the new worker publishes, readings
        carry a fault. Args: ``estimator``: a replacement (default: the same one).
        """
        if estimator is not None and not callable(getattr(estimator, "probs", None)):
            raise TypeError(f"estimator needs a probs(text) method, got {type(estimator).__name__}")
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
            probs, fault = _check_probs(out, self.classes, self.sum_tol)
        finally:
            if self._busy is not None and self._busy[0] == gen:
                self._busy = None
        if gen != self._gen:  # abandoned by restart(): drop the late result
            return
        if fault is not None:
            self.errors += 1
        self._state = (probs, t0, fault, tgen, self._state[4] + 1)


class ProcessEstimator:
    """A :class:`ProbEstimator` that runs the real estimator in a child process.

    A thread stuck inside an estimator cannot be killed; a process can. Each
    :meth:`probs` sends the text to the child (JSON lines over a pipe, no
    pickle) and waits at most ``timeout_s``; a child that does not answer in
    time is killed and respawned on the next call, and the call raises
    :class:`EthimonError` (so :class:`AsyncRiskSource` publishes a fault). Use
    it inside an :class:`AsyncRiskSource`.

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
        self._kwargs_json = json.dumps(dict(kwargs or {}))
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
            [self._python, "-c", "from ethimon.runtime._loop import _worker_main; _worker_main()", self.factory,
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
        self.kick()
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


@dataclass
class ReloadResult:
    """Outcome of :meth:`GovernedLoop.reload`.

    Attributes:
        ok: compiled (and verified) and queued for the swap; ``False``: rejected,
            the running spec stays.
        source: the path (or ``"<Spec>"``) that was loaded.
        spec_sha256: hash of the new spec (``None`` if it did not load).
        error: why it was rejected.
        applied: set once the loop has swapped it in (``wait_applied``).
        weakened: how the new spec weakens, or may weaken, monitoring compared
            with the running one (see :func:`weakenings`); non-empty only when
            refused for it or accepted with ``allow_weaker=True``.
        unjudged: the entries of ``weakened`` whose direction cannot be told
            (condition texts, constants, ...): refused like any weakening.
    """

    ok: bool
    source: str
    spec_sha256: str | None = None
    error: str | None = None
    applied: threading.Event = field(default_factory=threading.Event, repr=False)
    applied_at_cycle: int | None = None
    weakened: tuple[str, ...] = ()
    unjudged: tuple[str, ...] = ()

    def wait_applied(self, timeout: float | None = None) -> bool:
        """Block until the loop has swapped the new spec in (``False`` on timeout or rejection)."""
        return self.ok and self.applied.wait(timeout)


@dataclass
class LoopStats:
    """Counters of a :class:`GovernedLoop` (read them any time)."""

    cycles: int = 0
    overrides: int = 0
    fault_cycles: int = 0
    deadline_misses: int = 0
    skipped_slots: int = 0
    risk_faults: int = 0
    stale_overrides: int = 0
    audit_drops: int = 0
    audit_records: int = 0
    audit_faults: int = 0
    stalls: int = 0
    reloads_applied: int = 0
    reloads_rejected: int = 0
    max_cycle_s: float = 0.0
    max_late_s: float = 0.0
    max_gap_s: float = 0.0

    def as_dict(self) -> dict:
        return dict(self.__dict__)


def _verify_smt(spec: Spec) -> None:
    """Reject a spec unless every decision-logic property is proved (``ethimon.verify``, z3)."""
    from ..verify import verify_spec
    rep = verify_spec(spec, lints=False)
    if rep.exit_code != 0:
        bad = [f"{f.name}: {f.status}" for f in rep.findings if f.kind == "property"
               and f.status in ("refuted", "unknown")]
        raise EthimonError("verification failed: " + ("; ".join(bad) if bad else str(rep.error)))


def _sev(response: Any) -> int:
    from ..spec._model import Response
    return Response(response).severity


#: the reason attached to every change whose direction :func:`weakenings` cannot judge
CANNOT_TELL = "cannot tell whether this change weakens monitoring"


def _same_text(a: str | None, b: str | None) -> bool:
    """Equal condition texts up to whitespace (``x>=1`` and ``x >= 1`` still differ: not judged)."""
    if a is None or b is None:
        return a is b
    return " ".join(a.split()) == " ".join(b.split())


def weakenings(old: Spec, new: Spec, *, loop_max_age_s: float | None = None) -> tuple[list[str], list[str]]:
    """How ``new`` weakens monitoring compared with ``old``, judged field by field.

    Weaker (each one line in the first list): an obligation removed; an
    obligation's response less severe, a ``when`` added where there was none,
    ``within_cycles`` added or raised; τ raised; a risk weight (α, β, γ) lowered
    or the variance changed from sample to population (R_e smaller); the unsafe
    class or the number of classes changed; ``risk.response`` or ``on_fault``
    less severe; release mode manual → auto; the release bound τ − δ raised
    (hysteresis shrunk relative to τ) or ``hold_cycles`` lowered; the effective
    estimate age limit removed or raised (``risk.max_age_s``, else the loop's
    ``loop_max_age_s``); a signal's range widened or removed; the safe pose's
    joint-speed limit or tolerance raised.

    Cannot be judged field by field, so counted as possible weakenings too (in the
    first list, each ending in :data:`CANNOT_TELL`; the second list repeats just
    these): the text of a ``require`` or ``when`` that changed (beyond
    whitespace), a constant's value, a signal's type, the safe pose's joints, the
    estimator settings, the ``risk.allow`` opt-outs. ``require: 'true'`` or a
    constant ``min_d: -1`` would otherwise switch a check off unnoticed.

    Returns:
        ``(weakenings, cannot_tell)``; ``cannot_tell`` is a sublist of ``weakenings``.
    """
    weak: list[str] = []
    unjudged: list[str] = []
    old_obs = {o.id: o for o in old.obligations}
    new_obs = {o.id: o for o in new.obligations}
    for oid, o in old_obs.items():
        n = new_obs.get(oid)
        if n is None:
            weak.append(f"obligation {oid} removed")
            continue
        if _sev(n.response) < _sev(o.response):
            weak.append(f"obligation {oid}: response {o.response} -> {n.response} (less severe)")
        if o.when is None and n.when is not None:
            weak.append(f"obligation {oid}: when added ({n.when!r}): require is no longer checked every cycle")
        elif n.when is not None and not _same_text(o.when, n.when):
            unjudged.append(f"obligation {oid}: when changed ({o.when!r} -> {n.when!r})")
        if not _same_text(o.require, n.require):
            unjudged.append(f"obligation {oid}: require changed ({o.require!r} -> {n.require!r})")
        ow, nw = o.within_cycles or 0, n.within_cycles or 0
        if nw > ow:
            weak.append(f"obligation {oid}: within_cycles {ow} -> {nw} (more cycles to respond)")
    ro, rn = old.risk, new.risk
    if rn.threshold > ro.threshold:
        weak.append(f"risk.threshold raised {ro.threshold!r} -> {rn.threshold!r} (overrides fire at a higher R_e)")
    for w in ("alpha", "beta", "gamma"):
        if getattr(rn, w) < getattr(ro, w):
            weak.append(f"risk.{w} lowered {getattr(ro, w)!r} -> {getattr(rn, w)!r} (R_e smaller)")
    if ro.variance == "sample" and rn.variance == "population":
        weak.append("risk.variance sample -> population (R_e smaller)")
    if ro.classes != rn.classes or ro.unsafe_index % ro.classes != rn.unsafe_index % rn.classes:
        weak.append(f"risk classes/unsafe_index changed ({ro.classes}/{ro.unsafe_index} -> "
                    f"{rn.classes}/{rn.unsafe_index}): what counts as unsafe is redefined")
    if _sev(rn.response) < _sev(ro.response):
        weak.append(f"risk.response {ro.response} -> {rn.response} (less severe)")
    if _sev(new.on_fault) < _sev(old.on_fault):
        weak.append(f"on_fault {old.on_fault} -> {new.on_fault} (less severe)")
    if ro.release.mode == "manual" and rn.release.mode == "auto":
        weak.append("release mode manual -> auto (a latched override now releases by itself)")
    elif rn.release.mode == "auto":
        bo = release_bound(ro.threshold, ro.release.hysteresis)[0]
        bn = release_bound(rn.threshold, rn.release.hysteresis)[0]
        if bn > bo:
            weak.append(f"release bound τ − δ raised {float(bo):g} -> {float(bn):g} (hysteresis "
                        f"{ro.release.hysteresis!r} -> {rn.release.hysteresis!r}: a latch releases at a higher R_e)")
        if rn.release.hold_cycles < ro.release.hold_cycles:
            weak.append(f"release hold_cycles lowered {ro.release.hold_cycles} -> {rn.release.hold_cycles}")
    ao = ro.max_age_s if ro.max_age_s is not None else loop_max_age_s
    an = rn.max_age_s if rn.max_age_s is not None else loop_max_age_s
    if ao is not None and (an is None or an > ao):
        weak.append(f"risk.max_age_s {ao!r} -> {'none' if an is None else repr(an)} (older estimates accepted)")
    for name, so in old.signals.items():
        sn = new.signals.get(name)
        if sn is None:
            continue  # an obligation reading it changed or was removed, and is reported there
        if sn.type != so.type:
            unjudged.append(f"signal {name}: type {so.type} -> {sn.type}")
        elif so.range is not None and (sn.range is None or sn.range[0] < so.range[0] or sn.range[1] > so.range[1]):
            weak.append(f"signal {name}: range {list(so.range)} -> {list(sn.range) if sn.range else 'none'} "
                        "(values that faulted are now accepted)")
    for name, c in old.constants.items():
        if new.constants.get(name) != c:
            unjudged.append(f"constant {name} changed or removed")
    po, pn = old.safe_pose, new.safe_pose
    if pn.max_joint_speed_rad_s > po.max_joint_speed_rad_s:
        weak.append(f"safe_pose.max_joint_speed_rad_s raised {po.max_joint_speed_rad_s!r} -> "
                    f"{pn.max_joint_speed_rad_s!r}")
    if pn.tolerance_rad > po.tolerance_rad:
        weak.append(f"safe_pose.tolerance_rad raised {po.tolerance_rad!r} -> {pn.tolerance_rad!r}")
    if pn.joints_rad != po.joints_rad:
        unjudged.append("safe_pose.joints_rad changed")
    if rn.estimator != ro.estimator:
        unjudged.append("risk.estimator settings changed")
    if getattr(rn, "allow", None) != getattr(ro, "allow", None):
        unjudged.append("risk.allow opt-outs changed")
    unjudged = [f"{u}: {CANNOT_TELL}" for u in unjudged]
    return weak + unjudged, unjudged


_NUM = re.compile(r"[-+]?(?:\d+\.?\d*(?:e[-+]?\d+)?|nan|inf)", re.IGNORECASE)


def _fault_kind(faults: tuple[str, ...]) -> tuple[str, ...]:
    return tuple(_NUM.sub("#", f) for f in faults)


class GovernedLoop:
    """Steps a :class:`~ethimon.Monitor` at a fixed rate with async risk, a deadline and an audit trail.

    Args:
        monitor: a :class:`~ethimon.Monitor` (or a :class:`~ethimon.Spec` to build one).
        signals: called once per cycle for the spec's signals (a mapping); it may
            also be passed to :meth:`cycle` directly. An exception from it is a fault.
        risk: an :class:`AsyncRiskSource`; each cycle feeds its latest ``p`` and
            ``risk_age_s`` (and drops any ``risk``/``p_unsafe`` keys from the signals).
            A ``"module:function"`` string (or a :class:`ProcessEstimator`) builds one
            around an estimator in a **child process** (the recommended form: an
            estimator in a child cannot freeze the loop by holding the GIL); its task
            text starts as ``None`` (fail closed) until ``loop.risk.set_text(...)``.
            Without it, the signals must carry the risk input themselves.
        risk_kwargs: JSON-ready keyword arguments for a ``risk`` factory string.
        risk_env: extra environment variables for that child process.
        period_s: control period (0.001 = 1 kHz).
        deadline_s: a decision ready later than ``scheduled start + deadline_s`` is a
            missed deadline, which is a fault (default: ``period_s``).
        stall_s: a gap longer than this between the end of one cycle and the start
            of the next (the loop, or the whole interpreter, was frozen) is a stall:
            the resuming cycle overrides and ``stats.stalls`` counts it (default:
            ``period_s + deadline_s``).
        max_risk_age_s: oldest usable estimate when the spec has no ``risk.max_age_s``
            (when it has one, the monitor enforces that). ``None``: no limit here.
        audit: an :class:`~ethimon.audit.AuditLog`; state changes are always logged.
            Every cycle overrides while the log is unusable (its ``fault``: closed,
            writer failed or dead, writer behind its lag bounds) or refused a record.
        audit_every_cycle: log every cycle, not just state changes.
        verify: check run on a reloaded spec before the swap: a callable
            ``verify(spec)`` (raising or returning ``False`` rejects it), or ``"smt"``
            for :func:`ethimon.verify.verify_spec` (z3; any refuted or unproved
            property rejects the spec). ``None``: compile only.
        watchdog_s: if set, a :class:`Watchdog` thread calls ``on_stall`` (and logs a
            fault) when no cycle completes for this long.
        on_stall: the watchdog callback (e.g. trigger the hardware stop).
        on_decision: called with each cycle's decision (keep it quick).
        clock: time source in seconds (``time.perf_counter``; inject one in tests).
        sleep: how :meth:`run` waits (``time.sleep``).

    Example:
        >>> import ethimon
        >>> spec = ethimon.load_spec_text("{ethimon: 1, name: demo}")
        >>> class Fixed:
        ...     def probs(self, text):
        ...         return (0.95, 0.05)
        >>> src = AsyncRiskSource(Fixed(), text="wipe the table", start=False)
        >>> _ = src.poll_once()
        >>> loop = GovernedLoop(ethimon.Monitor(spec), risk=src, period_s=1.0)
        >>> loop.cycle({}).override
        False
        >>> src.set_text("new task")      # no estimate for it yet: fail closed
        >>> loop.cycle({}).faults[-1]
        'no risk estimate yet for the current task text'
    """

    def __init__(self, monitor: Monitor | Spec, *, signals: Callable[[], Mapping[str, Any]] | None = None,
                 risk: AsyncRiskSource | ProcessEstimator | str | None = None,
                 risk_kwargs: Mapping[str, Any] | None = None, risk_env: Mapping[str, str] | None = None,
                 period_s: float = 0.001, deadline_s: float | None = None, stall_s: float | None = None,
                 max_risk_age_s: float | None = 0.5, audit: Any = None, audit_every_cycle: bool = False,
                 verify: Callable[[Spec], Any] | str | None = None, watchdog_s: float | None = None,
                 on_stall: Callable[[str], None] | None = None,
                 on_decision: Callable[[Decision], None] | None = None,
                 clock: Callable[[], float] = time.perf_counter, sleep: Callable[[float], None] = time.sleep
                 ) -> None:
        if isinstance(monitor, Spec):
            monitor = Monitor(monitor)
        if not isinstance(monitor, Monitor):
            raise TypeError(f"GovernedLoop needs a Monitor or a Spec, got {type(monitor).__name__}")
        if not (isinstance(period_s, (int, float)) and period_s > 0 and math.isfinite(period_s)):
            raise ValueError(f"period_s={period_s!r}; expected a positive number of seconds")
        self.monitor = monitor
        self.period_s = float(period_s)
        self.deadline_s = float(deadline_s) if deadline_s is not None else self.period_s
        if not self.deadline_s > 0:
            raise ValueError(f"deadline_s={deadline_s!r}; expected > 0")
        self.stall_s = float(stall_s) if stall_s is not None else self.period_s + self.deadline_s
        if not self.stall_s > 0:
            raise ValueError(f"stall_s={stall_s!r}; expected > 0")
        self.max_risk_age_s = max_risk_age_s
        if isinstance(risk, str):
            risk = ProcessEstimator(risk, risk_kwargs, env=risk_env)
        elif risk_kwargs is not None or risk_env is not None:
            raise ValueError("risk_kwargs/risk_env need risk='module:function'")
        if isinstance(risk, ProcessEstimator):
            risk = AsyncRiskSource(risk, text=None, classes=monitor.spec.risk.classes)
        if risk is not None and not callable(getattr(risk, "snapshot", None)):
            raise TypeError(f"risk must be an AsyncRiskSource, a ProcessEstimator or 'module:function', "
                            f"got {type(risk).__name__}")
        self.risk = risk
        self.audit = audit
        self.audit_every_cycle = bool(audit_every_cycle)
        self.stats = LoopStats()
        self.last_decision: Decision | None = None
        self._signals = signals
        if verify == "smt":
            verify = _verify_smt
        elif verify is not None and not callable(verify):
            raise ValueError(f"verify={verify!r}; expected None, 'smt' or a callable verify(spec)")
        self._verify = verify
        self._on_decision = on_decision
        self._clock = clock
        self._sleep = sleep
        self._next: float | None = None  # scheduled start of the next cycle
        self._pending: tuple[Monitor, ReloadResult, str] | None = None
        self._reload_lock = threading.Lock()
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._state_key: tuple | None = None
        self._audit_failed = False
        self._stall_reason: str | None = None
        self._last_end: float | None = None  # end of the previous cycle (stall detection)
        from ..audit._log import spec_hash
        self._spec_hash_fn = spec_hash
        self.spec_sha256 = spec_hash(monitor.spec)
        self._age_guard = self.max_risk_age_s if monitor.spec.risk.max_age_s is None else None
        self._ids = monitor.obligation_ids
        self.watchdog: Watchdog | None = None
        if watchdog_s is not None:
            self.watchdog = Watchdog(watchdog_s, self._stalled)
            self._user_on_stall = on_stall
        isolation = None
        if risk is not None:
            isolation = "process" if getattr(risk, "isolated", False) else "thread"
        self.estimator_isolation = isolation
        self._log("start", spec=monitor.spec.name, spec_sha256=self.spec_sha256,
                  model_id=risk.model_id if risk is not None else None, period_s=self.period_s,
                  deadline_s=self.deadline_s, stall_s=self.stall_s, obligations=list(self._ids),
                  estimator_isolation=isolation)

    # ------------------------------------------------------------------ properties
    @property
    def spec(self) -> Spec:
        """The spec running now."""
        return self.monitor.spec

    # ------------------------------------------------------------------ one cycle
    def cycle(self, signals: Mapping[str, Any] | None = None) -> Decision:
        """Run one control cycle now and return its decision (never raises).

        Reads the signals (argument, or the ``signals`` callable), adds the
        latest risk reading, steps the monitor and escalates to an override for
        any fault around it: risk reading fault or too old, signal source
        error, missed deadline, a stall before this cycle, an audit log that is
        unusable or refused a record, an override carried over a spec reload.
        """
        clock = self._clock
        now = clock()
        sched = self._next if self._next is not None else now
        if self._pending is not None:
            self._apply_reload()
        m = self.monitor
        st = self.stats
        reasons: list[str] = []
        if self.watchdog is not None:
            # a stall its thread could not report (it was frozen too) fires now, into this cycle
            self.watchdog.kick()
        if self._last_end is not None:
            gap = now - self._last_end
            if gap > st.max_gap_s:
                st.max_gap_s = gap
            if gap > self.stall_s:
                st.stalls += 1
                reasons.append(f"control loop stalled for {gap * 1e3:.1f} ms before cycle {st.cycles} "
                               f"(stall_s {self.stall_s * 1e3:g} ms): no decision was made meanwhile")
        if self.audit is not None:
            try:
                afault = getattr(self.audit, "fault", None)
            except Exception as exc:  # noqa: BLE001 - a broken log is a fault, not a crash
                afault = f"audit log health check raised {type(exc).__name__}: {exc}"[:300]
            if isinstance(afault, str) and afault:
                reasons.append(afault)
                st.audit_faults += 1
        try:
            if signals is None:
                if self._signals is None:
                    raise EthimonError("no signals given and no signals source configured")
                signals = self._signals()
            inputs = dict(signals)
        except Exception as exc:  # noqa: BLE001
            reasons.append(f"signal source raised {type(exc).__name__}: {exc}"[:300])
            inputs = {}
        reading = None
        if self.risk is not None:
            try:
                reading = self.risk.snapshot()
            except Exception as exc:  # noqa: BLE001
                reading = RiskReading(None, math.inf, f"risk source failed: {type(exc).__name__}: {exc}", 0)
            inputs.pop("risk", None)
            inputs.pop("p_unsafe", None)
            if reading.fault is None:
                inputs["p"] = reading.probs
                inputs["risk_age_s"] = reading.age_s
                if self._age_guard is not None and reading.age_s > self._age_guard:
                    reasons.append(f"risk estimate is stale: {reading.age_s:.3f} s > {self._age_guard:g} s")
            else:
                inputs.pop("p", None)
                inputs.pop("risk_age_s", None)
                reasons.append(reading.fault)
        d = m.step(inputs)
        if self._stall_reason is not None:
            reasons.append(self._stall_reason)
            self._stall_reason = None
        if self._audit_failed:
            reasons.append(f"audit log failed or its queue is full, or its writer is behind its lag bounds "
                           f"({self.stats.audit_drops} records refused)")
        if self._carry_latch:
            reasons.append("override latched before the spec reload is carried over")
            self._carry_latch = False
        end = clock()
        late = end - sched
        if late > self.deadline_s:
            reasons.append(f"control cycle {self.stats.cycles} missed its deadline: decision ready "
                           f"{late * 1e3:.3f} ms after its start time (deadline {self.deadline_s * 1e3:g} ms)")
            self.stats.deadline_misses += 1
        if reasons:
            d = m.fault(*reasons, decision=d)
        st.cycles += 1
        if end - now > st.max_cycle_s:
            st.max_cycle_s = end - now
        if late > st.max_late_s:
            st.max_late_s = late
        if d.override:
            st.overrides += 1
        if d.faults:
            st.fault_cycles += 1
            if reading is not None and (reading.fault is not None or
                                        (self._age_guard is not None and reading.age_s > self._age_guard)):
                st.risk_faults += 1
            if any("stale" in f for f in d.faults):
                st.stale_overrides += 1
        # schedule the next slot; after an overrun, skip to the first grid slot not yet
        # past (no burst of catch-up cycles)
        P = self.period_s
        nxt = sched + P
        if nxt < end:
            k = math.ceil((end - sched) / P)
            st.skipped_slots += k - 1
            nxt = sched + k * P
        self._next = nxt
        if self.audit is not None:
            self._audit(d, inputs, reading)
        self._last_end = clock()
        self.last_decision = d
        if self._on_decision is not None:
            try:
                self._on_decision(d)
            except Exception as exc:  # noqa: BLE001 - recorded, and the next cycle overrides
                self._stall_reason = f"on_decision callback raised {type(exc).__name__}: {exc}"[:300]
        return d

    _carry_latch = False

    def _audit(self, d: Decision, inputs: dict, reading: RiskReading | None) -> None:
        key = (d.override, d.response, d.violations, _fault_kind(d.faults) if d.faults else ())
        if not self.audit_every_cycle and key == self._state_key:
            return
        prev = self._state_key
        self._state_key = key
        event = "cycle"
        if prev is None or prev[0] != d.override:
            event = "override_on" if d.override else "override_off"
        elif key != prev:
            event = "change"
        ok = self._log("decision", event=event, loop_cycle=self.stats.cycles - 1, cycle=d.cycle,
                       override=d.override, response=d.response.value, violations=list(d.violations),
                       faults=list(d.faults), latched=d.latched, risk=d.risk,
                       margins=dict(zip(self._ids, d.margins)) if d.margins else {},
                       inputs=inputs, risk_age_s=reading.age_s if reading is not None else None,
                       spec_sha256=self.spec_sha256,
                       model_id=self.risk.model_id if self.risk is not None else None)
        if not ok:
            self._state_key = None  # log the state again once the queue has room

    def _log(self, kind: str, **fields: Any) -> bool:
        if self.audit is None:
            return True
        try:
            ok = bool(self.audit.append(kind, **fields))
        except Exception:  # noqa: BLE001 - a broken log is a fault, not a crash
            ok = False
        if ok:
            self.stats.audit_records += 1
            self._audit_failed = False
        else:
            self.stats.audit_drops += 1
            self._audit_failed = True
        return ok

    # ------------------------------------------------------------------ running
    def run(self, duration_s: float | None = None, *, cycles: int | None = None) -> LoopStats:
        """Run cycles at ``period_s`` until ``duration_s``, ``cycles`` or :meth:`stop`.

        Returns:
            :attr:`stats`.
        """
        clock, sleep = self._clock, self._sleep
        self._stop.clear()
        t_end = None if duration_s is None else clock() + float(duration_s)
        n = 0
        if self.watchdog is not None:
            self.watchdog.start()
        self._next = None
        self._last_end = None  # the time before run() is not a stall
        try:
            while not self._stop.is_set():
                self.cycle()
                n += 1
                if cycles is not None and n >= cycles:
                    break
                wait = self._next - clock()
                if t_end is not None and self._next >= t_end:
                    break
                if wait > 0.0:
                    sleep(wait)
        finally:
            if self.watchdog is not None:
                self.watchdog.stop()
        return self.stats

    def start(self, duration_s: float | None = None) -> threading.Thread:
        """Run :meth:`run` in a daemon thread; :meth:`stop` ends it."""
        t = threading.Thread(target=self.run, args=(duration_s,), name="ethimon-loop", daemon=True)
        self._thread = t
        self._stop.clear()
        t.start()
        return t

    def stop(self, timeout: float = 2.0) -> None:
        """Ask :meth:`run` to return after the current cycle (and wait for a :meth:`start` thread)."""
        self._stop.set()
        t = self._thread
        if t is not None and t is not threading.current_thread():
            t.join(timeout)

    def _stalled(self, reason: str) -> None:
        self._stall_reason = reason
        self._log("fault", reason=reason, source="watchdog")
        cb = getattr(self, "_user_on_stall", None)
        if cb is not None:
            cb(reason)

    # ------------------------------------------------------------------ reload
    def reload(self, source: str | os.PathLike | Spec, *, allow_weaker: bool = False) -> ReloadResult:
        """Compile (and verify) a new spec in the calling thread, then swap it in between cycles.

        Trust model: whoever can call ``reload`` can change what is monitored,
        but not *silently weaken* it. A spec that weakens monitoring compared
        with the running one (see :func:`weakenings`: an obligation removed, τ
        raised, the release made easier, a response or ``on_fault`` made less
        severe, ``max_age_s`` removed or raised, a signal range widened, ...) is
        refused unless ``allow_weaker=True``; the refusal and an allowed
        weakening are both recorded in the audit log with the list of
        weakenings. A change whose direction cannot be told field by field (the
        text of a condition beyond whitespace, a constant's value, a signal's
        type, the safe pose's joints, the estimator settings) counts as a
        possible weakening: refused the same way, listed with
        "cannot tell whether this change weakens monitoring" (and in ``unjudged``).

        Args:
            source: a spec file path, or a loaded :class:`~ethimon.Spec`.
            allow_weaker: accept a spec that weakens monitoring (a deliberate,
                recorded decision).

        Returns:
            A :class:`ReloadResult`. Rejected (``ok=False``, old spec keeps
            running) if it does not load, compile or verify, or weakens
            monitoring without ``allow_weaker``. Both outcomes are recorded in
            the audit log, and so is the swap itself.
        """
        from .._api import load_spec
        label = "<Spec>" if isinstance(source, Spec) else os.fspath(source)
        weak: tuple[str, ...] = ()
        unjudged: tuple[str, ...] = ()
        try:
            spec = source if isinstance(source, Spec) else load_spec(source)
            new = Monitor(spec, margins=self.monitor._margins_on)
            guard = self.max_risk_age_s if self.risk is not None else None
            w, u = weakenings(self.monitor.spec, spec, loop_max_age_s=guard)
            weak, unjudged = tuple(w), tuple(u)
            if weak and not allow_weaker:
                raise EthimonError("reload refused: the new spec weakens monitoring: " + "; ".join(weak)
                                   + ". The running spec stays; pass allow_weaker=True to accept a weaker spec")
            if self._verify is not None:
                verdict = self._verify(spec)
                if verdict is False:
                    raise EthimonError("verification failed")
            h = self._spec_hash_fn(spec)
        except Exception as exc:  # noqa: BLE001 - rejected, never raised into the loop's owner
            msg = str(exc) if isinstance(exc, EthimonError) else f"{type(exc).__name__}: {exc}"
            res = ReloadResult(False, label, None, msg[:4000], weakened=weak, unjudged=unjudged)
            self.stats.reloads_rejected += 1
            self._log("reload", status="rejected", source=label, error=res.error,
                      running_spec_sha256=self.spec_sha256, weakened=list(weak), unjudged=list(unjudged))
            return res
        res = ReloadResult(True, label, h, weakened=weak, unjudged=unjudged)
        with self._reload_lock:
            old = self._pending
            self._pending = (new, res, label)
        if old is not None:
            self._log("reload", status="superseded", source=old[2], spec_sha256=old[1].spec_sha256)
        self._log("reload", status="accepted", source=label, spec_sha256=h, running_spec_sha256=self.spec_sha256,
                  allow_weaker=bool(allow_weaker), weakened=list(weak), unjudged=list(unjudged))
        return res

    def reload_async(self, source: str | os.PathLike | Spec, *, allow_weaker: bool = False) -> Future:
        """:meth:`reload` in a helper thread; the future's result is the :class:`ReloadResult`."""
        fut: Future = Future()

        def work() -> None:
            try:
                fut.set_result(self.reload(source, allow_weaker=allow_weaker))
            except BaseException as exc:  # pragma: no cover - reload() catches everything
                fut.set_exception(exc)

        threading.Thread(target=work, name="ethimon-reload", daemon=True).start()
        return fut

    def _apply_reload(self) -> None:
        with self._reload_lock:
            pending, self._pending = self._pending, None
        if pending is None:
            return
        new, res, label = pending
        old = self.monitor
        self._carry_latch = old.latched
        self.monitor = new
        old_hash, self.spec_sha256 = self.spec_sha256, res.spec_sha256
        self._ids = new.obligation_ids
        self._age_guard = self.max_risk_age_s if new.spec.risk.max_age_s is None else None
        self._state_key = None
        self.stats.reloads_applied += 1
        res.applied_at_cycle = self.stats.cycles
        self._log("reload", status="applied", source=label, spec_sha256=res.spec_sha256,
                  previous_spec_sha256=old_hash, loop_cycle=self.stats.cycles, carried_latch=old.latched)
        res.applied.set()

    def __repr__(self) -> str:
        return (f"GovernedLoop(spec={self.spec.name!r}, period_s={self.period_s:g}, "
                f"cycles={self.stats.cycles}, misses={self.stats.deadline_misses})")

