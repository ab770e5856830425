"""Issue 32 item 1 (escalation visible): a stop 0/1 whose power-off the brakes cannot hold is held
powered instead, and the reason is in the cycle's record and in the audit log."""

from __future__ import annotations

import json

import pytest

from tests.sim._scenarios import run_scenario

pytestmark = [pytest.mark.sim, pytest.mark.slow]


def test_a_refused_power_off_is_in_the_cycle_record_and_the_audit_log(tmp_path):
    pytest.importorskip("pybullet")
    from ethimon.audit import AuditLog
    log = AuditLog(tmp_path / "sim.jsonl", fsync="never")
    try:
        _, res = run_scenario("payload_weak_brakes_held_powered", {"duration_s": 1.6}, audit=log)
    finally:
        log.close()
    assert res.brakes_escalated
    esc = [r for r in res.trace if r.escalated]
    assert esc and "power-off refused" in esc[0].escalated and esc[0].powered
    assert "joint 2 needs 68.6 N·m" in esc[0].escalated and "held powered (a stop 2)" in esc[0].escalated
    recs = [json.loads(line) for line in (tmp_path / "sim.jsonl").read_text().splitlines()]
    brakes = [r for r in recs if r["kind"] == "brakes"]
    assert brakes and brakes[0]["escalated"] is True and brakes[0]["reason"] == esc[0].escalated
    assert brakes[0]["cycle"] == esc[0].cycle
