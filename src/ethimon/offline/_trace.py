"""``check_trace``: a whole recorded trace through a spec's obligations at once, with numpy.

What :class:`~ethimon.Monitor` does cycle by cycle, done column by column:

1. The input boundary (:mod:`._columns`): which cycles have a missing, NaN,
   out-of-range or mistyped input (those are fault cycles), and R_e per cycle.
2. The obligations on the valid cycles (:mod:`._eval`): segments between faults
   are independent histories; every operator is a linear scan. Where an
   expression raises (division by zero, square root of a negative number) the
   monitor has an internal fault that also clears the history, so the cycles
   after the first such fault of a segment are evaluated again as a fresh
   segment; a run of cycles that raise even as the first cycle of a segment is
   taken in one go. After ``_MAX_PASSES`` rounds the rest of such a segment is
   stepped through a fresh :class:`~ethimon.Monitor` (the only fallback; the
   result says how many cycles took it).
3. On fault cycles the stateless obligations whose inputs are valid are judged
   (as the monitor does), vectorised over those cycles.
4. The latches, one per rule (each obligation, the risk rule, the fault rule), and
   their release (``auto``: hysteresis, ``hold_cycles``, the exact bound τ − δ;
   ``manual``: held), from per-cycle firings with running maxima instead of a loop.

Fault reasons are the monitor's own: they are produced on demand
(:meth:`OfflineResult.faults_at`) by stepping a :class:`~ethimon.Monitor` over
the cycle (an input fault) or over its segment (an internal fault), so they are
worded exactly as the monitor words them.
"""

from __future__ import annotations

import os
from collections.abc import Iterator, Mapping
from typing import Any

import numpy as np

from ..runtime import Decision
from ..runtime import Monitor
from ..language import SEVERITY_ORDER, Response, Spec
from ..compiler import Plan, stateless_slots
from ._columns import Inputs, read_inputs, row
from ._eval import Evaluator, last_index

__all__ = ["check_trace", "OfflineResult", "iter_rows"]

_RESPONSES = SEVERITY_ORDER  # severity -> Response
#: rounds of "an expression raised: evaluate the rest of the segment again" before the rest is stepped
_MAX_PASSES = 8


def _plan(spec: Any):
    from ..compiler import plan_of
    return plan_of(spec)


