"""Issue 34 item 3: a decision's margins readable by rule id, and the latched rules by name."""

from __future__ import annotations

import math

import pytest

import ethimon
from ethimon.runtime import Monitor

SPEC = """
ethimon: 1
name: names
signals:
  human_distance: {unit: m}
  speed: {unit: m/s}
obligations:
  - id: separation
    require: human_distance >= 0.5
    response: safe_pose
  - id: slow
    require: speed <= 1.0
    response: stop_2
    release: {hold_cycles: 3}
"""


@pytest.fixture()
def mon() -> Monitor:
    return Monitor(ethimon.load_spec_text(SPEC))


def test_margin_by_rule_id(mon: Monitor) -> None:
    d = mon.step({"risk": 0.1, "human_distance": 0.8, "speed": 0.25})
    assert d.margin("separation") == pytest.approx(0.3)
    assert d.margin("slow") == pytest.approx(0.75)
    assert d.margins_by_id() == {"separation": pytest.approx(0.3), "slow": pytest.approx(0.75)}
    with pytest.raises(KeyError, match="no rule 'nope'.*separation, slow"):
        d.margin("nope")


def test_margins_share_the_monitors_id_tuple(mon: Monitor) -> None:
    a = mon.step({"risk": 0.1, "human_distance": 0.8, "speed": 0.25})
    b = mon.step({"risk": 0.1, "human_distance": 0.9, "speed": 0.25})
    assert a.ids is mon.obligation_ids and b.ids is mon.obligation_ids  # by reference: no per-step copy


def test_margin_of_a_fault_cycle_is_nan(mon: Monitor) -> None:
    d = mon.step({"risk": 0.1, "human_distance": 0.8})  # speed missing: fail closed
    assert d.override and math.isnan(d.margin("slow"))


def test_latched_rules_by_name(mon: Monitor) -> None:
    d = mon.step({"risk": 0.1, "human_distance": 0.8, "speed": 2.0})
    assert d.override and d.latched_rules == ("slow",)
    d = mon.step({"risk": 0.1, "human_distance": 0.8, "speed": 0.2})  # held by the release rule (3 clean cycles)
    assert d.override and d.latched and d.latched_rules == ("slow",)
    assert d.as_dict()["latched_rules"] == ["slow"]
    for _ in range(3):
        d = mon.step({"risk": 0.1, "human_distance": 0.8, "speed": 0.2})
    assert not d.override and d.latched_rules == ()


def test_latched_rules_on_a_fault_and_an_outside_fault(mon: Monitor) -> None:
    d = mon.step({"risk": 0.1, "human_distance": 0.8})
    assert "fault" in d.latched_rules
    m2 = Monitor(ethimon.load_spec_text(SPEC))
    d = m2.fault("watchdog", decision=m2.step({"risk": 0.1, "human_distance": 0.8, "speed": 0.2}))
    assert d.latched_rules == ("fault",)
