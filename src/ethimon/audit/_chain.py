"""Check an audit log's hash chain: tampering, deletion, reordering, truncation."""

from __future__ import annotations

import json
import os
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import BinaryIO

from .._files import open_regular
from ..errors import AuditFormatError, AuditTampered
from ._log import FORMAT, GENESIS, MAX_RECORD_BYTES, canonical, key_id, record_hash

__all__ = ["AuditReport", "verify_log", "read_log"]


@dataclass(frozen=True)
class AuditReport:
    """Result of :func:`verify_log`.

    Attributes:
        ok: the chain is intact (and closed, if that was required).
        records: complete, verified records.
        closed: the log ends with a ``close`` record (the writer finished cleanly).
        torn_tail: the file ends in a partial line (a write cut short by a kill);
            that line was never reported written and is ignored.
        error: what is wrong, or ``None``.
        line: 1-based line of the first problem, or ``None``.
        head: hash of the last verified record (compare with an anchor kept elsewhere).
        log_id: the log's id from its ``open`` record.
        kinds: number of records of each kind.
        keyed: the chain is HMAC-keyed and was checked with its key. An unkeyed chain can be rebuilt by
            anyone who can write the file (a record dropped, the rest rehashed): only its head, kept
            elsewhere (``expect_head``), shows that.
        head_checked: the log ended at the head given (``expect_head``).
    """

    ok: bool
    records: int
    closed: bool
    torn_tail: bool = False
    error: str | None = None
    line: int | None = None
    head: str = GENESIS
    log_id: str | None = None
    kinds: dict = field(default_factory=dict)
    keyed: bool = False
    head_checked: bool = False

    def summary(self) -> str:
        """One line for humans."""
        if not self.ok:
            where = f"line {self.line}: " if self.line else ""
            return f"TAMPERED: {where}{self.error}"
        state = "closed" if self.closed else "not closed (writer killed or still running)"
        torn = "; ignored a partial last line" if self.torn_tail else ""
        if self.keyed:
            trust = "keyed (HMAC-SHA256)"
        else:
            trust = "unkeyed: anyone who can write the file can rebuild the chain" + (
                ", but it ends at the head given" if self.head_checked else
                "; check it with --head COUNT:HASH kept elsewhere, or write logs with a key")
        return (f"ok: {self.records} records, chain intact, {state}{torn}; {trust}; "
                f"head {self.records}:{self.head}")


def _audit_error(message: str, *, path: str, hint: str | None = None) -> AuditFormatError:
    return AuditFormatError(f"{path}: {message}" + (f" ({hint})" if hint else ""))


def _open_regular(path: str) -> BinaryIO:
    """Open ``path`` for reading without ever blocking: only a regular file is accepted
    (:func:`ethimon._files.open_regular`; a FIFO or ``/dev/stdin`` is an :class:`AuditFormatError`)."""
    return open_regular(path, "rb", what="audit log", error=_audit_error)


def _read_lines(fh: BinaryIO) -> Iterator[tuple[int, bytes | None]]:
    """``(line number, raw line)``; ``raw`` is ``None`` for a line longer than
    :data:`MAX_RECORD_BYTES`; reading stops there (at most ``MAX_RECORD_BYTES + 1`` bytes are held)."""
    lineno = 0
    while True:
        raw = fh.readline(MAX_RECORD_BYTES + 1)
        if not raw:
            return
        lineno += 1
        if len(raw) > MAX_RECORD_BYTES:
            yield lineno, None
            return  # nothing after an over-long line is looked at
        yield lineno, raw


