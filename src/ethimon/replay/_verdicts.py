"""The one checking step of a replay: the monitor over resampled columns.

:func:`check_columns` takes one column per monitor input (float64, NaN =
unusable: missing, stale or a bad recorded value) plus the risk input, and
returns per-cycle verdicts. An unusable input is left out of its cycle, so the
monitor fails closed on it exactly as on an input that did not arrive.

Two engines give the same verdicts: :func:`ethimon.offline.check_trace` (numpy,
whole columns at once; NaN entries passed as masked = missing) when that module
is available, else :meth:`ethimon.Monitor.step` over the cycles (the reference
semantics). ``engine="step"`` forces the latter.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..compiler import plan_of
from ..runtime import Monitor
from ..language import Spec

__all__ = ["CycleResults", "check_columns"]


@dataclass
class CycleResults:
    """Per-cycle verdicts of one replay (``n`` cycles, ``m`` obligations).

    Attributes:
        ids: obligation ids in ``Monitor.obligation_ids`` order, then ``"risk"``.
        override: bool[n].
        severity: int8[n], the response's severity (0 none .. 4 stop_0).
        violated: bool[n, m + 1], column ``j`` is ``ids[j]`` (the last one is the risk rule).
        margins: float64[n, m] (NaN on fault cycles).
        risk: float64[n], R_e (NaN when no usable risk input).
        fault: bool[n], the cycle failed closed.
        latched: bool[n].
        faults: the monitor's fault reasons (``Decision.faults``) of each fault cycle whose reasons differ
            from the cycle before (:meth:`faults_at` finds those of any cycle).
        engine: what checked the cycles (``"Monitor.step"``).
    """

    ids: tuple[str, ...]
    override: np.ndarray
    severity: np.ndarray
    violated: np.ndarray
    margins: np.ndarray
    risk: np.ndarray
    fault: np.ndarray
    latched: np.ndarray
    faults: dict[int, tuple]
    engine: str = "Monitor.step"
    _faults_at: Any = None
    #: the step engine: ``Monitor.latched_rules`` at each cycle where it changed (``holding_at`` reads it)
    holding: dict[int, tuple] | None = None
    _holding_at: Any = None

    def holding_at(self, k: int) -> tuple:
        """The rules whose latch holds the override at cycle ``k`` (``Monitor.latched_rules``): the
        latch that keeps the arm stopped, which is not always the rule that fired last."""
        if not self.override[k]:
            return ()
        if self._holding_at is not None:
            return tuple(self._holding_at(k))
        keys = [c for c in (self.holding or {}) if c <= k]
        return self.holding[max(keys)] if keys else ()

    def faults_at(self, k: int) -> tuple:
        """The monitor's fault reasons of cycle ``k`` (empty if it did not fail closed)."""
        if not self.fault[k]:
            return ()
        if self._faults_at is not None:
            return tuple(self._faults_at(k))
        keys = [c for c in self.faults if c <= k]
        return self.faults[max(keys)] if keys else ()

    def followed_by(self, b: CycleResults, s: int) -> CycleResults:
        """Cycles ``[0, s)`` of these results then ``b`` (checked by a fresh monitor from cycle ``s``)."""
        a = self
        faults = dict(a.faults)
        faults.update({k + s: v for k, v in b.faults.items()})
        fa, fb = a.faults_at, b.faults_at

        def faults_at(k: int) -> tuple:
            return fa(k) if k < s else fb(k - s)

        ha, hb = a.holding_at, b.holding_at

        def holding_at(k: int) -> tuple:
            return ha(k) if k < s else hb(k - s)

        cat = np.concatenate
        return CycleResults(a.ids, cat([a.override, b.override]), cat([a.severity, b.severity]),
                            cat([a.violated, b.violated]), cat([a.margins, b.margins]), cat([a.risk, b.risk]),
                            cat([a.fault, b.fault]), cat([a.latched, b.latched]), faults, b.engine, faults_at,
                            None, holding_at)


def check_columns(spec: Spec, columns: dict[str, np.ndarray], n: int, *,
                  risk_key: str = "p", engine: str = "auto") -> CycleResults:
    """Check ``n`` cycles of resampled inputs.

    Args:
        spec: the compiled spec.
        columns: one float64[n] column per spec signal (a bool signal as 1.0/0.0), NaN where the
            input is unusable; the risk input under ``risk_key``: ``"p"`` a float64[n, K] array
            (a NaN row: no estimate), ``"p_unsafe"``/``"risk"`` a float64[n] column; and
            ``"risk_age_s"`` when the spec sets ``risk.max_age_s``.
        engine: ``"auto"`` (the offline checker if available, else the step loop), ``"offline"``
            or ``"step"``.

    A NaN input is left out of that cycle's inputs, so the monitor fails closed on it
    ("signal ... is missing") exactly as for an input that did not arrive; ±inf is passed on, and the
    monitor refuses it as an invalid value.
    """
    if engine not in ("auto", "offline", "step"):
        raise ValueError(f"engine must be 'auto', 'offline' or 'step', got {engine!r}")
    if engine != "step" and n > 0:
        try:
            from ..offline import check_trace
        except ImportError:
            if engine == "offline":
                raise
        else:
            if engine == "offline":
                return _offline(check_trace, spec, columns, n, risk_key)
            try:
                return _offline(check_trace, spec, columns, n, risk_key)
            except Exception as exc:  # noqa: BLE001 - the reference loop still checks the bag
                res = _step(spec, columns, n, risk_key)
                res.engine = f"Monitor.step (the offline checker failed: {type(exc).__name__}: {exc})"[:300]
                return res
    return _step(spec, columns, n, risk_key)


