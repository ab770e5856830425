"""``ethimon replay --mcap OUT``: each cycle's verdict as MCAP topics on the bag's own timeline.

Foxglove (or any MCAP viewer) then shows where and why the arm would have been
stopped, beside the inputs the monitor saw. Channels are JSON-encoded, each with
a JSON Schema (``jsonschema``); every message's log and publish time is its
cycle's bag time (ns). Topics:

* ``/ethimon/decision``: ``override``, ``response``, ``violations``, ``fault``, ``latched`` (every cycle)
* ``/ethimon/margins``: one number per obligation (``null`` where not evaluated; every cycle)
* ``/ethimon/risk``: ``R_e`` (``null``: no usable risk input, or ``risk: none``), the threshold ``tau``
  and ``checked`` (false with ``risk: none``; every cycle)
* ``/ethimon/faults``: the monitor's fault reasons, written when they change (``[]`` when they clear)
* ``/ethimon/inputs/<signal>``: the held value the monitor read (``null``: missing or stale; every cycle)

Written with the ``mcap`` package (``pip install 'ethimon[ros]'``), imported when a file is written.
"""

from __future__ import annotations

import json
import math
import os
from typing import Any

from .._files import open_regular
from ..errors import BagError, DependencyNotInstalled
from ..language import Response, Spec

__all__ = ["TOPICS", "write_mcap"]

TOPICS = ("/ethimon/decision", "/ethimon/margins", "/ethimon/risk", "/ethimon/faults")
_RESP = {r.severity: r.value for r in Response}


def _num(x: float) -> float | str | None:
    if x != x:
        return None
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return float(x)


def _schema(title: str, props: dict[str, Any]) -> bytes:
    return json.dumps({"$schema": "https://json-schema.org/draft/2020-12/schema", "title": title,
                       "type": "object", "properties": props}).encode()


_NUM = {"type": ["number", "string", "null"]}


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
    tr, grid, cols = res.trace, res.grid, res.columns
    if tr is None or grid is None or cols is None:
        raise ValueError("write_mcap needs a BagReplay made with keep_trace=True")
    ids = tr.ids[:-1]
    names = [n for n in spec.signals if n in cols]
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

        def channel(topic: str, title: str, props: dict[str, Any]) -> int:
            sid = w.register_schema(name=title, encoding="jsonschema", data=_schema(title, props))
            return w.register_channel(topic=topic, message_encoding="json", schema_id=sid)

        c_dec = channel("/ethimon/decision", "ethimon.Decision", {
            "override": {"type": "boolean"}, "response": {"type": "string"},
            "violations": {"type": "array", "items": {"type": "string"}}, "fault": {"type": "boolean"},
            "latched": {"type": "boolean"}, "cycle": {"type": "integer"}})
        c_mg = channel("/ethimon/margins", "ethimon.Margins", {oid: _NUM for oid in ids})
        c_risk = channel("/ethimon/risk", "ethimon.Risk", {"R_e": _NUM, "tau": {"type": "number"},
                                                           "checked": {"type": "boolean"}})
        c_f = channel("/ethimon/faults", "ethimon.Faults", {"faults": {"type": "array", "items": {
            "type": "object", "properties": {"kind": {"type": "string"}, "message": {"type": "string"},
                                             "subject": {"type": ["string", "null"]}}}}})
        c_in = {nm: channel(f"/ethimon/inputs/{nm}", "ethimon.Input", {"value": _NUM}) for nm in names}
        tau = float(spec.risk.threshold)
        checked = not any(c.id == "risk" and c.status == "NOT CHECKED" for c in res.checks)
        over, sev, viol, fault, lat = (tr.override.tolist(), tr.severity.tolist(), tr.violated, tr.fault.tolist(),
                                       tr.latched.tolist())
        margins, risk = tr.margins.tolist(), tr.risk.tolist()
        inputs = {nm: cols[nm].tolist() for nm in names}
        prev_faults: Any = ()
        dumps = json.dumps
        for k in range(grid.size):
            t = int(grid[k])
            v = [tr.ids[j] for j in viol[k].nonzero()[0]] if viol[k].any() else []

            def put(cid: int, obj: Any) -> None:
                w.add_message(channel_id=cid, log_time=t, publish_time=t, sequence=k, data=dumps(obj).encode())

            put(c_dec, {"cycle": k, "override": bool(over[k]), "response": _RESP[int(sev[k])] if over[k] else "none",
                        "violations": v, "fault": bool(fault[k]), "latched": bool(lat[k])})
            put(c_mg, {oid: _num(margins[k][j]) for j, oid in enumerate(ids)})
            put(c_risk, {"R_e": _num(risk[k]) if checked else None, "tau": tau, "checked": checked})
            fs = tr.faults_at(k) if fault[k] else ()
            if fs != prev_faults:
                put(c_f, {"faults": [{"kind": getattr(x, "kind", "fault"), "message": str(getattr(x, "message", x)),
                                      "subject": getattr(x, "subject", None)} for x in fs]})
                prev_faults = fs
                n += 1
            for nm in names:
                put(c_in[nm], {"value": _num(inputs[nm][k])})
            n += 3 + len(names)
        w.finish()
    return n
