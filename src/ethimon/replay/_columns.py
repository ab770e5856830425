"""A bag's samples on the monitor's cycle grid: every input zero-order held (:func:`resample`), the
task texts scored, the samples that no cycle would judge refused (or counted, with ``samples: latest``)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..compiler import plan_of
from ..language import Spec
from ._bag import BagData, BagError
from ._collect import Series
from ..io import Hold, Mapping, hold, judged
from ._scoring import Scorer, _Lazy

__all__ = ["resample"]


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
            lasts.append(int(s.times[-1] if s.visible is None else s.visible.max()))
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
        early = (s.times if s.visible is None else s.visible) < grid[0]
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
        jitter = med >= 0.5 * period and cnt <= max(1, n // 10)
        if jitter:  # an ordinary recording: a few samples a cycle apart land in one cycle
            why = (f"which is a recorder's ordinary jitter (a message every {med / 1e6:.1f} ms against cycles of "
                   f"{period / 1e6:.1f} ms, so now and then two land in one cycle)")
            hint = ("write 'samples: latest' in the mapping (for this signal or all): each cycle then judges the "
                    "latest sample, as the live monitor does, and the samples in between are counted in the report")
        else:
            hint = (f"write 'samples: latest' to judge the latest sample each cycle, as the live monitor does; or "
                    f"raise rate_hz{'' if need > 10 * float(mapping.rate_hz) else f' to {math.ceil(need):g}'} so "
                    "each sample gets a cycle; or check the recorder's clock (a log time that jumps back puts "
                    "samples out of order)")
        raise BagError(
            f"signal {name!r}: {cnt:,} of {n:,} samples on {s.topic} fall between two cycles behind a newer "
            f"sample (first at t = {t_first:.3f} s), {why}; the monitor would never judge them", data.path,
            hint=hint)
    return out, before


def resample(data: BagData, mapping: Mapping, spec: Spec, *, score: Scorer | None = None,
             p: Sequence[float] | None = None) -> Resampled:
    """Zero-order-held columns of every input on the monitor's cycle grid (:func:`ethimon.io.hold`).

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
        grid = mapping.grid(span[0], span[1])
    except ValueError as exc:
        raise BagError(str(exc), data.path, hint="lower rate_hz or split the bag") from None
    n = grid.size
    columns: dict[str, np.ndarray] = {}
    codes: dict[str, np.ndarray] = {}
    idxs: dict[str, np.ndarray] = {}
    for name, s in data.series.items():
        vals, code, idx = hold(s.times, s.values, grid, mapping.limit_s(name), s.visible)
        columns[name] = vals
        codes[name] = code
        idxs[name] = idx
    warnings: list[str] = []
    judged_n, before = _judge_counts(data, mapping, grid, idxs, warnings)
    risk_key = mapping.risk_signal or "p"
    risk_note: dict[int, str] = {}
    tasks: list[dict[str, Any]] = []
    k_cls = plan_of(spec).risk_plan.classes
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
        codes["p"] = np.where(pos >= 0, Hold.OK, Hold.MISSING).astype(np.int8)
        for j, why in enumerate(notes):
            if why is not None:
                risk_note[j] = why
        codes["_task_row"] = which.astype(np.int64)
    if plan_of(spec).risk_plan.max_age_s is not None:
        # offline, each task text is scored the moment it arrives and re-scored by the loop every
        # cycle: the estimate is as old as this cycle (0 s); a mapped p_unsafe/risk topic carries
        # its own age, the time since its last message
        if risk_key in ("p", "risk") and risk_key not in mapping.signals:
            columns["risk_age_s"] = np.zeros(n)
        else:
            s = data.series[risk_key]
            idx = idxs[risk_key]  # the sample the hold took: its age, from its own time
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
    for w in mapping.lint(spec):
        sig = w.split("prev(", 1)[1].split(")", 1)[0]
        s = data.series.get(sig)
        if s is None or s.times.size < 2:
            continue
        med = float(np.median(np.diff(s.times)))
        if med > 1.5e9 / float(mapping.rate_hz):
            out.append(f"{w} ({s.topic} sends a message every {med / 1e6:.1f} ms, the cycles run every "
                       f"{1e3 / float(mapping.rate_hz):.1f} ms)")
    return out
