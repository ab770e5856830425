"""Hash-chained JSONL audit log written by a background thread.

Record layout (one JSON object per line, keys sorted, no spaces)::

    {"seq": 0, "kind": "open", "t": 1764064000.1, ..., "prev": "000…0", "hash": "ab12…"}

``hash = sha256(canonical JSON of the record without "hash")`` (HMAC-SHA256
when a key is given), and ``prev`` is the previous record's hash, so editing,
removing or reordering any record breaks the chain (see
:func:`~ethimon.audit.verify_log`). The first record is ``open``; a clean
:meth:`AuditLog.close` appends ``close``.

Durability: the writer thread drains the queue in batches, writes each batch,
flushes it to the OS and (by default) ``fsync``\\ s it, and only then advances
:attr:`AuditLog.durable_seq`. A record is *reported written* once its
sequence number is ``<= durable_seq`` (or :meth:`AuditLog.flush` returned after
it was appended); a process killed after that point does not lose it.

The control loop never blocks on the log: :meth:`AuditLog.append` is a
non-blocking ``put`` into a bounded queue and returns ``False`` when the queue
is full. The caller must treat that as a fault (``GovernedLoop`` overrides);
the writer then appends a ``dropped`` record with the count, so a drop is
never silent.
"""

from __future__ import annotations

import atexit
import hashlib
import hmac
import json
import math
import os
import queue
import threading
import time
import uuid
from collections.abc import Mapping
from typing import Any

__all__ = ["AuditLog", "FSYNC_POLICIES", "GENESIS", "canonical", "record_hash", "spec_hash", "jsonable"]

#: ``prev`` of the first record
GENESIS = "0" * 64
#: ``"always"``: fsync every batch (default); ``"interval"``: fsync at most every
#: ``fsync_interval_s`` (a kill loses nothing flushed, a power cut may lose the
#: last interval); ``"never"``: flush to the OS only (survives a process kill).
FSYNC_POLICIES = ("always", "interval", "never")
FORMAT = "ethimon-audit/1"

_STOP = object()


def canonical(record: Mapping[str, Any]) -> bytes:
    """The bytes that are hashed (and written): sorted keys, compact, no NaN."""
    return json.dumps(record, sort_keys=True, separators=(",", ":"), allow_nan=False,
                      ensure_ascii=True).encode("ascii")


def record_hash(record: Mapping[str, Any], key: bytes | None = None) -> str:
    """Hash of a record without its ``hash`` field (HMAC-SHA256 with ``key``)."""
    body = canonical({k: v for k, v in record.items() if k != "hash"})
    if key:
        return hmac.new(key, body, hashlib.sha256).hexdigest()
    return hashlib.sha256(body).hexdigest()


def spec_hash(spec: Any) -> str:
    """sha256 of a spec's canonical JSON (stable across file formatting and comments)."""
    try:
        data = spec.model_dump(mode="json")
    except AttributeError:
        data = spec
    return hashlib.sha256(canonical(jsonable(data))).hexdigest()


