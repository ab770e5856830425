"""The reloader of a :class:`~ethimon.loop.GovernedLoop`: a new spec compiled (and verified) in the caller's
thread, refused if it weakens monitoring or cannot carry a latch or a due response, swapped in between
two cycles; its outcome is a :class:`ReloadResult`. :class:`Reloader` owns the pending swap and the
recorded inputs a new monitor's temporal history is rebuilt from."""

from __future__ import annotations

import os
import threading
from collections import deque
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from .._api import load_spec
from ..audit import spec_hash
from ..compiler import Plan
from ..language._expr import walk  # the look-backs and windows a reloaded obligation reads
from ..errors import EthimonError
from ..runtime import Monitor
from ..language import Spec
from ._weakenings import unmapped_latches, weakenings

__all__ = ["ReloadResult", "Reloader"]


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
    look-back of every temporal operator of an obligation added up, by its row of the operator table (one
    cycle for a ``"one"`` look-back such as ``prev``, its window plus one for a windowed one), and its
    ``within_cycles``); ``None``: unbounded (a window without a bound)."""
    most = 0
    for ob in plan.obligations:
        d = 1 + (ob.within_cycles + 1 if ob.within_cycles is not None else 0)
        for root in (ob.when, ob.require):
            for node in walk(root) if root is not None else ():
                row = node.row
                if row is None or row.lookback == "none":
                    continue
                if row.lookback == "one":
                    d += 1
                    continue
                w = node.ann.window
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


class Reloader:
    """The hot reload of a loop's spec: checks a new spec against the running one, keeps it pending until
    the loop thread swaps it in between two cycles, and records the inputs of the last cycles so that the
    new monitor starts with the running one's temporal history.

    Args:
        verify: the check a new spec must pass (:attr:`LoopConfig.verify`): a callable ``verify(spec)``
            (raising or returning ``False`` rejects it), ``"smt"`` (z3) or ``None`` (compile only).
    """

    __slots__ = ("verify", "history", "pending", "lock", "spec_hash")

    def __init__(self, verify: Callable[[Spec], Any] | str | None = None) -> None:
        if verify == "smt":
            verify = _verify_smt
        elif verify is not None and not callable(verify):
            raise ValueError(f"verify={verify!r}; expected None, 'smt' or a callable verify(spec)")
        self.verify = verify
        #: the last cycles' inputs (:meth:`record`), sized by :meth:`track`
        self.history: deque = deque(maxlen=64)
        #: ``(new monitor, result, source label)`` waiting for the swap, or ``None``
        self.pending: tuple[Monitor, ReloadResult, str] | None = None
        self.lock = threading.Lock()
        self.spec_hash: Callable[[Spec], str] = spec_hash

    def track(self, plan: Plan) -> None:
        """Keep as many recorded cycles as ``plan``'s windows need (the recorded ones stay)."""
        self.history = deque(self.history, maxlen=history_len(plan))

    def record(self, inputs: Mapping[str, Any]) -> None:
        """One cycle's inputs (a reload rebuilds the new monitor's temporal history from these)."""
        self.history.append(inputs)

    def prepare(self, running: Monitor, source: str | os.PathLike | Spec, allow_weaker: bool,
                age_fallback: float | None) -> tuple[ReloadResult, Monitor | None]:
        """Load, compile, compare and verify ``source`` against the ``running`` monitor (never raises): the
        result, and the new monitor when accepted."""
        label = "<Spec>" if isinstance(source, Spec) else os.fspath(source)
        weak: tuple[str, ...] = ()
        unjudged: tuple[str, ...] = ()
        try:
            spec = source if isinstance(source, Spec) else load_spec(source)
            new = Monitor(spec, margins=running._margins_on, max_age_s=age_fallback)
            w, u = weakenings(running.spec, spec, loop_max_age_s=age_fallback)
            weak, unjudged = tuple(w), tuple(u)
            if weak and not allow_weaker:
                raise EthimonError("reload refused: the new spec weakens monitoring: " + "; ".join(weak)
                                   + ". The running spec stays; pass allow_weaker=True to accept a weaker spec")
            # checked again at the swap, against the latches held then (allow_weaker does not waive it)
            cannot = unmapped_latches(running.spec, spec, running.latched_rules)
            if cannot:
                raise EthimonError(_latch_refusal(cannot))
            due = running.pending_responses  # checked again at the swap, like the latches
            if due:
                raise EthimonError(_due_refusal(due))
            if self.verify is not None:
                verdict = self.verify(spec)
                if verdict is False:
                    raise EthimonError("verification failed")
            h = self.spec_hash(spec)
        except Exception as exc:  # noqa: BLE001 - rejected, never raised into the loop's owner
            msg = str(exc) if isinstance(exc, EthimonError) else f"{type(exc).__name__}: {exc}"
            return ReloadResult(False, label, None, msg[:4000], weakened=weak, unjudged=unjudged), None
        return ReloadResult(True, label, h, weakened=weak, unjudged=unjudged), new

    def queue(self, new: Monitor, res: ReloadResult) -> tuple[Monitor, ReloadResult, str] | None:
        """Make ``new`` the pending swap; the one it supersedes (settled, never applied), if any."""
        with self.lock:
            old = self.pending
            self.pending = (new, res, res.source)
        if old is not None:
            old[1].settled.set()  # never applied: its wait_applied() returns False now
        return old

    def take(self) -> tuple[Monitor, ReloadResult, str] | None:
        with self.lock:
            pending, self.pending = self.pending, None
        return pending

    def carry(self, old: Monitor, new: Monitor) -> tuple[str, str]:
        """Carry ``old``'s temporal history and latches over to ``new`` (never raises): ``('', '')`` when
        done, else (the refusal text for the result, its cause)."""
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
        if cannot:
            return (cannot[0] if cannot[0].startswith("reload refused: the running monitor's temporal")
                    else _latch_refusal(cannot)), "cannot"
        if due:
            return _due_refusal(due), "due"
        return "", ""

    def _carry_history(self, old: Monitor, new: Monitor) -> str:
        """Rebuild ``new``'s temporal history: step it through the recorded inputs of the cycles that make
        up ``old``'s history (as if it had run them), then release what those cycles latched (the running
        latches are carried next) and continue ``old``'s cycle count. '' when done, else why it cannot be."""
        held = old._cycle - old._hist0  # cycles since the running monitor's history last restarted
        buf = self.history
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