class OfflineResult:
    """Every cycle's verdicts for a recorded trace (see :func:`check_trace`).

    Arrays have one row per cycle (``n_cycles``):

    Attributes:
        obligation_ids: obligation ids in spec order (the columns of ``violated`` and ``margins``).
        override: the monitor's ``Decision.override``.
        response: severity of ``Decision.response`` (0 none, 1 safe_pose, 2 stop_2, 3 stop_1,
            4 stop_0); :meth:`response_at` gives the :class:`~ethimon.Response`.
        latched: ``Decision.latched`` (held by the release rules, no current violation).
        awaiting_release: ``Decision.awaiting_release`` (every latched manual rule is ready for
            ``Monitor.acknowledge()``).
        fault: the cycle failed closed (``Decision.faults`` non-empty).
        internal_error: the fault came from evaluating an expression (division by zero, ...),
            not from an input.
        violated: ``(n_cycles, n_obligations)`` verdicts: obligation ``k`` is in
            ``Decision.violations`` at cycle ``t`` (on a fault cycle: a stateless obligation
            with valid inputs that the monitor still judged).
        risk_violated: ``"risk"`` (R_e ≥ τ) is in ``Decision.violations``.
        risk: ``Decision.risk``, NaN where it is ``None``.
        margins: ``(n_cycles, n_obligations)`` ``Decision.margins`` (NaN on fault cycles), or
            ``None`` when checked with ``margins=False``.
        fallback_cycles: cycles that were stepped through :class:`~ethimon.Monitor` instead of
            being vectorised (0 unless expressions raised on many cycles; see ``fallback_reason``).
    """

    def __init__(self, spec: Spec, inputs: Inputs, obligation_ids: tuple[str, ...], margins_on: bool,
                 max_age_s: float | None = None) -> None:
        n, k = inputs.n, len(obligation_ids)
        self.spec = spec
        self.obligation_ids = obligation_ids
        self.n_cycles = n
        self.override = np.zeros(n, bool)
        self.response = np.zeros(n, np.int8)
        self.latched = np.zeros(n, bool)
        self.awaiting_release = np.zeros(n, bool)
        self.fault = inputs.input_fault.copy()
        self.internal_error = np.zeros(n, bool)
        self.violated = np.zeros((n, k), bool)
        self.risk_violated = np.zeros(n, bool)
        #: the tier rules' firings (``"judge"``, ``"confirm"``), for specs with risk.judge/confirm_threshold
        self.tier_violated = {"judge": np.zeros(n, bool), "confirm": np.zeros(n, bool)}
        self._tier_rows: list[dict[str, Any]] | None = None  # per-cycle judge/task_id inputs (tier specs)
        self.risk = inputs.risk
        self.margins = np.full((n, k), np.nan) if margins_on else None
        self.fallback_cycles = 0
        self.fallback_reason: str | None = None
        self.method = "vector"
        self._inputs = inputs
        self._max_age_s = max_age_s
        self._faults: dict[int, tuple] = {}
        self._scratch: Monitor | None = None  # steps input-fault cycles for their reasons
        self._replayer: Monitor | None = None  # replays a segment up to an internal fault
        self._last_fault: np.ndarray | None = None
        self._plan: Plan | None = None  # the plan checked (set by check_trace)
        #: per rule (obligation ids, "risk", "fault"): bool[n], its latch holds the override at that cycle
        #: (vector method); the step method records ``Monitor.latched_rules`` where it changes instead
        self._holding: dict[str, np.ndarray] = {}
        self._holding_changes: dict[int, tuple[str, ...]] | None = None

    def _monitor(self, margins: bool = False) -> Monitor:
        return Monitor(self._plan if self._plan is not None else self.spec, margins=margins,
                       max_age_s=self._max_age_s)

    # -- per cycle, as the monitor reports it ------------------------------------
    def response_at(self, t: int) -> Response:
        """The :class:`~ethimon.Response` of cycle ``t``."""
        return _RESPONSES[int(self.response[t])]

    def violations_at(self, t: int) -> tuple[str, ...]:
        """``Decision.violations`` of cycle ``t`` (obligation ids in spec order, then ``"risk"``, ``"judge"``, ``"confirm"``)."""
        out = [self.obligation_ids[k] for k in np.flatnonzero(self.violated[t])]
        if self.risk_violated[t]:
            out.append("risk")
        for tier in ("judge", "confirm"):   # the tier rules, in the monitor's order (after "risk")
            if self.tier_violated[tier][t]:
                out.append(tier)
        return tuple(out)

    def row(self, t: int) -> dict[str, Any]:
        """The inputs of cycle ``t`` as ``Monitor.step`` is given them."""
        return row(self._inputs, t)

    def faults_at(self, t: int) -> tuple:
        """``Decision.faults`` of cycle ``t``, worded by the monitor itself (empty if no fault)."""
        t = int(t)
        if not self.fault[t]:
            return ()
        got = self._faults.get(t)
        if got is None:
            if not self.internal_error[t]:
                if self._scratch is None:
                    self._scratch = self._monitor()
                got = self._scratch.step(self.row(t)).faults  # depends on this cycle's inputs only
            else:  # depends on the history since the last fault: replay that segment
                if self._last_fault is None:
                    idx = np.arange(self.n_cycles)
                    self._last_fault = np.maximum.accumulate(np.where(self.fault, idx, -1))
                start = int(self._last_fault[t - 1]) + 1 if t else 0
                if self._replayer is None:
                    self._replayer = self._monitor()
                m = self._replayer
                m.reset()  # a fresh history, as after the fault before the segment
                for s in range(start, t):
                    m.step(self.row(s))
                got = m.step(self.row(t)).faults
                if not got:  # pragma: no cover - a disagreement with the monitor is a bug
                    raise RuntimeError(f"offline checker bug: cycle {t} should be an internal fault")
            self._faults[t] = got
        return got

    def holding_at(self, t: int) -> tuple[str, ...]:
        """The rules whose latch holds the override at cycle ``t`` (``Monitor.latched_rules`` after
        that cycle's step): obligation ids in spec order, then ``"risk"``, ``"fault"`` and the tier
        rules; empty where the override is off."""
        t = int(t)
        if not self.override[t]:
            return ()
        if self._holding_changes is not None:
            keys = [c for c in self._holding_changes if c <= t]
            return self._holding_changes[max(keys)] if keys else ()
        return tuple(name for name, active in self._holding.items() if active[t])

    def decision(self, t: int) -> Decision:
        """The :class:`~ethimon.Decision` the monitor returns at cycle ``t`` of this trace."""
        t = int(t)
        risk = float(self.risk[t]) if self.risk[t] == self.risk[t] else None
        margins: tuple = ()
        if self.margins is not None:
            margins = tuple(float(x) for x in self.margins[t])
        return Decision(bool(self.override[t]), self.response_at(t), self.violations_at(t), margins, risk, t,
                        bool(self.latched[t]), self.faults_at(t), bool(self.awaiting_release[t]))

    def decisions(self) -> Iterator[Decision]:
        """Every cycle's :class:`~ethimon.Decision`, in order."""
        for t in range(self.n_cycles):
            yield self.decision(t)

    # -- per obligation ------------------------------------------------------------
    def summary(self) -> dict[str, dict[str, Any]]:
        """Per obligation (and ``"risk"``): first violation cycle, cycles violated, worst margin.

        The worst margin is the smallest margin over the cycles without a fault (``None``
        without margins or where every margin is NaN).
        """
        out: dict[str, dict[str, Any]] = {}
        ok = ~self.fault
        for k, oid in enumerate(self.obligation_ids):
            col = self.violated[:, k]
            hits = np.flatnonzero(col)
            worst = None
            if self.margins is not None and ok.any():
                m = self.margins[ok, k]
                m = m[~np.isnan(m)]
                if len(m):
                    worst = float(m.min())
            out[oid] = {"first_violation": int(hits[0]) if len(hits) else None,
                        "cycles_violated": int(len(hits)), "worst_margin": worst}
        hits = np.flatnonzero(self.risk_violated)
        out["risk"] = {"first_violation": int(hits[0]) if len(hits) else None, "cycles_violated": int(len(hits)),
                       "worst_margin": None}
        return out

    def __repr__(self) -> str:
        return (f"OfflineResult(spec={self.spec.name!r}, cycles={self.n_cycles}, "
                f"overrides={int(self.override.sum())}, faults={int(self.fault.sum())}, method={self.method!r})")


