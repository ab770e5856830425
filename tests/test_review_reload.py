"""Review finding on reload (issue 25): a bounded response that is due must not be forgotten by a reload."""

from __future__ import annotations

import ethimon
from ethimon.loop import GovernedLoop

SPEC = """ethimon: 1
name: w
signals:
  trigger: {type: bool}
  moving: {type: bool}
obligations:
  - {id: stop_after, when: trigger, require: "not moving", within_cycles: 5, response: stop_1}
"""
QUIET = {"trigger": False, "moving": True, "p_unsafe": 0.0}


def _run(reload_at):
    spec = ethimon.load_spec_text(SPEC)
    loop = GovernedLoop(ethimon.Monitor(spec), period_s=1.0, deadline_s=100.0)
    out, results = [loop.cycle({"trigger": True, "moving": True, "p_unsafe": 0.0}).override], []
    for i in range(8):
        if i == reload_at:
            results.append(loop.reload(spec))  # the same spec
        out.append(loop.cycle(QUIET).override)
    return out, results, loop


def test_reload_while_a_bounded_response_is_due_keeps_the_deadline():
    # The trigger came at cycle 0: 'not moving' is due by cycle 5. Before: reloading the same spec at
    # cycle 3 gave a monitor with a fresh history, the deadline was forgotten and the arm kept moving
    # (override never came).
    plain, _, _ = _run(None)
    assert plain == [False] * 5 + [True] * 4
    out, (res,), loop = _run(2)
    assert out == plain
    assert not res.ok and "stop_after" in res.error and "within_cycles" in res.error
    assert loop.stats.reloads_applied == 0


def test_reload_at_the_swap_is_refused_when_a_response_became_due_meanwhile():
    spec = ethimon.load_spec_text(SPEC)
    loop = GovernedLoop(ethimon.Monitor(spec), period_s=1.0, deadline_s=100.0)
    loop.cycle(QUIET)
    res = loop.reload(spec)  # nothing due now: accepted
    assert res.ok
    loop.monitor.step({"trigger": True, "moving": True, "p_unsafe": 0.0})
    out = [loop.cycle(QUIET).override for _ in range(6)]
    assert not res.ok and "stop_after" in res.error
    assert out[-1] is True


def test_reload_with_nothing_due_applies():
    out, (res,), loop = _run(7)  # the deadline has passed (latched): carried as a latch
    assert res.wait_applied(0) and out[-1] is True
