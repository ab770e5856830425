"""The governed control loop: async risk estimator, watchdog, hot spec reload.

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
import threading
import time
from collections import deque
from collections.abc import Callable, Mapping
from typing import Any

from ..audit import spec_hash
from ..errors import EthimonError
from ..runtime import Decision, Fault, Monitor
from ..language import Spec
from ._acknowledge import _Acknowledging
from ._process import ProcessEstimator
from ._reload import ReloadResult, _Reloading, _verify_smt, history_len
from ._source import AsyncJudgeSource, AsyncRiskSource, RiskReading
from ._stats import LoopStats
from ._watchdog import Watchdog

__all__ = ["GovernedLoop", "ReloadResult"]


class GovernedLoop(_Acknowledging, _Reloading):
    """Steps a :class:`~ethimon.Monitor` at a fixed rate with async risk, a deadline and an audit trail.

    Args:
        monitor: a :class:`~ethimon.Monitor` (or a :class:`~ethimon.Spec` to build one).
        signals: called once per cycle for the spec's signals (a mapping); it may
            also be passed to :meth:`cycle` directly. An exception from it is a fault, and
            so is each entry of the mapping's ``faults`` attribute when it has one (a
            source that judges its own inputs: ``ethimon.ros2`` reports stale topics there).
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
            (and the monitor was not built with its own ``max_age_s``): the loop sets it on
            the monitor, which alone judges the age, with one limit (see
            :attr:`~ethimon.Monitor.max_age_s`). ``None``: no limit here. Used only with a
            ``risk`` source.
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
        judge: the judge tier (``risk.judge``, ``risk.confirm_threshold``): ``"spec"`` (default) builds a
            :class:`~ethimon.risk.Judge` from the spec's ``risk.judge`` when it has one and there is a
            ``risk`` source; a :class:`~ethimon.risk.Judge` or an :class:`AsyncJudgeSource`; ``None``: no
            judge (the confirm band then goes to a person). The judge is asked once per distinct task
            text (in its own thread, answers kept by the text's hash); until it answers the monitor has no
            judgement, so in the band the arm holds. Each cycle feeds ``judge`` (its p_unsafe) and
            ``task_id`` (the text's sha256, to which an operator's confirmation is bound); every judge
            answer is a ``judge`` audit record (hash, model, verdict, latency, status; never the key).
        clock: time source in seconds (``time.perf_counter``; inject one in tests).
        sleep: how :meth:`run` waits (``time.sleep``).
        foxglove: a live Foxglove view of every cycle (decision, margins by rule, R_e against τ and
            τ_confirm, the judge/confirm state, every input; the ``--mcap`` file's channels):
            ``"[HOST:]PORT"`` or a port (``0``: a free one) starts a
            :class:`~ethimon.view.FoxgloveView` on it (loopback unless a host is named; closed by
            :meth:`stop`), or pass your own (any object with ``put(decision, inputs)``). It is fed once
            per cycle without blocking: a bounded queue whose oldest cycle is dropped, and counted, when
            a viewer falls behind. ``pip install 'ethimon[foxglove]'``.

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
        >>> src.set_text("new task")      # no estimate for it yet: the pending hold (stop 2)
        >>> d = loop.cycle({}); d.response, d.violations, d.faults
        (<Response.STOP_2: 'stop_2'>, ('pending',), ())
    """

    def __init__(self, monitor: Monitor | Spec, *, signals: Callable[[], Mapping[str, Any]] | None = None,
                 risk: AsyncRiskSource | ProcessEstimator | str | None = None,
                 risk_kwargs: Mapping[str, Any] | None = None, risk_env: Mapping[str, str] | None = None,
                 period_s: float = 0.001, deadline_s: float | None = None, stall_s: float | None = None,
                 max_risk_age_s: float | None = 0.5, audit: Any = None, audit_every_cycle: bool = False,
                 verify: Callable[[Spec], Any] | str | None = None, watchdog_s: float | None = None,
                 on_stall: Callable[[str], None] | None = None,
                 on_decision: Callable[[Decision], None] | None = None,
                 clock: Callable[[], float] = time.perf_counter, sleep: Callable[[float], None] = time.sleep,
                 judge: Any = "spec", acknowledge_clear: tuple[str, float] | None = None,
                 foxglove: Any = None) -> None:
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
            risk = AsyncRiskSource(risk, text=None)
        if risk is not None and not callable(getattr(risk, "snapshot", None)):
            raise TypeError(f"risk must be an AsyncRiskSource, a ProcessEstimator or 'module:function', "
                            f"got {type(risk).__name__}")
        self.risk = risk
        self._judge_from_spec = isinstance(judge, str)
        if isinstance(judge, str):
            if judge != "spec":
                raise ValueError(f"judge={judge!r}; expected 'spec', None, a Judge or an AsyncJudgeSource")
            judge = None
            if risk is not None and monitor.plan.risk.judge_list:  # risk.judge or risk.judges
                from ..risk import load_judge_for
                judge = load_judge_for(monitor.spec)
        if judge is not None and not isinstance(judge, AsyncJudgeSource):
            judge = AsyncJudgeSource(judge)
        if judge is not None and risk is None:
            raise ValueError("a judge needs a risk source (its task text is what the judge reads)")
        #: the judge tier's source (:class:`AsyncJudgeSource`), or ``None``
        self.judge: AsyncJudgeSource | None = judge
        self._task_text: str | None = None
        self._task_key: str | None = None
        self.audit = audit
        self.audit_every_cycle = bool(audit_every_cycle)
        self.stats = LoopStats()
        self.last_decision: Decision | None = None
        self._last_inputs: Mapping[str, Any] = {}
        if acknowledge_clear is not None:
            ok = (isinstance(acknowledge_clear, tuple) and len(acknowledge_clear) == 2
                  and isinstance(acknowledge_clear[0], str) and acknowledge_clear[0] in monitor.spec.signals
                  and isinstance(acknowledge_clear[1], (int, float)) and not isinstance(acknowledge_clear[1], bool)
                  and math.isfinite(acknowledge_clear[1]) and acknowledge_clear[1] >= 0)
            if not ok:
                raise ValueError(f"acknowledge_clear={acknowledge_clear!r}; expected (signal of the spec, minimum "
                                 f">= 0), e.g. ('human_distance', 1.5): the protective distance a manual reset needs")
        #: (signal, minimum): a manual reset is refused while that reading is missing or below it
        self.acknowledge_clear = acknowledge_clear
        self._signals = signals
        if verify == "smt":
            verify = _verify_smt
        elif verify is not None and not callable(verify):
            raise ValueError(f"verify={verify!r}; expected None, 'smt' or a callable verify(spec)")
        self._verify = verify
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
        self._pending: tuple[Monitor, ReloadResult, str] | None = None
        #: operator acknowledgements waiting for the loop thread: [operator, reason, done event, answer]
        self._acks: list[list[Any]] = []
        self._acks_lock = threading.Lock()
        self._running = False
        self._reload_lock = threading.Lock()
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._state_key: tuple | None = None
        self._audit_failed = False
        self._stall_reason: Fault | None = None
        self._last_end: float | None = None  # end of the previous cycle (stall detection)
        self._spec_hash_fn = spec_hash
        self.spec_sha256 = spec_hash(monitor.spec)
        # staleness is judged by the monitor alone, with one limit: the spec's risk.max_age_s, else
        # the monitor's own max_age_s, else (with a risk source) this loop's max_risk_age_s
        self._age_fallback: float | None = None
        if risk is not None:
            own = monitor.max_age_s if monitor.plan.risk.max_age_s is None else None
            self._age_fallback = own if own is not None else max_risk_age_s
            if monitor.max_age_s is None and self._age_fallback is not None:
                monitor.set_max_age(self._age_fallback)
        self._ids = monitor.obligation_ids
        #: the signals not seen yet since the start (awaited: a pending hold, see _await_signals)
        self._signal_names = tuple(monitor.spec.signals)
        self._unseen = set(self._signal_names)
        self._latch_t: dict[int, float] = {}
        self._history: deque = deque(maxlen=history_len(monitor.plan))  # the last cycles' inputs  # monitor cycle -> wall time, for cycles that set a latch
        #: why acknowledgements cannot reach this loop's monitor (``None``: they can); a node without
        #: authentication sets it (``holding()`` then says that only a person at the loop can release)
        self.acknowledge_refused: str | None = None
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
        refused = acknowledge_refused if acknowledge_refused is not None else self.acknowledge_refused
        out = []
        times = self._latch_t
        for h in self.monitor.holding():
            h["since_t_unix"] = times.get(h["since_cycle"])
            h["acknowledge_allowed"] = bool(h["acknowledge"]) and not refused
            if refused and h["release"] == "acknowledge":
                h["release"] = "person"
                h["how"] += f"; acknowledgements are refused here ({refused}): only a person at the loop releases it"
            out.append(h)
        if self._awaiting_start is not None:  # after the monitor's own latches (most severe first)
            h = self._restart_holding()
            h["since_t_unix"] = times.get(self._awaiting_start)
            h["acknowledge_allowed"] = False
            out.append(h)
        return out

    @property
    def hold_text(self) -> str:
        """:meth:`holding` in one line for a person ("" when the arm is free)."""
        return "; ".join(f"{h['rule']} ({h['response']}) since cycle {h['since_cycle']}, released {h['how']}"
                         for h in self.holding())

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
        if self._acks:
            self._apply_acks()
        m = self.monitor
        st = self.stats
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
        afault = self._audit_health()
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
        if self.risk is not None:
            text = None
            try:
                # the text read before and after the estimate: a set_text() in between (the planner's
                # thread) would pair one text's R_e with another text's judge verdict and task_id
                text = self.risk.text
                reading = self.risk.snapshot()
                if reading.fault is None and self.risk.text is not text:
                    reading = RiskReading(None, math.inf, "the task text changed while its estimate was read",
                                          reading.count)
            except Exception as exc:  # noqa: BLE001
                reading = RiskReading(None, math.inf, f"risk source failed: {type(exc).__name__}: {exc}", 0)
            inputs.pop("risk", None)
            inputs.pop("p_unsafe", None)
            inputs.pop("pending_s", None)  # the loop owns it: what it awaits
            if reading.fault is None:
                inputs["p"] = reading.probs  # judged by the monitor (one rule for every risk input)
                inputs["risk_age_s"] = reading.age_s  # judged by the monitor (one age limit)
            else:
                inputs.pop("p", None)
                inputs.pop("risk_age_s", None)
                if reading.pending_s is not None and not self._gone(inputs):
                    inputs["pending_s"] = reading.pending_s  # awaited: the monitor holds (stop 2) or fails closed
                else:
                    reasons.append(Fault("estimator", reading.fault))
            if self.judge is not None or m.plan.risk.confirm_threshold is not None:
                self._tier_inputs(inputs, text)
        if self._unseen and "pending_s" not in inputs and not self._gone(inputs):
            inputs["pending_s"] = 0.0  # a signal not seen since the start: awaited, no limit
        d = m.step(inputs)
        self._history.append(inputs)  # a reload rebuilds the new monitor's temporal history from these
        self._last_inputs = inputs
        if self._stall_reason is not None:
            reasons.append(self._stall_reason)
            self._stall_reason = None
        if self._audit_failed:
            reasons.append(Fault("audit", f"audit log failed or its queue is full, or its writer is behind its "
                                 f"lag bounds ({self.stats.audit_drops} records refused)"))
        end = clock()
        late = end - sched
        if late > self.deadline_s:
            reasons.append(Fault("deadline", f"control cycle {self.stats.cycles} missed its deadline: decision "
                                 f"ready {late * 1e3:.3f} ms after its start time (deadline "
                                 f"{self.deadline_s * 1e3:g} ms)"))
            self.stats.deadline_misses += 1
        if reasons:
            d = m.fault(*reasons, decision=d)
        if self._awaiting_start is not None:  # an acknowledged stop waits for the spec's start (restart:)
            d = self._restart_hold(d, inputs)
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
        if self.audit is not None:
            self._audit(d, inputs, reading)
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

    def _tier_inputs(self, inputs: dict, text: str | None) -> None:
        """``task_id`` (the hash of ``text``, the task text this cycle's estimate is for) and the judge's
        answer for it (asked once per text)."""
        if text is not self._task_text:
            self._task_text = text
            self._task_key = None if text is None else AsyncJudgeSource.key(text)
            if self.judge is not None:
                self.judge.ask(text, self._task_key)
        inputs["task_id"] = self._task_key  # the loop owns these two inputs
        j = self.judge
        if j is None:
            inputs.pop("judge", None)
            return
        jr = j.result(text, self._task_key) if text is not None else None
        inputs["judge"] = jr.p_unsafe if jr is not None else None
        if j._log:  # unlocked peek; drain() takes the lock
            for res in j.drain():
                self._log("judge", loop_cycle=self.stats.cycles, **res.audit_fields())

    def _audit(self, d: Decision, inputs: dict, reading: RiskReading | None) -> None:
        key = (d.override, d.response, d.violations, tuple((f.kind, f.subject) for f in d.faults) if d.faults else (),
               d.latched_rules)  # a rule released while another holds the override is a change too
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
                       faults=[f.message for f in d.faults], fault_kinds=[f.kind for f in d.faults],
                       latched=d.latched, latched_rules=list(d.latched_rules), risk=d.risk,
                       margins=dict(zip(self._ids, d.margins)) if d.margins else {},
                       inputs=inputs, risk_age_s=reading.age_s if reading is not None else None,
                       spec_sha256=self.spec_sha256,
                       model_id=self.risk.model_id if self.risk is not None else None)
        if not ok:
            self._state_key = None  # log the state again once the queue has room

    def _audit_health(self) -> str | None:
        """What the audit log reports as its fault (its ``fault`` text), or ``None`` when healthy or absent."""
        if self.audit is None:
            return None
        try:
            afault = getattr(self.audit, "fault", None)
        except Exception as exc:  # noqa: BLE001 - a broken log is a fault, not a crash
            return f"audit log health check raised {type(exc).__name__}: {exc}"[:300]
        return afault if isinstance(afault, str) and afault else None

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
            if self._acks:
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
        self._log("fault", reason=reason, source="watchdog")
        cb = getattr(self, "_user_on_stall", None)
        if cb is not None:
            cb(reason)

    # acknowledge: loop/_acknowledge.py; reload: loop/_reload.py
    def __repr__(self) -> str:
        return (f"GovernedLoop(spec={self.spec.name!r}, period_s={self.period_s:g}, "
                f"cycles={self.stats.cycles}, misses={self.stats.deadline_misses})")
