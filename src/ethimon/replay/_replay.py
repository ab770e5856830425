"""Replaying one bag: read, resample, score the task text, check, summarise."""

from __future__ import annotations

import copy
import math
import os
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import SpecError
from ..spec import Response, Spec
from ._bag import BagData, BagError, read_bag
from ._collect import Series
from ._verdicts import CycleResults, check_columns
from ._mapping import RISK_INPUTS, Mapping, check_against_spec, lint_mapping, load_mapping
from ._resample import MISSING, OK, STALE, cycle_grid, hold, judged

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
    status: str = ""  # PASS | FAIL | NOT EVALUATED (no cycle could judge it) | NOT CHECKED (risk: none)

    def __post_init__(self) -> None:
        if not self.status:
            self.status = "FAIL" if self.cycles else "PASS"

    @property
    def passed(self) -> bool:
        """True only for PASS: a rule NOT EVALUATED or NOT CHECKED did not pass."""
        return self.status == "PASS"

    def as_dict(self) -> dict[str, Any]:
        wm = self.worst_margin
        shown = wm if wm is None or math.isfinite(wm) else ("inf" if wm > 0 else "-inf")
        return {"id": self.id, "kind": self.kind, "response": self.response, "status": self.status,
                "passed": self.passed,
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
    latches: list[dict[str, Any]] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    started: dict[str, Any] = field(default_factory=dict)
    topics: dict[str, dict[str, Any]] = field(default_factory=dict)  # topic -> messages read, samples judged
    trace: CycleResults | None = field(default=None, repr=False)
    grid: np.ndarray | None = field(default=None, repr=False)
    columns: dict[str, np.ndarray] | None = field(default=None, repr=False)

    @property
    def passed(self) -> bool:
        """No check failed and every check was evaluated (a rule NOT CHECKED by the mapping's
        ``risk: none`` does not fail the bag)."""
        return all(c.status in ("PASS", "NOT CHECKED") for c in self.checks)

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
                "topics": self.topics, "latches": self.latches, "warnings": self.warnings, "started": self.started,
                "engine": self.engine}


@dataclass
class Resampled:
    grid: np.ndarray
    columns: dict[str, np.ndarray]
    codes: dict[str, np.ndarray]
    risk_key: str
    risk_note: dict[int, str]  # per cycle index of a risk row that is unusable: why (first only)
    tasks: list[dict[str, Any]]
    judged: dict[str, int] = field(default_factory=dict)  # signal -> samples some cycle judges
    before: dict[str, int] = field(default_factory=dict)  # signal -> samples before the first cycle
    warnings: list[str] = field(default_factory=list)


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


def _clock(s: Series) -> str:
    return f"{s.clock} time" + (f" + offset_s {s.offset_ns / 1e9:g}" if s.offset_ns else "")


def _check_overlap(data: BagData, mapping: Mapping) -> None:
    """Mapped inputs whose clocks never overlap (header vs log time, robot PC vs recorder) are an error
    naming the offset: a replay over both spans would judge only cycles where one of them is missing.
    A signal is usable from its first sample until its last one goes stale (never, without a limit)."""
    spans = []
    for name, s in data.series.items():
        if s.times.size:
            lim = mapping.limit_s(name)
            spans.append((name, s, int(s.times[0]), int(s.times[-1]),
                          math.inf if lim is None else int(s.times[-1]) + lim * 1e9))
    if len(spans) < 2:
        return
    a = min(spans, key=lambda x: x[4])  # usable until the earliest
    b = max(spans, key=lambda x: x[2])  # starts last
    if b[2] <= a[4]:
        return
    offset = (b[2] - a[2]) / 1e9
    raise BagError(
        f"the mapped inputs' clocks never overlap: {a[0]} ({a[1].topic}, {_clock(a[1])}) spans "
        f"{a[2] / 1e9:.3f} to {a[3] / 1e9:.3f} s, {b[0]} ({b[1].topic}, {_clock(b[1])}) starts "
        f"{(b[2] - a[3]) / 1e9:.3f} s after that ends: the two clocks are {offset:.3f} s apart", data.path,
        hint=f"a header stamp and the bag's log time are different clocks: map both with 'time: log', or, if "
             f"{b[1].topic}'s clock is off by a known amount, declare 'offset_s: {-offset:.3f}' on {b[0]}")


