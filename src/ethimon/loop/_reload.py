"""Hot spec reload of a :class:`~ethimon.loop.GovernedLoop`: compiled (and verified) in the caller's
thread, refused if it weakens monitoring or cannot carry a latch or a due response, swapped in between
two cycles; its outcome is a :class:`ReloadResult`."""

from __future__ import annotations

import os
import threading
from collections import deque
from concurrent.futures import Future
from dataclasses import dataclass, field

from .._api import load_spec
from ..compiler import Plan
from ..language._expr import TEMPORAL, Call, walk  # the names and windows a reloaded obligation reads
from ..errors import EthimonError
from ..runtime import Monitor
from ..language import Spec
from ._source import AsyncJudgeSource
from ._weakenings import unmapped_latches, weakenings

__all__ = ["ReloadResult"]


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
    #: set once the loop has swapped it in or refused it at the swap (``ok`` turns ``False`` then)
    settled: threading.Event = field(default_factory=threading.Event, repr=False)

    def wait_applied(self, timeout: float | None = None) -> bool:
        """Block until the loop has swapped the new spec in (``False`` on timeout or rejection,
        including a refusal at the swap: a latch that cannot be carried over)."""
        if not self.ok:
            return False
        self.settled.wait(timeout)
        return self.ok and self.applied.is_set()


def _latch_refusal(cannot: list[str]) -> str:
    return ("reload refused: a latched rule cannot be carried over to the new spec by identity (same id, "
            "response and release): " + "; ".join(cannot) + ". The running spec stays; release the latch "
            "first (acknowledge it, or let it release) or keep the rule as it is")


def _due_refusal(due: tuple[str, ...]) -> str:
    return ("reload refused: a bounded response is due (" + ", ".join(f"obligation {o}: its when fired, its "
            "require is not met yet, within_cycles running" for o in due) + "); a new monitor starts with a "
            "fresh history and would forget the deadline. The running spec stays; reload once it is met or "
            "has fired")


#: most recorded cycles a loop keeps to rebuild a reloaded monitor's temporal history
HISTORY_CAP = 4096


def history_depth(plan: Plan) -> int | None:
    """How many of the last cycles determine the temporal state of ``plan``'s monitor (an upper bound: the
    windows of every temporal operator of an obligation added up, its ``within_cycles``, one more for
    ``prev``); ``None``: unbounded (an operator without a window)."""
    most = 0
    for ob in plan.obligations:
        d = 1 + (ob.within_cycles + 1 if ob.within_cycles is not None else 0)
        for root in (ob.when, ob.require):
            for node in walk(root) if root is not None else ():
                if isinstance(node, Call) and node.func in TEMPORAL:
                    if node.func == "prev":
                        d += 1
                        continue
                    w = plan.windows.get(id(node))
                    if w is None:
                        return None
                    d += int(w) + 1
        most = max(most, d)
    return most


def history_len(plan: Plan) -> int:
    """The recorded cycles a loop keeps for ``plan`` (at least 64, at most :data:`HISTORY_CAP`)."""
    d = history_depth(plan)
    return HISTORY_CAP if d is None else min(HISTORY_CAP, max(64, d + 1))


def _history_refusal(held: int, kept: int, need: int | None) -> str:
    return (f"reload refused: the running monitor's temporal history spans {held} cycles and {kept} are "
            f"recorded, but the new spec's windows need {'all of them (a window without a bound)' if need is None else need}: "
            "an event held in a window would be forgotten. The running spec stays; reload after a fault or "
            "reset cleared the history, or bound the window")


def _verify_smt(spec: Spec) -> None:
    """Reject a spec unless every decision-logic property is proved (``ethimon.verify``, z3)."""
    from ..verify import verify_spec  # lazy: z3 only when verify='smt'
    rep = verify_spec(spec, lints=False)
    if rep.exit_code != 0:
        bad = [f"{f.name}: {f.status}" for f in rep.findings if f.kind == "property"
               and f.status in ("refuted", "unknown")]
        raise EthimonError("verification failed: " + ("; ".join(bad) if bad else str(rep.error)))


