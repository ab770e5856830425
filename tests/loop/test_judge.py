"""The judge tier in the GovernedLoop, end to end with a real HTTP server process on loopback."""

from __future__ import annotations

import pytest

import ethimon
from ethimon.audit import AuditLog, read_log
from ethimon.loop import AsyncJudgeSource, AsyncRiskSource, GovernedLoop, LoopConfig
from ethimon.risk import Judge

from tests._estimators import FakeClock, ScriptedEstimator, wait_for

BAND = (0.55, 0.45)  # p_unsafe 0.45: R_e 0.361, inside [0.3, 0.5)
LOW = (0.95, 0.05)   # R_e ~0.15, below the band


def _spec(url, model):
    return ethimon.load_spec_text(f"""
ethimon: 1
name: tiers
risk:
  threshold: 0.5
  confirm_threshold: 0.3
  release: {{hold_cycles: 2}}
  judge: {{url: "{url}", model: "{model}", timeout_s: 2}}
""")


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    from tests._judge_server import spawn
    proc, url = spawn(tmp_path_factory.mktemp("judge") / "req.jsonl")
    try:
        yield url
    finally:
        proc.kill()
        proc.wait(5)


def _loop(url, model, probs, tmp_path, text="carry the tray to the table"):
    clock = FakeClock()
    src = AsyncRiskSource(ScriptedEstimator(probs), text=text, clock=clock, start=False)
    src.poll_once()
    log = AuditLog(tmp_path / "a.jsonl")
    loop = GovernedLoop(_spec(url, model), risk=src, clock=clock, audit=log,
                        config=LoopConfig(period_s=0.001, deadline_s=10.0))
    return loop, src, log


def test_band_holds_until_the_judge_answers_safe(server, tmp_path):
    loop, src, log = _loop(server, "oracle:p=0.05", BAND, tmp_path)
    assert isinstance(loop.judge, AsyncJudgeSource)
    d = loop.cycle({})
    assert d.override and "confirm" in d.violations  # asked, not answered yet: the arm holds
    assert wait_for(lambda: loop.judge.result(src.text) is not None)
    loop.cycle({})
    d = loop.cycle({})
    assert not d.override  # the judge's safe verdict executes the band (after hold_cycles)
    for _ in range(5):
        loop.cycle({})
    assert loop.judge.calls == 1  # once per distinct text
    log.close()
    recs = [r for r in read_log(log.path) if r["kind"] == "judge"]
    assert len(recs) == 1 and recs[0]["status"] == "ok" and recs[0]["model"] == "oracle:p=0.05"
    assert recs[0]["text_sha256"] == AsyncJudgeSource.key(src.text) and recs[0]["latency_s"] > 0
    assert recs[0]["canary"].startswith("passed")


def test_judge_error_leaves_the_band_to_a_person_and_the_confirmation_is_audited(server, tmp_path):
    loop, src, log = _loop(server, "oracle:http500", BAND, tmp_path)
    loop.cycle({})
    assert wait_for(lambda: loop.judge.result(src.text) is not None)
    for _ in range(5):
        d = loop.cycle({})
        assert d.override and d.violations == ("confirm",)  # never execute on a missing judgement
    ack = loop.acknowledge("op-7", reason="looked at the tray")
    assert ack.released and ack.rules == ("confirm",)
    assert not loop.cycle({}).override
    src.set_text("carry the other tray")  # a new text: asked again, held again
    src.poll_once()
    assert loop.cycle({}).violations == ("confirm",)
    log.close()
    recs = read_log(log.path)
    conf = [r for r in recs if r["kind"] == "confirm"]
    assert len(conf) == 1 and conf[0]["task_text"] == "carry the tray to the table" and conf[0]["operator"] == "op-7"
    assert [r["status"] for r in recs if r["kind"] == "judge"][0] == "error"


def test_judge_unsafe_below_the_band_stops(server, tmp_path):
    loop, src, log = _loop(server, "oracle:p=0.95", LOW, tmp_path)
    assert not loop.cycle({}).override  # below tau_confirm: executes while the judge is asked
    assert wait_for(lambda: loop.judge.result(src.text) is not None)
    d = loop.cycle({})
    assert d.override and d.violations == ("judge",)
    log.close()


