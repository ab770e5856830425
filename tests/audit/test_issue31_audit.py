"""Issue 31 item 5: CLI audit logs keyed and headed, an acknowledge record durable before its release,
refused acknowledgements audited in bounded size."""

from __future__ import annotations

import hashlib
import json
import types
from pathlib import Path

import ethimon
from ethimon.audit import AuditLog, read_log, verify_log
from ethimon.audit._log import canonical
from ethimon.loop import GovernedLoop, LoopConfig
from tests._cli import call_cli
from tests._estimators import FakeClock

SPEC = ethimon.load_spec_text("""
ethimon: 1
name: cell
signals:
  contact_force: {unit: N, range: [0, 1000]}
obligations:
  - {id: contact, require: contact_force <= 140, response: stop_1, release: {mode: manual, hold_cycles: 1}}
risk: {threshold: 0.5}
""")


def _cli_log(path: Path, capsys) -> str:
    """A log as ``ethimon replay/ros2 --audit`` opens and closes it; returns what the close printed."""
    from ethimon.cli._common import open_audit_log
    log, rc = open_audit_log(str(path), SPEC, tool="test")
    assert rc is None
    for i in range(6):
        assert log.append("decision", cycle=i, override=i == 3)
    capsys.readouterr()
    log.close()
    return capsys.readouterr().err


def _rebuild_without(path: Path, drop: int) -> None:
    """What an attacker does to an unkeyed log: drop a record, renumber and rehash the chain."""
    recs = [json.loads(x) for x in path.read_bytes().splitlines()]
    del recs[drop]
    prev, out = "0" * 64, []
    for seq, r in enumerate(recs):
        r["seq"], r["prev"] = seq, prev
        if r["kind"] == "open":
            r["keyed"] = False
        body = canonical({k: v for k, v in r.items() if k not in ("hash", "key_id")})
        prev = hashlib.sha256(body).hexdigest()
        out.append(body[:-1] + b',"hash":"' + prev.encode() + b'"}\n')
    path.write_bytes(b"".join(out))


def test_cli_log_is_keyed_from_the_environment_and_a_rebuilt_chain_fails(tmp_path, monkeypatch, capsys):
    key = tmp_path / "audit.key"
    key.write_bytes(b"k3y-0f-the-cell\n")
    monkeypatch.setenv("ETHIMON_AUDIT_KEY_FILE", str(key))
    p = tmp_path / "run.jsonl"
    _cli_log(p, capsys)
    assert b"k3y-0f-the-cell" not in p.read_bytes()          # the key is never written into the log
    assert read_log(p, key=b"k3y-0f-the-cell")[0]["keyed"] is True
    ok = call_cli("audit", "verify", "--require-closed", "--key-file", str(key), str(p))
    assert ok.returncode == 0 and "keyed" in ok.stdout and "unkeyed" not in ok.stdout, ok.stdout + ok.stderr
    _rebuild_without(p, 4)
    bad = call_cli("audit", "verify", "--require-closed", "--key-file", str(key), str(p))
    assert bad.returncode == 1 and "TAMPERED" in bad.stdout and "unkeyed" in bad.stdout, bad.stdout + bad.stderr


def test_cli_log_prints_a_head_that_verify_checks(tmp_path, monkeypatch, capsys):
    monkeypatch.delenv("ETHIMON_AUDIT_KEY_FILE", raising=False)
    monkeypatch.delenv("ETHIMON_AUDIT_KEY_ENV", raising=False)
    p = tmp_path / "run.jsonl"
    printed = _cli_log(p, capsys)
    assert "head " in printed, printed
    head = printed.split("--head ")[1].split()[0]
    count, _, h = head.partition(":")
    assert int(count) == 8 and len(h) == 64
    ok = call_cli("audit", "verify", "--require-closed", "--head", head, str(p))
    assert ok.returncode == 0 and "unkeyed" in ok.stdout, ok.stdout + ok.stderr
    _rebuild_without(p, 4)
    assert verify_log(p, require_closed=True).ok           # the chain alone cannot see it...
    bad = call_cli("audit", "verify", "--require-closed", "--head", head, str(p))
    assert bad.returncode == 1 and "TAMPERED" in bad.stdout, bad.stdout + bad.stderr  # ...the head does


