"""Replaying one bag: read it, resample it (`_columns`), check the cycles, summarise each rule (`_result`)."""

from __future__ import annotations

import math
import os
import re
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from ..compiler import plan_of
from ..errors import SpecError
from ..language import Spec
from ._bag import BagData, read_bag
from ._columns import Resampled, resample
from ._fault_causes import _why_fault
from ..io import Hold, Mapping, load_mapping
from ._replay_audit import _audit
from ._result import BagReplay, CheckResult
from ._scoring import Scorer
from ._verdicts import CycleResults, check_columns

__all__ = ["replay_bag", "replay_data"]


def _start_cycle(rs: Resampled, data: BagData) -> int:
    """The first cycle where every mapped input (and the task text) has been seen; 0 if none is."""
    seen = np.ones(rs.grid.size, dtype=bool)
    for name in data.series:
        seen &= rs.codes[name] != Hold.MISSING
    if "p" in rs.codes:
        seen &= rs.codes["p"] != Hold.MISSING
    return int(np.argmax(seen)) if seen.any() else 0


_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def _evaluable(rs: Resampled, spec: Spec) -> dict[str, np.ndarray]:
    """Per obligation, the cycles where every signal it reads is usable (so the monitor evaluates it,
    also on a cycle that fails closed for another input)."""
    usable: dict[str, np.ndarray] = {}
    for name, sig in spec.signals.items():
        col = rs.columns.get(name)
        if col is None:
            usable[name] = np.zeros(rs.grid.size, dtype=bool)
            continue
        ok = np.isfinite(col)
        if sig.type == "bool":
            ok &= (col == 0.0) | (col == 1.0)
        elif sig.range is not None:
            ok &= (col >= sig.range[0]) & (col <= sig.range[1])
        usable[name] = ok
    out = {}
    for ob in spec.obligations:
        names = {n for text in (ob.when, ob.require) for n in _NAME.findall(text or "") if n in spec.signals}
        ok = np.ones(rs.grid.size, dtype=bool)
        for n in names:
            ok &= usable[n]
        out[ob.id] = ok
    return out


def _worst(values: np.ndarray, violated: np.ndarray) -> tuple[float | None, int]:
    """The smallest margin over the cycles that judged it, ``-inf`` if a violating cycle had bad inputs
    (its margin is unknown: it counts as a violation of any size); and how many such cycles."""
    known = values[~np.isnan(values)]
    blind = int((violated & np.isnan(values)).sum())
    if blind:
        return -math.inf, blind
    return (float(known.min()) if known.size else None), 0


#: how many override runs a replay result lists (the one to the end of the bag is always among them)
MAX_RUNS = 200
#: the running count in Monitor.holding()'s words ("... (3 of 10 now)")
_COUNT = re.compile(r" \(\d+ of \d+ now\)")


def _release_words(spec: Spec) -> dict[str, str]:
    """How each rule's latch is released, in a person's words: what :meth:`Monitor.holding
    <ethimon.Monitor.holding>` says of it (live and replay in the same words), without its running count."""
    from ..runtime import Monitor
    m = Monitor(spec)
    m.carry_latches((*m.obligation_ids, "risk", "fault", "judge", "confirm"))  # a tier rule the spec lacks: none
    return {h["rule"]: released_words(h["how"]) for h in m.holding()}


def released_words(how: str) -> str:
    """``Monitor.holding()``'s ``how`` to follow "released": "by an acknowledgement once ...", "by itself ...",
    "when an acknowledgement confirms ..."; its running count left out."""
    how = _COUNT.sub("", how)
    if how.startswith("an acknowledgement confirms"):
        return "when " + how
    return how if how.startswith("by ") else "by " + how


