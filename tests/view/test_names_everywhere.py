"""Issue 34 item 3: the latched rules by name in ``/ethimon/decision`` and in the audit log records (the
loop's and a replay's)."""

from __future__ import annotations

import json

import pytest

import ethimon
from ethimon.audit import AuditLog, read_log
from ethimon.loop import GovernedLoop, LoopConfig

SPEC = """
ethimon: 1
name: names
signals:
  a: {unit: m, range: [0, 10]}
obligations:
  - {id: oa, require: a >= 1, release: {hold_cycles: 3}}
"""


def test_ros2_decision_json_names_the_latched_rules() -> None:
    from ethimon.io import decision_json
    m = ethimon.Monitor(ethimon.load_spec_text(SPEC))
    m.step({"a": 0.5, "risk": 0.1})
    d = m.step({"a": 2.0, "risk": 0.1})  # held by oa's release rule
    doc = json.loads(decision_json(d, m.obligation_ids))
    assert doc["latched"] and doc["latched_rules"] == ["oa"] and doc["margins"] == {"oa": 1.0}


def test_loop_audit_records_name_the_latched_rules(tmp_path) -> None:
    log = AuditLog(tmp_path / "a.jsonl")
    loop = GovernedLoop(ethimon.load_spec_text(SPEC), audit=log, config=LoopConfig(period_s=1.0))
    for a in (2.0, 0.5, 2.0, 2.0, 2.0, 2.0):
        loop.cycle({"a": a, "risk": 0.1})
    log.close()
    recs = [r for r in read_log(tmp_path / "a.jsonl") if r.get("kind") == "decision"]
    assert [(r["override"], r["latched_rules"]) for r in recs] == [(False, []), (True, ["oa"]), (True, ["oa"]),
                                                                  (False, [])]


@pytest.mark.slow  # writes a bag (rosbags)
def test_replay_audit_records_name_the_latched_rules(tmp_path) -> None:
    pytest.importorskip("rosbags")
    from ethimon.replay import load_mapping_text, replay_bag
    from tests.replay.test_replay_bags import ns, write
    write(tmp_path / "b", "mcap", [(ns(i * 0.05), "/a", "f64", 0.5 if i == 10 else 2.0) for i in range(20)])
    log = AuditLog(tmp_path / "r.jsonl")
    replay_bag(tmp_path / "b", ethimon.load_spec_text(SPEC),
               load_mapping_text("ethimon: 1\nrate_hz: 20\nmax_age_s: 0.1\nrisk: none\nsignals:\n  a: {topic: /a}\n"),
               audit=log)
    log.close()
    recs = [r for r in read_log(tmp_path / "r.jsonl") if r.get("kind") == "decision"]
    assert [(r["cycle"], r["latched_rules"]) for r in recs] == [(0, []), (10, ["oa"]), (11, ["oa"]), (13, [])]  # released on the 3rd clean cycle
