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

The control loop never blocks on the log: :meth:`AuditLog.append` serialises
the record (a snapshot of the fields, capped at ``max_record_bytes``) and puts
it into a bounded queue without waiting. The writer's *lag* -- records
accepted but not yet durable, their bytes, and the age of the oldest -- is
bounded by ``max_pending``, ``max_pending_bytes`` and ``max_lag_s``:
``append`` returns ``False`` when accepting the record would pass a bound (or
the queue is full, or the log is closed or broken), and :attr:`AuditLog.fault`
names the reason while the log is unusable (closed, writer dead or failed,
oldest pending record too old). The caller must treat both as faults
(``GovernedLoop`` checks :attr:`~AuditLog.fault` every cycle and overrides);
the writer appends a ``dropped`` record with the count of refused records, so
a drop is never silent.
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
from collections import deque
from collections.abc import Callable, Mapping
from typing import Any, NamedTuple

__all__ = ["AuditLag", "AuditLog", "FSYNC_POLICIES", "GENESIS", "KEY_ENV", "KEY_FILE_ENV", "MAX_RECORD_BYTES",
           "bounded", "canonical", "key_id", "key_from_env", "record_hash", "spec_hash", "jsonable"]

#: ``prev`` of the first record
GENESIS = "0" * 64
#: ``"always"``: fsync every batch (default); ``"interval"``: fsync at most every
#: ``fsync_interval_s`` (a kill loses nothing flushed, a power cut may lose the
#: last interval); ``"never"``: flush to the OS only (survives a process kill).
FSYNC_POLICIES = ("always", "interval", "never")
FORMAT = "ethimon-audit/1"
#: longest record line (newline included) that :class:`AuditLog` writes and
#: :func:`~ethimon.audit.verify_log` reads: 1 MiB
MAX_RECORD_BYTES = 1 << 20

_STOP = object()
_RESERVED = frozenset({"seq", "prev", "hash"})  # set by the writer
_FIXED = ("kind", "t")                          # never omitted from a record
_LINE_OVERHEAD = 200  # the "prev", "seq" and "hash" members, separators, braces and newline
_BATCH_BYTES = 4 << 20
#: environment variable naming the HMAC key file of the logs the CLI writes (``--audit``)
KEY_FILE_ENV = "ETHIMON_AUDIT_KEY_FILE"
#: environment variable naming *another* environment variable that holds the key itself
KEY_ENV = "ETHIMON_AUDIT_KEY_ENV"
_MAX_KEY_BYTES = 4096


def key_id(key: bytes) -> str:
    """A public name of an HMAC key (written into the ``open`` record; it reveals nothing of the key):
    the first 16 hex digits of ``HMAC-SHA256(key, "ethimon-audit key id")``."""
    return hmac.new(key, b"ethimon-audit key id", hashlib.sha256).hexdigest()[:16]


def key_from_env(environ: Mapping[str, str] | None = None) -> tuple[bytes | None, str]:
    """The HMAC key the operator names in the environment, and where it came from.

    ``ETHIMON_AUDIT_KEY_FILE=PATH``: the key is the file's content (a regular file, surrounding
    whitespace stripped); ``ETHIMON_AUDIT_KEY_ENV=NAME``: the key is the value of the variable
    ``NAME``. Neither set: ``(None, "")`` (an unkeyed log). The key is never written into a log.

    Raises:
        ValueError: a named file or variable is missing, unreadable, empty or longer than 4 KiB (one
            line naming it, never its content).
    """
    env = os.environ if environ is None else environ
    path, name = env.get(KEY_FILE_ENV), env.get(KEY_ENV)
    if path and name:
        raise ValueError(f"both {KEY_FILE_ENV} and {KEY_ENV} are set; name the audit key one way")
    if path:
        from .._files import open_regular
        try:
            with open_regular(path, "rb", what="audit key file") as fh:
                key = fh.read(_MAX_KEY_BYTES + 1).strip()
        except OSError as exc:
            raise ValueError(f"{path}: cannot read the audit key ({KEY_FILE_ENV}): {exc.strerror or exc}") from None
        except Exception as exc:  # noqa: BLE001 - a located SpecError from open_regular (a FIFO, a folder)
            raise ValueError(f"{KEY_FILE_ENV}: {exc}") from None
        where = f"key file {path} ({KEY_FILE_ENV})"
    elif name:
        raw = env.get(name)
        if raw is None:
            raise ValueError(f"{KEY_ENV} names the variable {name}, which is not set")
        key = raw.strip().encode("utf-8", "surrogateescape")
        where = f"environment variable {name} ({KEY_ENV})"
    else:
        return None, ""
    if not key:
        raise ValueError(f"the audit key from the {where} is empty")
    if len(key) > _MAX_KEY_BYTES:
        raise ValueError(f"the audit key from the {where} is longer than {_MAX_KEY_BYTES} bytes")
    return key, where


