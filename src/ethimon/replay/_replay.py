"""Replaying one bag: read, resample, score the task text, check, summarise."""

from __future__ import annotations

import copy
import math
import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import SpecError
from ..spec import Response, Spec
from ._bag import BagData, BagError, read_bag
from ._check import CycleResults, check_columns
from ._mapping import RISK_INPUTS, Mapping, check_against_spec, load_mapping
from ._resample import MISSING, OK, STALE, cycle_grid, hold

__all__ = ["BagReplay", "CheckResult", "TaskScorer", "replay_bag", "replay_data", "resample"]

Scorer = Callable[[str], Sequence[float]]


@dataclass
class CheckResult:
    """One obligation (or the risk rule, or the input faults) over a whole bag.

    ``first_t_ns`` is the bag timestamp of the first violating cycle, ``first_t_s`` the
    seconds since the replay's first cycle; ``worst_margin`` is the smallest robustness
    margin over the cycles where it was evaluated (for ``risk``: τ − the largest R_e).
    """

    id: str
    kind: str  # "obligation" | "risk" | "faults"
    response: str
    cycles: int
    first_cycle: int | None
    first_t_ns: int | None
    first_t_s: float | None
    worst_margin: float | None
    detail: str = ""

    @property
    def passed(self) -> bool:
        return self.cycles == 0

    def as_dict(self) -> dict[str, Any]:
        wm = self.worst_margin
        shown = wm if wm is None or math.isfinite(wm) else ("inf" if wm > 0 else "-inf")
        return {"id": self.id, "kind": self.kind, "response": self.response, "passed": self.passed,
                "cycles_violated": self.cycles, "first_violation": None if self.first_cycle is None else {
                    "cycle": self.first_cycle, "bag_time_ns": self.first_t_ns, "t_s": self.first_t_s},
                "worst_margin": shown, "detail": self.detail}


@dataclass
class BagReplay:
    """The verdicts of one bag."""

    path: str
    storage: str
    rate_hz: float
    cycles: int
    start_ns: int
    end_ns: int
    checks: list[CheckResult]
    override_cycles: int
    first_override: int | None
    signals: dict[str, dict[str, Any]] = field(default_factory=dict)
    tasks: list[dict[str, Any]] = field(default_factory=list)
    engine: str = "Monitor.step"
    trace: CycleResults | None = field(default=None, repr=False)
    grid: np.ndarray | None = field(default=None, repr=False)
    columns: dict[str, np.ndarray] | None = field(default=None, repr=False)

    @property
    def passed(self) -> bool:
        return all(c.passed for c in self.checks)

    def check(self, cid: str) -> CheckResult:
        for c in self.checks:
            if c.id == cid:
                return c
        raise KeyError(cid)

    def as_dict(self) -> dict[str, Any]:
        return {"name": self.path, "path": self.path, "passed": self.passed, "storage": self.storage,
                "rate_hz": self.rate_hz, "cycles": self.cycles, "start_ns": self.start_ns,
                "end_ns": self.end_ns, "duration_s": (self.end_ns - self.start_ns) / 1e9,
                "override_cycles": self.override_cycles, "first_override_cycle": self.first_override,
                "checks": [c.as_dict() for c in self.checks], "signals": self.signals, "tasks": self.tasks,
                "engine": self.engine}


@dataclass
class Resampled:
    grid: np.ndarray
    columns: dict[str, np.ndarray]
    codes: dict[str, np.ndarray]
    risk_key: str
    risk_note: dict[int, str]  # per cycle index of a risk row that is unusable: why (first only)
    tasks: list[dict[str, Any]]


