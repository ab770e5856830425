"""Review findings on the confirm band (issue 26): an acknowledgement confirms what the operator saw."""

from __future__ import annotations

import ethimon
from ethimon.audit import AuditLog, read_log
from ethimon.loop import AsyncRiskSource, GovernedLoop, LoopConfig
from ethimon.risk import text_sha256
from ethimon.testing import ReferenceMonitor

from tests._estimators import FakeClock, ScriptedEstimator

BAND_ONLY = """ethimon: 1
name: band
signals: {d: {unit: m, range: [0, 4]}}
risk:
  threshold: 0.5
  confirm_threshold: 0.3
  release: {hysteresis: 0.05, hold_cycles: 2}
obligations:
  - {id: near, require: "d >= 0.5", response: stop_1}
"""


def test_acknowledge_naming_another_task_does_not_confirm_the_one_in_the_band():
    # The operator is shown task "a" (in the band) and confirms it; meanwhile the planner has replaced
    # it with "b" (also in the band). Before: acknowledge() confirmed the last cycle's task, "b",
    # which no person had seen, and the arm executed it.
    spec = ethimon.load_spec_text(BAND_ONLY)
    for m in (ethimon.Monitor(spec), ReferenceMonitor(spec)):
        assert m.step({"d": 2.0, "risk": 0.35, "task_id": "a"}).violations == ("confirm",)
        assert m.step({"d": 2.0, "risk": 0.35, "task_id": "b"}).override
        ack = m.acknowledge(task_id="a")
        assert not ack.released and "confirm" in ack.rules
        assert m.step({"d": 2.0, "risk": 0.35, "task_id": "b"}).override  # still held for a person
        ack = m.acknowledge(task_id="b")  # the text in the band now, confirmed as such
        assert ack.released and ack.rules == ("confirm",)
        assert not m.step({"d": 2.0, "risk": 0.35, "task_id": "b"}).override


def test_acknowledge_without_a_task_still_confirms_the_current_one():
    spec = ethimon.load_spec_text(BAND_ONLY)
    for m in (ethimon.Monitor(spec), ReferenceMonitor(spec)):
        m.step({"d": 2.0, "risk": 0.35, "task_id": "a"})
        assert m.acknowledge().released
        assert not m.step({"d": 2.0, "risk": 0.35, "task_id": "a"}).override


def test_task_id_does_not_matter_when_no_confirm_is_latched():
    spec = ethimon.load_spec_text(BAND_ONLY.replace("response: stop_1", "response: stop_1, release: {mode: manual, hold_cycles: 1}"))
    m = ethimon.Monitor(spec)
    m.step({"d": 0.1, "risk": 0.1, "task_id": "a"})
    m.step({"d": 2.0, "risk": 0.1, "task_id": "a"})
    assert m.acknowledge(task_id="zzz").released  # a manual obligation latch: no task involved


def test_loop_confirms_only_the_text_the_operator_names(tmp_path):
    clock = FakeClock()
    band = (0.55, 0.45)  # R_e 0.361: inside [0.3, 0.5)
    src = AsyncRiskSource(ScriptedEstimator(band), text="carry the tray", clock=clock, start=False)
    src.poll_once()
    log = AuditLog(tmp_path / "a.jsonl")
    loop = GovernedLoop(ethimon.load_spec_text(BAND_ONLY), risk=src,
                        clock=clock, audit=log, config=LoopConfig(period_s=0.001, deadline_s=10.0))
    shown = src.text
    assert "confirm" in loop.cycle({"d": 2.0}).violations
    src.set_text("carry the knife to the child")  # the planner's next text, also in the band
    src.poll_once()
    assert loop.cycle({"d": 2.0}).override
    ack = loop.acknowledge("op-1", reason="looked at the tray", task_sha256=text_sha256(shown))
    assert not ack.released
    assert loop.cycle({"d": 2.0}).override
    now = text_sha256(src.text)
    assert loop.acknowledge("op-1", reason="read it", task_sha256=now).released
    assert not loop.cycle({"d": 2.0}).override
    log.close()
    confirms = [r for r in read_log(tmp_path / "a.jsonl") if r.get("kind") == "confirm"]
    assert [c["task_sha256"] for c in confirms] == [now]


# -- the risk reading and the judge's verdict are for one text -----------------------------------

JUDGED = BAND_ONLY.replace("  release: {hysteresis: 0.05, hold_cycles: 2}\n",
                           "  release: {hysteresis: 0.05, hold_cycles: 1}\n"
                           "  judge: {url: 'http://127.0.0.1:9/v1', model: m}\n")
A_BAND = "move the blade near the hand"   # R_e in the band, the judge unsure
B_LOW = "wipe the table"                  # R_e low, the judge says safe


class _ByText:
    def probs(self, text):
        return (0.55, 0.45) if text == A_BAND else (0.95, 0.05)


class _Judge:
    model = "scripted"

    def judge(self, text):
        from ethimon.risk import JudgeResult
        p = 0.5 if text == A_BAND else 0.05
        return JudgeResult(p, "ok", 0.0, "?", p, "scripted", text_sha256(text))


class _Racing(AsyncRiskSource):
    """set_text() from the planner's thread lands just after the loop took its risk reading."""
    switch_to = None

    def snapshot(self):
        r = super().snapshot()
        if self.switch_to is not None:
            self.set_text(self.switch_to)
            self.switch_to = None
        return r


