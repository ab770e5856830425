"""Reload judged on meaning, and latches carried by identity (issue 25, rows 1-4).

Each test here failed on the code before the fix: a reload of the same spec turned a latched
manual stop into one ``Fault("reload")`` of the new monitor (row 1), a signal replaced by a
constant of the same name or a signal nobody reads removed passed as no weakening (rows 2, 3),
a manual risk rule's hold and hysteresis were never compared (row 4).

Review finding on reload (issue 25): a bounded response that is due must not be forgotten by a reload.
"""

from __future__ import annotations

import pytest
import ethimon
from ethimon.audit import AuditLog, read_log
from ethimon.loop import GovernedLoop, LoopConfig
from ethimon.loop._weakenings import weakenings
from tests._estimators import FakeClock

BASE = """
ethimon: 1
name: cell
signals:
  d: {unit: m, range: [0, 10]}
  f: {unit: N, range: [0, 500]}
risk: {threshold: 0.5, release: {mode: MODE, hysteresis: 0.2, hold_cycles: 50}}
on_fault: {response: safe_pose, release: FAULT}
obligations:
  - {id: keep_away, require: "d >= 0.5", response: stop_2}
  - {id: contact, require: "f <= 140", response: stop_0}
"""


def _spec(mode="auto", fault="manual"):
    return ethimon.load_spec_text(BASE.replace("MODE", mode).replace("FAULT", fault))


def _loop(spec, **kw):
    clock = FakeClock()
    return GovernedLoop(ethimon.Monitor(spec), clock=clock,
                        config=LoopConfig(period_s=0.001, max_risk_age_s=None), **kw), clock


SAFE = {"d": 2.0, "f": 0.0, "p_unsafe": 0.0}


# ------------------------------------------------------------------ row 2: signal -> constant
def test_a_signal_replaced_by_a_constant_of_the_same_name_is_a_weakening():
    old = _spec()
    new = ethimon.load_spec_text(BASE.replace("MODE", "auto").replace("FAULT", "manual")
                                 .replace("  d: {unit: m, range: [0, 10]}\n", "")
                                 .replace("obligations:", "constants: {d: {value: 100, unit: m}}\nobligations:"))
    weak, _ = weakenings(old, new)
    assert any("signal d replaced by a constant" in w for w in weak), weak
    assert any("keep_away: d means a number signal -> the constant 100.0" in w for w in weak), weak
    loop, _ = _loop(old)
    res = loop.reload(new)
    assert not res.ok and "weakens monitoring" in res.error


# ------------------------------------------------------------------ row 3: unread signal removed
def test_removing_a_signal_no_obligation_reads_is_a_weakening():
    text = BASE.replace("MODE", "auto").replace("FAULT", "manual").replace(
        "  f: {unit: N", "  guard: {unit: m, range: [0, 1]}\n  f: {unit: N")
    old = ethimon.load_spec_text(text)
    new = ethimon.load_spec_text(text.replace("  guard: {unit: m, range: [0, 1]}\n", ""))
    m_old, m_new = ethimon.Monitor(old), ethimon.Monitor(new)
    frame = {**SAFE, "guard": 7.0}  # out of the guard's range: the old spec fails closed on it
    assert m_old.step(frame).override and not m_new.step(frame).override
    weak, _ = weakenings(old, new)
    assert any("signal guard removed" in w for w in weak), weak
    assert not _loop(old)[0].reload(new).ok


# ------------------------------------------------------------------ row 4: manual risk release
@pytest.mark.parametrize("edit, needle", [
    (("hold_cycles: 50", "hold_cycles: 1"), "release hold_cycles lowered 50 -> 1"),
    (("hysteresis: 0.2", "hysteresis: 0"), "release bound τ − δ raised 0.3 -> 0.5"),
])
def test_a_manual_risk_rules_hold_and_hysteresis_are_compared(edit, needle):
    old = _spec("manual")
    new = ethimon.load_spec_text(BASE.replace("MODE", "manual").replace("FAULT", "manual").replace(*edit))
    weak, _ = weakenings(old, new)
    # the risk rule's own entry (not only the obligations' default hold)
    assert any(w.startswith(needle) for w in weak), weak
    assert not _loop(old)[0].reload(new).ok


