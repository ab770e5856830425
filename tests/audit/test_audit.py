"""Audit log: hash chain, tamper/truncation/reorder detection, durability, bounded queue, CLI."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from ethimon.audit import AuditFormatError, AuditLog, read_log, spec_hash, verify_log

ROOT = Path(__file__).resolve().parents[2]


def _write(path: Path, n: int = 20, **kw) -> str:
    with AuditLog(path, meta={"spec_sha256": "ab" * 32}, **kw) as log:
        for i in range(n):
            assert log.append("decision", cycle=i, override=i % 3 == 0, margins={"a": 0.5, "b": float("-inf")},
                              inputs={"x": float("nan"), "flag": True})
    return log.head


def _lines(path: Path) -> list[bytes]:
    return path.read_bytes().splitlines(keepends=True)


@pytest.mark.slow
def test_roundtrip_chain_is_intact(tmp_path):
    p = tmp_path / "a.jsonl"
    head = _write(p)
    rep = verify_log(p, require_closed=True, expect_head=head)
    assert rep.ok and rep.closed and rep.records == 22 and not rep.torn_tail
    assert rep.kinds == {"open": 1, "decision": 20, "close": 1}
    recs = read_log(p)
    assert recs[1]["inputs"] == {"x": "nan", "flag": True}  # NaN made JSON-safe, not dropped
    assert recs[1]["margins"]["b"] == "-inf"
    assert [r["seq"] for r in recs] == list(range(22))


def test_log_never_overwrites(tmp_path):
    p = tmp_path / "a.jsonl"
    _write(p, 1)
    with pytest.raises(FileExistsError):
        AuditLog(p)


@pytest.mark.parametrize("attack", ["edit", "delete_middle", "swap", "duplicate", "drop_head",
                                    "append_after_close", "dup_key", "bad_json"])
def test_tampering_is_detected(tmp_path, attack):
    p = tmp_path / "a.jsonl"
    _write(p)
    lines = _lines(p)
    if attack == "edit":
        lines[5] = lines[5].replace(b'"override":false', b'"override":true', 1)
        assert lines[5] != _lines(p)[5]
    elif attack == "delete_middle":
        del lines[7]
    elif attack == "swap":
        lines[4], lines[5] = lines[5], lines[4]
    elif attack == "duplicate":
        lines.insert(6, lines[6])
    elif attack == "drop_head":
        del lines[0]
    elif attack == "append_after_close":
        lines.append(lines[3])
    elif attack == "dup_key":  # a misleading duplicate key that json.loads would hide
        lines[5] = lines[5].replace(b'{"cycle"', b'{"override":true,"cycle"', 1)
    elif attack == "bad_json":
        lines[5] = b"{not json\n"
    p.write_bytes(b"".join(lines))
    rep = verify_log(p)
    assert not rep.ok
    assert rep.error and rep.summary().startswith("TAMPERED")


def test_recomputed_chain_without_key_is_caught_with_key(tmp_path):
    """With an HMAC key, an attacker who rewrites a record and rehashes the chain is still caught."""
    import hashlib
    from ethimon.audit._log import canonical
    p = tmp_path / "k.jsonl"
    _write(p, 5, key=b"secret")
    assert verify_log(p, key=b"secret").ok
    recs = [json.loads(x) for x in _lines(p)]
    recs[2]["override"] = not recs[2]["override"]
    prev = recs[0]["hash"]
    out = [_lines(p)[0]]
    for r in recs[1:]:
        r["prev"] = prev
        body = canonical({k: v for k, v in r.items() if k != "hash"})
        r["hash"] = hashlib.sha256(body).hexdigest()
        out.append(body[:-1] + b',"hash":"' + r["hash"].encode() + b'"}\n')
        prev = r["hash"]
    p.write_bytes(b"".join(out))
    assert not verify_log(p, key=b"secret").ok
    with pytest.raises(AuditFormatError):
        verify_log(p)  # keyed log without the key is bad input, not "ok"


def test_truncation(tmp_path):
    p = tmp_path / "a.jsonl"
    head = _write(p)
    lines = _lines(p)
    # complete records cut from the tail: caught by require_closed / expect_head
    p.write_bytes(b"".join(lines[:-3]))
    assert verify_log(p).ok  # a plain chain cannot know about a missing tail...
    assert not verify_log(p, require_closed=True).ok
    assert not verify_log(p, expect_head=head).ok
    # a torn last line (kill mid-write) is ignored, never counted
    p.write_bytes(b"".join(lines[:-3]) + lines[-3][:40])
    rep = verify_log(p)
    assert rep.ok and rep.torn_tail and rep.records == len(lines) - 3


def test_bad_input(tmp_path):
    with pytest.raises(AuditFormatError):
        verify_log(tmp_path / "missing.jsonl")
    empty = tmp_path / "empty.jsonl"
    empty.write_bytes(b"")
    with pytest.raises(AuditFormatError):
        verify_log(empty)
    other = tmp_path / "other.jsonl"
    other.write_text('{"hello": 1}\n')
    with pytest.raises(AuditFormatError):
        verify_log(other)
    with pytest.raises(AuditFormatError):
        verify_log(tmp_path)


def test_full_queue_is_reported_not_silent(tmp_path):
    p = tmp_path / "q.jsonl"
    log = AuditLog(p, queue_size=1)
    # Hold the writer inside a write so the queue stays full.
    import threading
    gate = threading.Event()
    real_write = log._write

    def slow_write(records, force_sync=False):
        gate.wait(5.0)
        real_write(records, force_sync)

    log._write = slow_write
    results = [log.append("decision", cycle=i) for i in range(50)]
    assert not all(results)
    assert log.dropped == results.count(False) > 0
    gate.set()
    log.close()
    recs = read_log(p)
    dropped = [r for r in recs if r["kind"] == "dropped"]
    assert dropped and sum(r["count"] for r in dropped) == log.dropped
    assert recs[-1]["kind"] == "close" and recs[-1]["dropped_total"] == log.dropped


def test_flush_reports_durable_seq(tmp_path):
    p = tmp_path / "f.jsonl"
    with AuditLog(p, fsync="interval", fsync_interval_s=10.0) as log:
        for i in range(100):
            log.append("decision", cycle=i)
        seq = log.flush()
        assert seq == 100 and log.durable_seq == 100
        assert verify_log(p).records == 101


def test_spec_hash_ignores_formatting(tmp_path):
    import ethimon
    a = ethimon.load_spec_text("ethimon: 1\nname: demo\nrisk: {threshold: 0.5}\n")
    b = ethimon.load_spec_text("# comment\nethimon: 1\nname:   demo\nrisk:\n  threshold: 0.50\n")
    c = ethimon.load_spec_text("ethimon: 1\nname: demo\nrisk: {threshold: 0.4}\n")
    assert spec_hash(a) == spec_hash(b) != spec_hash(c)


_KILL_CHILD = textwrap.dedent("""
    import sys, time
    from ethimon.audit import AuditLog
    log = AuditLog(sys.argv[1], fsync="always")
    n = 0
    while True:
        for _ in range(50):
            log.append("decision", cycle=n, payload="x" * 200)
            n += 1
        seq = log.flush()
        print(seq, log.head, flush=True)   # reported written