def _bag_span(data: BagData, mapping: Mapping) -> tuple[int, int] | None:
    firsts, lasts = [], []
    for s in data.series.values():
        if s.times.size:
            firsts.append(int(s.times[0]))
            lasts.append(int(s.times[-1]))
    if data.texts:
        firsts.append(data.texts[0][0])
        lasts.append(data.texts[-1][0])
    if not firsts:
        return None
    t0 = min(firsts)
    if mapping.start == "all_seen":
        inputs = [int(s.times[0]) if s.times.size else None for s in data.series.values()]
        if mapping.task is not None:
            inputs.append(data.texts[0][0] if data.texts else None)
        if all(x is not None for x in inputs):
            t0 = max(x for x in inputs if x is not None)
    return t0, max(lasts)


def resample(data: BagData, mapping: Mapping, spec: Spec, *, score: Scorer | None = None,
             p: Sequence[float] | None = None) -> Resampled:
    """Zero-order-held columns of every input on the monitor's cycle grid (see :mod:`._resample`)."""
    span = _bag_span(data, mapping)
    if span is None:
        topics = sorted({sm.topic for sm in mapping.signals.values()})
        raise BagError(f"none of the mapped topics has a message ({', '.join(topics)})", data.path,
                       hint="topics in this bag: " + (", ".join(sorted(data.topics)) or "none"))
    try:
        grid = cycle_grid(span[0], span[1], mapping.rate_hz)
    except ValueError as exc:
        raise BagError(str(exc), data.path, hint="lower rate_hz or split the bag") from None
    n = grid.size
    columns: dict[str, np.ndarray] = {}
    codes: dict[str, np.ndarray] = {}
    for name, s in data.series.items():
        vals, code, _ = hold(s.times, s.values, grid, mapping.limit_s(name))
        columns[name] = vals
        codes[name] = code
    risk_key = next((k for k in RISK_INPUTS if k in mapping.signals), "p")
    risk_note: dict[int, str] = {}
    tasks: list[dict[str, Any]] = []
    k_cls = int(spec.risk.classes)
    if p is not None:
        columns["p"] = np.tile(np.asarray(tuple(float(x) for x in p), dtype=np.float64), (n, 1))
        risk_key = "p"
    elif risk_key == "p":
        texts = data.texts
        table: list[tuple[float, ...] | None] = []
        notes: list[str | None] = []
        cache: dict[str, int] = {}
        idx_of_msg = np.zeros(len(texts), dtype=np.int64)
        est = _Lazy(spec, score)
        for i, (t, text) in enumerate(texts):
            j = cache.get(text)
            if j is None:
                j = cache[text] = len(table)
                probs, why = est.score(text, k_cls)
                table.append(probs)
                notes.append(why)
                tasks.append({"bag_time_ns": t, "text": text, "p": list(probs) if probs else None,
                              "error": why})
            idx_of_msg[i] = j
        times = np.asarray([t for t, _ in texts], dtype=np.int64)
        pos = np.searchsorted(times, grid, side="right") - 1
        rows = np.full((len(table) + 1, k_cls), np.nan)  # last row: no text yet / unusable
        for j, probs in enumerate(table):
            if probs is not None:
                rows[j] = probs
        which = np.where(pos >= 0, idx_of_msg[np.maximum(pos, 0)] if len(texts) else -1, len(table))
        which = np.where(which < 0, len(table), which)
        columns["p"] = rows[which]
        codes["p"] = np.where(pos >= 0, OK, MISSING).astype(np.int8)
        for j, why in enumerate(notes):
            if why is not None:
                risk_note[j] = why
        codes["_task_row"] = which.astype(np.int64)
    if spec.risk.max_age_s is not None:
        # offline, each task text is scored the moment it arrives and re-scored by the loop every
        # cycle: the estimate is as old as this cycle (0 s); a mapped p_unsafe/risk topic carries
        # its own age, the time since its last message
        if risk_key == "p":
            columns["risk_age_s"] = np.zeros(n)
        else:
            s = data.series[risk_key]
            idx = np.searchsorted(s.times, grid, side="right") - 1
            columns["risk_age_s"] = np.where(idx >= 0, (grid - s.times[np.maximum(idx, 0)]) / 1e9, np.nan)
    return Resampled(grid, columns, codes, risk_key, risk_note, tasks)