def test_a_condition_reading_risk_changes_meaning_with_the_formula():
    text = BASE.replace("MODE", "auto").replace("FAULT", "manual").replace(
        "obligations:\n", "obligations:\n  - {id: calm, require: \"risk <= 0.45\"}\n")
    old = ethimon.load_spec_text(text)
    new = ethimon.load_spec_text(text.replace("threshold: 0.5,", "threshold: 0.5, alpha: 0.3, beta: 0.5,"))
    weak, unjudged = weakenings(old, new)
    assert any("calm: risk means R_e" in u for u in unjudged), weak


def test_an_unread_constant_changing_is_not_a_weakening():
    text = BASE.replace("MODE", "auto").replace("FAULT", "manual").replace(
        "obligations:", "constants: {spare: 1.0}\nobligations:")
    old = ethimon.load_spec_text(text)
    new = ethimon.load_spec_text(text.replace("spare: 1.0", "spare: -5.0"))
    assert weakenings(old, new) == ([], [])


# ------------------------------------------------------------------ row 1: latches carried by identity
STOP = {"d": 2.0, "f": 300.0, "p_unsafe": 0.0}


@pytest.mark.parametrize("fault", ["manual", "auto"])
def test_a_latched_manual_stop_stays_latched_across_a_reload_of_the_same_spec(fault):
    spec = _spec(fault=fault)
    loop, clock = _loop(spec)
    d = loop.cycle(STOP)
    assert d.response.value == "stop_0" and loop.monitor.latched_rules == ("contact",)
    res = loop.reload(_spec(fault=fault))
    assert res.ok
    for _ in range(60):  # far past every hold: a manual latch never releases by itself
        clock.advance(0.001)
        d = loop.cycle(SAFE)
        assert d.override and d.response.value == "stop_0", d  # not on_fault's safe_pose: the arm stays put
    assert res.wait_applied(0) and loop.monitor.latched_rules == ("contact",)
    assert not d.faults
    assert loop.acknowledge("op").released
    clock.advance(0.001)
    assert not loop.cycle(SAFE).override


def test_a_reload_that_cannot_map_a_latched_rule_is_refused(tmp_path):
    log = AuditLog(tmp_path / "a.jsonl")
    loop, clock = _loop(_spec(), audit=log)
    before = loop.spec_sha256
    loop.cycle(STOP)
    weaker_rel = ethimon.load_spec_text(BASE.replace("MODE", "auto").replace("FAULT", "manual")
                                        .replace("response: stop_0}", "response: stop_0, release: auto}"))
    res = loop.reload(weaker_rel, allow_weaker=True)  # allow_weaker does not waive a latch
    assert not res.ok and "contact: latched" in res.error and "cannot be carried over" in res.error
    gone = ethimon.load_spec_text(BASE.replace("MODE", "auto").replace("FAULT", "manual")
                                  .replace('  - {id: contact, require: "f <= 140", response: stop_0}\n', ""))
    assert "no such rule" in loop.reload(gone, allow_weaker=True).error
    clock.advance(0.001)
    assert loop.cycle(SAFE).response.value == "stop_0" and loop.spec_sha256 == before
    log.close()
    recs = [r for r in read_log(tmp_path / "a.jsonl") if r["kind"] == "reload"]
    assert [r["status"] for r in recs] == ["rejected", "rejected"] and "contact" in recs[0]["error"]


def test_a_rule_latched_between_reload_and_swap_refuses_the_swap(tmp_path):
    log = AuditLog(tmp_path / "s.jsonl")
    loop, clock = _loop(_spec(), audit=log)
    loop.cycle(SAFE)
    before = loop.spec_sha256
    other = ethimon.load_spec_text(BASE.replace("MODE", "auto").replace("FAULT", "manual")
                                   .replace("response: stop_0}", "response: stop_0, release: {mode: manual, "
                                            "hold_cycles: 80}}"))
    res = loop.reload(other)
    assert res.ok  # nothing latched yet
    loop.monitor.step(STOP)  # the contact rule latches before the loop swaps (a cycle of its own)
    clock.advance(0.001)
    d = loop.cycle(SAFE)
    assert not res.ok and not res.wait_applied(0) and "contact" in res.error
    assert loop.spec_sha256 == before and d.response.value == "stop_0"
    log.close()
    recs = [r for r in read_log(tmp_path / "s.jsonl") if r["kind"] == "reload"]
    assert recs[-1]["status"] == "rejected" and recs[-1]["stage"] == "swap" and recs[-1]["latched"] == ["contact"]