def _override_runs(tr: CycleResults, grid: np.ndarray, rate_hz: float, spec: Spec, fresh: int = 0,
                   limit: int = MAX_RUNS) -> tuple[list[dict[str, Any]], int]:
    """Every run of override cycles: when it began and why, how long it lasted, whether it lasted
    to the end of the bag, and which latch held it at its last cycle (the latch that keeps the arm
    stopped, not the last rule that fired). At most ``limit`` runs are listed (the one that lasts to
    the end of the bag always is); the second value is how many runs there are in all. ``ended`` is
    ``"end_of_bag"``, ``"fresh_start"`` (the start-up cycles before every input was seen, which a fresh
    monitor follows at cycle ``fresh``) or ``"released"``."""
    ov = tr.override.astype(np.int8)
    if not ov.any():
        return [], 0
    edges = np.flatnonzero(np.diff(np.concatenate([[0], ov, [0]])))
    pairs = list(zip(edges[0::2].tolist(), edges[1::2].tolist()))
    total = len(pairs)
    if total > limit:
        pairs = pairs[:limit - 1] + [pairs[-1]]
    words = _release_words(spec)
    t0 = int(grid[0])
    out = []
    for a, b in pairs:
        why = [tr.ids[j] for j in np.flatnonzero(tr.violated[a])]
        if tr.fault[a]:
            why.append("inputs (" + "; ".join(str(f) for f in tr.faults_at(a))[:200] + ")")
        held = list(tr.holding_at(b - 1))
        out.append({"from_cycle": int(a), "cycles": int(b - a), "seconds": round((b - a) / rate_hz, 9),
                    "t_s": round((int(grid[a]) - t0) / 1e9, 9), "until_end": bool(b == grid.size),
                    "ended": ("end_of_bag" if b == grid.size else "fresh_start" if b == fresh > 0 else "released"),
                    "cause": ", ".join(why) or "a latch from before",
                    "held_by": held, "released_by": {h: words.get(h, "") for h in held}})
    return out, total


def _task_outcomes(rs: Any, tr: CycleResults, grid: np.ndarray, spec: Spec) -> None:
    """Each task text's R_e and outcome, as the monitor judged it in the first cycle that read it."""
    rows = rs.codes.get("_task_row")
    if rows is None or not rs.tasks:
        return
    t0 = int(grid[0])
    col = {oid: j for j, oid in enumerate(tr.ids)}
    plan = plan_of(spec)
    tau, tau_confirm = plan.risk_plan.threshold, plan.tiers.confirm_threshold
    for j, task in enumerate(rs.tasks):
        hit = np.flatnonzero(rows == j)
        if not hit.size:
            task.update(r_e=None, outcome="never read: a newer text replaced it before the next cycle", cycle=None)
            continue
        k = int(hit[0])
        r = float(tr.risk[k]) if tr.risk[k] == tr.risk[k] else None
        v = tr.violated[k]
        if r is None:
            outcome = "no estimate: fails closed (" + (task.get("error") or "no usable probabilities") + ")"
        elif v[col["risk"]]:
            outcome = f"stopped: R_e ≥ τ = {tau:g}"
        elif "judge" in col and v[col["judge"]]:
            outcome = "stopped by the judge's unsafe verdict"
        elif "confirm" in col and v[col["confirm"]]:
            outcome = (f"held for a person's confirmation: τ_confirm = {tau_confirm:g} ≤ R_e "
                       f"< τ = {tau:g}")
        else:
            held = ", ".join(tr.holding_at(k)) if tr.override[k] else ""
            outcome = ("executes (below the risk tiers)" if not held else
                       f"below the risk tiers, but the arm is still held by the latch of {held}")
        task.update(r_e=None if r is None else round(r, 6), outcome=outcome, cycle=k,
                    t_s=round((int(grid[k]) - t0) / 1e9, 9))


