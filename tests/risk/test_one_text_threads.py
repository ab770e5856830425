"""check / simulate / replay / the loop's child score one text per call: they ask for one torch thread
(torch's default of 2 spins on busy cores; measured 10-100x slower per sentence under load)."""

from __future__ import annotations

import json

import ethimon
import ethimon.risk


class _Probs:
    def probs(self, text):
        return (0.9, 0.1)


def _recording(calls):
    def fake(spec, **kw):
        calls.append(kw)
        return _Probs()
    return fake


def test_scenario_session_loads_its_estimator_with_one_thread(monkeypatch):
    from ethimon.scenario import ScenarioSession
    calls = []
    monkeypatch.setattr(ethimon.risk, "load_estimator_for", _recording(calls))
    spec = ethimon.load_spec("specs/cobot_cell.yaml")
    assert ScenarioSession().estimator_for(spec)().probs("hand over the knife") == (0.9, 0.1)
    assert calls and calls[0]["num_threads"] == 1


def test_replay_task_scorer_loads_its_estimator_with_one_thread(monkeypatch):
    from ethimon.replay import TaskScorer
    calls = []
    monkeypatch.setattr(ethimon.risk, "load_estimator_for", _recording(calls))
    scorer = TaskScorer(ethimon.load_spec("specs/cobot_cell.yaml"))
    assert tuple(scorer("pour the coffee")) == (0.9, 0.1)
    assert calls[0]["num_threads"] == 1


def test_process_estimator_child_gets_one_thread_unless_asked():
    from ethimon.loop import ProcessEstimator
    assert json.loads(ProcessEstimator()._kwargs_json)["num_threads"] == 1
    assert json.loads(ProcessEstimator(kwargs={"num_threads": 2})._kwargs_json)["num_threads"] == 2


def test_set_max_age_is_public_and_checks_its_argument():
    import pytest
    m = ethimon.Monitor(ethimon.load_spec("specs/cobot_cell.yaml"))  # the spec sets no risk.max_age_s
    assert m.max_age_s is None
    m.set_max_age(0.5)
    assert m.max_age_s == 0.5
    d = m.step({"p_unsafe": 0.1, "human_distance": 3, "ee_speed": 0.1, "contact_force": 0, "joint_speed_max": 0})
    assert d.override and any(f.kind == "missing" and f.subject == "risk_age_s" for f in d.faults)
    with pytest.raises(ValueError):
        m.set_max_age(float("nan"))
    m.set_max_age(None)
    assert m.max_age_s is None
