"""``ethimon replay --mcap OUT`` / ``--foxglove [HOST:]PORT``: each cycle's verdict as the verdict channels
(:mod:`ethimon.view`) on the bag's own timeline, written to an MCAP file or served to a live Foxglove view.

Foxglove (or any MCAP viewer) then shows where and why the arm would have been stopped, beside the
inputs the monitor saw. The channels, their names and JSON Schemas are those of the live view
(``ethimon ros2 --foxglove``), so one layout (``examples/foxglove/ethimon-layout.json``) opens both;
every message's log and publish time is its cycle's bag time (ns). Topics (see :mod:`ethimon.view`):

* ``/ethimon/decision``: ``override``, ``response``, ``violations``, ``fault``, ``latched``, ``latched_rules``
  (the rules whose latch holds the override, by name), ``awaiting_release`` (every cycle)
* ``/ethimon/margins``: one number per obligation, by its id (``null`` where not evaluated; every cycle)
* ``/ethimon/risk``: ``R_e`` (``null``: no usable risk input, or ``risk: none``), ``tau``, ``tau_confirm``,
  ``checked`` (false with ``risk: none``), ``band``, ``judge``, ``confirm_hold``, ``judge_hold`` (every cycle)
* ``/ethimon/faults``: the monitor's fault reasons, written when they change (``[]`` when they clear)
* ``/ethimon/inputs/<signal>``: the held value the monitor read (``null``: missing or stale; every cycle)

Written with the ``mcap`` package (``pip install 'ethimon[ros]'``), imported when a file is written;
served with ``foxglove-sdk`` (``pip install 'ethimon[foxglove]'``).
"""

from __future__ import annotations

import os
import time
from collections.abc import Iterator
from typing import Any

from .._files import open_regular
from ..errors import BagError, DependencyNotInstalled
from ..language import Response, Spec
from ..view import FAULTS, TOPICS, VerdictChannels

__all__ = ["TOPICS", "serve_verdicts", "verdict_messages", "write_mcap"]

_RESP = {r.severity: r.value for r in Response}


def verdict_messages(res: Any, spec: Spec) -> tuple[VerdictChannels, Iterator[tuple[int, int, list]]]:
    """The channels of a replay and its cycles' messages: ``(channels, iterator of (bag time ns, cycle,
    [(topic, message), ...]))``; ``res`` a :class:`BagReplay` made with ``keep_trace=True``. The faults
    message comes on the cycles where the reasons change."""
    tr, grid, cols = res.trace, res.grid, res.columns
    if tr is None or grid is None or cols is None:
        raise ValueError("the verdicts of a replay need a BagReplay made with keep_trace=True")
    ids = tr.ids[:tr.margins.shape[1]]  # the obligations (then "risk" and the tiers' rules)
    names = [n for n in spec.signals if n in cols]
    checked = not any(c.id == "risk" and c.status == "NOT CHECKED" for c in res.checks)
    ch = VerdictChannels.of_spec(spec, ids, names, checked)

    def cycles() -> Iterator[tuple[int, int, list]]:
        over, sev, viol, fault, lat = (tr.override.tolist(), tr.severity.tolist(), tr.violated, tr.fault.tolist(),
                                       tr.latched.tolist())
        margins, risk = tr.margins.tolist(), tr.risk.tolist()
        inputs = {nm: cols[nm].tolist() for nm in names}
        judge = cols["judge"].tolist() if "judge" in cols and getattr(cols["judge"], "dtype", None) is not None \
            and cols["judge"].dtype.kind == "f" else None
        prev_faults: Any = ()
        for k in range(grid.size):
            v = [tr.ids[j] for j in viol[k].nonzero()[0]] if viol[k].any() else []
            held = tuple(tr.holding_at(k)) if over[k] else ()
            msgs = ch.messages(k, bool(over[k]), _RESP[int(sev[k])], v, bool(fault[k]), bool(lat[k]), held,
                               margins[k], risk[k], judge[k] if judge is not None else None,
                               {nm: inputs[nm][k] for nm in names})
            fs = tr.faults_at(k) if fault[k] else ()
            if fs != prev_faults:
                msgs.insert(3, (FAULTS, ch.faults(fs)))
                prev_faults = fs
            yield int(grid[k]), k, msgs

    return ch, cycles()


def write_mcap(res: Any, path: str | os.PathLike, spec: Spec) -> int:
    """Write the per-cycle verdicts of ``res`` (a :class:`BagReplay` with ``keep_trace=True``) to a new
    MCAP file ``path``; returns the number of messages written.

    Raises:
        BagError: the file cannot be written.
        DependencyNotInstalled: the ``mcap`` package is not installed.
    """
    try:
        from mcap.writer import Writer
    except ImportError as exc:
        raise DependencyNotInstalled(f"--mcap writes MCAP with the mcap package, which is not installed ({exc}); "
                                     "pip install 'ethimon[ros]'") from None
    ch, cycles = verdict_messages(res, spec)
    spath = os.fspath(path)

    def refuse(message: str, path: str | None = None, hint: str | None = None) -> BagError:
        return BagError(f"--mcap: {message}", path, hint=hint)

    try:
        f = open_regular(spath, "wb", what="MCAP output file", error=refuse)
    except OSError as exc:
        raise BagError(f"--mcap: cannot write {spath}: {exc.strerror or exc}", res.path) from None
    n = 0
    with f:
        w = Writer(f)
        w.start(profile="", library="ethimon replay")
        cid = {}
        for topic, title, data in ch.schemas():
            sid = w.register_schema(name=title, encoding="jsonschema", data=data)
            cid[topic] = w.register_channel(topic=topic, message_encoding="json", schema_id=sid)
        dumps = _dumps
        for t, k, msgs in cycles:
            for topic, obj in msgs:
                w.add_message(channel_id=cid[topic], log_time=t, publish_time=t, sequence=k, data=dumps(obj))
            n += len(msgs)
        w.finish()
    return n


def _dumps(obj: Any) -> bytes:
    import json
    return json.dumps(obj, allow_nan=False).encode()


def serve_verdicts(res: Any, view: Any, spec: Spec, *, speed: float = 1.0,
                   sleep: Any = time.sleep, clock: Any = time.monotonic) -> int:
    """Serve the per-cycle verdicts of ``res`` (``keep_trace=True``) to a live view (a
    :class:`~ethimon.view.FoxgloveView`, or any object with ``put_messages(messages, t_ns)``), paced
    on the bag's timeline: ``speed`` 1 is the bag's own pace, 2 twice as fast, 0 as fast as the view
    takes them (a replay is no control loop: then it waits for the view's queue to drain every 256
    cycles, so nothing is dropped). Returns the number of cycles served."""
    if not (isinstance(speed, (int, float)) and speed >= 0 and speed == speed and speed != float("inf")):
        raise ValueError(f"speed={speed!r}; expected a number >= 0 (0: no pacing)")
    _, cycles = verdict_messages(res, spec)
    start = t0 = None
    n = 0
    for t, _, msgs in cycles:
        if speed > 0:
            if t0 is None:
                t0, start = t, clock()
            wait = start + (t - t0) / 1e9 / speed - clock()
            if wait > 0:
                sleep(wait)
        elif n % 256 == 255:
            flush = getattr(view, "flush", None)
            if flush is not None:
                flush()
        view.put_messages(msgs, t)
        n += 1
    return n