def replay_data(data: BagData, spec: Spec, mapping: Mapping, *, score: Scorer | None = None,
                p: Sequence[float] | None = None, audit: Any = None, keep_trace: bool = False,
                engine: str = "auto") -> BagReplay:
    """Check the samples of one bag (already read) against ``spec`` (``engine``: see :func:`check_columns`).

    The monitor starts fresh at the first cycle where every input has been seen: the cycles before
    fail closed (an input is missing) but do not latch the rest of the bag.
    """
    rs = resample(data, mapping, spec, score=score, p=p)
    n = rs.grid.size
    s0 = _start_cycle(rs, data)
    if 0 < s0 < n:
        head = check_columns(spec, {k: v[:s0] for k, v in rs.columns.items()}, s0, risk_key=rs.risk_key,
                             engine=engine)
        tail = check_columns(spec, {k: v[s0:] for k, v in rs.columns.items()}, n - s0, risk_key=rs.risk_key,
                             engine=engine)
        tr = head.followed_by(tail, s0)
    else:
        tr = check_columns(spec, rs.columns, n, risk_key=rs.risk_key, engine=engine)
    grid = rs.grid
    t0 = int(grid[0])

    def at(k: int | None) -> tuple[int | None, int | None, float | None]:
        if k is None:
            return None, None, None
        return k, int(grid[k]), round((int(grid[k]) - t0) / 1e9, 9)

    # what the cycles say (their verdicts, then why they failed closed) before the results are written
    _task_outcomes(rs, tr, grid, spec)
    runs, n_runs = _override_runs(tr, grid, float(mapping.rate_hz), spec, s0)
    nf = int(tr.fault.sum())
    first_f = int(np.argmax(tr.fault)) if nf else None
    why_fault = "; ".join(_why_fault(rs, tr, data, mapping, spec)) if first_f is not None else ""
    checks: list[CheckResult] = []
    ob_resp = {ob.id: str(ob.response) for ob in spec.obligations}
    rp = plan_of(spec).risk_plan
    risk_resp = str(rp.latch.response)  # the risk rule's response, which the judge's verdict also gives
    can = _evaluable(rs, spec)
    # 'risk: none' holds R_e at 0: a rule that reads R_e (an obligation naming it, the tier rules)
    # would be judged on that stand-in, so it is NOT CHECKED, never PASS (or FAIL)
    no_re = _reads_risk(spec) | {"judge", "confirm"} if p is None and not mapping.risk_checked else set()
    for j, oid in enumerate(tr.ids):
        col = tr.violated[:, j]
        cnt = int(col.sum())
        first = int(np.argmax(col)) if cnt else None
        detail, status = "", ""
        if oid in no_re and oid != "risk":
            kind = "obligation" if oid in ob_resp else "tier"
            resp = ob_resp.get(oid) or (risk_resp if oid == "judge" else "stop_2")
            checks.append(CheckResult(oid, kind, resp, 0, None, None, None, None,
                                      "reads R_e, which 'risk: none' in the mapping does not give (the bag has "
                                      "no task text): not checked", "NOT CHECKED"))
            continue
        if oid == "risk":
            kind, resp = "risk", risk_resp
            if p is None and not mapping.risk_checked:
                checks.append(CheckResult(oid, kind, resp, 0, None, None, None, None,
                                          "risk: none in the mapping (the bag has no task text): R_e was not "
                                          "computed, the risk rule not checked", "NOT CHECKED"))
                continue
            worst, blind = _worst(rp.threshold - tr.risk, col)
            evaluated = bool((~np.isnan(tr.risk)).any())
        elif oid in ("judge", "confirm") and oid not in ob_resp:  # the tier rules (no margin)
            worst, blind = None, 0
            kind, resp = "tier", risk_resp if oid == "judge" else "stop_2"
            evaluated = bool((~np.isnan(tr.risk)).any())
        else:
            kind, resp = "obligation", ob_resp[oid]
            worst, blind = _worst(tr.margins[:, j], col)
            evaluated = bool((~np.isnan(tr.margins[:, j])).any() or can[oid].any())
        if blind:
            detail = (f"{blind} violating cycle{'s' if blind != 1 else ''} had bad inputs (margin unknown: "
                      "worst margin -inf)")
        if not cnt and not evaluated:
            status, detail = "NOT EVALUATED", "no cycle had the inputs to evaluate it (every cycle failed closed)"
        checks.append(CheckResult(oid, kind, resp, cnt, *at(first), worst, detail, status))
    checks.append(CheckResult("inputs", "faults", str(spec.on_fault), nf, *at(first_f), None, why_fault))
    signals: dict[str, dict[str, Any]] = {}
    for name, s in data.series.items():
        code = rs.codes[name]
        signals[name] = {"topic": s.topic, "type": s.msgtype, "clock": s.clock, "offset_s": s.offset_ns / 1e9,
                         "messages": s.read, "samples": int(s.times.size), "judged": rs.judged.get(name, 0),
                         "before_first_cycle": rs.before.get(name, 0), "unusable_messages": s.bad,
                         "missing_cycles": int((code == Hold.MISSING).sum()),
                         "stale_cycles": int((code == Hold.STALE).sum()), "max_age_s": mapping.limit_s(name)}
    if mapping.task is not None and p is None:
        code = rs.codes["p"]
        signals["task"] = {"topic": mapping.task.topic, "messages": len(data.texts),
                           "judged": rs.judged.get("task", 0), "missing_cycles": int((code == Hold.MISSING).sum())}
    topics: dict[str, dict[str, Any]] = {}
    for name, sg in signals.items():  # per topic: messages read, and the fewest of them any of its signals judged
        tp = topics.setdefault(sg["topic"], {"read": sg["messages"], "judged": sg["judged"], "signals": []})
        tp["read"] = max(tp["read"], sg["messages"])
        tp["judged"] = min(tp["judged"], sg["judged"])
        tp["signals"].append(name)
    n_over = int(tr.override.sum())
    res = BagReplay(data.path, data.storage, float(mapping.rate_hz), n, t0, int(grid[-1]), checks, n_over,
                    int(np.argmax(tr.override)) if n_over else None, signals, rs.tasks, tr.engine,
                    runs, rs.warnings,
                    {"cycle": s0, "t_s": round((int(grid[s0]) - t0) / 1e9, 9), "note": (
                        f"every input seen from cycle {s0}: the monitor starts fresh there (the {s0} cycle"
                        f"{'s' if s0 != 1 else ''} before fail closed but latch nothing after)") if s0 else ""},
                    topics, override_runs=n_runs)
    if keep_trace:
        res.trace, res.grid, res.columns = tr, grid, rs.columns
    if audit is not None:
        _audit(audit, res, tr, rs, spec)
    return res


