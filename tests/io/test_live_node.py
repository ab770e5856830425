"""``ethimon.io.LiveNode``: what every transport's node shares (issue 33 item 3), run on a ``MemoryChannel``
so no middleware is needed: the loop at the mapping's rate with the watchdog default, the one estimator
hand-over, the audit record, the last override on close, and the refusals each transport used to write
(or, for zenoh, forget) itself."""

from __future__ import annotations

import pytest

import ethimon
from ethimon.audit import read_log
from ethimon.audit import AuditLog
from ethimon.io import MemoryChannel, load_mapping_text

from tests._estimators import FakeClock

SPEC = """
ethimon: 1
name: node
signals: {d: {unit: m, range: [0, 4]}}
risk: {threshold: 0.5, release: {mode: auto, hysteresis: 0.05, hold_cycles: 1}}
on_fault: {response: stop_1, release: {mode: auto, hold_cycles: 1}}
obligations:
  - {id: near, require: "d >= 0.5", response: stop_1}
"""
MAPPING = """
ethimon: 1
rate_hz: 50
max_age_s: 0.5
signals:
  d: {topic: /d, type: std_msgs/msg/Float64}
task: {topic: /task}
"""


class Fixed:
    def probs(self, text):
        return (0.9, 0.1)


class Closing(MemoryChannel):
    closed = 0

    def close(self):
        self.closed += 1


def _node(mapping=MAPPING, **kw):
    from ethimon.io import LiveNode
    ch = Closing(clock=kw.pop("clock", None))
    made = []

    def open_channel(topics, period_s):
        made.append((topics, period_s))
        return ch
    n = LiveNode(ethimon.load_spec_text(SPEC), load_mapping_text(mapping, "m.yaml"), open_channel, **kw)
    return n, ch, made


def test_a_node_runs_its_loop_on_the_channel_and_closes_with_an_override(tmp_path):
    log = AuditLog(tmp_path / "a.jsonl")
    clock = FakeClock(100.0)
    n, ch, made = _node(estimator=Fixed(), audit=log, clock=clock, audit_fields={"transport": "memory"})
    (topics, period), = made
    assert period == pytest.approx(0.02) and n.loop.config.watchdog_s == pytest.approx(0.1)
    assert [(t.topic, t.task) for t in topics] == [("/d", False), ("/task", True)]
    ch.publish("d", 2.0, t_log=clock())
    n.loop.cycle()
    assert ch.overrides and ch.decisions
    n.close()
    n.close()  # once
    assert ch.overrides[-1] is True and ch.closed == 1
    log.close()
    rec = next(r for r in read_log(tmp_path / "a.jsonl") if r.get("kind") == "ros2")
    assert rec["transport"] == "memory" and rec["rate_hz"] == 50.0
    assert rec["topics"] == {"/d": "std_msgs/msg/Float64", "/task": "?"}


def test_a_function_is_handed_over_as_an_estimator():
    n, ch, _ = _node(estimator=lambda text: (0.2, 0.8))  # as_estimator: text -> probabilities
    try:
        assert n.loop.risk.estimator.probs("x") == (0.2, 0.8)
    finally:
        n.close()


@pytest.mark.parametrize("mapping, kw, says", [
    (MAPPING, {"estimator": Fixed(), "estimator_kwargs": {"model_dir": "x"}}, "estimator_kwargs need"),
    (MAPPING.replace("task: {topic: /task}\n", "  p_unsafe: {topic: /p, type: std_msgs/msg/Float64}\n"),
     {"estimator": Fixed()}, "needs a task topic"),
])
def test_what_no_node_accepts(mapping, kw, says):
    with pytest.raises(ValueError, match=says):
        _node(mapping, **kw)


def test_risk_none_cannot_run_live_and_nothing_is_opened():
    m = MAPPING.replace("task: {topic: /task}\n", "risk: none\n")
    with pytest.raises(ethimon.SpecError, match="'risk: none' cannot run live") as e:
        _node(m)
    assert "m.yaml:" in str(e.value)


def test_a_channel_that_fails_to_open_leaves_nothing_running():
    from ethimon.io import LiveNode
    spec = ethimon.load_spec_text(SPEC)

    def broken(topics, period_s):
        raise RuntimeError("no wire")
    with pytest.raises(RuntimeError, match="no wire"):
        LiveNode(spec, load_mapping_text(MAPPING, "m.yaml"), broken, estimator=Fixed())


def test_zenoh_refuses_estimator_kwargs_it_would_ignore():
    """Before: ZenohMonitor took ``estimator_kwargs`` with an estimator object and silently dropped them
    (Ros2Monitor refused them); the one node builder refuses them for both."""
    pytest.importorskip("zenoh")
    pytest.importorskip("rosbags")
    from ethimon.zenoh import ZenohMonitor, zenoh_config
    m = MAPPING.replace("task: {topic: /task}", "task: {topic: /task, type: std_msgs/msg/String}")
    with pytest.raises(ValueError, match="estimator_kwargs need"):
        n = ZenohMonitor(ethimon.load_spec_text(SPEC), load_mapping_text(m, "m.yaml"), estimator=Fixed(),
                         estimator_kwargs={"model_dir": "x"}, config=zenoh_config(listen=["tcp/127.0.0.1:0"]))
        n.close()