def test_a_text_change_during_the_cycle_never_pairs_one_texts_risk_with_anothers_verdict():
    # Before: the loop read the risk estimate (text A: in the band, the judge unsure), then the task
    # text (already B: judged safe) for task_id and the judge input; the band saw A's R_e with B's
    # safe verdict and the arm executed on a judgement of neither text.
    from ethimon.loop import AsyncJudgeSource
    clock = FakeClock()
    src = _Racing(_ByText(), text=B_LOW, clock=clock, start=False)
    src.poll_once()
    judge = AsyncJudgeSource(_Judge(), start=False)
    loop = GovernedLoop(ethimon.load_spec_text(JUDGED), risk=src, judge=judge,
                        clock=clock, config=LoopConfig(period_s=0.001, deadline_s=10.0))
    loop.cycle({"d": 2.0})
    judge.work_once()  # B judged safe, cached
    assert not loop.cycle({"d": 2.0}).override
    src.set_text(A_BAND)
    src.poll_once()
    loop.cycle({"d": 2.0})
    judge.work_once()  # A: unsure
    d = loop.cycle({"d": 2.0})
    assert d.override and "confirm" in d.violations  # A in the band: held for a person
    src.switch_to = B_LOW  # the planner switches to B while this cycle reads A's estimate
    d = loop.cycle({"d": 2.0})
    assert d.override, d


def test_judge_url_with_an_impossible_port_is_a_located_error():
    # Before: 'http://127.0.0.1:99999/v1' loaded; every judge call then failed (ValueError: Port out of
    # range), found only at run time.
    import pytest
    from ethimon.errors import SpecError
    text = ('ethimon: 1\nname: j\nrisk:\n  threshold: 0.5\n  confirm_threshold: 0.3\n'
            '  judge: {url: "http://127.0.0.1:99999/v1", model: m}\n')
    with pytest.raises(SpecError) as ei:
        ethimon.load_spec_text(text, path="j.yaml")
    assert (ei.value.line, "port") == (6, "port") and "99999" in str(ei.value)


TIERS_J = BAND_ONLY.replace("  release: {hysteresis: 0.05, hold_cycles: 2}\n",
                            "  release: {hysteresis: 0.05, hold_cycles: 1}\n"
                            "  judge: {url: 'http://127.0.0.1:9/v1', model: m}\n")


def test_a_text_the_judge_stops_ends_the_confirmation_of_the_one_before():
    # Before: a cycle where the judge's unsafe verdict fired returned before the confirmation was
    # checked against its task_id: task "a" confirmed, then "b" (judged unsafe), then "a" again
    # executed on the old confirmation, although the confirmation holds "until the text changes".
    spec = ethimon.load_spec_text(TIERS_J)
    for m in (ethimon.Monitor(spec), ReferenceMonitor(spec)):
        assert m.step({"d": 2.0, "risk": 0.35, "task_id": "a"}).violations == ("confirm",)
        assert m.acknowledge(task_id="a").released
        assert not m.step({"d": 2.0, "risk": 0.35, "task_id": "a"}).override
        assert m.step({"d": 2.0, "risk": 0.35, "task_id": "b", "judge": 0.95}).violations == ("judge",)
        for _ in range(2):
            d = m.step({"d": 2.0, "risk": 0.35, "task_id": "a"})
        assert d.override and "confirm" in d.violations, (type(m).__name__, d)


def test_confirming_while_the_judge_stops_a_text_confirms_that_text():
    # Before: the judge's cycles did not record their task_id, so a confirmation then bound to the
    # text before it ("a"), which the operator no longer saw, and "a" executed when it came back.
    spec = ethimon.load_spec_text(TIERS_J.replace("hold_cycles: 1", "hold_cycles: 5"))
    for m in (ethimon.Monitor(spec), ReferenceMonitor(spec)):
        m.step({"d": 2.0, "risk": 0.35, "task_id": "a"})
        m.step({"d": 2.0, "risk": 0.35, "task_id": "b", "judge": 0.95})
        ack = m.acknowledge()  # the text held now is b
        assert ack.released and ack.rules == ("confirm",)
        for _ in range(2):
            d = m.step({"d": 2.0, "risk": 0.35, "task_id": "a"})
        assert d.override and "confirm" in d.violations, (type(m).__name__, d)


def test_a_confirmation_needs_a_task_id_to_bind_to():
    # Before: with no task_id input (a source that gives p_unsafe only, e.g. an ethimon ros2 mapping
    # with a p_unsafe topic) a confirmation was bound to None and held for every later text while
    # R_e stayed in the band: the operator confirmed one command and the next ones executed unseen.
    spec = ethimon.load_spec_text(BAND_ONLY)
    for m in (ethimon.Monitor(spec), ReferenceMonitor(spec)):
        assert m.step({"d": 2.0, "risk": 0.35}).violations == ("confirm",)
        ack = m.acknowledge()
        assert not ack.released and ack.rules == ("confirm",) and "task_id" in ack.message
        assert m.step({"d": 2.0, "risk": 0.41}).override  # another command, still in the band: held
        for _ in range(2):  # leaving the band releases the hold by itself (hold_cycles 2)
            d = m.step({"d": 2.0, "risk": 0.2})
        assert not d.override
