"""Issue 32 item 4 for a real cell: GovernedLoop keeps the stop after a reset until the spec's start.

With a ``restart:`` block, an accepted acknowledgement of a manual latch never starts motion: the loop
keeps overriding (stop 2, a reason a person sees) until the start condition, a
:meth:`GovernedLoop.start_motion` command or the rising edge of the spec's start input; a start is
refused while the monitor overrides for another reason or no acknowledged stop waits. With
``restart.standstill`` named, an acknowledgement is refused until the robot reports the stop completed.
"""

from __future__ import annotations

import pytest

import ethimon
from ethimon import Response
from ethimon.errors import SpecError
from ethimon.loop import GovernedLoop, LoopConfig
from tests._estimators import FakeClock

SPEC = """\
ethimon: 1
name: restart_loop
signals:
  human_distance: {unit: m, range: [0, 10]}
  at_rest: {type: bool}
  start_button: {type: bool}
obligations:
  - {id: near, require: human_distance > 0.5, response: stop_1, release: {mode: manual, hold_cycles: 2}}
%s
"""

CLEAR = {"human_distance": 2.0, "at_rest": True, "start_button": False, "p_unsafe": 0.0}
NEAR = dict(CLEAR, human_distance=0.2)


class _Records:
    """An in-memory audit log (what the loop calls: append, fault, flush): no file, no fsync."""

    fault = None
    max_lag_s = 1.0

    def __init__(self):
        self.records = []

    def append(self, kind, **fields):
        self.records.append(dict(fields, kind=kind))
        return True

    def flush(self, timeout=None):
        pass


def _loop(restart="restart: {start: command}", **kw):
    spec = ethimon.load_spec_text(SPEC % restart)
    return GovernedLoop(ethimon.Monitor(spec), clock=FakeClock(), config=LoopConfig(period_s=0.001), **kw)


def _latched_then_clear(loop, clear=CLEAR):
    assert loop.cycle(NEAR).response is Response.STOP_1
    for _ in range(2):
        d = loop.cycle(clear)
    assert d.override and d.awaiting_release


def test_an_accepted_acknowledgement_holds_stop_2_until_the_start_command():
    loop = _loop(audit=_Records())
    _latched_then_clear(loop)
    assert loop.acknowledge("ops-1", reason="checked the cell")
    for _ in range(3):  # the reset never starts motion by itself
        d = loop.cycle(CLEAR)
        assert d.override and d.response is Response.STOP_2
        assert not d.faults and d.violations == ()
        assert "restart" in d.latched_rules
    assert any("acknowledged; waiting for the start (GovernedLoop.start_motion())" in r for r in d.reasons)
    assert "acknowledged; waiting for the start (GovernedLoop.start_motion())" in loop.hold_text
    [h] = loop.holding()
    assert h["rule"] == "restart" and h["response"] == "stop_2" and h["release"] == "start"
    s = loop.start_motion("ops-1", reason="cell clear")
    assert s.released and "started" in s.message
    d = loop.cycle(CLEAR)
    assert not d.override and loop.hold_text == ""
    assert not loop.start_motion("ops-1").released  # nothing waits any more
    starts = [r for r in loop.audit.records if r["kind"] == "start_motion"]
    assert [r["accepted"] for r in starts] == [True, False]
    assert starts[0]["operator"] == "ops-1" and starts[0]["reason"] == "cell clear"


def test_a_start_is_refused_with_a_reason_when_no_acknowledged_stop_waits_or_the_monitor_overrides():
    loop = _loop()
    loop.cycle(CLEAR)
    s = loop.start_motion("ops-1")
    assert not s.released and "no acknowledged stop waits for a start" in s.message
    _latched_then_clear(loop)
    s = loop.start_motion("ops-1")  # latched, not yet acknowledged
    assert not s.released and "no acknowledged stop waits for a start" in s.message
    assert loop.acknowledge("ops-1")
    assert loop.cycle(NEAR).override  # someone walks in: the rule fires again
    s = loop.start_motion("ops-1")
    assert not s.released and "the monitor overrides" in s.message and "near" in s.message
    with pytest.raises(ValueError, match="operator"):
        loop.start_motion(" ")


