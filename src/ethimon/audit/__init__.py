"""Audit trail: a hash-chained, fsync'd JSONL log of what the monitor decided and why.

::

    from ethimon.audit import AuditLog, verify_log
    with AuditLog("run.jsonl", meta={"spec_sha256": spec_hash(spec)}) as log:
        ...                     # GovernedLoop(..., audit=log) appends the records
    verify_log("run.jsonl").ok  # False if a record was edited, removed or reordered

On the command line: ``ethimon audit verify run.jsonl`` (exit 0 ok, 1 tampered, 2 bad input).

Bounds: one record line is at most :data:`MAX_RECORD_BYTES` (1 MiB; larger
records lose their largest fields, marked ``"truncated"``); the writer's lag
is bounded by ``AuditLog(max_pending=10_000, max_pending_bytes=32 MiB,
max_lag_s=1.0)``, past which ``append`` refuses and ``AuditLog.fault`` is set;
``verify_log`` reads only regular files and never more than one capped line.
"""

from __future__ import annotations

from ._log import FSYNC_POLICIES, MAX_RECORD_BYTES, AuditLag, AuditLog, spec_hash
from ..errors import AuditFormatError, AuditTampered
from ._chain import AuditReport, read_log, verify_log

__all__ = ["AuditFormatError", "AuditLag", "AuditTampered", "AuditLog", "AuditReport", "FSYNC_POLICIES", "MAX_RECORD_BYTES",
           "read_log", "spec_hash", "verify_log"]