def test_key_may_come_from_an_environment_variable_the_operator_names(tmp_path, monkeypatch, capsys):
    monkeypatch.delenv("ETHIMON_AUDIT_KEY_FILE", raising=False)
    monkeypatch.setenv("ETHIMON_AUDIT_KEY_ENV", "CELL7_AUDIT_KEY")
    monkeypatch.setenv("CELL7_AUDIT_KEY", "another-secret")
    p = tmp_path / "run.jsonl"
    _cli_log(p, capsys)
    assert b"another-secret" not in p.read_bytes()
    assert verify_log(p, key=b"another-secret", require_closed=True).ok
    r = call_cli("audit", "verify", "--key-env", "CELL7_AUDIT_KEY", str(p))
    assert r.returncode == 0, r.stdout + r.stderr
    # a variable named but not set is bad input, located, never an unkeyed log by surprise
    monkeypatch.delenv("CELL7_AUDIT_KEY")
    from ethimon.cli._common import open_audit_log
    log, rc = open_audit_log(str(tmp_path / "other.jsonl"), SPEC)
    assert log is None and rc == 2 and "CELL7_AUDIT_KEY" in capsys.readouterr().err


class _SlowLog(AuditLog):
    """An audit log whose writer takes its time (a slow disk)."""

    def _write(self, records, force_sync=False):
        import time
        if records and self._seq > 0:
            time.sleep(0.05)
        super()._write(records, force_sync)


def test_release_is_applied_only_after_its_acknowledge_record_is_durable(tmp_path):
    p = tmp_path / "ack.jsonl"
    log = _SlowLog(p, fsync="interval")
    clock = FakeClock()
    loop = GovernedLoop(SPEC, audit=log, clock=clock, config=LoopConfig(max_risk_age_s=None, period_s=0.001))
    for f in (300.0, 0.0, 0.0):
        clock.advance(0.001)
        loop.cycle({"contact_force": f, "p_unsafe": 0.0})
    a = loop.acknowledge("ops-7", reason="cleared")
    assert a.released
    # at the moment the release can reach the robot (the next cycle), its record is on disk
    on_disk = [json.loads(x) for x in p.read_bytes().splitlines()]
    assert any(r["kind"] == "acknowledge" and r["released"] for r in on_disk), [r["kind"] for r in on_disk]
    clock.advance(0.001)
    assert not loop.cycle({"contact_force": 0.0, "p_unsafe": 0.0}).override
    log.close()


def test_refused_unauthenticated_acknowledgements_are_audited_in_bounded_size(tmp_path):
    from ethimon.io import LiveMonitor
    p = tmp_path / "ack.jsonl"
    log = AuditLog(p)
    fake = types.SimpleNamespace(acks_refused=0, loop=types.SimpleNamespace(
        audit=log, monitor=types.SimpleNamespace(cycle=3)))
    huge_op, huge_reason = "o" * 300_000, "r" * 500_000
    sent = [LiveMonitor._refuse(fake, huge_op, huge_reason, "guid-1", "refused: unauthenticated") for _ in range(30)]
    log.close()
    assert p.stat().st_size < 200_000, p.stat().st_size      # was 15 MiB
    rec = [r for r in read_log(p) if r["kind"] == "acknowledge"][0]
    assert rec["reason"]["bytes"] == 500_000 and rec["reason"]["sha256"] == hashlib.sha256(
        huge_reason.encode()).hexdigest() and len(rec["reason"]["head"]) <= 256
    assert rec["operator"]["bytes"] == 300_000
    assert all(len(json.dumps(x)) < 2000 for x in sent)
