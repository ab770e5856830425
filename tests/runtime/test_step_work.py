"""Issue 33, "``Monitor.step`` no slower" after the compose refactor: the work of one cycle, counted.

The compose refactor (``Monitor`` holding ``Latches``, ``Tiers``, ``RiskInput``) measured ~5 % slower
than the tree before it (``base5``, 52f829d) on the no-margins path of ``bench/monitor/step_peers.py``.
Timings are not asserted in tests (the machine is shared); what ``step`` executes is: the bytecode
instructions run in ``step``'s own frame and the Python calls it makes, per cycle, traced with
``sys.settrace`` (deterministic). The budgets are the pre-compose tree's counts on the bench's S1-S4
spec (a clean cycle 321 instructions, a violating one 458, a latched clean one 349; 13 / 14 / 14
calls). Instruction counts belong to one CPython minor version: the test runs on 3.11 (the version
the bench figures are taken on) and is skipped on others.
"""

from __future__ import annotations

import sys

import pytest

import ethimon

pytestmark = pytest.mark.skipif(sys.version_info[:2] != (3, 11),
                                reason="bytecode counts are CPython 3.11's (the bench's version)")

SPEC = """
ethimon: 1
name: s1_s4_w10
signals:
  speed:    {unit: m/s, range: [0, 10]}
  distance: {unit: m, range: [0, 20]}
  contact:  {type: bool}
  force:    {unit: N, range: [0, 1000]}
constants:
  v_max: {value: 1.5, unit: m/s}
  v_stop: {value: 0.1, unit: m/s}
  v_slow: {value: 0.25, unit: m/s}
  d_min: {value: 0.5, unit: m}
  f_max: {value: 140.0, unit: N}
obligations:
  - {id: S1, require: "speed <= v_max"}
  - {id: S2, when: "contact", require: "speed <= v_stop", within_cycles: 10}
  - {id: S3, require: "distance >= d_min or speed <= v_slow"}
  - {id: S4, require: "once(force > f_max, 10) implies speed <= v_slow"}
"""

CLEAN = {"speed": 0.05, "distance": 5.0, "contact": False, "force": 10.0, "p_unsafe": 0.05}
FAST = dict(CLEAN, speed=2.0)  # S1 violated


def _work(m: ethimon.Monitor, row: dict) -> tuple[int, int, ethimon.Decision]:
    """(instructions run in ``step``'s own frame, Python calls made, the Decision) for one cycle."""
    code = type(m).step.__code__
    n = [0, 0]

    def trace(frame, event, arg):
        if event == "call":
            n[1] += 1
        if frame.f_code is not code:
            return None
        frame.f_trace_opcodes = True
        if event == "opcode":
            n[0] += 1
        return trace

    old = sys.gettrace()
    sys.settrace(trace)
    try:
        d = m.step(row)
    finally:
        sys.settrace(old)
    return n[0], n[1], d


@pytest.mark.parametrize("margins", [False, True])
def test_a_cycle_runs_no_more_bytecode_in_step_than_before_the_compose_refactor(margins):
    m = ethimon.Monitor(ethimon.load_spec_text(SPEC, "<s1_s4>"), margins=margins)
    m.step(CLEAN)
    extra = 5 if margins else 0  # the margins call: the same few instructions in both trees
    ops, calls, d = _work(m, CLEAN)
    assert not d.override
    assert ops <= 321 + extra, f"clean cycle: {ops} instructions in step (pre-compose: {321 + extra})"
    assert calls <= 13 + 11 * margins
    ops, calls, d = _work(m, FAST)
    assert d.override and d.violations == ("S1",)
    assert ops <= 458 + extra, f"violating cycle: {ops} instructions in step (pre-compose: {458 + extra})"
    assert calls <= 14 + 11 * margins
    ops, calls, d = _work(m, CLEAN)  # S1 still latched: a clean cycle that releases nothing yet
    assert d.override and d.latched
    assert ops <= 349 + extra, f"latched clean cycle: {ops} instructions in step (pre-compose: {349 + extra})"
    assert calls <= 14 + 11 * margins