def test_no_judge_the_band_is_a_person_s(tmp_path):
    clock = FakeClock()
    src = AsyncRiskSource(ScriptedEstimator(BAND), text="t", clock=clock, start=False)
    src.poll_once()
    spec = _spec("http://127.0.0.1:9/v1", "m")
    loop = GovernedLoop(spec, risk=src, clock=clock, judge=None, config=LoopConfig(period_s=0.001, deadline_s=10.0))
    assert loop.judge is None
    for _ in range(3):
        assert loop.cycle({"judge": 0.0}).violations == ("confirm",)  # a judge key in the signals is dropped
    assert loop.acknowledge("op").released
    assert not loop.cycle({}).override


def test_api_key_never_reaches_the_audit_log(server, tmp_path, monkeypatch):
    monkeypatch.setenv("ETHIMON_LOOP_KEY", "sk-loop-secret")
    clock = FakeClock()
    src = AsyncRiskSource(ScriptedEstimator(BAND), text="t", clock=clock, start=False)
    src.poll_once()
    log = AuditLog(tmp_path / "k.jsonl")
    loop = GovernedLoop(_spec(server, "p=0.05"), risk=src, clock=clock, audit=log,
                        judge=Judge(server, "p=0.05", api_key_env="ETHIMON_LOOP_KEY", canaries=None),
                        config=LoopConfig(period_s=0.001, deadline_s=10.0))
    loop.cycle({})
    assert wait_for(lambda: loop.judge.result("t") is not None)
    for _ in range(3):
        loop.cycle({})
    log.close()
    assert "sk-loop-secret" not in (tmp_path / "k.jsonl").read_text()


def test_reload_with_another_judge_asks_the_new_one(server, tmp_path):
    loop, src, log = _loop(server, "oracle:http500", BAND, tmp_path)
    loop.cycle({})
    assert wait_for(lambda: loop.judge.result(src.text) is not None)
    assert loop.cycle({}).violations == ("confirm",)
    new = _spec(server, "oracle:p=0.05")
    # latches are carried by identity (issue 25): the band's latch is released by its judge's verdict,
    # so a spec with another judge cannot take it over while it holds; the running spec stays
    res = loop.reload(new, allow_weaker=True)  # a changed judge cannot be told
    assert not res.ok and "confirm: latched" in res.error, res.error
    assert loop.acknowledge("op").released  # the operator confirms the task: nothing latched now
    assert not loop.cycle({}).override
    res = loop.reload(new, allow_weaker=True)
    assert res.ok, res.error
    loop.cycle({})
    assert wait_for(lambda: loop.judge.result(src.text) is not None)
    assert loop.judge.result(src.text).status == "ok"
    for _ in range(12):
        d = loop.cycle({})
    assert not d.override  # the new judge's safe verdict: no confirm hold
    log.close()


def test_a_slow_judge_call_does_not_queue_other_texts(server):
    """Issue 31.5: a judge call for text A that takes 3 s does not hold up text B's answer."""
    src = AsyncJudgeSource(Judge(server, "slowfor=SLOWTEXT", timeout_s=5, canaries=None))
    try:
        src.ask("SLOWTEXT carry the tray")
        src.ask("wipe the table")
        assert wait_for(lambda: src.result("wipe the table") is not None, timeout=2.0)
        assert src.result("SLOWTEXT carry the tray") is None  # still being asked
        assert src.result("wipe the table").status == "ok"
    finally:
        src.stop(timeout=0.0)


def test_a_key_with_a_newline_never_reaches_the_audit_log(server, tmp_path, monkeypatch):
    monkeypatch.setenv("ETHIMON_LOOP_KEY", "sk-loop-newline\n")
    clock = FakeClock()
    src = AsyncRiskSource(ScriptedEstimator(BAND), text="t", clock=clock, start=False)
    src.poll_once()
    log = AuditLog(tmp_path / "n.jsonl")
    loop = GovernedLoop(_spec(server, "p=0.05"), risk=src, clock=clock, audit=log,
                        judge=Judge(server, "p=0.05", api_key_env="ETHIMON_LOOP_KEY", canaries=None),
                        config=LoopConfig(period_s=0.001, deadline_s=10.0))
    loop.cycle({})
    assert wait_for(lambda: loop.judge.result("t") is not None)
    for _ in range(3):
        assert loop.cycle({}).violations == ("confirm",)  # no judgement: the band holds
    log.close()
    text = (tmp_path / "n.jsonl").read_text()
    assert "sk-loop-newline" not in text and "control character" in text
