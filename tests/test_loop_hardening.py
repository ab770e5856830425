"""Hardening of the governed loop and the audit trail (issue 11).

Hangs and unbounded memory: ``audit verify`` on a FIFO / ``/dev/stdin`` / an
over-long line; a writer that falls behind (records, bytes, age); a log closed
or a writer dead mid-run; an estimator that holds the GIL. And reloads that
weaken monitoring.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import threading
import time
import tracemalloc
from pathlib import Path

import pytest

import ethimon
from ethimon.audit import AuditFormatError, AuditLog, read_log, verify_log
from ethimon.audit import _log
from ethimon.audit._log import GENESIS, canonical, record_hash
from ethimon.runtime import AsyncRiskSource, GovernedLoop, ProcessEstimator, Watchdog

from _estimators import FakeClock, ScriptedEstimator, wait_for

ROOT = Path(__file__).resolve().parents[1]
MAX_RECORD_BYTES = getattr(_log, "MAX_RECORD_BYTES", 1 << 20)  # the documented cap: 1 MiB

CELL = """
ethimon: 1
name: cell
signals:
  human_distance: {unit: m, range: [0, 10]}
risk: {threshold: 0.5, max_age_s: 0.2, release: {mode: auto, hysteresis: 0.05, hold_cycles: 2}}
on_fault: safe_pose
obligations:
  - {id: keep_away, require: "human_distance >= 0.5", response: stop_2}
