"""Why a replay's cycles failed closed, in the bag's words (missing, stale or unusable inputs, task texts
not seen or not scored), then the monitor's own reasons for the rest."""

from __future__ import annotations

import numpy as np

from ..language import Spec
from ._bag import BagData
from ._columns import Resampled
from ..io import Hold, Mapping, hold
from ._verdicts import CycleResults


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
        missing = code == Hold.MISSING
        if s.times.size == 0:
            have = "is not in this bag" if s.topic not in data.topics else "has no message"
            add(missing, f"{name}: topic {s.topic} {have}")
        else:
            add(missing, f"{name}: no message on {s.topic} yet")
        stale = code == Hold.STALE
        if stale.any():
            k = int(np.argmax(stale & tr.fault)) if (stale & tr.fault).any() else int(np.argmax(stale))
            i = int(hold(s.times, s.values, grid[k:k + 1], None, s.visible)[2][0])  # the sample that cycle held
            age = (int(grid[k]) - int(s.times[i])) / 1e9
            add(stale, f"{name}: stale (last {s.topic} message {age:.3f} s old, max_age_s "
                       f"{mapping.limit_s(name):g})")
        col = rs.columns[name]
        ok = code == Hold.OK
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
        add(rs.codes["p"] == Hold.MISSING, f"risk: no task text on {mapping.task.topic} yet")
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