""")


@pytest.mark.slow
def test_kill_loses_no_record_reported_written(tmp_path):
    p = tmp_path / "kill.jsonl"
    child = subprocess.Popen([sys.executable, "-c", _KILL_CHILD, str(p)], stdout=subprocess.PIPE, text=True,
                             cwd=ROOT)
    try:
        reported = []
        for line in child.stdout:
            reported.append(line.split())
            if len(reported) >= 5:
                break
        os.kill(child.pid, signal.SIGKILL)
    finally:
        child.wait(10)
    last_seq, last_head = int(reported[-1][0]), reported[-1][1]
    rep = verify_log(p)
    assert rep.ok and not rep.closed
    assert rep.records - 1 >= last_seq  # every reported record is there (seq 0 is "open")
    recs = read_log(p)
    assert recs[last_seq]["hash"] == last_head
    assert [r["cycle"] for r in recs[1:last_seq + 1]] == list(range(last_seq))


@pytest.mark.slow
def test_log_left_open_is_closed_at_exit(tmp_path):
    p = tmp_path / "exit.jsonl"
    code = ("import sys\nfrom ethimon.audit import AuditLog\nlog = AuditLog(sys.argv[1])\n"
            "for i in range(500):\n    log.append('decision', cycle=i)\n")
    subprocess.run([sys.executable, "-c", code, str(p)], check=True, timeout=60, cwd=ROOT)
    rep = verify_log(p, require_closed=True)
    assert rep.ok and rep.kinds["decision"] == 500


def _cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "ethimon.cli._audit_cmds", *args], capture_output=True,
                          text=True, timeout=60, cwd=ROOT)


@pytest.mark.slow
def test_cli_verify_exit_codes(tmp_path):
    p = tmp_path / "a.jsonl"
    _write(p)
    r = _cli("audit", "verify", str(p))
    assert r.returncode == 0, r.stderr
    assert "ok: 22 records" in r.stdout and len(r.stdout.strip().splitlines()) == 1
    lines = _lines(p)
    lines[3] = lines[3].replace(b'"cycle":2', b'"cycle":9')
    p.write_bytes(b"".join(lines))
    r = _cli("audit", "verify", str(p))
    assert r.returncode == 1 and "TAMPERED: line 4" in r.stdout
    r = _cli("audit", "verify", str(tmp_path / "nope.jsonl"))
    assert r.returncode == 2 and "Traceback" not in r.stderr and len(r.stderr.strip().splitlines()) == 1
    r = _cli("audit", "verify")
    assert r.returncode == 2


@pytest.mark.slow
def test_cli_require_closed(tmp_path):
    p = tmp_path / "a.jsonl"
    _write(p)
    p.write_bytes(b"".join(_lines(p)[:-1]))
    assert _cli("audit", "verify", str(p)).returncode == 0
    r = _cli("audit", "verify", "--require-closed", str(p))
    assert r.returncode == 1 and "close" in r.stdout


def test_read_log_names_an_over_long_line_instead_of_stopping_silently(tmp_path, monkeypatch):
    import ethimon.audit._chain as v
    path = tmp_path / "l.jsonl"
    log = AuditLog(path)
    log.append("note", text="x")
    log.close()
    real = v.verify_log

    def verify_then_change(p, **kw):  # the file changes between the check and the read
        rep = real(p, **kw)
        lines = Path(p).read_bytes().splitlines(keepends=True)
        Path(p).write_bytes(lines[0] + b"x" * (v.MAX_RECORD_BYTES + 10) + b"\n" + b"".join(lines[1:]))
        return rep
    monkeypatch.setattr(v, "verify_log", verify_then_change)
    with pytest.raises(AuditFormatError, match=r"l\.jsonl: line 2 is longer than"):
        read_log(path)