def bounded(value: Any, limit: int = 256) -> Any:
    """A field from an untrusted sender, bounded for the audit log: a string longer than ``limit``
    characters becomes ``{"head": its first limit characters, "chars": n, "bytes": n, "sha256": hex}``
    (the digest of its UTF-8 bytes, so a copy kept elsewhere can be matched); anything else as is."""
    if isinstance(value, str) and len(value) > limit:
        data = value.encode("utf-8", "surrogatepass")
        return {"head": value[:limit], "chars": len(value), "bytes": len(data),
                "sha256": hashlib.sha256(data).hexdigest()}
    return value


class AuditLag(NamedTuple):
    """How far the writer is behind (see :meth:`AuditLog.lag`).

    Attributes:
        records: records accepted by :meth:`AuditLog.append` and not yet durable.
        bytes: their size as written.
        age_s: age of the oldest of them (``0.0`` when none).
    """

    records: int
    bytes: int
    age_s: float


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


_ENC = json.JSONEncoder(sort_keys=True, separators=(",", ":"), allow_nan=False, ensure_ascii=True)


def _split(rec: Mapping[str, Any]) -> tuple[bytes, bytes, bytes]:
    """Canonical JSON members of a record without ``seq``/``prev``/``hash``, in three runs:
    the keys sorting before ``"prev"``, between ``"prev"`` and ``"seq"``, and after ``"seq"``.

    The writer joins them with the ``prev`` and ``seq`` members in between, which is
    byte for byte :func:`canonical` of the whole record (sorted keys, compact).
    Raises ``ValueError``/``TypeError``/``RecursionError`` for what JSON cannot hold.
    """
    lo: dict = {}
    mid: dict = {}
    hi: dict = {}
    for k, v in rec.items():
        (lo if k < "prev" else mid if k < "seq" else hi)[k] = v
    return (_ENC.encode(lo)[1:-1].encode("ascii"), _ENC.encode(mid)[1:-1].encode("ascii"),
            _ENC.encode(hi)[1:-1].encode("ascii"))


def _size(parts: tuple[bytes, bytes, bytes]) -> int:
    return len(parts[0]) + len(parts[1]) + len(parts[2]) + _LINE_OVERHEAD