def verify_log(path: str | os.PathLike, *, key: bytes | None = None, require_closed: bool = False,
               expect_head: str | None = None) -> AuditReport:
    """Verify an audit log written by :class:`~ethimon.audit.AuditLog`.

    Every complete line must be a record whose ``seq`` counts up from 0, whose
    ``prev`` is the previous record's ``hash`` and whose ``hash`` matches its
    content; the first record is ``open`` and nothing follows ``close``. A
    final line without its newline is a torn write (a kill mid-write, never
    reported written) and is ignored.

    Memory and time are bounded: only a regular file is read (a FIFO,
    ``/dev/stdin`` on a pipe, a socket or a device is refused at once instead of
    blocking), and no line longer than :data:`~ethimon.audit.MAX_RECORD_BYTES`
    (1 MiB, newline included; :class:`~ethimon.audit.AuditLog` never writes a
    longer one) is read into memory: such a line fails verification with its
    line number.

    Args:
        path: the log file.
        key: the HMAC key, if the log was written with one.
        require_closed: a log without a ``close`` record fails (detects a
            truncated tail of a log known to have finished).
        expect_head: the head kept elsewhere: ``"COUNT:HASH"`` as :attr:`AuditLog.head_token` gives it
            (the CLI prints it when it closes a log) or the bare hash of the last record; the log must
            end exactly there (detects truncation, and a chain rebuilt after a record was dropped or
            changed, which an unkeyed chain alone cannot show).

    Returns:
        An :class:`AuditReport`; ``ok`` is ``False`` for tampering.

    Raises:
        AuditFormatError: unreadable, not a regular file, empty, or not an ethimon audit log.

    Example:
        >>> verify_log("run.jsonl").summary()   # doctest: +SKIP
        'ok: 1204 records, chain intact, closed; head 3f9c0a1b2c3d4e5f'
    """
    path = os.fspath(path)
    expect_count = None
    if expect_head is not None:
        expect_count, expect_head = _parse_head(expect_head, path)
    with _open_regular(path) as fh:
        rep = _verify_stream(path, fh, key, require_closed, expect_head)
    if rep.ok and expect_count is not None and rep.records != expect_count:
        return AuditReport(False, rep.records, rep.closed, rep.torn_tail,
                           f"log has {rep.records} records, the head given says {expect_count} (records removed or "
                           f"added)", None, rep.head, rep.log_id, rep.kinds, rep.keyed)
    return rep


def _parse_head(token: str, path: str) -> tuple[int | None, str]:
    """``COUNT:HASH`` (what a closing CLI log prints) or a bare 64-hex ``HASH``."""
    count, sep, h = str(token).strip().rpartition(":")
    if not sep:
        count, h = "", token.strip()
    h = h.lower()
    if len(h) != 64 or any(c not in "0123456789abcdef" for c in h) or (sep and not count.isdigit()):
        raise AuditFormatError(f"{path}: head {str(token)[:80]!r} is not COUNT:HASH (a record count and a 64-digit "
                               "hex hash, as printed when the log was closed)")
    return (int(count) if sep else None), h