def iter_rows(spec: Spec | str | os.PathLike, columns: Mapping[str, Any], *,
              length: int | None = None) -> Iterator[dict[str, Any]]:
    """Each cycle's inputs as :func:`check_trace` defines them (``Monitor.step(row)`` checks the same)."""
    if not isinstance(spec, Spec):
        from .._api import load_spec
        spec = load_spec(spec)
    inp = read_inputs(_plan(spec), columns, length)
    for t in range(inp.n):
        yield row(inp, t)


def check_trace(spec: Spec | Plan | str | os.PathLike, columns: Mapping[str, Any], *, margins: bool = True,
                length: int | None = None, method: str = "vector",
                max_age_s: float | None = None) -> OfflineResult:
    """Check a whole recorded trace, equal cycle by cycle to ``Monitor.step`` over it.

    Args:
        spec: a :class:`~ethimon.Spec`, its compiled :class:`~ethimon.compiler.Plan` (whose resolved
            releases are what is checked) or the path of a spec file.
        columns: column name → one value per cycle: the spec's signals, one risk input
            (``risk``, ``p_unsafe``, or ``p`` as a 2-d array of class probabilities), and
            ``risk_age_s`` if the spec sets ``risk.max_age_s``. A missing column, a masked
            entry or ``None`` is a missing input; NaN, out-of-range and mistyped values fail
            closed exactly where the monitor fails closed. Other columns are ignored.
        margins: compute every obligation's margin per cycle (as ``Monitor(spec, margins=True)``).
        length: the number of cycles, needed only if no column the spec reads is given.
        method: ``"vector"`` (numpy), or ``"step"`` (``Monitor.step`` over every cycle; the
            reference it equals, slower).
        max_age_s: the age limit of risk estimates when the spec sets no ``risk.max_age_s``
            (as ``Monitor(spec, max_age_s=...)``); then a ``risk_age_s`` column is read.

    Returns:
        An :class:`OfflineResult`.

    Raises:
        ValueError: a column of the wrong shape or length (the message names it).

    Example:
        >>> import ethimon, numpy as np
        >>> from ethimon.offline import check_trace
        >>> spec = ethimon.load_spec_text('''
        ... ethimon: 1
        ... name: demo
        ... signals: {speed: {unit: m/s, range: [0, 3]}}
        ... obligations:
        ...   - {id: slow, require: "speed <= 1.0"}
        ... ''')
        >>> res = check_trace(spec, {"speed": np.array([0.5, 1.5, 0.2, np.nan]), "p_unsafe": np.full(4, 0.05)})
        >>> res.violated[:, 0].tolist(), res.fault.tolist()
        ([False, True, False, False], [False, False, False, True])
        >>> res.summary()["slow"]["first_violation"]
        1
    """
    if isinstance(spec, Plan):
        plan, spec = spec, spec.spec
    else:
        if not isinstance(spec, Spec):
            from .._api import load_spec
            spec = load_spec(spec)
        plan = _plan(spec)
    if method not in ("vector", "step"):
        raise ValueError(f"method must be 'vector' or 'step', got {method!r}")
    Monitor(plan, margins=False, max_age_s=max_age_s)  # the same argument checks as the monitor's
    inp = read_inputs(plan, columns, length, max_age_s=max_age_s)
    ids = tuple(ob.id for ob in plan.obligations)
    res = OfflineResult(spec, inp, ids, margins, max_age_s)
    res._plan = plan
    if inp.n == 0:
        return res
    if plan.tiers.on:  # a confirm band or a judge (one, or a panel: risk.judges)
        # the tier rules (confirm band, judge) have no vector form: every cycle through the monitor,
        # with the recorded judge answers (a 'judge' column, NaN/None: no judgement) and task ids
        res._tier_rows = _tier_rows(columns, inp.n)
        method = "step"
    with np.errstate(all="ignore"):
        if method == "step":
            _step_all(res, inp, margins)
            if res._tier_rows is not None:
                res.fallback_reason = "the spec has a confirm band or a judge (stepped through Monitor)"
            return res
        _valid_cycles(res, plan, inp, margins)
        _fault_cycles(res, plan, inp)
    _latch(res, plan, inp)
    return res