def _omitted(nbytes: int) -> dict:
    return {"omitted": "field too large for one audit record", "bytes": nbytes}


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
        max_pending: most records accepted but not yet durable (default 10,000).
        max_pending_bytes: most bytes accepted but not yet durable (default 32 MiB).
        max_lag_s: oldest age of a record accepted but not yet durable (default
            1 s); past it, :attr:`fault` is set and :meth:`append` refuses.
        max_record_bytes: cap of one record line (default and maximum
            :data:`MAX_RECORD_BYTES`, 1 MiB). A larger record keeps its small
            fields; its largest fields are replaced by ``{"omitted": ..., "bytes": n}``
            and listed in ``"truncated"`` (counted in :attr:`oversize`).
        clock: monotonic time source for the lag age (inject one in tests).
        on_close: called with the log after a clean :meth:`close` (the CLI prints the head there).

    Raises:
        FileExistsError: ``path`` exists.
        ValueError: bad ``fsync``/``queue_size`` or bound.

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
                 meta: Mapping[str, Any] | None = None, max_pending: int = 10_000,
                 max_pending_bytes: int = 32 << 20, max_lag_s: float = 1.0,
                 max_record_bytes: int = MAX_RECORD_BYTES, clock: Callable[[], float] = time.monotonic,
                 on_close: Callable[["AuditLog"], None] | None = None) -> None:
        if fsync not in FSYNC_POLICIES:
            raise ValueError(f"fsync={fsync!r}; expected one of {', '.join(FSYNC_POLICIES)}")
        if not isinstance(queue_size, int) or queue_size < 1:
            raise ValueError(f"queue_size={queue_size!r}; expected an int >= 1")
        if not isinstance(max_pending, int) or max_pending < 1:
            raise ValueError(f"max_pending={max_pending!r}; expected an int >= 1")
        if not isinstance(max_record_bytes, int) or not 1024 <= max_record_bytes <= MAX_RECORD_BYTES:
            raise ValueError(f"max_record_bytes={max_record_bytes!r}; expected an int in [1024, {MAX_RECORD_BYTES}]")
        if not isinstance(max_pending_bytes, int) or max_pending_bytes < max_record_bytes:
            raise ValueError(f"max_pending_bytes={max_pending_bytes!r}; expected an int >= max_record_bytes "
                             f"({max_record_bytes})")
        if not (isinstance(max_lag_s, (int, float)) and 0 < max_lag_s < math.inf):
            raise ValueError(f"max_lag_s={max_lag_s!r}; expected a positive number of seconds")
        self.max_pending = max_pending
        self.max_pending_bytes = max_pending_bytes
        self.max_lag_s = float(max_lag_s)
        self.max_record_bytes = max_record_bytes
        self._clock = clock
        self.path = os.fspath(path)
        self.fsync = fsync
        self.fsync_interval_s = float(fsync_interval_s)
        self.log_id = uuid.uuid4().hex
        if key is not None and not (isinstance(key, bytes) and key):
            raise ValueError("key must be non-empty bytes (or None for an unkeyed log)")
        self._key = key
        self._on_close = on_close
        self._q: queue.Queue = queue.Queue(maxsize=queue_size)
        self._fh = open(self.path, "xb")  # noqa: SIM115 - owned by the writer thread
        self._seq = 0            # next seq to assign (writer thread only)
        self._prev = GENESIS     # hash of the last written record (writer thread only)
        self._durable_seq = -1
        self._dropped_pending = 0
        self._dropped_total = 0
        self._lock = threading.Lock()  # guards the lag counters, the drop counters and _closed
        self._pending_n = 0
        self._pending_bytes = 0
        self._times: deque = deque()   # (clock time, bytes) of each record not yet durable, oldest first
        self.oversize = 0
        self._closed = False
        self._error: BaseException | None = None
        self._last_fsync = 0.0
        fields = {**jsonable(dict(meta or {})), "format": FORMAT, "log_id": self.log_id, "pid": os.getpid(),
                  "fsync": fsync, "keyed": bool(key)}
        if key:
            fields["key_id"] = key_id(key)
        self._write([self._encode("open", time.time(), fields)[0]])
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

        The fields are serialised now (:func:`jsonable`, then canonical JSON), so
        the record is a snapshot: changing a passed dict afterwards changes
        nothing. A record longer than ``max_record_bytes`` keeps its small
        fields and loses its largest ones (see the class doc).

        Args:
            kind: record kind (``decision``, ``fault``, ``reload``, ...).
            fields: JSON-ready-ish fields (``seq``, ``prev`` and ``hash`` are the writer's and ignored).

        Returns:
            ``True`` if queued; ``False`` if accepting it would pass
            ``max_pending`` or ``max_pending_bytes``, the oldest pending record
            is older than ``max_lag_s``, the queue is full, or the log is closed
            or broken. A ``False`` is a fault for the caller; the writer records
            the number of refused records in a ``dropped`` record.
        """
        if self._closed or self._error is not None or not self._thread.is_alive():
            return False
        t = time.time()
        try:
            parts, size, cut = self._encode(kind, t, fields)
        except Exception as exc:  # noqa: BLE001 - recorded, never raised into the loop
            parts, size, cut = self._encode(kind, t, {"unserialisable": f"{type(exc).__name__}: {exc}"[:500]})
        now = self._clock()
        with self._lock:
            if self._closed:
                return False
            ok = (self._pending_n < self.max_pending and self._pending_bytes + size <= self.max_pending_bytes
                  and not (self._times and now - self._times[0][0] > self.max_lag_s))
            if ok:
                try:
                    self._q.put_nowait((parts, size))
                except queue.Full:
                    ok = False
            if not ok:
                self._dropped_pending += 1
                self._dropped_total += 1
                return False
            self._pending_n += 1
            self._pending_bytes += size
            self._times.append((now, size))
            if cut:
                self.oversize += 1
        return True

    def lag(self) -> AuditLag:
        """Records and bytes accepted but not yet durable, and the age of the oldest."""
        with self._lock:
            n, b = self._pending_n, self._pending_bytes
            oldest = self._times[0][0] if self._times else None
        return AuditLag(n, b, 0.0 if oldest is None else max(0.0, self._clock() - oldest))

    @property
    def fault(self) -> str | None:
        """Why the log cannot be trusted to record the next decision now, or ``None``.

        Set while the log is closed, its writer failed or died, or the writer is
        behind past a bound (oldest record not yet durable older than
        ``max_lag_s``). A caller that must not act unrecorded treats it as a
        fault every cycle (``GovernedLoop`` does).
        """
        err = self._error
        if err is not None:
            return f"audit writer failed: {type(err).__name__}: {err}"[:300]
        if self._closed:
            return "audit log is closed: decisions are no longer recorded"
        if not self._thread.is_alive():
            return "audit writer thread died: decisions are no longer recorded"
        times = self._times  # fast path (every control cycle): no lock, one clock read
        if not times:
            return None
        try:
            oldest = times[0][0]
        except IndexError:  # emptied by the writer meanwhile
            return None
        if self._clock() - oldest <= self.max_lag_s:
            return None
        lag = self.lag()
        if lag.age_s > self.max_lag_s:
            return (f"audit log is behind: oldest record not yet durable is {lag.age_s:.3f} s old "
                    f"(max_lag_s {self.max_lag_s:g}); {lag.records} records, {lag.bytes} bytes pending")
        return None

    def _encode(self, kind: str, t: float, fields: Mapping[str, Any]) -> tuple[tuple, int, bool]:
        """The record's canonical member runs (see :func:`_split`), its line size, and whether
        fields were cut to fit ``max_record_bytes``."""
        # jsonable() always: it also makes every key a str (the encoder would sort int keys
        # numerically, not as the text a verifier re-sorts)
        rec = jsonable({k: v for k, v in fields.items() if k not in _RESERVED})
        rec["kind"] = jsonable(kind)
        rec["t"] = t
        parts = _split(rec)
        size = _size(parts)
        if size <= self.max_record_bytes:
            return parts, size, False
        # too large: replace the largest fields (never kind/t) by a marker until it fits
        lengths = {k: len(_ENC.encode({k: v})) for k, v in rec.items() if k not in _FIXED}
        cut: list[str] = []
        for k in sorted(lengths, key=lengths.__getitem__, reverse=True):
            rec[k] = _omitted(lengths[k])
            cut.append(k)
            rec["truncated"] = sorted(cut)
            parts = _split(rec)
            size = _size(parts)
            if size <= self.max_record_bytes:
                return parts, size, True
        # thousands of small fields: keep only kind and t
        rec = {"kind": rec["kind"], "t": t, "omitted_fields": len(lengths)}
        parts = _split(rec)
        return parts, _size(parts), True

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

    @property
    def records(self) -> int:
        """Records written so far (``open`` and ``close`` included)."""
        return self._seq

    @property
    def head_token(self) -> str:
        """``"COUNT:HASH"`` of the last record written: what ``ethimon audit verify --head`` checks (keep it
        outside the log; a chain rebuilt after a record was dropped or changed cannot end there)."""
        return f"{self._seq}:{self._prev}"

    def head_summary(self) -> str:
        """Two lines for the person who runs the writer (the CLI prints them when it closes a log): the
        head, and the command that checks the log against it."""
        how = "keyed (HMAC-SHA256)" if self.keyed else "unkeyed: keep this head elsewhere, only it shows a rebuilt chain"
        return (f"audit: {self.path}: {self.records} records, {how}; head {self.head_token}\n"
                f"audit: check it with: ethimon audit verify {self.path} --require-closed --head {self.head_token}")

    @property
    def keyed(self) -> bool:
        """Whether the chain is HMAC-keyed."""
        return bool(self._key)

    def pending(self) -> int:
        """Records queued and not yet taken by the writer (see :meth:`lag` for those not yet durable)."""
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
        with self._lock:
            if self._closed:
                return
            self._closed = True
        atexit.unregister(self._at_exit)
        if self._thread.is_alive():
            try:  # waits only while the queue is full, which a live writer is draining
                self._q.put(_STOP, timeout=timeout)
            except queue.Full:
                pass
            self._thread.join(timeout)
        if self._thread.is_alive():
            lag = self.lag()
            raise TimeoutError(f"audit writer did not finish within {timeout} s ({lag.records} records, "
                               f"{lag.bytes} bytes not yet durable)")
        if self._error is not None:
            raise OSError(f"audit writer failed: {self._error}") from self._error
        if self._on_close is not None:
            self._on_close(self)

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
                n_user = 0
                nbytes = 0
                while True:
                    if item is _STOP:
                        stop = True
                    elif isinstance(item, threading.Event):
                        waiters.append(item)
                    else:
                        parts, size = item
                        batch.append(parts)
                        n_user += 1
                        nbytes += size
                    if len(batch) >= 4096 or nbytes >= _BATCH_BYTES:
                        break
                    try:
                        item = q.get_nowait()
                    except queue.Empty:
                        break
                with self._lock:
                    dropped, self._dropped_pending = self._dropped_pending, 0
                if dropped:
                    batch.append(self._encode("dropped", time.time(), {
                        "count": dropped, "reason": "audit queue full or writer behind: records refused "
                                                    "(the loop overrode)"})[0])
                if stop:
                    batch.append(self._encode("close", time.time(), {"dropped_total": self._dropped_total})[0])
                self._write(batch, force_sync=stop or bool(waiters))
                if n_user:
                    with self._lock:
                        for _ in range(n_user):
                            _, size = self._times.popleft()
                            self._pending_bytes -= size
                        self._pending_n -= n_user
                for w in waiters:
                    w.set()
        except BaseException as exc:  # noqa: BLE001 - surfaced through .error / append() -> False
            self._error = exc
        finally:
            try:
                self._fh.close()
            except OSError:  # pragma: no cover
                pass

    def _write(self, records: list[tuple[bytes, bytes, bytes]], force_sync: bool = False) -> None:
        """Chain, hash and write records given as member runs (see :func:`_split`)."""
        if not records:
            return
        out = []
        prev, seq, key = self._prev, self._seq, self._key
        for lo, mid, hi in records:
            # canonical JSON of the record: its members and seq/prev in sorted key order
            members = [m for m in (lo, b'"prev":"' + prev.encode("ascii") + b'"', mid,
                                   b'"seq":' + str(seq).encode("ascii"), hi) if m]
            body = b"{" + b",".join(members) + b"}"
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
