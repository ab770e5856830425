"""One way to hand an estimator to loop, the live node, replay and scenarios (issue 33 item 4):
whatever ``ethimon.risk.as_estimator`` takes (an object with ``probs(text)``, a function
``text -> probabilities``, a zero-argument factory) is taken by each, and scores the same.

Before: ``AsyncRiskSource`` and ``GovernedLoop(risk=...)`` refused a function or a factory
(``TypeError``), the live node passed its estimator on unchecked, and replay sniffed
``hasattr(score, "probs")``: five consumers, four rules."""

from __future__ import annotations

import pytest

import ethimon
from ethimon.loop import AsyncRiskSource, GovernedLoop, LoopConfig

from tests._estimators import FakeClock

SPEC = """
ethimon: 1
name: handover
signals: {d: {unit: m, range: [0, 4]}}
risk: {threshold: 0.5, release: {mode: auto, hysteresis: 0.05, hold_cycles: 1}}
on_fault: {response: stop_1, release: {mode: auto, hold_cycles: 1}}
obligations:
  - {id: near, require: "d >= 0.5", response: stop_1}
"""
P = (0.8, 0.2)


class Obj:
    def probs(self, text):
        return P


FORMS = {"object": Obj(), "function": lambda text: P, "factory": Obj}


@pytest.mark.parametrize("form", sorted(FORMS))
def test_the_async_source_takes_every_form(form):
    src = AsyncRiskSource(FORMS[form], text="carry the tray", clock=FakeClock(), start=False)
    assert src.poll_once().probs == P


@pytest.mark.parametrize("form", sorted(FORMS))
def test_the_governed_loop_takes_every_form(form):
    clock = FakeClock()
    loop = GovernedLoop(ethimon.load_spec_text(SPEC), risk=FORMS[form], clock=clock,
                        config=LoopConfig(period_s=0.01, deadline_s=1e6))
    try:
        loop.risk.set_text("carry the tray")
        assert loop.risk.poll_once().probs == P
    finally:
        loop.stop()


@pytest.mark.parametrize("form", sorted(FORMS))
def test_replay_scoring_takes_every_form(form):
    from ethimon.replay._scoring import _Lazy
    got, fault = _Lazy(ethimon.load_spec_text(SPEC), FORMS[form]).score("carry the tray", 2)
    assert got == P and fault is None


def test_what_is_no_estimator_is_still_refused():
    with pytest.raises(TypeError):
        AsyncRiskSource(object(), start=False)
    with pytest.raises(TypeError):
        AsyncRiskSource(None, start=False)  # never a silently loaded model


def test_a_builtin_scoring_function_is_taken_as_one():
    """``dict.__getitem__`` has no signature Python can read: replay always took it as ``text -> probs``
    (a test's fixed scores), and the one hand-over does too."""
    from ethimon.risk import as_estimator
    assert as_estimator({"carry the tray": P}.__getitem__).probs("carry the tray") == P