def _check_types(data: BagData, spec: Spec) -> None:
    """A bool field feeds only a bool signal (the monitor refuses bools as numbers)."""
    for name, s in data.series.items():
        if s.kind != "bool":
            continue
        sig = spec.signals.get(name)
        if sig is None or sig.type != "bool":
            what = f"a {sig.type} signal" if sig is not None else "a probability"
            raise BagError(f"signal {name!r} is {what} in spec {spec.name!r}, but {s.topic} ({s.msgtype}) gives "
                           "true/false: a bool is not a number", data.path,
                           hint=f"declare {name!r} with 'type: bool' in the spec, or map a numeric field")


def _judge_counts(data: BagData, mapping: Mapping, grid: np.ndarray, idxs: dict[str, np.ndarray],
                  warnings: list[str]) -> tuple[dict[str, int], dict[str, int]]:
    """Samples judged per signal. A sample superseded between two cycles (a topic faster than the
    cycles, a burst, a backwards clock jump) is an error unless the mapping says ``samples: latest``
    (then a warning: each cycle judges the latest, as the monitor does online)."""
    period = 1e9 / float(mapping.rate_hz)
    out, before = {}, {}
    for name, s in data.series.items():
        n = s.times.size
        if n == 0:
            out[name] = before[name] = 0
            continue
        ok = judged(s.times, s.values, idxs[name])
        early = s.times < grid[0]
        before[name] = int((early & ~ok).sum())
        if before[name]:
            if mapping.samples_of(name) != "latest":  # 'every': no sample goes unjudged in silence
                raise BagError(
                    f"signal {name!r}: {before[name]:,} of {n:,} samples on {s.topic} come before the first cycle "
                    f"('start: all_seen' starts once every input has been seen) and no cycle would judge them",
                    data.path,
                    hint="drop 'start: all_seen' (the cycles then start at the first message and fail closed until "
                         "every input is there), or write 'samples: latest' to accept that the start-up samples "
                         "are counted, not judged")
            warnings.append(f"{name}: {before[name]:,} of {n:,} samples on {s.topic} come before the first cycle "
                            f"('start: all_seen') and are not judged")
        between = ~ok & ~early
        cnt = int(between.sum())
        out[name] = int(ok.sum())
        if not cnt:
            continue
        gaps = np.diff(s.times)
        med = float(np.median(gaps)) if gaps.size else math.inf
        k = int(np.argmax(between))
        t_first = (int(s.times[k]) - int(grid[0])) / 1e9
        pos = gaps[gaps > 0]
        need = min(1e9 / float(pos.min()), 100_000.0) if pos.size else mapping.rate_hz
        if mapping.samples_of(name) == "latest":
            warnings.append(f"{name}: {cnt:,} of {n:,} samples on {s.topic} (a message every {med / 1e6:.2f} ms) "
                            f"fall between cycles at {mapping.rate_hz:g} Hz and are not judged ('samples: latest': "
                            f"each cycle judges the latest); rate_hz {math.ceil(need):g} judges each")
            continue
        if med >= 2 * period:
            why = (f"although the topic (a message every {med / 1e6:.1f} ms) is slower than the cycles "
                   f"({period / 1e6:.1f} ms): a burst, or a clock that jumps backwards")
        else:
            why = (f"the topic (a message every {med / 1e6:.2f} ms) is faster than the cycles "
                   f"({period / 1e6:.2f} ms)")
        raise BagError(
            f"signal {name!r}: {cnt:,} of {n:,} samples on {s.topic} fall between two cycles behind a newer "
            f"sample (first at t = {t_first:.3f} s), {why}; the monitor would never judge them", data.path,
            hint=f"raise rate_hz to {math.ceil(need):g} so each sample gets a cycle, check the recorder's clock "
                 "(a log time that jumps back puts samples out of order), or write 'samples: latest' to judge the "
                 "latest sample each cycle, as the monitor does online")
    return out, before


