"""Audit trail: a hash-chained, fsync'd JSONL log of what the monitor decided and why.

::

    from ethimon.audit import AuditLog, verify_log
    with AuditLog("run.jsonl", meta={"spec_sha256": spec_hash(spec)}) as log:
        ...                     # GovernedLoop(..., audit=log) appends the records
    verify_log("run.jsonl").ok  # False if a record was edited, removed or reordered

On the command line: ``ethimon audit verify run.jsonl`` (exit 0 ok, 1 tampered, 2 bad input).
"""

from __future__ import annotations

from ._log import FSYNC_POLICIES, AuditLog, jsonable, spec_hash
from ._verify import AuditFormatError, AuditReport, read_log, verify_log

__all__ = ["AuditFormatError", "AuditLog", "AuditReport", "FSYNC_POLICIES", "jsonable", "read_log",
           "spec_hash", "verify_log"]