def _reads_risk(spec: Spec) -> set[str]:
    """The ids of the obligations whose ``when`` or ``require`` reads R_e (a name that is neither a
    signal nor a constant: the built-in ``risk``)."""
    from ..compiler import plan_of
    from ..language._expr import Name, walk
    known = set(spec.signals) | set(spec.constants)
    out = set()
    for ob in plan_of(spec).obligations:
        for root in (ob.when, ob.require):
            if root is not None and any(isinstance(n, Name) and n.id not in known for n in walk(root)):
                out.add(ob.id)
    return out


def replay_bag(bag: str | os.PathLike, spec: Spec | str | os.PathLike, mapping: Mapping | str | os.PathLike, *,
               score: Scorer | None = None, p: Sequence[float] | None = None, audit: Any = None,
               keep_trace: bool = False, engine: str = "auto",
               on_progress: Callable[[int, int], None] | None = None) -> BagReplay:
    """Replay one ROS bag through the monitor of ``spec``.

    Args:
        bag: a ROS 2 bag folder (sqlite3 or MCAP storage), a ``.mcap``/``.db3`` file, or a ROS 1 ``.bag``.
        spec: a compiled spec (:func:`ethimon.load_spec`) or the path of a spec file.
        mapping: a :class:`Mapping` or the path of a mapping file.
        score: scores a task text (text → class probabilities); default: the spec's estimator,
            loaded when the first task text arrives.
        p: fixed class probabilities for every cycle instead of scoring task texts (tests, or a
            bag without a task topic).
        audit: an :class:`ethimon.audit.AuditLog` to append the decisions to (one record per change).
        keep_trace: keep the per-cycle verdicts, grid and columns on the result.
        engine: what checks the resampled cycles: ``"auto"`` (:func:`ethimon.offline.check_trace`
            when available, else ``Monitor.step`` per cycle), ``"offline"`` or ``"step"``; the
            verdicts are the same.
        on_progress: called as ``on_progress(messages_read, messages_total)`` while the bag is read.

    Raises:
        SpecError: a bad mapping file, or one that does not fit the spec.
        BagError: the bag cannot be read or lacks a mapped field.
        DependencyNotInstalled: rosbags is not installed (``pip install 'ethimon[ros]'``).
    """
    if not isinstance(mapping, Mapping):
        mapping = load_mapping(mapping)
    if isinstance(spec, (str, os.PathLike)):
        from ..compiler import plan_of
        from ..language import parse_spec_file
        spec = parse_spec_file(spec)
        plan_of(spec)  # compiled now, as ethimon.load_spec does: its errors surface here
    if not isinstance(spec, Spec):
        raise SpecError(f"replay_bag needs a spec (a path, or ethimon.load_spec's result), got {type(spec).__name__}")
    mapping.check(spec, risk_given=p is not None)
    data = read_bag(bag, mapping, on_progress=on_progress)
    return replay_data(data, spec, mapping, score=score, p=p, audit=audit, keep_trace=keep_trace, engine=engine)