def resample(data: BagData, mapping: Mapping, spec: Spec, *, score: Scorer | None = None,
             p: Sequence[float] | None = None) -> Resampled:
    """Zero-order-held columns of every input on the monitor's cycle grid (see :mod:`._resample`).

    Raises:
        BagError: no mapped message at all, inputs whose clocks never overlap, a bool field mapped
            to a numeric signal, samples that no cycle could judge (see :func:`_judge_counts`).
    """
    span = _bag_span(data, mapping)
    if span is None:
        topics = sorted({sm.topic for sm in mapping.signals.values()})
        raise BagError(f"none of the mapped topics has a message ({', '.join(topics)})", data.path,
                       hint="topics in this bag: " + (", ".join(sorted(data.topics)) or "none"))
    _check_types(data, spec)
    _check_overlap(data, mapping)
    try:
        grid = cycle_grid(span[0], span[1], mapping.rate_hz)
    except ValueError as exc:
        raise BagError(str(exc), data.path, hint="lower rate_hz or split the bag") from None
    n = grid.size
    columns: dict[str, np.ndarray] = {}
    codes: dict[str, np.ndarray] = {}
    idxs: dict[str, np.ndarray] = {}
    for name, s in data.series.items():
        vals, code, idx = hold(s.times, s.values, grid, mapping.limit_s(name))
        columns[name] = vals
        codes[name] = code
        idxs[name] = idx
    warnings: list[str] = []
    judged_n, before = _judge_counts(data, mapping, grid, idxs, warnings)
    risk_key = next((k for k in RISK_INPUTS if k in mapping.signals), "p")
    risk_note: dict[int, str] = {}
    tasks: list[dict[str, Any]] = []
    k_cls = int(spec.risk.classes)
    if p is not None:
        columns["p"] = np.tile(np.asarray(tuple(float(x) for x in p), dtype=np.float64), (n, 1))
        risk_key = "p"
    elif not mapping.risk_checked:
        # 'risk: none': R_e held at 0 so that the risk rule never fires; it is reported NOT CHECKED
        columns["risk"] = np.zeros(n)
        risk_key = "risk"
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
        judged_n["task"] = _judge_texts(data, mapping, grid, times, pos, warnings)
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
        if risk_key in ("p", "risk") and risk_key not in mapping.signals:
            columns["risk_age_s"] = np.zeros(n)
        else:
            s = data.series[risk_key]
            idx = np.searchsorted(s.times, grid, side="right") - 1
            columns["risk_age_s"] = np.where(idx >= 0, (grid - s.times[np.maximum(idx, 0)]) / 1e9, np.nan)
    warnings.extend(_held_prev_warnings(data, mapping, spec))
    return Resampled(grid, columns, codes, risk_key, risk_note, tasks, judged_n, before, warnings)


def _judge_texts(data: BagData, mapping: Mapping, grid: np.ndarray, times: np.ndarray, pos: np.ndarray,
                 warnings: list[str]) -> int:
    """Task texts judged: a text replaced before any cycle saw it would never reach the monitor (its
    risk score hidden), an error unless ``samples: latest``; same-time texts are judged if equal."""
    texts = data.texts
    ok = np.zeros(len(texts), dtype=bool)
    ok[pos[pos >= 0]] = True
    for i in range(len(texts) - 2, -1, -1):  # a repeat at the same time is judged with its twin
        if texts[i][0] == texts[i + 1][0] and texts[i][1] == texts[i + 1][1]:
            ok[i] = ok[i] or ok[i + 1]
    missed = ~ok & (times >= grid[0])
    if missed.any():
        k = int(np.argmax(missed))
        what = (f"{int(missed.sum()):,} of {len(texts):,} task texts on {mapping.task.topic} are replaced before a "
                f"cycle sees them (first at t = {(int(times[k]) - int(grid[0])) / 1e9:.3f} s: "
                f"{texts[k][1][:60]!r})")
        if mapping.samples == "latest":
            warnings.append(f"task: {what}: not judged ('samples: latest')")
        else:
            raise BagError(f"task: {what}: the risk of those commands would never reach the monitor", data.path,
                           hint="raise rate_hz so that each text gets a cycle, or write 'samples: latest' to judge "
                           "only the text current at each cycle, as the monitor does online")
    return int(ok.sum())


def _held_prev_warnings(data: BagData, mapping: Mapping, spec: Spec) -> list[str]:
    """``prev()`` of an input whose topic is slower than the cycles: the lint, with the bag's rates."""
    out = []
    for w in lint_mapping(mapping, spec):
        sig = w.split("prev(", 1)[1].split(")", 1)[0]
        s = data.series.get(sig)
        if s is None or s.times.size < 2:
            continue
        med = float(np.median(np.diff(s.times)))
        if med > 1.5e9 / float(mapping.rate_hz):
            out.append(f"{w} ({s.topic} sends a message every {med / 1e6:.1f} ms, the cycles run every "
                       f"{1e3 / float(mapping.rate_hz):.1f} ms)")
    return out


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


