"""risk.judges (consensus) and risk.judge_may_hold_above_tau on the Monitor itself (issue 30.3)."""

import pytest

import ethimon
from ethimon.errors import SpecError

JUDGE = "{url: 'http://127.0.0.1:9/v1', model: m}"


def _spec(extra="", judge=f"judge: {JUDGE}", tc="confirm_threshold: 0.3"):
    return ethimon.load_spec_text(f"ethimon: 1\nname: h\nrisk:\n  threshold: 0.5\n  {tc}\n  response: stop_0\n"
                                  f"  release: {{hold_cycles: 2}}\n  {judge}\n  {extra}\n")


HOLD = "judge_may_hold_above_tau: {ceiling: 0.8}"


def _step(m, r, j, task="t"):
    return m.step({"risk": r, "judge": j, "task_id": task})


def test_without_the_option_a_safe_verdict_never_lowers_a_tau_stop():
    m = ethimon.Monitor(_spec())
    d = _step(m, 0.6, 0.0)
    assert d.violations == ("risk",) and d.response.value == "stop_0"


def test_a_safe_verdict_holds_a_tau_stop_for_a_person_never_executes():
    m = ethimon.Monitor(_spec(HOLD))
    d = _step(m, 0.6, 0.05)
    assert d.override and d.violations == ("confirm",) and d.response.value == "stop_2"
    for _ in range(5):  # the judge alone never releases it
        assert _step(m, 0.6, 0.05).override
    assert m.acknowledge(task_id="t").released  # a person does
    assert not _step(m, 0.6, 0.05).override
    d = _step(m, 0.6, None)  # the verdict is gone (a failed canary, a restart): the stop is back
    assert d.violations == ("risk",)


@pytest.mark.parametrize("r, j", [(0.6, None), (0.6, 0.5), (0.6, 0.95), (0.8, 0.0), (0.95, 0.0)])
def test_no_hold_without_a_safe_verdict_or_at_the_ceiling(r, j):
    m = ethimon.Monitor(_spec(HOLD))
    d = _step(m, r, j)
    assert "risk" in d.violations or "judge" in d.violations
    assert d.response.value == "stop_0"


def test_a_risk_latch_from_before_the_verdict_gives_way_to_the_hold():
    m = ethimon.Monitor(_spec(HOLD))
    assert _step(m, 0.6, None).violations == ("risk",)  # the judge has not answered yet
    for _ in range(3):
        d = _step(m, 0.6, 0.05)
    assert d.override and d.response.value == "stop_2" and m.latched_rules == ("confirm",)
    assert m.acknowledge(task_id="t").released
    assert not _step(m, 0.6, 0.05).override


def test_the_hold_without_a_band():
    m = ethimon.Monitor(_spec(HOLD, tc=""))
    assert _step(m, 0.6, 0.05).violations == ("confirm",)
    assert m.acknowledge(task_id="t").released and not _step(m, 0.6, 0.05).override
    assert _step(m, 0.6, 0.05, task="u").violations == ("confirm",)  # a new text: asked again


def test_consensus_input_in_the_band():
    spec = _spec(judge=f"judges: [{JUDGE}, {JUDGE}]")
    m = ethimon.Monitor(spec)
    assert not _step(m, 0.4, 0.0).override  # every judge said safe
    m = ethimon.Monitor(spec)
    assert _step(m, 0.4, 1.0).violations == ("judge",)  # one said unsafe
    m = ethimon.Monitor(spec)
    assert _step(m, 0.4, None).violations == ("confirm",)  # no consensus: a person


@pytest.mark.parametrize("extra, judge, where", [
    ("judge_may_hold_above_tau: {ceiling: 0.5}", f"judge: {JUDGE}", "ceiling"),
    ("judge_may_hold_above_tau: {ceiling: 1.5}", f"judge: {JUDGE}", "ceiling"),
    ("judge_may_hold_above_tau: {ceiling: 0.8}", "", "needs a judge"),
    (f"judges: [{JUDGE}]", f"judge: {JUDGE}", "both judge and judges")])
def test_bad_tier_options_are_located_errors(extra, judge, where):
    with pytest.raises(SpecError, match=where):
        _spec(extra, judge=judge)


HOLD_SPEC = """ethimon: 1
name: hold
signals: {d: {unit: m, range: [0, 4]}}
risk:
  threshold: 0.5
  confirm_threshold: 0.3
  response: stop_0
  release: {hysteresis: 0.05, hold_cycles: 2}
  judges:
    - {url: "http://127.0.0.1:9/v1", model: a, safe_below: 0.2, unsafe_from: 0.8}
    - {url: "http://127.0.0.1:9/v1", model: b, safe_below: 0.1, unsafe_from: 0.9}
  judge_may_hold_above_tau: {ceiling: 0.8}
obligations:
  - {id: near, require: "d >= 0.5", response: stop_1}
"""


def _verify(text, tmp_path):
    from ethimon.verify import verify_spec
    p = tmp_path / "hold.yaml"
    p.write_text(text)
    return {f.name: f for f in verify_spec(ethimon.load_spec(p)).findings}


@pytest.mark.slow
@pytest.mark.parametrize("response", ["stop_0", "safe_pose"])
def test_verify_proves_the_hold_and_lint_names_it(tmp_path, response):
    """With ``risk.response: safe_pose`` (below stop_2) a τ-stop without a safe verdict is a safe pose and a
    held text stop_2: the hold property asks for an override at least the lesser of the two (it asked for
    stop_2 and was refuted on a correct monitor)."""
    pytest.importorskip("z3")
    got = _verify(HOLD_SPEC.replace("response: stop_0", f"response: {response}"), tmp_path)
    for name in ("tier.stop", "tier.hold_above_tau", "tier.band", "tier.judge_unsafe", "tier.raise_only",
                 "tier.adds_only"):
        assert got[name].status == "proved", got[name]
    assert got["tier.agrees"].status == "ok", got["tier.agrees"]
    assert "judge_may_hold_above_tau" in got["lint.confirm_band"].message and "0.8" in got["lint.confirm_band"].message


@pytest.mark.slow
def test_verify_refutes_a_monitor_whose_judge_executes_above_tau(tmp_path, monkeypatch):
    pytest.importorskip("z3")
    from ethimon.runtime._tiers import Tiers
    real_tier = Tiers.tier

    def lax(self, r, jp, get):  # a regression: the held text executes on the judge's word alone
        out = real_tier(self, r, jp, get)
        return None if out is not None and out[0] == "confirm" and r >= self.tau else out
    monkeypatch.setattr(Tiers, "tier", lax)
    assert _verify(HOLD_SPEC, tmp_path)["tier.agrees"].status == "refuted"