class TaskScorer:
    """Scores task texts with the spec's risk estimator, loaded on the first text and then kept:
    share one across the bags of a run so the model loads once.

    Args:
        spec: whose ``risk.estimator`` block picks the model.
        model_dir: overrides the spec's model directory.

    A load failure (``ModelError``, ``DependencyNotInstalled``) is raised on every use, as a fresh
    exception (the bag being replayed is an error, not a run of fault cycles).
    """

    def __init__(self, spec: Spec, *, model_dir: str | None = None) -> None:
        self.spec, self.model_dir = spec, model_dir
        self._probs: Scorer | None = None
        self._failed: BaseException | None = None

    def load(self) -> None:
        if self._probs is not None:
            return
        if self._failed is not None:
            exc = copy.copy(self._failed)  # a fresh copy: no traceback chained across bags
            exc.__traceback__ = exc.__context__ = exc.__cause__ = None
            raise exc
        try:
            from ..risk import default_threads, load_estimator_for  # lazy: torch only when a text must be scored
            # texts are scored one at a time: one thread (torch's default of 2 spins on busy cores)
            self._probs = load_estimator_for(self.spec, model_dir=self.model_dir,
                                             num_threads=default_threads(1)).probs
        except Exception as exc:
            self._failed = exc
            raise

    def __call__(self, text: str) -> Sequence[float]:
        self.load()
        assert self._probs is not None
        return self._probs(text)


class _Lazy:
    """Scores task texts: ``score`` if given, else the spec's estimator (loaded on the first text)."""

    def __init__(self, spec: Spec, score: Scorer | None) -> None:
        self.fn = score if score is not None else TaskScorer(spec)

    def score(self, text: str, k: int) -> tuple[tuple[float, ...] | None, str | None]:
        load = getattr(self.fn, "load", None)
        if load is not None:
            load()  # a model that cannot be loaded is an error of the replay, not an estimator fault
        try:
            got = tuple(float(x) for x in self.fn(text))
        except Exception as exc:  # noqa: BLE001 - an estimator failure is a fault on those cycles
            return None, f"the risk estimator failed on this text: {type(exc).__name__}: {exc}"[:300]
        if len(got) != k:
            return None, f"the risk estimator gave {len(got)} probabilities; the spec has risk.classes {k}"
        return got, None