def jsonable(v: Any, _depth: int = 0) -> Any:
    """A JSON-safe copy: non-finite floats become ``"nan"``/``"inf"``/``"-inf"``,
    unknown objects their ``repr`` (truncated), mappings/sequences recursively."""
    if v is None or v is True or v is False or isinstance(v, str):
        return v
    if isinstance(v, int):
        return int(v)
    if isinstance(v, float):
        if math.isfinite(v):
            return v
        return "nan" if v != v else ("inf" if v > 0 else "-inf")
    if _depth > 8:
        return "<too deep>"
    if isinstance(v, Mapping):
        return {str(k): jsonable(x, _depth + 1) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [jsonable(x, _depth + 1) for x in v]
    try:  # numpy scalars and the like
        import numbers
        if isinstance(v, numbers.Integral):
            return int(v)
        if isinstance(v, numbers.Real):
            return jsonable(float(v))
    except Exception:  # pragma: no cover
        pass
    text = repr(v)
    return {"repr": text[:200]}


class AuditLog:
    """Append-only, hash-chained JSONL audit log with a background writer.

    Args:
        path: the log file; it must not exist yet (a log is never appended to
            by a second writer, which would fork the chain).
        queue_size: bound of the in-memory queue (records waiting to be written).
        fsync: one of :data:`FSYNC_POLICIES`.
        fsync_interval_s: for ``fsync="interval"``.
        key: optional secret for HMAC-SHA256 chaining (then a forger without
            the key cannot rebuild the chain).
        meta: extra JSON-ready fields for the ``open`` record (spec hash, model id, host...).

    Raises:
        FileExistsError: ``path`` exists.
        ValueError: bad ``fsync``/``queue_size``.

    Example:
        >>> import tempfile, os
        >>> from ethimon.audit import AuditLog, verify_log
        >>> path = os.path.join(tempfile.mkdtemp(), "run.jsonl")
        >>> with AuditLog(path, meta={"spec": "demo"}) as log:
        ...     log.append("fault", reason="estimator hung")
        True
        >>> verify_log(path).ok
        True
    """

    def __init__(self, path: str | os.PathLike, *, queue_size: int = 65536, fsync: str = "always",
                 fsync_interval_s: float = 0.05, key: bytes | None = None,
                 meta: Mapping[str, Any] | None = None) -> None:
        if fsync not in FSYNC_POLICIES:
            raise ValueError(f"fsync={fsync!r}; expected one of {', '.join(FSYNC_POLICIES)}")
        if not isinstance(queue_size, int) or queue_size < 1:
            raise ValueError(f"queue_size={queue_size!r}; expected an int >= 1")
        self.path = os.fspath(path)
        self.fsync = fsync
        self.fsync_interval_s = float(fsync_interval_s)
        self.log_id = uuid.uuid4().hex
        self._key = key
        self._q: queue.Queue = queue.Queue(maxsize=queue_size)
        self._fh = open(self.path, "xb")  # noqa: SIM115 - owned by the writer thread
        self._seq = 0            # next seq to assign (writer thread only)
        self._prev = GENESIS     # hash of the last written record (writer thread only)
        self._durable_seq = -1
        self._dropped_pending = 0
        self._dropped_total = 0
        self._drop_lock = threading.Lock()
        self._closed = False
        self._error: BaseException | None = None
        self._last_fsync = 0.0
        self._write([{"kind": "open", "format": FORMAT, "log_id": self.log_id, "t": time.time(),
                      "pid": os.getpid(), "fsync": fsync, "keyed": bool(key), **jsonable(dict(meta or {}))}])
        self._thread = threading.Thread(target=self._run, name="ethimon-audit-writer", daemon=True)
        self._thread.start()
        atexit.register(self._at_exit)

    def _at_exit(self) -> None:
        """A log left open at interpreter exit still gets its queue written and closed."""
        try:
            self.close(timeout=5.0)
        except Exception:  # noqa: BLE001 - never raise at exit
            pass

    # ------------------------------------------------------------------ caller side
    def append(self, kind: str, **fields: Any) -> bool:
        """Queue one record without blocking.

        Args:
            kind: record kind (``decision``, ``fault``, ``reload``, ...).
            fields: JSON-ready-ish fields (sanitised by the writer with :func:`jsonable`).

        Returns:
            ``True`` if queued; ``False`` if the queue is full or the log is
            closed or broken. A ``False`` is a fault for the caller; the writer
            records the number of dropped records in a ``dropped`` record.
        """
        if self._closed or self._error is not None:
            return False
        try:
            self._q.put_nowait((kind, time.time(), fields))
        except queue.Full:
            with self._drop_lock:
                self._dropped_pending += 1
                self._dropped_total += 1
            return False
        return True

    @property
    def durable_seq(self) -> int:
        """Highest ``seq`` that is written, flushed and synced per the policy (-1: none)."""
        return self._durable_seq

    @property
    def dropped(self) -> int:
        """Records refused by :meth:`append` because the queue was full (total)."""
        return self._dropped_total

    @property
    def error(self) -> BaseException | None:
        """The I/O error that stopped the writer, if any (then ``append`` returns ``False``)."""
        return self._error

    @property
    def head(self) -> str:
        """Hash of the last record written (an anchor to keep elsewhere)."""
        return self._prev

    def pending(self) -> int:
        """Records queued but not yet written."""
        return self._q.qsize()

    def flush(self, timeout: float | None = 5.0) -> int:
        """Block until every record appended so far is durable; return :attr:`durable_seq`.

        Raises:
            TimeoutError: not durable within ``timeout`` seconds.
            OSError: the writer failed.
        """
        if self._error is not None:
            raise OSError(f"audit writer failed: {self._error}") from self._error
        if self._closed and not self._thread.is_alive():
            return self._durable_seq
        done = threading.Event()
        try:
            self._q.put(done, timeout=timeout)
        except queue.Full:
            raise TimeoutError(f"audit log not flushed within {timeout} s (queue full)") from None
        deadline = None if timeout is None else time.monotonic() + timeout
        while not done.wait(0.05):
            if self._error is not None:
                raise OSError(f"audit writer failed: {self._error}") from self._error
            if not self._thread.is_alive():
                break
            if deadline is not None and time.monotonic() > deadline:
                raise TimeoutError(f"audit log not flushed within {timeout} s ({self.pending()} pending)")
        return self._durable_seq

    def close(self, timeout: float | None = 10.0) -> None:
        """Write everything queued, append a ``close`` record, sync and close the file."""
        if self._closed:
            return
        self._closed = True
        atexit.unregister(self._at_exit)
        self._q.put(_STOP)  # blocks only if full, which the writer is draining
        self._thread.join(timeout)
        if self._thread.is_alive():  # pragma: no cover
            raise TimeoutError("audit writer did not finish")
        if self._error is not None:
            raise OSError(f"audit writer failed: {self._error}") from self._error

    def __enter__(self) -> "AuditLog":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __repr__(self) -> str:
        return f"AuditLog({self.path!r}, durable_seq={self._durable_seq}, pending={self.pending()})"

    # ------------------------------------------------------------------ writer side
    def _run(self) -> None:
        q = self._q
        stop = False
        try:
            while not stop:
                item = q.get()
                batch = []
                waiters = []
                while True:
                    if item is _STOP:
                        stop = True
                    elif isinstance(item, threading.Event):
                        waiters.append(item)
                    else:
                        kind, t, fields = item
                        batch.append({"kind": kind, "t": t, **jsonable(fields)})
                    if len(batch) >= 4096:
                        break
                    try:
                        item = q.get_nowait()
                    except queue.Empty:
                        break
                with self._drop_lock:
                    dropped, self._dropped_pending = self._dropped_pending, 0
                if dropped:
                    batch.append({"kind": "dropped", "t": time.time(), "count": dropped,
                                  "reason": "audit queue full: records refused (the loop overrode)"})
                if stop:
                    batch.append({"kind": "close", "t": time.time(), "dropped_total": self._dropped_total})
                self._write(batch, force_sync=stop or bool(waiters))
                for w in waiters:
                    w.set()
        except BaseException as exc:  # noqa: BLE001 - surfaced through .error / append() -> False
            self._error = exc
        finally:
            try:
                self._fh.close()
            except OSError:  # pragma: no cover
                pass

    def _write(self, records: list[dict], force_sync: bool = False) -> None:
        if not records:
            return
        out = []
        prev, seq, key = self._prev, self._seq, self._key
        for rec in records:
            rec["seq"] = seq
            rec["prev"] = prev
            try:
                body = canonical(rec)
            except (TypeError, ValueError):  # pragma: no cover - jsonable() makes this unreachable
                rec = {"kind": rec.get("kind"), "seq": seq, "prev": prev, "t": rec.get("t"),
                       "unserialisable": repr(rec)[:500]}
                body = canonical(rec)
            h = hmac.new(key, body, hashlib.sha256).hexdigest() if key else hashlib.sha256(body).hexdigest()
            out.append(body[:-1] + b',"hash":"' + h.encode() + b'"}\n')
            prev = h
            seq += 1
        fh = self._fh
        fh.write(b"".join(out))
        fh.flush()
        now = time.monotonic()
        if self.fsync != "never" and force_sync or self.fsync == "always" or (
                self.fsync == "interval" and now - self._last_fsync >= self.fsync_interval_s):
            os.fsync(fh.fileno())
            self._last_fsync = now
        self._prev, self._seq = prev, seq
        self._durable_seq = seq - 1
