"""Audit trail: a hash-chained, fsync'd JSONL log of what the monitor decided and why.

::

    from ethimon.audit import AuditLog, verify_log
    with AuditLog("run.jsonl", meta={"spec_sha256": spec_hash(spec)}) as log:
        ...                     # GovernedLoop(..., audit=log) appends the records
    verify_log("run.jsonl").ok  # False if a record was edited, removed or reordered

On the command line: ``ethimon audit verify run.jsonl`` (exit 0 ok, 1 tampered, 2 bad input).

An unkeyed chain shows edits, but anyone who can write the file can drop a record and rebuild the
rest: key the log (``AuditLog(key=...)``; the CLI's ``--audit`` logs take the key the operator names
in ``ETHIMON_AUDIT_KEY_FILE`` or ``ETHIMON_AUDIT_KEY_ENV``, :func:`key_from_env`) and/or keep its
head (:attr:`AuditLog.head_token`, printed by the CLI on close) elsewhere and check it with
``verify_log(expect_head=...)`` / ``ethimon audit verify --head COUNT:HASH``.

Bounds: one record line is at most :data:`MAX_RECORD_BYTES` (1 MiB; larger
records lose their largest fields, marked ``"truncated"``); the writer's lag
is bounded by ``AuditLog(max_pending=10_000, max_pending_bytes=32 MiB,
max_lag_s=1.0)``, past which ``append`` refuses and ``AuditLog.fault`` is set;
``verify_log`` reads only regular files and never more than one capped line.
"""

from __future__ import annotations

from ._log import FSYNC_POLICIES, KEY_ENV, KEY_FILE_ENV, MAX_RECORD_BYTES, AuditLag, AuditLog, bounded, key_from_env, \
    spec_hash
from ..errors import AuditFormatError, AuditTampered
from ._chain import AuditReport, read_log, verify_log

__all__ = ["AuditLog", "AuditReport", "bounded", "read_log", "verify_log"]
