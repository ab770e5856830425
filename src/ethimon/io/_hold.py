"""The one hold: a signal's last sample, its staleness and its future-stamp rule, in two forms that agree
(a property checks it): :func:`hold` over a whole recording at once (numpy, replay) and :class:`Hold`, one
sample at a time as they arrive (live).

Cycle ``k`` is at ``t0 + rint(k * 1e9 / rate_hz)`` ns (float64 arithmetic, as
written); the grid runs until a cycle at or after the bag's last sample, so the
tail is judged too. At cycle time ``t`` a signal takes the last sample with time ``<= t``
(a sample at exactly ``t`` counts); with ``time: header`` a sample is first held at the later of its
log (receive) time and its stamp, and its age is counted from its stamp, as live. It is *missing* when it has no such
sample yet, and *stale* when that sample is older than its limit:
``t - t_sample > max_age_s * 1e9``. A missing or stale input is unusable
(NaN in its column): the monitor fails closed on that cycle, as it does
online for a missing input.

Live, :class:`Hold` does the same one sample at a time: a cycle at time ``t`` takes the last sample
that arrived (its time: the receive time, or the header stamp plus ``offset_s``), *missing* before
the first, *stale* when ``t - t_sample > max_age_s``. A sample is held from the first cycle at or after
its own time: a header stamp a little ahead of the cycle that took it waits for its time (never fresh
longer than ``max_age_s`` after its stamp); one further ahead than the mapping's ``future_tolerance_s`` is a
fault, and no value, until a sample whose time has come replaces it (its age cannot be judged). A
sample that a newer one replaces before any cycle read it is never judged: with ``samples: every``
that is a fault on the next cycle (replay refuses such a bag, for the same reason), with ``samples:
latest`` it is counted. ``derive: rate`` takes the rate between consecutive messages at their own
times (:func:`~ethimon.io.rate_between`), the first message giving none, as replay does.
"""

from __future__ import annotations

import math
from collections import deque
from typing import Any

import numpy as np

from ..errors import BagError
from ..runtime import Fault

#: ``sm`` below: a signal's mapping entry (:class:`~ethimon.io.SignalMap`; not imported: the mapping imports this)
from ._values import is_truth, numbers_of, rate_between, reduce_value

__all__ = ["OK", "MISSING", "STALE", "MAX_CYCLES", "Hold", "cycle_grid", "hold", "judged"]

OK, MISSING, STALE = 0, 1, 2
#: most cycles one bag may replay to (e.g. 13.9 hours at 1 kHz)
MAX_CYCLES = 50_000_000
#: how far ahead of the clock that judges it a sample time may be before it is a fault (s; a mapping's
#: ``future_tolerance_s`` default)
FUTURE_TOLERANCE_S = 0.005


def cycle_grid(t0: int, t_end: int, rate_hz: float) -> np.ndarray:
    """Cycle times (int64 ns) ``t0 + rint(k * 1e9 / rate_hz)`` from ``t0`` up to and including the first
    cycle at or after ``t_end`` (a sample in the bag's tail is judged by that last cycle)."""
    if t_end < t0:
        return np.zeros(0, dtype=np.int64)
    if not (rate_hz > 0 and np.isfinite(rate_hz)):
        raise ValueError(f"rate_hz must be a positive number, got {rate_hz!r}")
    span = (int(t_end) - int(t0)) * float(rate_hz) / 1e9
    if span > MAX_CYCLES:
        raise ValueError(f"{int(span):,} cycles at {rate_hz:g} Hz: more than the limit of {MAX_CYCLES:,}")
    n = int(span) + 3
    k = np.arange(n, dtype=np.float64)
    grid = int(t0) + np.rint(k * (1e9 / float(rate_hz))).astype(np.int64)
    last = int(np.searchsorted(grid, t_end, side="left"))  # the first cycle at or after t_end
    return grid[: last + 1]