def _start_cycle(rs: Resampled, data: BagData) -> int:
    """The first cycle where every mapped input (and the task text) has been seen; 0 if none is."""
    seen = np.ones(rs.grid.size, dtype=bool)
    for name in data.series:
        seen &= rs.codes[name] != MISSING
    if "p" in rs.codes:
        seen &= rs.codes["p"] != MISSING
    return int(np.argmax(seen)) if seen.any() else 0


def _join(a: CycleResults, b: CycleResults, s: int) -> CycleResults:
    """Cycles ``[0, s)`` of ``a`` then ``b`` (checked by a fresh monitor from cycle ``s``)."""
    faults = dict(a.faults)
    faults.update({k + s: v for k, v in b.faults.items()})
    fa, fb = a.faults_at, b.faults_at

    def faults_at(k: int) -> tuple:
        return fa(k) if k < s else fb(k - s)

    cat = np.concatenate
    return CycleResults(a.ids, cat([a.override, b.override]), cat([a.severity, b.severity]),
                        cat([a.violated, b.violated]), cat([a.margins, b.margins]), cat([a.risk, b.risk]),
                        cat([a.fault, b.fault]), cat([a.latched, b.latched]), faults, b.engine, faults_at)


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


def _latches(tr: CycleResults, grid: np.ndarray, rate_hz: float, limit: int = 20) -> list[dict[str, Any]]:
    """Runs of latched cycles (the override held after its cause), with what latched and for how long."""
    lat = tr.latched.astype(np.int8)
    if not lat.any():
        return []
    edges = np.flatnonzero(np.diff(np.concatenate([[0], lat, [0]])))
    out = []
    t0 = int(grid[0])
    for a, b in zip(edges[0::2], edges[1::2]):
        if len(out) >= limit:
            break
        trig = a - 1 if a > 0 else a
        why = [tr.ids[j] for j in np.flatnonzero(tr.violated[trig])]
        if tr.fault[trig]:
            why.append("inputs (" + "; ".join(str(f) for f in tr.faults_at(trig))[:200] + ")")
        out.append({"from_cycle": int(a), "cycles": int(b - a), "seconds": round((b - a) / rate_hz, 9),
                    "t_s": round((int(grid[a]) - t0) / 1e9, 9), "until_end": bool(b == grid.size),
                    "after": ", ".join(why) or "an earlier override"})
    return out


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
        tr = _join(head, tail, s0)
    else:
        tr = check_columns(spec, rs.columns, n, risk_key=rs.risk_key, engine=engine)
    grid = rs.grid
    t0 = int(grid[0])

    def at(k: int | None) -> tuple[int | None, int | None, float | None]:
        if k is None:
            return None, None, None
        return k, int(grid[k]), round((int(grid[k]) - t0) / 1e9, 9)

    checks: list[CheckResult] = []
    ob_resp = {ob.id: str(ob.response) for ob in spec.obligations}
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
            resp = ob_resp.get(oid) or (str(spec.risk.response) if oid == "judge" else "stop_2")
            checks.append(CheckResult(oid, kind, resp, 0, None, None, None, None,
                                      "reads R_e, which 'risk: none' in the mapping does not give (the bag has "
                                      "no task text): not checked", "NOT CHECKED"))
            continue
        if oid == "risk":
            kind, resp = "risk", str(spec.risk.response)
            if p is None and not mapping.risk_checked:
                checks.append(CheckResult(oid, kind, resp, 0, None, None, None, None,
                                          "risk: none in the mapping (the bag has no task text): R_e was not "
                                          "computed, the risk rule not checked", "NOT CHECKED"))
                continue
            worst, blind = _worst(float(spec.risk.threshold) - tr.risk, col)
            evaluated = bool((~np.isnan(tr.risk)).any())
        elif oid in ("judge", "confirm") and oid not in ob_resp:  # the tier rules (no margin)
            worst, blind = None, 0
            kind, resp = "tier", str(spec.risk.response) if oid == "judge" else "stop_2"
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
    nf = int(tr.fault.sum())
    first_f = int(np.argmax(tr.fault)) if nf else None
    detail = "; ".join(_why_fault(rs, tr, data, mapping, spec)) if first_f is not None else ""
    checks.append(CheckResult("inputs", "faults", str(spec.on_fault), nf, *at(first_f), None, detail))
    signals: dict[str, dict[str, Any]] = {}
    for name, s in data.series.items():
        code = rs.codes[name]
        signals[name] = {"topic": s.topic, "type": s.msgtype, "clock": s.clock, "offset_s": s.offset_ns / 1e9,
                         "messages": s.read, "samples": int(s.times.size), "judged": rs.judged.get(name, 0),
                         "before_first_cycle": rs.before.get(name, 0), "unusable_messages": s.bad,
                         "missing_cycles": int((code == MISSING).sum()),
                         "stale_cycles": int((code == STALE).sum()), "max_age_s": mapping.limit_s(name)}
    if mapping.task is not None and p is None:
        code = rs.codes["p"]
        signals["task"] = {"topic": mapping.task.topic, "messages": len(data.texts),
                           "judged": rs.judged.get("task", 0), "missing_cycles": int((code == MISSING).sum())}
    topics: dict[str, dict[str, Any]] = {}
    for name, sg in signals.items():  # per topic: messages read, and the fewest of them any of its signals judged
        tp = topics.setdefault(sg["topic"], {"read": sg["messages"], "judged": sg["judged"], "signals": []})
        tp["read"] = max(tp["read"], sg["messages"])
        tp["judged"] = min(tp["judged"], sg["judged"])
        tp["signals"].append(name)
    n_over = int(tr.override.sum())
    res = BagReplay(data.path, data.storage, float(mapping.rate_hz), n, t0, int(grid[-1]), checks, n_over,
                    int(np.argmax(tr.override)) if n_over else None, signals, rs.tasks, tr.engine,
                    _latches(tr, grid, float(mapping.rate_hz)), rs.warnings,
                    {"cycle": s0, "t_s": round((int(grid[s0]) - t0) / 1e9, 9), "note": (
                        f"every input seen from cycle {s0}: the monitor starts fresh there (the {s0} cycle"
                        f"{'s' if s0 != 1 else ''} before fail closed but latch nothing after)") if s0 else ""},
                    topics)
    if keep_trace:
        res.trace, res.grid, res.columns = tr, grid, rs.columns
    if audit is not None:
        _audit(audit, res, tr, rs, spec)
    return res