class _Reloading:
    """:meth:`reload`, :meth:`reload_async` and the swap between cycles (a base of ``GovernedLoop``)."""

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
        label = "<Spec>" if isinstance(source, Spec) else os.fspath(source)
        weak: tuple[str, ...] = ()
        unjudged: tuple[str, ...] = ()
        try:
            spec = source if isinstance(source, Spec) else load_spec(source)
            new = Monitor(spec, margins=self.monitor._margins_on, max_age_s=self._age_fallback)
            w, u = weakenings(self.monitor.spec, spec, loop_max_age_s=self._age_fallback)
            weak, unjudged = tuple(w), tuple(u)
            if weak and not allow_weaker:
                raise EthimonError("reload refused: the new spec weakens monitoring: " + "; ".join(weak)
                                   + ". The running spec stays; pass allow_weaker=True to accept a weaker spec")
            # checked again at the swap, against the latches held then (allow_weaker does not waive it)
            cannot = unmapped_latches(self.monitor.spec, spec, self.monitor.latched_rules)
            if cannot:
                raise EthimonError(_latch_refusal(cannot))
            due = self.monitor.pending_responses  # checked again at the swap, like the latches
            if due:
                raise EthimonError(_due_refusal(due))
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
            old[1].settled.set()  # never applied: its wait_applied() returns False now
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

    def _carry_history(self, old: Monitor, new: Monitor) -> str:
        """Rebuild ``new``'s temporal history: step it through the recorded inputs of the cycles that make
        up ``old``'s history (as if it had run them), then release what those cycles latched (the running
        latches are carried next) and continue ``old``'s cycle count. '' when done, else why it cannot be."""
        held = old._cycle - old._hist0  # cycles since the running monitor's history last restarted
        buf = self._history
        need = history_depth(new.plan)
        k = min(held, len(buf))
        if k < held and (need is None or need > k):
            return _history_refusal(held, k, need)
        if need is not None:
            k = min(k, need)
        for inputs in list(buf)[len(buf) - k:] if k else ():
            new.step(inputs)
        new.release()
        h = new._cycle - new._hist0
        new._cycle = old._cycle
        new._hist0 = new._cycle - h
        return ""

    def _apply_reload(self) -> None:
        with self._reload_lock:
            pending, self._pending = self._pending, None
        if pending is None:
            return
        new, res, label = pending
        old = self.monitor
        latched = old.latched_rules
        try:
            cannot = unmapped_latches(old.spec, new.spec, latched)
        except Exception as exc:  # noqa: BLE001 - a latch that cannot be carried keeps the old spec
            cannot = [f"carrying the latches raised {type(exc).__name__}: {exc}"]
        try:
            due = () if cannot else old.pending_responses
        except Exception as exc:  # noqa: BLE001 - cannot tell: keep the old spec
            due = (f"? ({type(exc).__name__}: {exc})",)
        if not cannot and not due:
            try:
                why = self._carry_history(old, new)
                if why:
                    cannot = [why]
                else:
                    new.carry_latches(latched)  # same id, same response, same release: the latch goes on
                    for name in latched:  # since the cycle it latched in the running monitor
                        new._since[new._names.index(name)] = old._since[old._names.index(name)]
            except Exception as exc:  # noqa: BLE001 - what cannot be carried keeps the old spec
                cannot = [f"carrying the history and latches raised {type(exc).__name__}: {exc}"]
        if cannot or due:
            res.ok = False
            res.error = ((cannot[0] if cannot[0].startswith("reload refused: the running monitor's temporal")
                          else _latch_refusal(cannot)) if cannot else _due_refusal(due))[:4000]
            self.stats.reloads_rejected += 1
            self._log("reload", status="rejected", stage="swap", source=label, spec_sha256=res.spec_sha256,
                      error=res.error, running_spec_sha256=self.spec_sha256, latched=list(latched),
                      loop_cycle=self.stats.cycles)
            res.settled.set()
            return
        self.monitor = new
        self._history = deque(self._history, maxlen=history_len(new.plan))
        old_hash, self.spec_sha256 = self.spec_sha256, res.spec_sha256
        self._ids = new.obligation_ids
        self._state_key = None
        if self._judge_from_spec and self.risk is not None and (new.plan.risk.judge_list != old.plan.risk.judge_list):
            # the judge the new spec names (or none); its texts are asked again
            if self.judge is not None:
                self.judge.stop(timeout=0.0)
            from ..risk import load_judge_for
            j = load_judge_for(new.spec)
            self.judge = AsyncJudgeSource(j) if j is not None else None
            self._task_text = self._task_key = None
        self.stats.reloads_applied += 1
        res.applied_at_cycle = self.stats.cycles
        self._log("reload", status="applied", source=label, spec_sha256=res.spec_sha256,
                  previous_spec_sha256=old_hash, loop_cycle=self.stats.cycles, carried_latch=bool(latched),
                  carried_rules=list(latched))
        res.applied.set()
        res.settled.set()