def hold(times: np.ndarray, values: np.ndarray, grid: np.ndarray,
         max_age_s: float | None, visible: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Zero-order hold of one signal on ``grid``.

    ``times`` (ascending) are the samples' own times, from which their age is counted; ``visible`` (same
    order; ``None``: ``times``) when each can first be held: with ``time: header`` the later of its log
    (receive) time and its stamp, as live holds a sample from the cycle that took it, or from its stamp if
    that is still ahead. A cycle holds, of the samples visible by then, the one with the latest time (equal
    times: the later in ``times`` order), as live does: a sample visible after one with a later time was
    held is never held.

    Returns:
        ``(values, code, index)``: the held value (NaN when missing or stale), the code per
        cycle (:data:`OK`, :data:`MISSING`, :data:`STALE`) and the index of the held sample (-1: none).
    """
    if visible is None:
        idx = np.searchsorted(times, grid, side="right") - 1
    else:
        order = np.argsort(visible, kind="stable")
        newest = np.maximum.accumulate(order) if order.size else order  # the latest time among the visible
        pos = np.searchsorted(visible[order], grid, side="right") - 1
        idx = np.where(pos >= 0, newest[np.maximum(pos, 0)] if order.size else -1, -1)
    seen = idx >= 0
    safe = np.where(seen, idx, 0)
    if times.size:
        vals = np.where(seen, values[safe], np.nan)
        age = grid - times[safe]
    else:
        vals = np.full(grid.shape, np.nan)
        age = np.zeros(grid.shape, dtype=np.int64)
    code = np.where(seen, OK, MISSING).astype(np.int8)
    if max_age_s is not None:
        stale = seen & (age > max_age_s * 1e9)
        code[stale] = STALE
        vals = np.where(stale, np.nan, vals)
    return vals, code, np.where(seen, idx, -1)


def judged(times: np.ndarray, values: np.ndarray, idx: np.ndarray) -> np.ndarray:
    """Which samples some cycle judges: those held by a cycle (``idx`` from :func:`hold`), and those
    sharing a time and a value with one that is (the one cycle judges both)."""
    out = np.zeros(times.size, dtype=bool)
    held = idx[idx >= 0]
    out[held] = True
    if times.size > 1:
        same = np.flatnonzero(times[:-1] == times[1:])
        for i in same[::-1]:  # a run of equal times: the last one is held
            a, b = values[i], values[i + 1]
            if a == b or (a != a and b != b):
                out[i] = out[i] or out[i + 1]
    return out


class Hold:
    """One mapped signal live: its samples as a cycle takes them (:meth:`put`), read once per cycle (:meth:`read`).

    A sample is held from the first cycle at or after its own time (its receive time, or header stamp plus
    ``offset_s``): a stamp a little ahead of the cycle that took it waits for its time (the sample before it
    is still held, and ages); a stamp further ahead than ``tolerance_s`` is a fault (and no value) from the
    cycle that took it until a sample whose time has come replaces it: its age cannot be judged. Times are
    integer nanoseconds, as in replay.

    Args:
        name: the monitor input.
        sm: its mapping entry (reduction, ``derive``, ``offset_s``, ``samples``).
        limit_s: its staleness limit (``None``: never stale).
        every: ``samples: every`` (a sample replaced before a cycle read it is a fault).
        tolerance_s: how far ahead of the cycle that takes it a sample time may be.
        truth: a bool input of the spec (a true/false value feeds it; anywhere else it is invalid).
        bool_message: the message for a true/false value on a number input (:func:`~ethimon.io.bool_mismatch`).

    Attributes:
        received, judged, skipped, before: samples put, read by a cycle, replaced unread (after the first
            read), replaced before the first read (start-up, not judged).
    """

    #: the codes :func:`hold` gives each cycle of a recording (a held value, none yet, too old)
    OK, MISSING, STALE = OK, MISSING, STALE

    __slots__ = ("name", "sm", "limit", "every", "tol", "truth", "bool_message", "last", "read_yet", "prev",
                 "received", "judged", "skipped", "before", "_unread", "_skip_note", "_bad_note", "off", "pending")

    def __init__(self, name: str, sm: Any, limit_s: float | None, *, every: bool = True,
                 tolerance_s: float = FUTURE_TOLERANCE_S, truth: bool = False,
                 bool_message: str | None = None) -> None:
        self.name, self.sm, self.limit, self.every = name, sm, limit_s, every
        self.tol, self.truth, self.bool_message = float(tolerance_s), truth, bool_message
        self.off = int(round(sm.offset_s * 1e9))
        self.last: tuple[Any, int] | None = None  # (value, sample time in ns)
        self.prev: tuple[np.ndarray | None, int] | None = None  # derive: rate, the message before
        #: samples taken whose time has not come yet: [value, time ns, stamped beyond the tolerance, taken at ns]
        self.pending: deque[list] = deque()
        self.read_yet = False
        self.received = self.judged = self.skipped = self.before = 0
        self._unread = False
        self._skip_note: str | None = None
        self._bad_note: str | None = None

    def put(self, value: Any, t: float, topic: str = "", *, now: float | None = None) -> None:
        """A cycle took a sample: ``value`` is the field's value (before reduction), ``t`` its time (receive
        time, or header stamp) in seconds, ``offset_s`` added here; ``now`` the taking cycle's time on the same
        clock (default ``t``)."""
        t = int(round(t * 1e9)) + self.off
        self.received += 1
        x: Any
        if self.sm.derive == "rate":
            try:
                arr = None if is_truth(value) else numbers_of(value)
            except BagError:
                arr = None
            prev, self.prev = self.prev, (arr, t)
            if is_truth(value):
                self._bad_note = f"{self.name}: 'derive: rate' of a bool field ({topic})"
            if prev is None:
                return  # the first message gives no rate
            x = rate_between(prev[0], arr, (t - prev[1]) / 1e9, self.sm)
        elif is_truth(value) and not isinstance(value, np.ndarray):
            if self.truth:
                x = bool(value)
            else:
                x = math.nan
                self._bad_note = self.bool_message or (f"signal {self.name!r}: {topic} gives true/false: a bool is "
                                                       "not a number")
        else:
            try:
                x = reduce_value(value, self.sm)
            except BagError as exc:
                x = math.nan
                self._bad_note = f"{self.name}: {exc.message}"[:300]
            if self.truth and x == x:
                x = bool(x)
        c = t if now is None else int(round(now * 1e9))
        self.pending.append([x, t, t - c > self.tol * 1e9, c])

    def _hold(self, x: Any, t: int) -> None:
        last = self.last
        if last is not None and t < last[1]:  # arrived after a newer sample was held: no cycle holds it
            self._unjudged()
            return
        if last is not None and self._unread and not (last[1] == t and (last[0] == x or (last[0] != last[0]
                                                                                        and x != x))):
            self._unjudged()
        self.last = (x, t)
        self._unread = True

    def _unjudged(self) -> None:
        """A sample no cycle will read: counted (and a fault under ``samples: every``)."""
        if self.read_yet:
            self.skipped += 1
            if self.every and self._skip_note is None:
                self._skip_note = (f"signal {self.name!r}: a sample on {self.sm.topic} was replaced by a newer "
                                   "one before a cycle read it; the monitor would never judge it ('samples: "
                                   "every'; 'samples: latest' judges the latest each cycle)")
        else:
            self.before += 1

    def read(self, now: float, faults: list[Fault]) -> Any:
        """The value this cycle (at ``now``, the clock of the sample times) takes, or ``None`` when it has none
        to give: missing (no fault added: the monitor names it), stale or stamped beyond the tolerance in the
        future (a fault added). A value that cannot be formed is NaN (the monitor refuses it as invalid)."""
        c = int(round(now * 1e9))
        pend = self.pending
        if pend and any(p[1] <= c for p in pend):
            # every sample whose time has come, by time (stably: in the order taken among equal times), as
            # replay's hold orders a recording; one older than the sample held is never held (not judged)
            keep: deque[list] = deque()
            due = []
            for p in pend:
                (due if p[1] <= c else keep).append(p)
            due.sort(key=lambda p: p[1])
            for p in due:
                self._hold(p[0], p[1])
            self.pending = pend = keep
        if self._skip_note is not None:
            faults.append(Fault("signals", self._skip_note, self.name))
            self._skip_note = None
        if self._bad_note is not None:
            faults.append(Fault("invalid", self._bad_note, self.name))
            self._bad_note = None
        # a sample stamped beyond the tolerance makes the input unusable from the cycle that took it until a
        # sample whose time has come replaces it (what replay of the recording holds: see recorded_data)
        held_t = self.last[1] if self.last is not None else None
        ahead = next((p for p in reversed(pend) if p[2] and (held_t is None or p[3] > held_t)), None)
        if ahead is not None:
            faults.append(Fault("stale", f"{self.name}: a {self.sm.topic} sample is stamped {(ahead[1] - c) / 1e9:.3f} "
                                f"s in the future (more than future_tolerance_s {self.tol:g} when it arrived): its "
                                "age cannot be judged (the robot's clock runs ahead of this one, or the stamp is "
                                "forged; declare offset_s)", self.name))
            if self.last is not None:
                self.read_yet = True
            return None
        last = self.last
        if last is None:
            return None
        self.read_yet = True
        if self._unread:
            self._unread = False
            self.judged += 1
        value, t = last
        age_ns = c - t
        if self.limit is not None and age_ns > self.limit * 1e9:
            faults.append(Fault("stale", f"{self.name}: stale (last {self.sm.topic} message {age_ns / 1e9:.3f} s old, "
                                f"max_age_s {self.limit:g})", self.name))
            return None
        return value

    def age(self, now: float) -> float | None:
        """Seconds since the held sample; ``None`` before the first."""
        return None if self.last is None else max(0.0, (int(round(now * 1e9)) - self.last[1]) / 1e9)