def replay_data(data: BagData, spec: Spec, mapping: Mapping, *, score: Scorer | None = None,
                p: Sequence[float] | None = None, audit: Any = None, keep_trace: bool = False,
                engine: str = "auto") -> BagReplay:
    """Check the samples of one bag (already read) against ``spec`` (``engine``: see :func:`check_columns`)."""
    rs = resample(data, mapping, spec, score=score, p=p)
    n = rs.grid.size
    tr = check_columns(spec, rs.columns, n, risk_key=rs.risk_key, engine=engine)
    grid = rs.grid
    t0 = int(grid[0])

    def at(k: int | None) -> tuple[int | None, int | None, float | None]:
        if k is None:
            return None, None, None
        return k, int(grid[k]), round((int(grid[k]) - t0) / 1e9, 9)

    checks: list[CheckResult] = []
    ob_resp = {ob.id: str(ob.response) for ob in spec.obligations}
    for j, oid in enumerate(tr.ids):
        col = tr.violated[:, j]
        cnt = int(col.sum())
        first = int(np.argmax(col)) if cnt else None
        if oid == "risk":
            r = tr.risk[~np.isnan(tr.risk)]
            worst = float(spec.risk.threshold) - float(r.max()) if r.size else None
            kind, resp = "risk", str(spec.risk.response)
        elif oid in ("judge", "confirm") and oid not in ob_resp:  # the tier rules (no margin)
            worst = None
            kind, resp = "tier", str(spec.risk.response) if oid == "judge" else "stop_2"
        else:
            mg = tr.margins[:, j]
            mg = mg[~np.isnan(mg)]
            worst = float(mg.min()) if mg.size else None
            kind, resp = "obligation", ob_resp[oid]
        checks.append(CheckResult(oid, kind, resp, cnt, *at(first), worst))
    nf = int(tr.fault.sum())
    first_f = int(np.argmax(tr.fault)) if nf else None
    detail = "; ".join(_why_fault(rs, tr, data, mapping)) if first_f is not None else ""
    checks.append(CheckResult("inputs", "faults", str(spec.on_fault), nf, *at(first_f), None, detail))
    signals: dict[str, dict[str, Any]] = {}
    for name, s in data.series.items():
        code = rs.codes[name]
        signals[name] = {"topic": s.topic, "messages": int(s.times.size), "unusable_messages": s.bad,
                         "missing_cycles": int((code == MISSING).sum()),
                         "stale_cycles": int((code == STALE).sum()), "max_age_s": mapping.limit_s(name)}
    if mapping.task is not None and p is None:
        code = rs.codes["p"]
        signals["task"] = {"topic": mapping.task.topic, "messages": len(data.texts),
                           "missing_cycles": int((code == MISSING).sum())}
    n_over = int(tr.override.sum())
    res = BagReplay(data.path, data.storage, float(mapping.rate_hz), n, t0, int(grid[-1]), checks, n_over,
                    int(np.argmax(tr.override)) if n_over else None, signals, rs.tasks, tr.engine)
    if keep_trace:
        res.trace, res.grid, res.columns = tr, grid, rs.columns
    if audit is not None:
        _audit(audit, res, tr, rs, spec)
    return res


def _why_fault(rs: Resampled, tr: CycleResults, data: BagData, mapping: Mapping) -> list[str]:
    """Why cycles failed closed, in the bag's words: each cause with its cycle count and first time
    (missing, stale or unusable inputs; task texts not yet seen or not scored), then the monitor's
    own reasons for fault cycles that no such cause explains (e.g. a value out of its range)."""
    grid = rs.grid
    t0 = int(grid[0])
    causes: list[tuple[int, str]] = []
    explained = np.zeros(grid.size, dtype=bool)

    def add(mask: np.ndarray, text: str) -> None:
        mask = mask & tr.fault
        cnt = int(mask.sum())
        if cnt:
            k = int(np.argmax(mask))
            causes.append((k, f"{text} on {cnt} cycle{'s' if cnt != 1 else ''} from t = {(int(grid[k]) - t0) / 1e9:.3f} s"))
            explained[mask] = True

    for name, s in data.series.items():
        code = rs.codes[name]
        missing = code == MISSING
        if s.times.size == 0:
            have = "is not in this bag" if s.topic not in data.topics else "has no message"
            add(missing, f"{name}: topic {s.topic} {have}")
        else:
            add(missing, f"{name}: no message on {s.topic} yet")
        stale = code == STALE
        if stale.any():
            k = int(np.argmax(stale & tr.fault)) if (stale & tr.fault).any() else int(np.argmax(stale))
            i = int(np.searchsorted(s.times, grid[k], side="right") - 1)
            age = (int(grid[k]) - int(s.times[i])) / 1e9
            add(stale, f"{name}: stale (last {s.topic} message {age:.3f} s old, max_age_s "
                       f"{mapping.limit_s(name):g})")
        add((code == OK) & np.isnan(rs.columns[name]),
            f"{name}: the {s.topic} message held has no usable value (NaN, an empty array or an index past its end)")
    if rs.risk_key == "p" and "p" in rs.codes and mapping.task is not None:
        add(rs.codes["p"] == MISSING, f"risk: no task text on {mapping.task.topic} yet")
        rows = rs.codes["_task_row"]
        for j, why in rs.risk_note.items():
            add(rows == j, f"risk: {why}")
    rest = tr.fault & ~explained
    if rest.any():
        k = int(np.argmax(rest))
        cnt = int(rest.sum())
        texts = "; ".join(str(f) for f in tr.faults_at(k)) or "fault"
        causes.append((k, f"{texts} (monitor) on {cnt} cycle{'s' if cnt != 1 else ''} from "
                          f"t = {(int(grid[k]) - t0) / 1e9:.3f} s"))
    return [text for _, text in sorted(causes, key=lambda c: c[0])]