def _nan_masked(col: np.ndarray) -> np.ma.MaskedArray:
    """NaN = no usable input (missing); ±inf stays a value, which the monitor refuses as what it is."""
    return np.ma.masked_array(col, mask=np.isnan(col))


def _offline(check_trace: Any, spec: Spec, columns: dict[str, np.ndarray], n: int, risk_key: str) -> CycleResults:
    cols: dict[str, Any] = {name: _nan_masked(columns[name]) for name in spec.signals}
    if risk_key in columns:
        cols[risk_key] = _nan_masked(columns[risk_key])
    if "risk_age_s" in columns:
        cols["risk_age_s"] = _nan_masked(columns["risk_age_s"])
    for key in ("judge", "task_id"):  # recorded judge answers (tier specs)
        if key in columns:
            cols[key] = columns[key]
    off = check_trace(spec, cols, length=n)
    tiers = _tier_ids(spec)
    ids = tuple(off.obligation_ids) + ("risk",) + tiers
    violated = np.concatenate([off.violated, off.risk_violated[:, None]]
                              + [off.tier_violated[t][:, None] for t in tiers], axis=1)
    margins = off.margins if off.margins is not None else np.full((n, len(off.obligation_ids)), math.nan)
    return CycleResults(ids, off.override.copy(), off.response.astype(np.int8), violated, margins,
                        np.asarray(off.risk, dtype=np.float64), off.fault.copy(), off.latched.copy(), {},
                        f"ethimon.offline.check_trace ({off.method})", off.faults_at, None, off.holding_at)


def _tier_ids(spec: Spec) -> tuple[str, ...]:
    """The tier rules a spec has, as extra result columns (after ``"risk"``)."""
    t = plan_of(spec).tiers   # hold_ceiling is set only with a judge
    held = t.confirm_threshold is not None or t.hold_ceiling is not None
    return (("judge",) if t.judge_cuts is not None else ()) + (("confirm",) if held else ())


def _step(spec: Spec, columns: dict[str, np.ndarray], n: int, risk_key: str) -> CycleResults:
    mon = Monitor(spec)
    tiers = _tier_ids(spec)
    ids = tuple(mon.obligation_ids) + ("risk",) + tiers
    col_of = {oid: j for j, oid in enumerate(ids)}
    m = len(ids) - 1 - len(tiers)
    override = np.zeros(n, dtype=bool)
    severity = np.zeros(n, dtype=np.int8)
    violated = np.zeros((n, len(ids)), dtype=bool)
    margins = np.full((n, m), math.nan)
    risk = np.full(n, math.nan)
    fault = np.zeros(n, dtype=bool)
    latched = np.zeros(n, dtype=bool)
    faults: dict[int, tuple] = {}
    last: tuple = ()
    sig = [(name, columns[name].tolist()) for name in spec.signals]
    rcol = columns.get(risk_key)
    if rcol is None:
        rlist = [None] * n
    elif rcol.ndim == 2:
        rlist = [None if any(x != x for x in row) else tuple(row) for row in rcol.tolist()]
    else:
        rlist = [None if x != x else x for x in rcol.tolist()]
    age = columns.get("risk_age_s")
    alist = age.tolist() if age is not None else None
    jcol = columns.get("judge") if tiers else None
    jlist = list(jcol) if jcol is not None else None
    tcol = columns.get("task_id") if tiers else None
    tlist = list(tcol) if tcol is not None else None
    step = mon.step
    holding: dict[int, tuple] = {}
    held: tuple = ()
    for k in range(n):
        inp = {}
        for name, lst in sig:
            v = lst[k]
            if v == v:
                inp[name] = v
        r = rlist[k]
        if r is not None:
            inp[risk_key] = r
        if alist is not None and alist[k] == alist[k]:
            inp["risk_age_s"] = alist[k]
        if jlist is not None and jlist[k] is not None and jlist[k] == jlist[k]:
            inp["judge"] = jlist[k]
        if tlist is not None and tlist[k] is not None:
            inp["task_id"] = tlist[k]
        d = step(inp)
        if d.override:
            override[k] = True
            severity[k] = d.response.severity
        for v in d.violations:
            violated[k, col_of[v]] = True
        if d.margins:
            margins[k] = d.margins
        if d.risk is not None:
            risk[k] = d.risk
        if d.faults:
            fault[k] = True
            if d.faults != last:
                faults[k] = last = d.faults
        else:
            last = ()
        latched[k] = d.latched
        if d.override or held:
            now = mon.latched_rules if d.override else ()
            if now != held:
                holding[k] = held = now
    return CycleResults(ids, override, severity, violated, margins, risk, fault, latched, faults, holding=holding)
