"""Names everywhere in the audit log (issue 34 item 3): a decision record names the latched rules and
gives the margins by rule id, and a change of which rules hold the latch is a record of its own (the
log never keeps naming a rule that has released while another holds the same override)."""

from __future__ import annotations

import pytest

import ethimon
from ethimon.audit import AuditLog, read_log
from ethimon.loop import GovernedLoop, LoopConfig

SPEC = """\
ethimon: 1
name: two_latches
signals:
  a: {unit: m, range: [0, 10]}
  b: {unit: m, range: [0, 10]}
obligations:
  - id: near_a
    require: a >= 1
    release: {mode: auto, hold_cycles: 2}
  - id: near_b
    require: b >= 1
    release: {mode: auto, hold_cycles: 6}
"""


def _records(tmp_path, steps):
    log = AuditLog(tmp_path / "a.jsonl")
    loop = GovernedLoop(ethimon.Monitor(ethimon.load_spec_text(SPEC)), audit=log,
                        config=LoopConfig(period_s=1.0, deadline_s=100.0))
    decisions = [loop.cycle({**s, "p_unsafe": 0.0}) for s in steps]
    log.close()
    return decisions, [r for r in read_log(tmp_path / "a.jsonl") if r.get("kind") == "decision"]


def test_the_audit_log_names_the_latched_rules_and_the_margins(tmp_path):
    steps = [{"a": 5, "b": 5}, {"a": 0.5, "b": 0.5}] + [{"a": 5, "b": 5}] * 8
    decisions, recs = _records(tmp_path, steps)
    on = next(r for r in recs if r["event"] == "override_on")
    assert on["latched_rules"] == ["near_a", "near_b"] and on["violations"] == ["near_a", "near_b"]
    assert on["margins"] == {"near_a": -0.5, "near_b": -0.5}
    # near_a releases after 2 good cycles, near_b holds the override 4 more: the log says so when it happens
    first = next(d for d in decisions if d.latched_rules == ("near_b",))
    assert first.override and first.response.value == "safe_pose"  # the same override, the same response
    held = [r["latched_rules"] for r in recs if r["override"]]
    assert held[-1] == ["near_b"], held
    changed = next(r for r in recs if r["latched_rules"] == ["near_b"])
    assert changed["cycle"] == first.cycle and changed["event"] == "change"
    assert recs[-1]["event"] == "override_off" and recs[-1]["latched_rules"] == []


@pytest.mark.slow
def test_a_replay_audit_records_each_change_of_the_latched_rules(tmp_path):
    pytest.importorskip("rosbags")
    from ethimon.replay import load_mapping_text, replay_bag
    from tests.replay.test_replay_bags import ns, write

    # 10 Hz: both rules violated at 0.2 s, both good again from 0.3 s; near_a releases after 2 cycles,
    # near_b after 6: near_b alone holds the override for 4 cycles
    msgs = []
    for i in range(15):
        v = 0.5 if i == 2 else 5.0
        msgs += [(ns(i * 0.1), "/a", "f64", v), (ns(max(0.0, i * 0.1 - 0.001)), "/b", "f64", v)]
    bag = write(tmp_path / "b", "mcap", msgs)
    mapping = load_mapping_text("ethimon: 1\nrate_hz: 10\nmax_age_s: 0.2\nrisk: none\nsignals:\n"
                                "  a: {topic: /a}\n  b: {topic: /b}\n")
    log = AuditLog(str(tmp_path / "r.jsonl"), fsync="interval")
    replay_bag(bag, ethimon.load_spec_text(SPEC), mapping, audit=log)
    log.close()
    recs = [r for r in read_log(str(tmp_path / "r.jsonl")) if r["kind"] == "decision"]
    held = [r["latched_rules"] for r in recs if r["override"]]
    assert held[0] == ["near_a", "near_b"] and held[-1] == ["near_b"], held
    assert recs[-1]["event"] == "override_off"