def _audit(log: Any, res: BagReplay, tr: CycleResults, rs: Resampled, spec: Spec) -> None:
    """Append the decisions of a replay to an :class:`~ethimon.audit.AuditLog`, one record per change."""
    ids = tr.ids[:tr.margins.shape[1]]  # the obligations (then "risk" and any tier rules)

    def append(kind: str, **fields: Any) -> None:
        for _ in range(200):
            if log.append(kind, **fields):
                return
            log.flush(timeout=5.0)
        raise BagError("the audit log refused records (its writer is behind or failed)", res.path)

    append("replay", bag=res.path, storage=res.storage, rate_hz=res.rate_hz, cycles=res.cycles,
           start_ns=res.start_ns, engine=res.engine)
    prev = None
    names = list(spec.signals)
    for k in range(res.cycles):
        viol = tuple(oid for j, oid in enumerate(tr.ids) if tr.violated[k, j])
        key = (bool(tr.override[k]), int(tr.severity[k]), viol, bool(tr.fault[k]))
        if key == prev:
            continue
        event = "change" if prev is not None and prev[0] == key[0] else (
            "override_on" if key[0] else "override_off")
        prev = key
        resp = _RESP[int(tr.severity[k])] if tr.override[k] else "none"
        append("decision", event=event, bag=res.path, cycle=k, bag_time_ns=int(rs.grid[k]),
               override=bool(tr.override[k]), response=resp, violations=list(viol),
               faults=[_fault_dict(f) for f in tr.faults_at(k)],
               latched=bool(tr.latched[k]),
               risk=None if tr.risk[k] != tr.risk[k] else float(tr.risk[k]),
               margins={oid: float(tr.margins[k, j]) for j, oid in enumerate(ids)},
               inputs={nm: float(rs.columns[nm][k]) for nm in names})
    append("replay_result", bag=res.path, passed=res.passed,
           checks=[c.as_dict() for c in res.checks])


_RESP = {r.severity: r.value for r in Response}


def _fault_dict(f: Any) -> Any:
    as_dict = getattr(f, "as_dict", None)
    return as_dict() if as_dict is not None else str(f)


def replay_bag(bag: str | os.PathLike, spec: Spec, mapping: Mapping | str | os.PathLike, *,
               score: Scorer | None = None, p: Sequence[float] | None = None, audit: Any = None,
               keep_trace: bool = False, engine: str = "auto") -> BagReplay:
    """Replay one ROS bag through the monitor of ``spec``.

    Args:
        bag: a ROS 2 bag folder (sqlite3 or MCAP storage), a ``.mcap``/``.db3`` file, or a ROS 1 ``.bag``.
        spec: a compiled spec (:func:`ethimon.load_spec`).
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

    Raises:
        SpecError: a bad mapping file, or one that does not fit the spec.
        BagError: the bag cannot be read or lacks a mapped field.
        DependencyNotInstalled: rosbags is not installed (``pip install 'ethimon[ros]'``).
    """
    if not isinstance(mapping, Mapping):
        mapping = load_mapping(mapping)
    if not isinstance(spec, Spec):
        raise SpecError(f"replay_bag needs a loaded spec (ethimon.load_spec), got {type(spec).__name__}")
    check_against_spec(mapping, spec, risk_given=p is not None)
    data = read_bag(bag, mapping)
    return replay_data(data, spec, mapping, score=score, p=p, audit=audit, keep_trace=keep_trace, engine=engine)
