"""GovernedLoop restart rules (issue 23: a manual reset a safety engineer signs, ISO 13849-1 5.2.2).

An operator's acknowledgement is refused, and not remembered, while the last cycle had a rule firing
(the confirm band's hold excepted: acknowledging is how it is confirmed) or a fault, or, with
``acknowledge_clear=(signal, min)``, while that reading was missing or below ``min`` (a person inside
the protective distance).
"""

import ethimon
from ethimon import GovernedLoop

SPEC = """
ethimon: 1
name: cell
signals:
  human_distance: {unit: m, range: [0, 10]}
  contact_force: {unit: N, range: [0, 1000]}
obligations:
  - {id: contact, require: contact_force <= 140, response: stop_1, release: {mode: manual, hold_cycles: 2}}
  - {id: near, require: human_distance >= 0.5, response: stop_2, release: {mode: auto, hold_cycles: 1}}
risk: {threshold: 0.5}
"""


def _loop(**kw):
    return GovernedLoop(ethimon.load_spec_text(SPEC), max_risk_age_s=None, **kw)


def _cycle(loop, d, f):
    return loop.cycle({"human_distance": d, "contact_force": f, "p_unsafe": 0.0})


def test_acknowledge_refused_while_any_rule_fires():
    loop = _loop()
    _cycle(loop, 2.0, 300.0)  # contact: stop_1, manual
    for _ in range(2):
        _cycle(loop, 2.0, 0.0)
    _cycle(loop, 0.3, 0.0)  # the auto 'near' rule fires on the last cycle
    a = loop.acknowledge("op")
    assert not a.released and "near" in a.message
    # refused is not remembered: nothing is released when the person steps back
    assert _cycle(loop, 2.0, 0.0).override
    assert _cycle(loop, 2.0, 0.0).override
    assert loop.acknowledge("op").released
    assert not _cycle(loop, 2.0, 0.0).override


def test_acknowledge_clear_refuses_with_a_person_inside_the_protective_distance():
    loop = _loop(acknowledge_clear=("human_distance", 1.5))
    _cycle(loop, 2.0, 300.0)
    for _ in range(2):
        _cycle(loop, 0.9, 0.0)  # no rule fires (0.9 >= 0.5) but inside 1.5 m
    a = loop.acknowledge("op")
    assert not a.released and "1.5" in a.message and "human_distance" in a.message
    _cycle(loop, 2.0, 0.0)
    assert loop.acknowledge("op").released


def test_acknowledge_clear_refuses_without_the_reading_and_checks_its_arguments():
    loop = _loop(acknowledge_clear=("human_distance", 1.5))
    _cycle(loop, 2.0, 300.0)
    for _ in range(2):
        _cycle(loop, 2.0, 0.0)
    loop.cycle({"contact_force": 0.0, "p_unsafe": 0.0})  # the distance is missing: a fault too
    assert not loop.acknowledge("op").released
    import pytest
    for bad in (("human_distance",), ("nope", 1.0), ("human_distance", float("nan")), ("human_distance", -1.0)):
        with pytest.raises((ValueError, TypeError)):
            _loop(acknowledge_clear=bad)