"""
SAFE = {"human_distance": 2.0}


def _loop(clock=None, spec=CELL, **kw):
    clock = clock or FakeClock()
    if "risk" not in kw:
        src = AsyncRiskSource(ScriptedEstimator(), text="wipe the table", clock=clock, start=False)
        src.poll_once()
        kw["risk"] = src
    return GovernedLoop(ethimon.Monitor(ethimon.load_spec_text(spec)), period_s=0.001, clock=clock, **kw), clock


def _gate_writer(log):
    """Hold the writer thread inside its next write until the returned event is set."""
    gate = threading.Event()
    real = log._write

    def slow(records, force_sync=False):
        gate.wait(10.0)
        real(records, force_sync)

    log._write = slow
    return gate


# ================================================================ audit verify: hangs and memory
def _in_thread(fn, timeout=5.0):
    out: dict = {}

    def work():
        try:
            out["value"] = fn()
        except BaseException as exc:  # noqa: BLE001
            out["exc"] = exc

    t = threading.Thread(target=work, daemon=True)
    t.start()
    t.join(timeout)
    return t.is_alive(), out


def test_verify_refuses_a_fifo_without_blocking(tmp_path):
    fifo = tmp_path / "log.fifo"
    os.mkfifo(fifo)
    hung, out = _in_thread(lambda: verify_log(fifo))
    if hung:  # unblock the stuck open() so the thread can end, then fail
        fd = os.open(fifo, os.O_WRONLY | os.O_NONBLOCK)
        os.close(fd)
    assert not hung, "verify_log blocked on a FIFO"
    assert isinstance(out.get("exc"), AuditFormatError) and "not a regular file" in str(out["exc"])


def test_cli_verify_refuses_dev_stdin_pipe_without_blocking():
    # stdin is a pipe nobody writes to: reading it would block forever
    proc = subprocess.Popen([sys.executable, "-m", "ethimon.cli._audit_cmds", "audit", "verify", "/dev/stdin"],
                            stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            cwd=ROOT)
    try:
        out, err = proc.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()
        pytest.fail("audit verify /dev/stdin blocked")
    assert proc.returncode == 2 and "regular file" in err and "Traceback" not in err


def _record(seq: int, prev: str, **fields) -> tuple[bytes, str]:
    rec = {"kind": fields.pop("kind", "decision"), "t": 1.0, "seq": seq, "prev": prev, **fields}
    h = record_hash(rec)
    body = canonical(rec)
    return body[:-1] + b',"hash":"' + h.encode() + b'"}\n', h


def _log_with_line3(payload: str) -> bytes:
    l0, h0 = _record(0, GENESIS, kind="open", format="ethimon-audit/1", log_id="x")
    l1, h1 = _record(1, h0, cycle=0)
    l2, _ = _record(2, h1, cycle=1, inputs={"blob": payload})
    return l0 + l1 + l2


def test_verify_refuses_an_over_long_record_naming_its_line(tmp_path):
    p = tmp_path / "big.jsonl"
    p.write_bytes(_log_with_line3("x" * (MAX_RECORD_BYTES + 10)))  # a correctly hashed, but huge, record
    rep = verify_log(p)
    assert not rep.ok and rep.line == 3 and rep.records == 2
    assert "longer than" in rep.error and str(MAX_RECORD_BYTES) in rep.error
    # just under the cap still verifies
    p2 = tmp_path / "ok.jsonl"
    p2.write_bytes(_log_with_line3("x" * (MAX_RECORD_BYTES - 400)))
    assert verify_log(p2).ok


def test_verify_memory_is_bounded_on_a_huge_line(tmp_path):
    p = tmp_path / "huge.jsonl"
    head = _log_with_line3("y")
    with open(p, "wb") as fh:
        fh.write(head)
        chunk = b"z" * (1 << 20)
        for _ in range(24):  # a 24 MiB line without a newline
            fh.write(chunk)
    tracemalloc.start()
    try:
        rep = verify_log(p)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert not rep.ok and rep.line == 4 and "longer than" in rep.error
    assert peak < 8 * MAX_RECORD_BYTES, f"peak {peak / 2**20:.1f} MiB"


def test_over_long_first_line_is_not_an_audit_log(tmp_path):
    p = tmp_path / "blob.jsonl"
    p.write_bytes(b"x" * (MAX_RECORD_BYTES + 5) + b"\n")
    with pytest.raises(AuditFormatError, match="line 1 is longer than"):
        verify_log(p)


# ================================================================ audit writer: lag bounds
def test_close_does_not_hang_when_the_writer_died_with_a_full_queue(tmp_path):
    log = AuditLog(tmp_path / "z.jsonl", queue_size=2)
    gate = threading.Event()

    def failing(records, force_sync=False):
        gate.wait(10.0)
        raise OSError(5, "Input/output error")

    log._write = failing
    assert log.append("decision", cycle=0)
    assert wait_for(lambda: log.pending() == 0)
    assert log.append("decision", cycle=1) and log.append("decision", cycle=2)  # the queue is full
    gate.set()
    assert wait_for(lambda: not log._thread.is_alive())
    hung, out = _in_thread(lambda: log.close(timeout=1.0))
    assert not hung, "close() blocked on the full queue of a dead writer"
    assert isinstance(out.get("exc"), OSError) and "Input/output error" in str(out["exc"])

def test_append_refuses_past_the_pending_records_bound(tmp_path):
    log = AuditLog(tmp_path / "a.jsonl", max_pending=5)
    gate = _gate_writer(log)
    try:
        assert log.append("decision", cycle=-1)
        assert wait_for(lambda: log.pending() == 0)  # the writer holds record -1 inside its write
        results = [log.append("decision", cycle=i) for i in range(10)]
        assert results.count(True) == 4 and results.count(False) == 6  # -1 plus 4 = 5 pending
        lag = log.lag()
        assert lag.records == 5 and lag.bytes > 0
        assert log.fault is None  # at the bound, not past it; the refusals are the fault
    finally:
        gate.set()
    log.close()
    recs = read_log(tmp_path / "a.jsonl")
    assert sum(r["count"] for r in recs if r["kind"] == "dropped") == 6 == log.dropped


def test_append_refuses_past_the_pending_bytes_bound(tmp_path):
    log = AuditLog(tmp_path / "b.jsonl", max_pending_bytes=20_000, max_record_bytes=4096)
    gate = _gate_writer(log)
    try:
        results = [log.append("decision", inputs={"blob": "x" * 3000}) for _ in range(12)]
        assert 4 <= results.count(True) <= 6 and not results[-1]
        assert log.lag().bytes <= 20_000
    finally:
        gate.set()
    log.close()
    assert verify_log(tmp_path / "b.jsonl", require_closed=True).ok


def test_old_pending_record_is_a_fault_and_refuses_appends(tmp_path):
    clock = FakeClock()
    log = AuditLog(tmp_path / "c.jsonl", max_lag_s=0.5, clock=clock)
    gate = _gate_writer(log)
    try:
        assert log.append("decision", cycle=0)
        clock.advance(0.4)
        assert log.fault is None and log.lag().age_s == pytest.approx(0.4)
        clock.advance(0.2)
        assert "0.600 s" in log.fault and "max_lag_s 0.5" in log.fault
        assert not log.append("decision", cycle=1)
    finally:
        gate.set()
    assert wait_for(lambda: log.lag().records == 0)
    assert log.fault is None and log.append("decision", cycle=2)
    log.close()


def test_a_huge_record_is_capped_not_queued_whole(tmp_path):
    log = AuditLog(tmp_path / "e.jsonl")
    big = {f"s{i}": "v" * 1000 for i in range(3000)}  # ~3 MB of signals
    assert log.append("decision", override=True, faults=["x"], inputs=big)
    assert log.lag().bytes <= MAX_RECORD_BYTES
    log.close()
    assert verify_log(tmp_path / "e.jsonl", require_closed=True).ok
    rec = [r for r in read_log(tmp_path / "e.jsonl") if r["kind"] == "decision"][0]
    assert rec["override"] is True and rec["faults"] == ["x"]  # the decision itself is kept
    assert rec["inputs"]["omitted"].startswith("field too large") and rec["truncated"] == ["inputs"]
    assert log.oversize == 1
    line = [ln for ln in (tmp_path / "e.jsonl").read_bytes().splitlines() if b'"decision"' in ln][0]
    assert len(line) < MAX_RECORD_BYTES


def test_append_takes_a_snapshot_of_its_fields(tmp_path):
    log = AuditLog(tmp_path / "f.jsonl")
    gate = _gate_writer(log)
    inputs = {"x": 1.0}
    log.append("decision", inputs=inputs)
    inputs["x"] = 99.0  # the caller reuses its dict
    gate.set()
    log.close()
    assert [r for r in read_log(tmp_path / "f.jsonl") if r["kind"] == "decision"][0]["inputs"] == {"x": 1.0}


def test_serialised_records_stay_canonical_with_odd_keys_and_values(tmp_path):
    log = AuditLog(tmp_path / "k.jsonl")
    assert log.append("decision", inputs={10: 1, 9: 2, "n": {2: float("nan"), 1: float("-inf")}}, p=(0.5, 0.5),
                      seq=99, prev="forged", hash="forged", obj=object())
    log.close()
    assert verify_log(tmp_path / "k.jsonl", require_closed=True).ok
    rec = read_log(tmp_path / "k.jsonl")[1]
    assert rec["inputs"] == {"10": 1, "9": 2, "n": {"2": "nan", "1": "-inf"}} and rec["seq"] == 1
