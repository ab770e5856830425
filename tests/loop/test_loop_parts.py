"""Issue 33 item 1: ``GovernedLoop`` is a pacer over parts that own their state, configured by one frozen
``LoopConfig``: no mixin bases, no part reading ``self.*`` names another module assigns, a bad setting is a
``ValueError`` naming the field, and the parts are injectable."""

from __future__ import annotations

import ast
import dataclasses
import math
from pathlib import Path

import pytest

import ethimon
from ethimon.loop import AckGate, GovernedLoop, LoopConfig, Reloader

LOOP = Path(ethimon.__file__).resolve().parent / "loop"
SPEC = """
ethimon: 1
name: parts
signals:
  human_distance: {unit: m, range: [0, 10]}
obligations:
  - {id: keep_away, require: "human_distance >= 0.5", response: stop_2}
"""


def _spec():
    return ethimon.load_spec_text(SPEC)


def test_the_loop_has_no_mixin_bases():
    assert GovernedLoop.__mro__ == (GovernedLoop, object)
    for cls in (AckGate, Reloader, LoopConfig):
        assert cls.__mro__ == (cls, object)


def _self_names(cls: ast.ClassDef) -> tuple[set[str], set[str]]:
    """(names the class defines or assigns on ``self``, names it reads from ``self``)."""
    own = {n.name for n in cls.body if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))}
    own |= {t.id for n in cls.body if isinstance(n, (ast.Assign, ast.AnnAssign))
            for t in (n.targets if isinstance(n, ast.Assign) else [n.target]) if isinstance(t, ast.Name)}
    for n in cls.body:  # __slots__ = (...)
        if isinstance(n, ast.Assign) and any(isinstance(t, ast.Name) and t.id == "__slots__" for t in n.targets):
            own |= {e.value for e in ast.walk(n.value) if isinstance(e, ast.Constant) and isinstance(e.value, str)}
    reads: set[str] = set()
    for node in ast.walk(cls):
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == "self":
            (own.add if isinstance(node.ctx, ast.Store) else reads.add)(node.attr)
    return own, reads


@pytest.mark.slow  # parses six modules (about 0.1 s; more on a loaded machine)
def test_each_part_reads_only_the_state_it_owns():
    """No class of the loop reads a ``self.*`` name it does not define or assign itself (a mixin would: the
    old ``_Acknowledging`` read 15 such names, ``_Reloading`` 8)."""
    inherited = {"reasons"}  # _RestartHold extends Decision, a value class, on purpose
    for module in ("_acknowledge.py", "_config.py", "_feed.py", "_governed.py", "_reload.py", "_sink.py"):
        tree = ast.parse((LOOP / module).read_text(encoding="utf-8"))
        for cls in [n for n in tree.body if isinstance(n, ast.ClassDef)]:
            own, reads = _self_names(cls)
            foreign = sorted(reads - own - inherited)
            assert not foreign, f"{module}: {cls.name} reads self.{foreign} assigned elsewhere"


def test_loop_config_is_frozen_and_resolves_its_defaults():
    c = LoopConfig(period_s=0.01)
    assert (c.deadline, c.stall) == (0.01, 0.02)
    assert LoopConfig(period_s=0.01, deadline_s=0.005, stall_s=1.0).stall == 1.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        c.period_s = 1.0  # type: ignore[misc]
    loop = GovernedLoop(_spec(), config=LoopConfig(period_s=0.01, deadline_s=math.inf))
    assert (loop.period_s, loop.deadline_s, loop.stall_s) == (0.01, math.inf, math.inf)


@pytest.mark.parametrize("bad, field", [
    ({"period_s": 0}, "period_s"), ({"period_s": math.inf}, "period_s"), ({"period_s": "1"}, "period_s"),
    ({"deadline_s": math.nan}, "deadline_s"), ({"stall_s": -1.0}, "stall_s"), ({"watchdog_s": 0.0}, "watchdog_s"),
    ({"max_risk_age_s": -0.1}, "max_risk_age_s"), ({"audit_every_cycle": 1}, "audit_every_cycle"),
    ({"acknowledge_clear": ("human_distance",)}, "acknowledge_clear"), ({"verify": "z4"}, "verify"),
    ({"period_s": True}, "period_s"),
])
def test_a_bad_setting_is_a_value_error_naming_the_field(bad, field):
    with pytest.raises(ValueError, match=field):
        LoopConfig(**bad)


def test_a_clear_signal_the_spec_lacks_is_refused_with_the_spec_named():
    with pytest.raises(ValueError, match="'nope' is not a signal of spec 'parts'"):
        GovernedLoop(_spec(), config=LoopConfig(acknowledge_clear=("nope", 1.0)))


def test_the_old_keyword_form_and_a_non_config_are_refused():
    with pytest.raises(TypeError):
        GovernedLoop(_spec(), period_s=0.01)  # type: ignore[call-arg]
    with pytest.raises(TypeError, match="LoopConfig"):
        GovernedLoop(_spec(), config={"period_s": 0.01})  # type: ignore[arg-type]


def test_injected_parts_are_used_and_a_setting_given_twice_is_refused():
    gate, reloader = AckGate(clear=("human_distance", 1.5)), Reloader(verify=lambda spec: False)
    loop = GovernedLoop(_spec(), gate=gate, reloader=reloader, config=LoopConfig(period_s=1.0))
    assert loop.acknowledge_clear == ("human_distance", 1.5)
    res = loop.reload(_spec())
    assert not res.ok and res.error == "verification failed"
    loop.cycle({"human_distance": 1.0, "p_unsafe": 0.0})
    assert gate.clear_refusal({"human_distance": 1.0}).endswith("(acknowledge_clear)")
    with pytest.raises(ValueError, match="verify"):
        GovernedLoop(_spec(), reloader=Reloader(), config=LoopConfig(verify="smt"))
    with pytest.raises(ValueError, match="acknowledge_clear"):
        GovernedLoop(_spec(), gate=AckGate(), config=LoopConfig(acknowledge_clear=("human_distance", 1.0)))