# -- valid cycles ------------------------------------------------------------------------

def _evaluate(plan, inp: Inputs, cycles: np.ndarray, starts: np.ndarray, margins: bool):
    """``(violated per obligation, margins per obligation or None, err or None)`` on ``cycles``."""
    ev = Evaluator(plan, inp, cycles, starts)
    ev.touch_temporal()
    err = ev.update_err
    viol = []
    for ob in plan.obligations:
        v, e = ev.obligation(ob)
        viol.append(v)
        if e is not None:
            err = e if err is None else err | e
    marg = [ev.margin(ob) for ob in plan.obligations] if margins else None
    return viol, marg, err


def _commit(res: OfflineResult, cycles: np.ndarray, sel, viol, marg) -> None:
    if isinstance(sel, slice) and len(cycles) == res.n_cycles and viol:  # every cycle, in order
        res.violated = np.stack(viol, axis=1)
        if marg is not None:
            res.margins = np.stack(marg, axis=1)
        return
    c = cycles[sel]
    for k, v in enumerate(viol):
        res.violated[c, k] = v[sel]
        if marg is not None:
            res.margins[c, k] = marg[k][sel]


def _valid_cycles(res: OfflineResult, plan, inp: Inputs, margins: bool) -> None:
    n = inp.n
    todo = np.flatnonzero(~inp.input_fault)
    fresh_err = None  # per cycle: raises even as the first cycle of a segment
    passes = 0
    while len(todo):
        starts = np.ones(len(todo), bool)
        starts[1:] = np.diff(todo) != 1
        viol, marg, err = _evaluate(plan, inp, todo, starts, margins)
        if err is None or not err.any():
            _commit(res, todo, slice(None), viol, marg)
            return
        seg = np.cumsum(starts) - 1
        first = np.full(int(seg[-1]) + 1, len(todo))
        bad = np.flatnonzero(err)
        segs, at = np.unique(seg[bad], return_index=True)
        first[segs] = bad[at]
        keep = np.arange(len(todo)) < first[seg]
        _commit(res, todo, keep, viol, marg)
        if fresh_err is None:
            ok = np.flatnonzero(~inp.input_fault)
            _, _, e0 = _evaluate(plan, inp, ok, np.ones(len(ok), bool), False)
            fresh_err = np.zeros(n + 1, bool)
            if e0 is not None:
                fresh_err[ok] = e0
        # the first raise of each segment is an internal fault; so is every following cycle that
        # raises even with an empty history; the rest of the segment starts afresh after them
        nxt = np.minimum.accumulate(np.where(~fresh_err, np.arange(n + 1), n)[::-1])[::-1]
        errs = todo[first[segs]]
        restart = nxt[errs + 1]
        mark = np.zeros(n + 1, np.int64)
        np.add.at(mark, errs, 1)
        np.add.at(mark, restart, -1)
        res.internal_error |= np.cumsum(mark)[:n] > 0
        res.fault |= res.internal_error
        lim = np.full(int(seg[-1]) + 1, n)
        lim[segs] = restart
        rest = (~keep) & (todo >= lim[seg])
        todo = todo[rest]
        passes += 1
        if passes >= _MAX_PASSES and len(todo):
            _step_segments(res, todo, margins)
            res.fallback_reason = (f"expressions raised in {passes} rounds of re-evaluation; the rest of "
                                   "those segments was stepped through Monitor.step")
            return