def test_the_rising_edge_of_the_start_input_starts_motion_a_button_held_down_does_not():
    loop = _loop("restart: {start: start_button}")
    _latched_then_clear(loop, dict(CLEAR, start_button=True))
    assert loop.acknowledge("ops-1")
    held = dict(CLEAR, start_button=True)
    for _ in range(3):  # held down since before the reset: no edge
        d = loop.cycle(held)
        assert d.override and d.response is Response.STOP_2
    assert "the rising edge of input start_button" in loop.hold_text
    assert loop.cycle(CLEAR).override  # released ...
    d = loop.cycle(held)  # ... pressed: the start is taken on this cycle, motion from the next
    assert d.override
    assert not loop.cycle(held).override
    assert not loop.cycle(CLEAR).override


def test_a_start_edge_while_a_rule_fires_is_refused_and_not_remembered():
    loop = _loop("restart: {start: start_button}")
    _latched_then_clear(loop)
    assert loop.acknowledge("ops-1")
    loop.cycle(CLEAR)
    d = loop.cycle(dict(CLEAR, human_distance=0.2, start_button=True))  # pressed while someone is near
    assert d.override
    for _ in range(3):
        d = loop.cycle(dict(CLEAR, start_button=True))
        assert d.override and "restart" in d.latched_rules  # still waiting: that press did not count


def test_an_acknowledgement_is_refused_until_the_robot_reports_standstill():
    loop = _loop("restart: {start: command, standstill: at_rest}")
    moving = dict(CLEAR, at_rest=False)
    _latched_then_clear(loop, moving)
    a = loop.acknowledge("ops-1")
    assert not a.released and "the stop has not completed" in a.message and "at_rest" in a.message
    assert loop.monitor.latched_rules == ("near",)  # nothing was released
    loop.cycle(CLEAR)
    assert loop.acknowledge("ops-1")
    assert loop.cycle(CLEAR).override  # and it still waits for the start
    assert loop.start_motion("ops-1")
    assert not loop.cycle(CLEAR).override


def test_without_a_restart_block_the_loop_releases_on_the_acknowledgement_as_before():
    loop = _loop("")
    _latched_then_clear(loop)
    assert loop.acknowledge("ops-1")
    assert not loop.cycle(CLEAR).override
    assert "no restart" in loop.start_motion("ops-1").message


def test_restart_standstill_names_a_declared_bool_input_and_lint_says_when_it_is_missing(tmp_path):
    assert ethimon.load_spec_text(SPEC % "restart: {standstill: at_rest}").restart.standstill == "at_rest"
    assert ethimon.load_spec_text(SPEC % "").restart.standstill is None
    with pytest.raises(SpecError, match="standstill: 'moving' is not a declared signal"):
        ethimon.load_spec_text(SPEC % "restart: {standstill: moving}")
    with pytest.raises(SpecError, match="needs a bool input"):
        ethimon.load_spec_text(SPEC % "restart: {standstill: human_distance}")
    from ethimon.verify._policy import release_policy_warnings
    ws = release_policy_warnings(ethimon.load_spec_text(SPEC % "restart: {start: command}"))
    assert any("restart.standstill" in w and "must gate" in w for w in ws)
    assert not any("standstill" in w for w in release_policy_warnings(
        ethimon.load_spec_text(SPEC % "restart: {standstill: at_rest}")))


def test_a_reload_that_drops_the_restart_block_or_its_standstill_is_a_weakening():
    from ethimon.loop import weakenings
    full = ethimon.load_spec_text(SPEC % "restart: {start: start_button, standstill: at_rest}")
    weak, _ = weakenings(full, ethimon.load_spec_text(SPEC % ""))
    assert any("restart block removed" in w for w in weak)
    weak, _ = weakenings(full, ethimon.load_spec_text(SPEC % "restart: {start: start_button}"))
    assert any("restart.standstill at_rest removed" in w for w in weak)
    _, unjudged = weakenings(full, ethimon.load_spec_text(SPEC % "restart: {standstill: at_rest}"))
    assert any("restart.start start_button -> command" in u for u in unjudged)
    assert weakenings(full, full) == ([], [])



def test_the_restart_hold_says_since_when_and_that_an_acknowledgement_does_not_release_it():
    loop = _loop()
    _latched_then_clear(loop)
    assert loop.acknowledge("ops-1")
    loop.cycle(CLEAR)
    [h] = loop.holding()
    assert h["since_t_unix"] is not None and h["acknowledge_allowed"] is False
    a = loop.acknowledge("ops-1")  # a second reset does not start motion either
    assert not a.released and loop.cycle(CLEAR).override