def _reads_risk(spec: Spec) -> set[str]:
    """The ids of the obligations whose ``when`` or ``require`` reads R_e (a name that is neither a
    signal nor a constant: the built-in ``risk``)."""
    from ..compiler import plan_of
    from ..spec._expr import Name, walk
    known = set(spec.signals) | set(spec.constants)
    out = set()
    for ob in plan_of(spec).obligations:
        for root in (ob.when, ob.require):
            if root is not None and any(isinstance(n, Name) and n.id not in known for n in walk(root)):
                out.add(ob.id)
    return out


def _why_fault(rs: Resampled, tr: CycleResults, data: BagData, mapping: Mapping, spec: Spec) -> list[str]:
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
        col = rs.columns[name]
        ok = code == OK
        for sign, label in ((1, "+inf"), (-1, "-inf")):
            add(ok & np.isinf(col) & (np.sign(col) == sign), f"{name}: the {s.topic} message held is {label}")
        sig = spec.signals.get(name)
        fin = ok & np.isfinite(col)
        if sig is not None and sig.type == "bool":
            add(fin & (col != 0.0) & (col != 1.0), f"{name}: the {s.topic} value held is not a truth value (0 or 1)")
        elif sig is not None and sig.range is not None:
            lo, hi = sig.range
            out = fin & ((col < lo) | (col > hi))
            if out.any():
                k = int(np.argmax(out & tr.fault)) if (out & tr.fault).any() else int(np.argmax(out))
                add(out, f"{name}: the {s.topic} value held is outside its range [{lo:g}, {hi:g}] "
                         f"(e.g. {col[k]:g})")
        add(ok & np.isnan(col),
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
    checked = res.check("risk").status != "NOT CHECKED"  # risk: none holds R_e at 0: not a measured value
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
               risk=None if (tr.risk[k] != tr.risk[k] or not checked) else float(tr.risk[k]),
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
               keep_trace: bool = False, engine: str = "auto",
               on_progress: Callable[[int, int], None] | None = None) -> BagReplay:
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
        on_progress: called as ``on_progress(messages_read, messages_total)`` while the bag is read.

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
    data = read_bag(bag, mapping, on_progress=on_progress)
    return replay_data(data, spec, mapping, score=score, p=p, audit=audit, keep_trace=keep_trace, engine=engine)