def _step_segments(res: OfflineResult, todo: np.ndarray, margins: bool) -> None:
    """The fallback: step each run of consecutive cycles in ``todo`` through a fresh Monitor."""
    ids = {oid: k for k, oid in enumerate(res.obligation_ids)}
    breaks = np.flatnonzero(np.diff(todo) != 1) + 1
    m = res._monitor(margins)
    for run in np.split(todo, breaks):
        m.reset()  # each run follows a fault: a fresh history
        for t in run.tolist():
            d = m.step(res.row(t))
            res.fallback_cycles += 1
            if d.faults:
                res.internal_error[t] = True
                res.fault[t] = True
                res._faults[t] = d.faults
                continue
            for v in d.violations:
                if v != "risk":
                    res.violated[t, ids[v]] = True
            if margins:
                res.margins[t] = d.margins


def _step_all(res: OfflineResult, inp: Inputs, margins: bool) -> None:
    """``method="step"``: every cycle through one Monitor, read back into the arrays."""
    res.method = "step"
    ids = {oid: k for k, oid in enumerate(res.obligation_ids)}
    m = res._monitor(margins)
    risk = np.full(inp.n, np.nan)
    tiers = res._tier_rows
    res._holding_changes = changes = {}
    held: tuple[str, ...] = ()
    for t in range(inp.n):
        d = m.step(row(inp, t) if tiers is None else {**row(inp, t), **tiers[t]})
        if d.override or held:
            now = m.latched_rules if d.override else ()
            if now != held:
                changes[t] = held = now
        res.override[t] = d.override
        res.response[t] = d.response.severity
        res.latched[t] = d.latched
        res.awaiting_release[t] = d.awaiting_release
        res.fault[t] = bool(d.faults)
        if d.faults:
            res._faults[t] = d.faults
            res.internal_error[t] = not inp.input_fault[t]
        for v in d.violations:
            if v == "risk":
                res.risk_violated[t] = True
            elif v in res.tier_violated and v not in ids:
                res.tier_violated[v][t] = True
            else:
                res.violated[t, ids[v]] = True
        if margins and d.margins:
            res.margins[t] = d.margins
        if d.risk is not None:
            risk[t] = d.risk
    res.risk = risk
    res.fallback_cycles = inp.n
    res.fallback_reason = "method='step'"


def _tier_rows(columns: Mapping[str, Any], n: int) -> list[dict[str, Any]]:
    """Per cycle, the ``judge`` (a p_unsafe; NaN, masked or None: no judgement) and ``task_id`` inputs."""
    out: list[dict[str, Any]] = [{} for _ in range(n)]
    for key in ("judge", "task_id"):
        col = columns.get(key)
        if col is None:
            continue
        mask = np.ma.getmaskarray(col) if isinstance(col, np.ma.MaskedArray) else None
        vals = list(np.ma.getdata(col)) if isinstance(col, np.ma.MaskedArray) else list(col)
        if len(vals) != n:
            raise ValueError(f"column {key!r} has {len(vals)} values, expected {n}")
        for t, v in enumerate(vals):
            if (mask is not None and mask[t]) or v is None:
                continue
            if key == "judge":
                f = float(v) if isinstance(v, (int, float, np.floating, np.integer)) and not isinstance(v, bool) else v
                if isinstance(f, float) and f != f:
                    continue  # NaN: no judgement at this cycle
                out[t][key] = f
            else:
                out[t][key] = v
    return out


# -- fault cycles --------------------------------------------------------------------------

def _stateless_names(plan, ob) -> set[str] | None:
    """Inputs a stateless obligation reads (signal names, ``risk``), or ``None`` if it keeps state:
    the monitor's own rule (:func:`ethimon.compiler.stateless_slots`), by name."""
    used = stateless_slots(plan, ob)
    if used is None:
        return None
    return {name for name, slot in plan.slots.items() if slot in used}


