"""Issue 31 (live outputs a robot can trust): every fault found outside the monitor ends a pending
confirmation of a confirm-band text, as a fault the monitor finds itself does (docs/loop: "a fault ends
a confirmation"). Before: a missed deadline, a stall or a transport's own fault (a foreign publisher)
was added to the cycle by ``Monitor.fault(..., decision=d)``, which kept the confirmation: once the fault
cleared the arm ran the confirmed text without asking again."""

from __future__ import annotations

import pytest

import ethimon
from ethimon.loop import AsyncRiskSource, GovernedLoop, LoopConfig
from ethimon.runtime import Fault

from tests._estimators import FakeClock, ScriptedEstimator

BAND = """ethimon: 1
name: band
signals: {d: {unit: m, range: [0, 4]}}
risk:
  threshold: 0.5
  confirm_threshold: 0.3
  release: {hysteresis: 0.05, hold_cycles: 2}
on_fault: {response: stop_1, release: {mode: auto, hold_cycles: 1}}
obligations:
  - {id: near, require: "d >= 0.5", response: stop_1}
"""


class _Signals(dict):
    faults: tuple = ()


def _confirmed_loop():
    clock = FakeClock()
    src = AsyncRiskSource(ScriptedEstimator((0.55, 0.45)), text="carry the tray", clock=clock, start=False)
    src.poll_once()
    loop = GovernedLoop(ethimon.load_spec_text(BAND), risk=src, clock=clock,
                        config=LoopConfig(period_s=0.01, deadline_s=0.01))
    assert "confirm" in loop.cycle({"d": 2.0}).violations
    assert loop.acknowledge("op-1", reason="read it").released
    assert not loop.cycle({"d": 2.0}).override  # confirmed: the arm may run it
    return loop, clock


@pytest.mark.parametrize("how", ["deadline", "signals"])
def test_a_fault_outside_the_monitor_ends_the_confirmation(how):
    loop, clock = _confirmed_loop()
    if how == "deadline":
        clock.t += 0.002
        orig = loop._clock
        ticks = iter([clock.t, clock.t + 0.05])  # the cycle's decision ready 50 ms after its start
        loop._clock = lambda: next(ticks, clock.t + 0.05)
        d = loop.cycle({"d": 2.0})
        loop._clock = orig
        clock.t += 0.06
        kind = "deadline"
    else:
        s = _Signals(d=2.0)
        s.faults = (Fault("signals", "another publisher on /ethimon/override", "/ethimon/override"),)
        d = loop.cycle(s)
        kind = "signals"
    assert d.override and any(f.kind == kind for f in d.faults)
    for _ in range(5):  # the fault cleared; the text is still in the band: a person is asked again
        clock.t += 0.01
        d = loop.cycle({"d": 2.0})
    assert d.override and "confirm" in d.violations, d
