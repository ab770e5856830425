"""A replay's decisions appended to an :class:`~ethimon.audit.AuditLog`, one record per change."""

from __future__ import annotations

from typing import Any

from ..language import Response, Spec
from ._bag import BagError
from ._columns import Resampled
from ._result import BagReplay
from ._verdicts import CycleResults


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
        held = tuple(tr.holding_at(k))  # a rule released while another holds the override is a change too
        key = (bool(tr.override[k]), int(tr.severity[k]), viol, bool(tr.fault[k]), held)
        if key == prev:
            continue
        event = "change" if prev is not None and prev[0] == key[0] else (
            "override_on" if key[0] else "override_off")
        prev = key
        resp = _RESP[int(tr.severity[k])] if tr.override[k] else "none"
        append("decision", event=event, bag=res.path, cycle=k, bag_time_ns=int(rs.grid[k]),
               override=bool(tr.override[k]), response=resp, violations=list(viol),
               faults=[_fault_dict(f) for f in tr.faults_at(k)],
               latched=bool(tr.latched[k]), latched_rules=list(held),
               risk=None if (tr.risk[k] != tr.risk[k] or not checked) else float(tr.risk[k]),
               margins={oid: float(tr.margins[k, j]) for j, oid in enumerate(ids)},
               inputs={nm: float(rs.columns[nm][k]) for nm in names})
    append("replay_result", bag=res.path, passed=res.passed,
           checks=[c.as_dict() for c in res.checks])


_RESP = {r.severity: r.value for r in Response}


def _fault_dict(f: Any) -> Any:
    as_dict = getattr(f, "as_dict", None)
    return as_dict() if as_dict is not None else str(f)
