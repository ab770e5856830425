"""The governed control loop: a pacer holding an async risk feed, an acknowledgement gate, a reloader and
an audit sink, configured by one :class:`LoopConfig`.

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
                        risk=AsyncRiskSource(load_estimator(), text=task), audit=AuditLog("run.jsonl"),
                        config=LoopConfig(period_s=0.001))
    loop.run(duration_s=60)      # or call loop.cycle() from your own timer

The parts, each owning its state: the risk feed (``_feed.RiskFeed``: the risk source, the judge and the
task text they read), the acknowledgement gate (:class:`AckGate`: the requests waiting for the loop
thread, the restart rules), the reloader (:class:`Reloader`: the pending swap, the recorded inputs) and
the audit sink (``_sink.AuditSink``: the log, its health, the last logged state). The pacer owns the
schedule, the counters and the signals seen; it calls each part with what it needs.

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
import threading
import time
from collections.abc import Callable, Mapping
from concurrent.futures import Future
from typing import Any

from ..errors import EthimonError
from ..language import Spec
from ..runtime import Acknowledgement, Decision, Fault, Monitor
from ._acknowledge import AckGate
from ._config import LoopConfig
from ._feed import RiskFeed
from ._process import ProcessEstimator
from ._reload import ReloadResult, Reloader
from ._sink import AuditSink
from ._source import AsyncJudgeSource, AsyncRiskSource, RiskReading
from ._stats import LoopStats
from ._watchdog import Watchdog

__all__ = ["GovernedLoop", "ReloadResult"]

_DEFAULT = LoopConfig()


class GovernedLoop:
    """Steps a :class:`~ethimon.Monitor` at a fixed rate with async risk, a deadline and an audit trail.

    Args:
        monitor: a :class:`~ethimon.Monitor` (or a :class:`~ethimon.Spec` to build one).
        signals: called once per cycle for the spec's signals (a mapping); it may
            also be passed to :meth:`cycle` directly. An exception from it is a fault, and
            so is each entry of the mapping's ``faults`` attribute when it has one (a
            source that judges its own inputs: ``ethimon.ros2`` reports stale topics there).
        risk: an :class:`AsyncRiskSource`; each cycle feeds its latest ``p`` and
            ``risk_age_s`` (and drops any ``risk``/``p_unsafe`` keys from the signals).
            A ``"module:function"`` string (or a :class:`ProcessEstimator`, which also takes the
            factory's JSON arguments and environment) builds one around an estimator in a
            **child process** (the recommended form: an estimator in a child cannot freeze the loop
            by holding the GIL); its task text starts as ``None`` (fail closed) until
            ``loop.risk.set_text(...)``. Any estimator :func:`ethimon.risk.as_estimator` takes (an object
            with ``probs(text)``, a ``text -> p`` callable, a model directory as a ``Path``) is wrapped in an
            :class:`AsyncRiskSource` (a thread; task text ``None`` until set). Without ``risk``, the
            signals must carry the risk input themselves.
        audit: an :class:`~ethimon.audit.AuditLog`; state changes are always logged.
            Every cycle overrides while the log is unusable (its ``fault``: closed,
            writer failed or dead, writer behind its lag bounds) or refused a record.
        config: a :class:`LoopConfig`: period, deadline, stall limit, risk age, watchdog, audit of every
            cycle, the clearance a manual reset needs, the check a reloaded spec must pass.
        judge: the judge tier (``risk.judge``, ``risk.confirm_threshold``): ``"spec"`` (default) builds a
            :class:`~ethimon.risk.Judge` from the spec's ``risk.judge`` when it has one and there is a
            ``risk`` source; a :class:`~ethimon.risk.Judge` or an :class:`AsyncJudgeSource`; ``None``: no
            judge (the confirm band then goes to a person). The judge is asked once per distinct task
            text (in its own thread, answers kept by the text's hash); until it answers the monitor has no
            judgement, so in the band the arm holds. Each cycle feeds ``judge`` (its p_unsafe) and
            ``task_id`` (the text's sha256, to which an operator's confirmation is bound); every judge
            answer is a ``judge`` audit record (hash, model, verdict, latency, status; never the key).
        on_stall: the watchdog callback (``config.watchdog_s``; e.g. trigger the hardware stop).
        on_decision: called with each cycle's decision (keep it quick).
        foxglove: a live Foxglove view of every cycle (decision, margins by rule, R_e against τ and
            τ_confirm, the judge/confirm state, every input; the ``--mcap`` file's channels):
            ``"[HOST:]PORT"`` or a port (``0``: a free one) starts a
            :class:`~ethimon.view.FoxgloveView` on it (loopback unless a host is named; closed by
            :meth:`stop`), or pass your own (any object with ``put(decision, inputs)``). It is fed once
            per cycle without blocking: a bounded queue whose oldest cycle is dropped, and counted, when
            a viewer falls behind. ``pip install 'ethimon[foxglove]'``.
        clock: time source in seconds (``time.perf_counter``; inject one in tests).
        sleep: how :meth:`run` waits (``time.sleep``).
        reloader: the :class:`Reloader` to use (default: one built from ``config.verify``).
        gate: the :class:`AckGate` to use (default: one built from ``config.acknowledge_clear``).

    Example:
        >>> import ethimon
        >>> from ethimon.loop import LoopConfig
        >>> spec = ethimon.load_spec_text("{ethimon: 1, name: demo}")
        >>> class Fixed:
        ...     def probs(self, text):
        ...         return (0.95, 0.05)
        >>> src = AsyncRiskSource(Fixed(), text="wipe the table", start=False)
        >>> _ = src.poll_once()
        >>> loop = GovernedLoop(ethimon.Monitor(spec), risk=src, config=LoopConfig(period_s=1.0))
        >>> loop.cycle({}).override
        False
        >>> src.set_text("new task")      # no estimate for it yet: the pending hold (stop 2)
        >>> d = loop.cycle({}); d.response, d.violations, d.faults
        (<Response.STOP_2: 'stop_2'>, ('pending',), ())
    """

    def __init__(self, monitor: Monitor | Spec, *, signals: Callable[[], Mapping[str, Any]] | None = None,
                 risk: AsyncRiskSource | ProcessEstimator | str | Any = None, audit: Any = None,
                 config: LoopConfig = _DEFAULT, judge: Any = "spec",
                 on_stall: Callable[[str], None] | None = None,
                 on_decision: Callable[[Decision], None] | None = None, foxglove: Any = None,
                 clock: Callable[[], float] = time.perf_counter, sleep: Callable[[float], None] = time.sleep,
                 reloader: Reloader | None = None, gate: AckGate | None = None) -> None:
        if isinstance(monitor, Spec):
            monitor = Monitor(monitor)
        if not isinstance(monitor, Monitor):
            raise TypeError(f"GovernedLoop needs a Monitor or a Spec, got {type(monitor).__name__}")
        if not isinstance(config, LoopConfig):
            raise TypeError(f"config must be a LoopConfig (ethimon.loop.LoopConfig), got {type(config).__name__}")
        if reloader is not None and config.verify is not None:
            raise ValueError("config.verify and reloader= both given: set verify on the Reloader, or drop reloader=")
        if gate is not None and config.acknowledge_clear is not None:
            raise ValueError("config.acknowledge_clear and gate= both given: set clear on the AckGate, or drop gate=")
        #: the settings this loop runs with
        self.config = config
        self.monitor = monitor
        self.period_s = float(config.period_s)
        self.deadline_s = config.deadline
        self.stall_s = config.stall
        self.stats = LoopStats()
        #: the audit sink (the log: :attr:`audit`)
        self._sink = AuditSink(audit, config.audit_every_cycle, self.stats)
        #: the risk feed (``None``: the signals carry the risk input)
        self._feed: RiskFeed | None = None
        if risk is not None:
            self._feed = RiskFeed(risk, judge, monitor, config.max_risk_age_s)
        elif isinstance(judge, str):
            if judge != "spec":
                raise ValueError(f"judge={judge!r}; expected 'spec', None, a Judge or an AsyncJudgeSource")
        elif judge is not None:
            raise ValueError("a judge needs a risk source (its task text is what the judge reads)")
        self._gate = gate if gate is not None else AckGate(config.acknowledge_clear)
        self._gate.check(monitor.spec)
        self._reloader = reloader if reloader is not None else Reloader(config.verify)
        self._reloader.track(monitor.plan)
        self.last_decision: Decision | None = None
        self._last_inputs: Mapping[str, Any] = {}
        self._signals = signals
        self._on_decision = on_decision
        #: the live Foxglove view fed each cycle (``None``: none); ``_own_view``: this loop started it
        self.foxglove: Any = None
        self._own_view = False
        if foxglove is not None and not callable(getattr(foxglove, "put", None)):
            from ..view import FoxgloveView, VerdictChannels
            foxglove = FoxgloveView(VerdictChannels.of_spec(monitor.spec, monitor.obligation_ids), foxglove)
            self._own_view = True
        self.foxglove = foxglove
        self._clock = clock
        self._sleep = sleep
        self._next: float | None = None  # scheduled start of the next cycle
        self._running = False
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._stall_reason: Fault | None = None
        self._last_end: float | None = None  # end of the previous cycle (stall detection)
        self.spec_sha256 = self._reloader.spec_hash(monitor.spec)
        self._ids = monitor.obligation_ids
        #: the signals not seen yet since the start (awaited: a pending hold, see _gone)
        self._signal_names = tuple(monitor.spec.signals)
        self._unseen = set(self._signal_names)
        self._latch_t: dict[int, float] = {}  # monitor cycle -> wall time, for cycles that set a latch
        self.watchdog: Watchdog | None = None
        self._user_on_stall = on_stall
        if config.watchdog_s is not None:
            self.watchdog = Watchdog(config.watchdog_s, self._stalled)
        feed = self._feed
        #: ``"process"``, ``"thread"`` or ``None`` (no risk source): where the estimator runs
        self.estimator_isolation = feed.isolation if feed is not None else None
        self._sink.append("start", spec=monitor.spec.name, spec_sha256=self.spec_sha256,
                          model_id=feed.model_id if feed is not None else None, period_s=self.period_s,
                          deadline_s=self.deadline_s, stall_s=self.stall_s, obligations=list(self._ids),
                          estimator_isolation=self.estimator_isolation)

    # ------------------------------------------------------------------ the parts, read by name
    @property
    def spec(self) -> Spec:
        """The spec running now."""
        return self.monitor.spec

    @property
    def risk(self) -> AsyncRiskSource | None:
        """The risk source (``None``: the signals carry the risk input)."""
        return self._feed.risk if self._feed is not None else None

    @property
    def judge(self) -> AsyncJudgeSource | None:
        """The judge tier's source (:class:`AsyncJudgeSource`), or ``None``."""
        return self._feed.judge if self._feed is not None else None

    @property
    def audit(self) -> Any:
        """The audit log (``None``: none)."""
        return self._sink.log

    @property
    def max_risk_age_s(self) -> float | None:
        return self.config.max_risk_age_s

    @property
    def audit_every_cycle(self) -> bool:
        return self._sink.every_cycle

    @property
    def acknowledge_clear(self) -> tuple[str, float] | None:
        """(signal, minimum): a manual reset is refused while that reading is missing or below it."""
        return self._gate.clear

    @property
    def acknowledge_refused(self) -> str | None:
        """Why acknowledgements cannot reach this loop's monitor (``None``: they can); a node without
        authentication sets it (:meth:`holding` then says that only a person at the loop can release)."""
        return self._gate.refused

    @acknowledge_refused.setter
    def acknowledge_refused(self, why: str | None) -> None:
        self._gate.refused = why

    def holding(self, acknowledge_refused: str | None = None) -> list[dict]:
        """What holds the arm now: :meth:`Monitor.holding <ethimon.Monitor.holding>` (one dict per latched
        rule, the most severe first; empty when the arm is free), each with ``since_t_unix`` (the wall
        time of the cycle it latched, ``None`` if not seen by this loop) and ``acknowledge_allowed``.

        Args:
            acknowledge_refused: why acknowledgements cannot reach this loop (e.g. a node without
                authentication); default :attr:`acknowledge_refused`. Then a rule that needs one is
                released by ``"person"`` (at the loop: an authenticated acknowledgement or a restart), and its
                ``how`` says why.
        """
        gate = self._gate
        refused = acknowledge_refused if acknowledge_refused is not None else gate.refused
        out = []
        times = self._latch_t
        for h in self.monitor.holding():
            h["since_t_unix"] = times.get(h["since_cycle"])
            h["acknowledge_allowed"] = bool(h["acknowledge"]) and not refused
            if refused and h["release"] == "acknowledge":
                h["release"] = "person"
                h["how"] += f"; acknowledgements are refused here ({refused}): only a person at the loop releases it"
            out.append(h)
        if gate.awaiting_start is not None:  # after the monitor's own latches (most severe first)
            h = gate.holding(self.monitor.spec)
            h["since_t_unix"] = times.get(gate.awaiting_start)
            h["acknowledge_allowed"] = False
            out.append(h)
        return out

    @property
    def hold_text(self) -> str:
        """:meth:`holding` in one line for a person ("" when the arm is free)."""
        return "; ".join(f"{h['rule']} ({h['response']}) since cycle {h['since_cycle']}, released {h['how']}"
                         for h in self.holding())

    # ------------------------------------------------------------------ operator release (the gate)
    def acknowledge(self, operator: str, *, reason: str = "", timeout_s: float = 2.0,
                    task_sha256: str | None = None) -> Acknowledgement:
        """An operator's acknowledgement of the manual latches, checked and audited.

        :meth:`Monitor.acknowledge` through the loop: while :meth:`run` drives the
        monitor in another thread, the request is applied by the loop thread
        between two cycles (never during a step) and this call waits up to
        ``timeout_s`` for it; otherwise it is applied now. The monitor refuses it
        (releases nothing) while a manual rule has not held its release condition
        for its ``hold_cycles``. Every request, accepted or refused, is an
        ``acknowledge`` record in the audit log (operator, reason, result,
        monitor cycle); a request is refused without touching the monitor while
        the audit log reports a fault, so no release goes unrecorded. With a spec ``restart:`` block,
        also refused while its ``standstill`` input was false or missing on the last cycle (the stop has
        not completed), and an accepted one starts nothing: the loop holds until :meth:`start_motion`
        or the spec's start input rises.

        Args:
            operator: who acknowledges (a name or badge id; required).
            reason: why, in the operator's words (kept in the audit log).
            timeout_s: how long to wait for a running loop to apply it.
            task_sha256: the sha256 of the task text the operator was shown (``ethimon.risk.text_sha256``).
                While the confirm band holds, a confirmation naming another text than the one the loop
                holds when it applies the request (the planner replaced it meanwhile) is refused.
                ``None``: the text held then is confirmed (the audit record names it).

        Returns:
            The :class:`~ethimon.runtime.Acknowledgement`; refused if the loop did
            not apply it within ``timeout_s``.
        """
        return self._submit(AckGate.request(operator, reason, task_sha256, "acknowledge"), timeout_s)

    def start_motion(self, operator: str, *, reason: str = "", timeout_s: float = 2.0) -> Acknowledgement:
        """The separate start after an accepted acknowledgement (a spec ``restart: {start: command}``).

        With a spec ``restart:`` block an accepted acknowledgement of a manual latch is a reset that
        never starts motion: every cycle after it overrides (at least stop 2; ``"restart"`` among the
        decision's ``latched_rules``, its reason in :meth:`holding` and ``Decision.reasons``) until this
        start, or the rising edge of the spec's start input (``restart: {start: <bool input>}``; the
        edge is taken at the next cycle, as this call is). Refused, and not remembered, while no
        acknowledged stop waits for a start, while the last cycle's monitor decision overrides (a rule
        fires or holds, a fault) or, with ``acknowledge_clear``, a person is inside the protective
        distance, and while the audit log cannot record it. Applied between two cycles like
        :meth:`acknowledge`, audited as a ``start_motion`` record; motion resumes from the next cycle.

        Returns:
            The :class:`~ethimon.runtime.Acknowledgement` (``released``: started; ``message`` says why not).
        """
        return self._submit(AckGate.request(operator, reason, None, "start"), timeout_s)

    def _submit(self, req: Any, timeout_s: float) -> Acknowledgement:
        t = self._thread
        if self._running and t is not None and t is not threading.current_thread():
            return self._gate.wait(req, timeout_s)
        self._ack_now(req)
        return req.answer

    def _apply_acks(self) -> None:
        for req in self._gate.take():
            self._ack_now(req)

    def _ack_now(self, req: Any) -> None:
        """Apply one request to the monitor (in the loop thread, between two cycles)."""
        self._gate.apply(req, self.monitor, self.last_decision, self._last_inputs, self._sink, self._feed,
                         self.stats.cycles, self._latch_t)

    # ------------------------------------------------------------------ reload (the reloader)
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

        Latches are carried by identity: every rule latched in the running monitor
        when the swap happens is latched in the new one (a manual rule stays latched
        until acknowledged there; every release count restarts). That needs the rule
        in the new spec with the same id, response and release (mode, ``hold_cycles``;
        for the risk rule its bound τ − δ too); a reload that cannot map a latched
        rule is refused (also with ``allow_weaker=True``), here or, if the rule latched
        meanwhile, at the swap (``ok`` turns ``False``; the audit log says why), and
        the running spec stays.

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
        fallback = self._feed.age_fallback if self._feed is not None else None
        res, new = self._reloader.prepare(self.monitor, source, allow_weaker, fallback)
        weak, unjudged = list(res.weakened), list(res.unjudged)
        if new is None:
            self.stats.reloads_rejected += 1
            self._sink.append("reload", status="rejected", source=res.source, error=res.error,
                              running_spec_sha256=self.spec_sha256, weakened=weak, unjudged=unjudged)
            return res
        old = self._reloader.queue(new, res)
        if old is not None:
            self._sink.append("reload", status="superseded", source=old[2], spec_sha256=old[1].spec_sha256)
        self._sink.append("reload", status="accepted", source=res.source, spec_sha256=res.spec_sha256,
                          running_spec_sha256=self.spec_sha256, allow_weaker=bool(allow_weaker), weakened=weak,
                          unjudged=unjudged)
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
        """Swap a pending spec in (the loop thread, before a cycle), or refuse it at the swap."""
        pending = self._reloader.take()
        if pending is None:
            return
        new, res, label = pending
        old = self.monitor
        latched = old.latched_rules
        error, _ = self._reloader.carry(old, new)
        sink = self._sink
        if error:
            res.ok = False
            res.error = error[:4000]
            self.stats.reloads_rejected += 1
            sink.append("reload", status="rejected", stage="swap", source=label, spec_sha256=res.spec_sha256,
                        error=res.error, running_spec_sha256=self.spec_sha256, latched=list(latched),
                        loop_cycle=self.stats.cycles)
            res.settled.set()
            return
        self.monitor = new
        self._reloader.track(new.plan)
        old_hash, self.spec_sha256 = self.spec_sha256, res.spec_sha256
        self._ids = new.obligation_ids
        sink.state_key = None
        if self._feed is not None:
            self._feed.swap(old, new)
        self.stats.reloads_applied += 1
        res.applied_at_cycle = self.stats.cycles
        sink.append("reload", status="applied", source=label, spec_sha256=res.spec_sha256,
                    previous_spec_sha256=old_hash, loop_cycle=self.stats.cycles, carried_latch=bool(latched),
                    carried_rules=list(latched))
        res.applied.set()
        res.settled.set()

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
        if self._reloader.pending is not None:
            self._apply_reload()
        gate = self._gate
        if gate.queue:
            self._apply_acks()
        m = self.monitor
        st = self.stats
        sink = self._sink
        reasons: list[Fault] = []
        if self.watchdog is not None:
            # a stall its thread could not report (it was frozen too) fires now, into this cycle
            self.watchdog.kick()
        if self._last_end is not None:
            gap = now - self._last_end
            if gap > st.max_gap_s:
                st.max_gap_s = gap
            if gap > self.stall_s:
                st.stalls += 1
                reasons.append(Fault("stall", f"control loop stalled for {gap * 1e3:.1f} ms before cycle "
                                     f"{st.cycles} (stall_s {self.stall_s * 1e3:g} ms): no decision was made "
                                     "meanwhile"))
        afault = sink.health()
        if afault:
            reasons.append(Fault("audit", afault))
            st.audit_faults += 1
        try:
            if signals is None:
                if self._signals is None:
                    raise EthimonError("no signals given and no signals source configured")
                signals = self._signals()
            inputs = dict(signals)
            extra = getattr(signals, "faults", None)  # a source's own verdicts (stale, a foreign publisher)
            if extra:
                reasons.extend(f if isinstance(f, Fault) else Fault("signals", str(f)[:300]) for f in extra)
        except Exception as exc:  # noqa: BLE001
            reasons.append(Fault("signals", f"signal source raised {type(exc).__name__}: {exc}"[:300]))
            inputs = {}
        reading = None
        feed = self._feed
        if feed is not None:
            reading = feed.read(inputs, m, reasons, self._gone, sink, st.cycles)
        if self._unseen and "pending_s" not in inputs and not self._gone(inputs):
            inputs["pending_s"] = 0.0  # a signal not seen since the start: awaited, no limit
        d = m.step(inputs)
        self._reloader.record(inputs)  # a reload rebuilds the new monitor's temporal history from these
        self._last_inputs = inputs
        if self._stall_reason is not None:
            reasons.append(self._stall_reason)
            self._stall_reason = None
        if sink.failed:
            reasons.append(Fault("audit", f"audit log failed or its queue is full, or its writer is behind its "
                                 f"lag bounds ({st.audit_drops} records refused)"))
        end = clock()
        late = end - sched
        if late > self.deadline_s:
            reasons.append(Fault("deadline", f"control cycle {self.stats.cycles} missed its deadline: decision "
                                 f"ready {late * 1e3:.3f} ms after its start time (deadline "
                                 f"{self.deadline_s * 1e3:g} ms)"))
            self.stats.deadline_misses += 1
        if reasons:
            d = m.fault(*reasons, decision=d)
        if gate.awaiting_start is not None:  # an acknowledged stop waits for the spec's start (restart:)
            d = gate.hold(d, inputs, m.spec)
        st.cycles += 1
        if end - now > st.max_cycle_s:
            st.max_cycle_s = end - now
        if late > st.max_late_s:
            st.max_late_s = late
        if d.override:
            st.overrides += 1
            if not d.faults and "pending" in d.violations:
                st.pending_cycles += 1
            if m._nlat:
                self._note_latch(m, d.cycle)
        if d.faults:
            st.fault_cycles += 1
            stale = any(f.kind == "stale" for f in d.faults)
            if stale:
                st.stale_overrides += 1
            # the reading faulted, or the monitor refused what it carried (stale, or p unusable: no R_e)
            if reading is not None and ((reading.fault is not None and reading.pending_s is None)
                                        or stale or d.risk is None):
                st.risk_faults += 1
        # schedule the next slot; after an overrun, skip to the first grid slot not yet
        # past (no burst of catch-up cycles)
        P = self.period_s
        nxt = sched + P
        if nxt < end:
            k = math.ceil((end - sched) / P)
            st.skipped_slots += k - 1
            nxt = sched + k * P
        self._next = nxt
        if sink.log is not None:
            sink.decision(d, inputs, reading, self._ids, self.spec_sha256,
                          feed.model_id if feed is not None else None)
        self._last_end = clock()
        self.last_decision = d
        if self._on_decision is not None:
            try:
                self._on_decision(d)
            except Exception as exc:  # noqa: BLE001 - recorded, and the next cycle overrides
                self._stall_reason = Fault("callback", f"on_decision callback raised {type(exc).__name__}: {exc}"[:300])
        if self.foxglove is not None:
            try:
                self.foxglove.put(d, inputs)  # never blocks: a bounded queue, the oldest cycle dropped
            except Exception as exc:  # noqa: BLE001 - recorded, and the next cycle overrides
                self._stall_reason = Fault("callback", f"foxglove view raised {type(exc).__name__}: {exc}"[:300])
        return d

    def _gone(self, inputs: dict) -> bool:
        """Whether a signal seen since the start is missing now (a fault, never a pending hold); a signal
        not seen yet is awaited. Updates the signals seen (O(signals), only until all were seen or while
        something is awaited)."""
        unseen = self._unseen
        if unseen:
            for n in tuple(unseen):
                if inputs.get(n) is not None:
                    unseen.discard(n)
        return any(inputs.get(n) is None for n in self._signal_names if n not in unseen)

    def _note_latch(self, m: Monitor, cycle: int) -> None:
        """The wall time of a cycle at which a latch was set (for :meth:`holding`)."""
        times = self._latch_t
        if cycle in times or cycle not in m._since:
            return
        if len(times) >= 64:
            keep = set(m._since)
            for c in [c for c in times if c not in keep]:
                del times[c]
        times[cycle] = time.time()

    # ------------------------------------------------------------------ running
    def run(self, duration_s: float | None = None, *, cycles: int | None = None) -> LoopStats:
        """Run cycles at ``period_s`` until ``duration_s``, ``cycles`` or :meth:`stop`.

        Returns:
            :attr:`stats`.
        """
        clock, sleep = self._clock, self._sleep
        self._stop.clear()
        self._running = True
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
            self._running = False
            try:
                self.stats.held_by = self.hold_text
            except Exception as exc:  # noqa: BLE001 - a summary never hides the loop's own ending
                self.stats.held_by = f"? ({type(exc).__name__})"
            if self.watchdog is not None:
                self.watchdog.stop()
            if self._gate.queue:
                self._apply_acks()  # nobody waits forever for a loop that has ended
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
        if self._own_view:
            self.foxglove.close()

    def _stalled(self, reason: str) -> None:
        self._stall_reason = Fault("stall", reason)
        self._sink.append("fault", reason=reason, source="watchdog")
        cb = self._user_on_stall
        if cb is not None:
            cb(reason)

    def __repr__(self) -> str:
        return (f"GovernedLoop(spec={self.spec.name!r}, period_s={self.period_s:g}, "
                f"cycles={self.stats.cycles}, misses={self.stats.deadline_misses})")