def _fault_cycles(res: OfflineResult, plan, inp: Inputs) -> None:
    """On input-fault cycles, the stateless obligations whose inputs are all valid are still judged."""
    cycles = np.flatnonzero(inp.input_fault)
    if not len(cycles):
        return
    stateless = [(k, ob, names) for k, ob in enumerate(plan.obligations)
                 if (names := _stateless_names(plan, ob)) is not None]
    if not stateless:
        return
    ev = Evaluator(plan, inp, cycles, np.ones(len(cycles), bool))
    risk_ok = (inp.risk_ok & inp.age_ok)[cycles]
    for k, ob, names in stateless:
        v, e = ev.obligation(ob)
        hit = v.copy()
        if e is not None:
            hit &= ~e  # one that raises is skipped: the cycle fails closed anyway
        for name in names:
            hit &= risk_ok if name == "risk" else inp.ok[name][cycles]
        res.violated[cycles, k] = hit


# -- the latch -----------------------------------------------------------------------------

def _latch(res: OfflineResult, plan, inp: Inputs) -> None:
    """Override, response, the latched flag and ``awaiting_release`` from the per-cycle firings.

    One latch per rule, as the monitor keeps them: each obligation, the risk rule and
    the fault rule. A rule latches where it fires; its count is the run of cycles since
    the last cycle that fired it, faulted, or (the risk rule) had R_e not below τ − δ; an
    ``auto`` rule releases at the first cycle after a firing where that run reaches its
    ``hold_cycles``; a ``manual`` rule stays latched (``acknowledge()`` is an operator's, not
    the trace's). Everything is a running maximum or a cumulative sum over the trace.
    """
    n = inp.n
    idx = np.arange(n, dtype=np.int32 if n < 2 ** 31 - 1 else np.int64)
    tau = plan.threshold
    fault = res.fault
    res.risk_violated = inp.risk_ok & (np.where(inp.risk_ok, inp.risk, -np.inf) >= tau)
    fired_valid = np.zeros(n, bool)  # Decision.violations is not empty on a valid cycle
    rules = []  # (name, fires, severity, manual, hold, extra reset or None)
    for k, ob in enumerate(plan.obligations):  # releases, holds and severities: resolved in the plan
        col = res.violated[:, k]
        fired_valid |= col
        rules.append((ob.id, col, ob.response.severity, ob.manual, ob.release_hold, None))
    below = ~fault & inp.risk_ok & (np.where(inp.risk_ok, inp.risk, np.inf) < plan.release_cut)
    fired_valid |= res.risk_violated
    rr, fr = plan.risk_rule, plan.fault_rule
    rules.append(("risk", res.risk_violated, rr.severity, rr.manual, rr.hold, ~below))
    rules.append(("fault", fault, fr.severity, fr.manual, fr.hold, None))
    fired_valid &= ~fault
    level = np.zeros(n, np.int8)
    manual_active = np.zeros(n, bool)
    manual_waiting = np.zeros(n, bool)  # a latched manual rule whose count has not reached its hold
    for name, fire, sev, manual, hold, extra in rules:
        fires = np.flatnonzero(fire)
        if not len(fires):
            continue
        rst = fire | fault if extra is None else fire | fault | extra
        run = idx - last_index(rst, idx)  # the rule's count while latched
        if manual:
            active = np.zeros(n, bool)
            active[fires[0]:] = True
            manual_active |= active
            manual_waiting |= active & (run < hold)
        else:
            cand = np.flatnonzero(run == hold)
            j = np.searchsorted(fires, cand, side="right") - 1  # each candidate's last firing
            cand, j = cand[j >= 0], j[j >= 0]
            first = np.ones(len(cand), bool)
            first[1:] = j[1:] != j[:-1]
            released = cand[first]  # the first candidate after a firing releases the latch
            nxt = np.searchsorted(fires, released, side="right")
            starts = np.concatenate((fires[:1], fires[nxt[nxt < len(fires)]]))
            mark = np.zeros(n + 1, np.int32)
            mark[starts] += 1
            mark[released] -= 1
            active = np.cumsum(mark[:n]) > 0
        res._holding[name] = active
        np.maximum(level, np.where(active, np.int8(sev), np.int8(0)), out=level)
    res.override = level > 0
    res.response = level
    res.latched = res.override & ~fault & ~fired_valid
    res.awaiting_release = ~fault & manual_active & ~manual_waiting