def _verify_stream(path: str, fh, key: bytes | None, require_closed: bool,
                   expect_head: str | None) -> AuditReport:
    """Stream the lines (constant memory): a line without its newline can only be the last."""
    prev = GENESIS
    count = 0
    closed = False
    torn = False
    log_id = None
    kinds: dict[str, int] = {}
    keyed = False

    def bad(msg: str, line: int | None) -> AuditReport:
        return AuditReport(False, count, closed, torn, msg, line, prev, log_id, kinds, keyed)

    lineno = 0
    for lineno, raw in _read_lines(fh):
        if raw is None:
            if count == 0:
                raise AuditFormatError(f"{path}: line 1 is longer than {MAX_RECORD_BYTES} bytes (the audit record "
                                       "size cap); not an ethimon audit log")
            return bad(f"line longer than {MAX_RECORD_BYTES} bytes (the audit record size cap): not a record "
                       "AuditLog writes (appended or corrupted)", lineno)
        if not raw.endswith(b"\n"):
            torn = True
            break
        try:
            rec = json.loads(raw)
        except (ValueError, UnicodeDecodeError):
            if count == 0:
                raise AuditFormatError(f"{path}: line 1 is not JSON; not an ethimon audit log") from None
            return bad("not a JSON record (edited or corrupted)", lineno)
        if not isinstance(rec, dict):
            if count == 0:
                raise AuditFormatError(f"{path}: line 1 is not a JSON object; not an ethimon audit log")
            return bad("not a JSON object", lineno)
        if count == 0:
            if rec.get("kind") != "open" or rec.get("format") != FORMAT:
                if "hash" in rec and "seq" in rec:
                    return bad("first record is not the 'open' record (head of the log removed)", lineno)
                raise AuditFormatError(f"{path}: no '{FORMAT}' header on line 1; not an ethimon audit log")
            log_id = rec.get("log_id")
            keyed = bool(rec.get("keyed"))
            if keyed and not key:
                raise AuditFormatError(f"{path}: the log is HMAC-keyed; give the key")
            if key and not keyed:
                return bad("the log is unkeyed, but a key was given: it was written without the key, or rebuilt "
                           "by someone who does not have it", lineno)
            kid = rec.get("key_id")
            if key and kid is not None and kid != key_id(key):
                raise AuditFormatError(f"{path}: the key given (id {key_id(key)}) is not the key this log was "
                                       f"written with (id {str(kid)[:16]})")
        if closed:
            return bad("record after the 'close' record", lineno)
        h = rec.get("hash")
        if not isinstance(h, str):
            return bad("record has no hash", lineno)
        if rec.get("seq") != count:
            return bad(f"seq is {rec.get('seq')!r}, expected {count} (records removed, added or reordered)",
                       lineno)
        if rec.get("prev") != prev:
            return bad("prev does not match the previous record's hash (records removed or reordered)", lineno)
        try:
            want = record_hash(rec, key)
        except (TypeError, ValueError):
            return bad("record cannot be re-serialised", lineno)
        if want != h:
            return bad(f"hash mismatch: record seq {count} was modified", lineno)
        body = canonical({k: v for k, v in rec.items() if k != "hash"})
        if raw != body[:-1] + b',"hash":"' + h.encode("ascii") + b'"}\n':
            return bad(f"record seq {count} is not in canonical form (edited: duplicate keys, spacing)", lineno)
        prev = h
        count += 1
        kind = str(rec.get("kind"))
        kinds[kind] = kinds.get(kind, 0) + 1
        if kind == "close":
            closed = True
    if lineno == 0:
        raise AuditFormatError(f"{path}: empty file, not an audit log")
    if count == 0 and torn:
        raise AuditFormatError(f"{path}: only a partial first line; not a complete audit log")
    if expect_head is not None and prev != expect_head:
        return bad(f"log ends at {prev[:16]}…, expected head {expect_head[:16]}… (truncated or rewritten)",
                   None)
    if require_closed and not closed:
        return bad("no 'close' record (log truncated, or the writer was killed)", None)
    return AuditReport(True, count, closed, torn, None, None, prev, log_id, kinds, keyed, expect_head is not None)


def read_log(path: str | os.PathLike, *, key: bytes | None = None) -> list[dict]:
    """The verified records of a log.

    Raises:
        AuditFormatError: not an audit log, or a line longer than
            :data:`~ethimon.audit.MAX_RECORD_BYTES` (named by its number) when the
            records are read.
        AuditTampered: the chain does not verify (a ``ValueError``, as before).
    """
    path = os.fspath(path)
    rep = verify_log(path, key=key)
    if not rep.ok:
        raise AuditTampered(f"{path}: {rep.summary()}")
    out = []
    with _open_regular(path) as fh:
        for lineno, raw in _read_lines(fh):
            if raw is None:  # the file changed after it was verified: never stop silently
                raise AuditFormatError(f"{path}: line {lineno} is longer than {MAX_RECORD_BYTES} bytes (the audit "
                                       "record size cap): not a record AuditLog writes (appended or corrupted)")
            if not raw.endswith(b"\n") or len(out) >= rep.records:
                break
            out.append(json.loads(raw))
    return out