# -------- Review finding on reload (issue 25): a bounded response that is due must not be forgotten by a reload.

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
    loop = GovernedLoop(ethimon.Monitor(spec), config=LoopConfig(period_s=1.0, deadline_s=100.0))
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
    loop = GovernedLoop(ethimon.Monitor(spec), config=LoopConfig(period_s=1.0, deadline_s=100.0))
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


# -- issue 31: a reload keeps the temporal history ------------------------------------------------

_ONCE = """
ethimon: 1
name: once
signals: {x: {range: [0, 10]}, y: {range: [0, 10]}}
obligations:
  - {id: o, require: "once(y > 4, 3) implies x < 6", response: stop_2}
"""


def test_a_reload_of_the_same_file_keeps_an_event_held_by_once(tmp_path):
    path = tmp_path / "once.yaml"
    path.write_text(_ONCE)
    loop = GovernedLoop(ethimon.load_spec(path), config=LoopConfig(period_s=1.0, deadline_s=60.0))
    assert not loop.cycle({"x": 1.0, "y": 5.0, "p_unsafe": 0.0}).override  # the event
    assert loop.reload(path).ok
    d = loop.cycle({"x": 7.0, "y": 0.0, "p_unsafe": 0.0})  # swapped in before this cycle
    assert loop.stats.reloads_applied == 1
    assert d.override and d.violations == ("o",)  # the event one cycle ago is remembered
    assert loop.monitor.cycle == 2


def test_a_reload_that_cannot_carry_an_unbounded_window_is_refused_and_audited(tmp_path):
    from ethimon.loop import _reload
    text = _ONCE.replace('once(y > 4, 3)', 'since(y > 4, x > 8)')
    loop = GovernedLoop(ethimon.load_spec_text(text), config=LoopConfig(period_s=1.0, deadline_s=60.0))
    loop._reloader.history = __import__("collections").deque(loop._reloader.history, maxlen=2)
    for _ in range(3):
        loop.cycle({"x": 1.0, "y": 5.0, "p_unsafe": 0.0})
    res = loop.reload(ethimon.load_spec_text(text))
    assert res.ok and not res.wait_applied(0.0)
    loop.cycle({"x": 1.0, "y": 0.0, "p_unsafe": 0.0})
    assert not res.ok and "temporal history" in res.error and loop.stats.reloads_rejected == 1
    assert _reload.history_depth(loop.monitor.plan) is None


def test_the_history_a_reload_needs_covers_every_temporal_operator_of_the_table():
    """history_depth reads each operator's look-back from its row (language/_operators.py), not from a list
    of names: for every temporal row, used with window 3, it is at least what verify unrolls for it."""
    from ethimon.compiler import plan_of
    from ethimon.language import OPERATORS
    from ethimon.loop import _reload
    from ethimon.verify._encode import lookback

    arg = {"bool": "x > 1", "any": "x", "number": "x", "window": "3"}
    rows = [r for r in (OPERATORS.values() if hasattr(OPERATORS, "values") else OPERATORS) if r.lookback != "none"]
    assert {r.lookback for r in rows} >= {"one", "window"}
    for r in rows:
        call = f"{r.symbol}({', '.join(arg[a] for a in r.args)})"
        expr = call if r.result == "bool" else f"{call} > 1"
        spec = ethimon.load_spec_text("ethimon: 1\nname: t\nsignals:\n  x: {unit: m, range: [0, 10]}\n"
                                      f"obligations:\n  - {{id: o, require: '{expr}'}}\n")
        plan = plan_of(spec)
        need = lookback(plan, plan.obligations[0].require)
        depth = _reload.history_depth(plan)
        assert depth is not None and depth >= need + 1, (r.name, depth, need)
