"""Release policy per rule and for faults (issue 14, item 2).

Each rule (an obligation, the risk rule, the fault rule) has its own latch, released
automatically once its condition held ``hold_cycles`` cycles in a row, or manually by
``Monitor.acknowledge()`` (refused until then). Defaults: faults and stop categories 0
and 1 manual, stop 2 and safe_pose automatic, the hold from ``risk.release.hold_cycles``.
"""

from __future__ import annotations

import json
import math

import pytest

import ethimon
from ethimon import Response
from ethimon.runtime import Acknowledgement
from ethimon.testing import ReferenceMonitor
from ethimon.verify import verify_spec

BASE = """
ethimon: 1
name: rp
signals:
  d: {unit: m, range: [0, 10]}
  f: {unit: N, range: [0, 1000]}
risk: {threshold: 0.5, release: {mode: auto, hysteresis: 0.05, hold_cycles: 3}}
"""

OBS = """
obligations:
  - {id: keep_away, require: "d >= 0.5", response: stop_2}
  - {id: contact, require: "f <= 140", response: stop_0}
  - {id: slow, require: "d >= 1.0", response: safe_pose}
"""


def spec(extra: str = "", obligations: str = OBS) -> ethimon.Spec:
    return ethimon.load_spec_text(BASE + extra + obligations, "rp.yaml")


def ok(**kw):
    base = {"p_unsafe": 0.05, "d": 5.0, "f": 0.0}
    base.update(kw)
    return base


def both(s):
    return ethimon.Monitor(s), ReferenceMonitor(s)


def step2(m, ref, frame):
    a, b = m.step(frame), ref.step(frame)
    assert (a.override, a.response, a.violations, a.latched, bool(a.faults), a.awaiting_release) == \
        (b.override, b.response, b.violations, b.latched, bool(b.faults), b.awaiting_release), (a, b)
    assert m.latched_rules == ref.latched_rules
    return a


# -- the spec format -------------------------------------------------------------------------

def test_defaults_manual_for_faults_and_stop_0_1_auto_for_stop_2_and_safe_pose():
    s = spec(obligations=OBS + '  - {id: joint, require: "d <= 9", response: stop_1}\n')
    got = {ob.id: s.obligation_release(ob) for ob in s.obligations}
    assert got == {"keep_away": ("auto", 3), "contact": ("manual", 3), "slow": ("auto", 3), "joint": ("manual", 3)}
    assert s.fault_release() == ("manual", 3)
    assert s.on_fault == "safe_pose"  # still the response text, whatever form the file used


@pytest.mark.parametrize("text, want", [
    ("on_fault: stop_1\n", ("stop_1", ("manual", 3))),
    ("on_fault: {response: stop_0, release: auto}\n", ("stop_0", ("auto", 3))),
    ("on_fault: {response: stop_2, release: {mode: auto, hold_cycles: 7}}\n", ("stop_2", ("auto", 7))),
    ("on_fault: {release: manual}\n", ("safe_pose", ("manual", 3))),
    ("on_fault: {}\n", ("safe_pose", ("manual", 3))),
])
def test_on_fault_short_and_long_forms(text, want):
    s = spec(text)
    assert (s.on_fault, s.fault_release()) == want
    assert ethimon.Monitor(s).plan.on_fault is Response(want[0])
    plan = ethimon.Monitor(s).plan
    assert (plan.fault_rule.mode, plan.fault_rule.hold) == want[1]


def test_obligation_release_forms():
    s = spec(obligations="""
obligations:
  - {id: a, require: "d >= 0.5", response: stop_0, release: auto}
  - {id: b, require: "d >= 0.5", release: manual}
  - {id: c, require: "d >= 0.5", response: stop_1, release: {mode: auto, hold_cycles: 5}}
  - {id: e, require: "d >= 0.5", response: stop_1, release: {hold_cycles: 2}}
""")
    got = [s.obligation_release(ob) for ob in s.obligations]
    assert got == [("auto", 3), ("manual", 3), ("auto", 5), ("auto", 2)]  # a mapping without mode: auto


@pytest.mark.parametrize("text, where, words", [
    ("on_fault: sometimes\n", (8, 11), "expected safe_pose, stop_2, stop_1 or stop_0"),
    ("on_fault: {response: stop_1, release: later}\n", (8, 39), "expected auto, manual or {mode"),
    ("on_fault: {response: stop_1, relase: auto}\n", (8, 30), "did you mean 'release'"),
    ("on_fault: {response: stop_1, release: {mode: auto, hysteresis: 0.1}}\n", (8, 52), "unknown key 'hysteresis'"),
    ("on_fault: {response: stop_9}\n", (8, 22), "on_fault.response"),
])
def test_bad_fault_policies_are_located(text, where, words):
    with pytest.raises(ethimon.SpecError) as ei:
        spec(text)
    e = ei.value
    assert (e.line, e.column) == where and words in str(e), str(e)


@pytest.mark.parametrize("rel, words", [
    ("3", "valid dictionary"), ("[auto]", "valid dictionary"), ("sometimes", "expected auto, manual"),
    ("{mode: later}", "obligations[0].release.mode"), ("{hold_cycles: 0}", "greater than or equal to 1"),
    ("{hold_cycles: 2.0}", "whole number"),
])
def test_bad_obligation_release_is_located(rel, words):
    with pytest.raises(ethimon.SpecError) as ei:
        spec(obligations=f'obligations:\n  - {{id: a, require: "d >= 0.5", release: {rel}}}\n')
    assert ei.value.line == 9 and words in str(ei.value), str(ei.value)


def test_fault_is_a_reserved_obligation_id():
    with pytest.raises(ethimon.SpecError, match="'fault' is reserved"):
        spec(obligations='obligations:\n  - {id: fault, require: "d >= 0.5"}\n')


# -- the monitor -------------------------------------------------------------------------------

def test_stop_0_waits_for_an_acknowledgement_that_is_refused_while_the_rule_fails():
    m, ref = both(spec())
    d = step2(m, ref, ok(f=300.0))
    assert d.override and d.response is Response.STOP_0 and d.violations == ("contact",)
    a = m.acknowledge()
    assert a == ref.acknowledge()
    assert not a and a.rules == ("contact",) and a.message == "refused: contact still fails"
    for i in range(1, 3):
        d = step2(m, ref, ok())
        assert d.override and d.latched and not d.awaiting_release
        a = m.acknowledge()
        assert a == ref.acknowledge() and not a and a.message == f"refused: contact has held {i} of 3 cycles"
    for _ in range(20):  # ready, and it stays ready (and latched): nothing releases it by itself
        d = step2(m, ref, ok())
        assert d.override and d.latched and d.awaiting_release and d.response is Response.STOP_0
    assert "latched: waiting for an operator acknowledgement (Monitor.acknowledge())" in d.reasons
    a = m.acknowledge()
    assert a == ref.acknowledge()
    assert a and a.released and a.rules == ("contact",) and a.message == "released: contact"
    assert not m.latched and m.latched_rules == ()
    assert not step2(m, ref, ok()).override
    assert m.acknowledge() == Acknowledgement(False, (), "nothing awaits an acknowledgement")


def test_a_new_violation_after_acknowledging_latches_again():
    m, ref = both(spec())
    step2(m, ref, ok(f=300.0))
    for _ in range(3):
        step2(m, ref, ok())
    assert m.acknowledge() and ref.acknowledge()
    d = step2(m, ref, ok(f=500.0))
    assert d.override and d.response is Response.STOP_0 and not d.awaiting_release


def test_auto_rules_release_on_their_own_condition_and_the_response_follows_what_is_latched():
    m, ref = both(spec())
    d = step2(m, ref, ok(d=0.3))  # keep_away (stop_2) and slow (safe_pose)
    assert d.response is Response.STOP_2 and set(m.latched_rules) == {"keep_away", "slow"}
    # keep_away holds again at d = 0.8 (slow still fails): keep_away releases after 3 cycles
    responses = [step2(m, ref, ok(d=0.8)).response for _ in range(4)]
    assert responses == [Response.STOP_2, Response.STOP_2, Response.SAFE_POSE, Response.SAFE_POSE]
    assert m.latched_rules == ("slow",)
    ds = [step2(m, ref, ok(d=5.0)) for _ in range(3)]
    assert [d.override for d in ds] == [True, True, False]
    assert not any(d.awaiting_release for d in ds)
    assert m.acknowledge() == Acknowledgement(False, (), "nothing awaits an acknowledgement")


def test_acknowledge_leaves_automatic_latches_to_their_rule():
    m, ref = both(spec())
    step2(m, ref, ok(f=300.0, d=0.3))  # contact (manual) + keep_away, slow (auto)
    for _ in range(2):
        d = step2(m, ref, ok())
    assert not d.awaiting_release  # contact has held 2 of 3 cycles
    d = step2(m, ref, ok())  # the third clean cycle: the auto rules release, contact is ready
    assert d.override and d.awaiting_release and m.latched_rules == ("contact",)
    assert m.acknowledge().rules == ("contact",) and ref.acknowledge().rules == ("contact",)
    assert not step2(m, ref, ok()).override


def test_acknowledge_is_all_or_nothing():
    s = spec(obligations=OBS + '  - {id: joint, require: "d <= 9", response: stop_1}\n')
    m, ref = both(s)
    step2(m, ref, ok(f=300.0, d=9.5))  # contact (stop_0) and joint (stop_1), both manual
    for _ in range(3):
        step2(m, ref, ok(d=9.5))  # joint still fails, contact holds
    a = m.acknowledge()
    assert a == ref.acknowledge() and not a and a.rules == ("joint",) and a.message == "refused: joint still fails"
    assert set(m.latched_rules) == {"contact", "joint"}  # contact was not released on its own
    for _ in range(3):
        d = step2(m, ref, ok())
    assert d.awaiting_release and d.response is Response.STOP_0
    a = m.acknowledge()
    assert a.rules == ("contact", "joint") and a == ref.acknowledge()


def test_fault_latch_is_manual_by_default_and_counts_valid_cycles():
    m, ref = both(spec("on_fault: stop_1\n"))
    for frame in (ok(d=None), ok(d=math.nan), ok()):
        d = step2(m, ref, {k: v for k, v in frame.items() if v is not None})
    assert d.override and d.response is Response.STOP_1 and m.latched_rules == ("fault",)
    assert m.acknowledge().message == "refused: fault has held 1 of 3 cycles"
    for _ in range(2):
        d = step2(m, ref, ok())
    assert d.awaiting_release and d.as_dict()["awaiting_release"] is True
    json.dumps(d.as_dict())
    assert m.acknowledge() and ref.acknowledge()
    assert not step2(m, ref, ok()).override


def test_fault_latch_opted_in_to_auto_release():
    m, ref = both(spec("on_fault: {response: stop_1, release: {mode: auto, hold_cycles: 2}}\n"))
    step2(m, ref, ok(f=math.nan))
    assert [step2(m, ref, ok()).override for _ in range(2)] == [True, False]


def test_external_fault_with_a_decision_latches_the_fault_rule():
    m = ethimon.Monitor(spec("on_fault: stop_2\n"))
    d = m.fault("watchdog", decision=m.step(ok()))
    assert d.override and d.response is Response.STOP_2 and m.latched_rules == ("fault",)
    assert not m.acknowledge()
    for _ in range(3):
        d = m.step(ok())
    assert d.awaiting_release and m.acknowledge()


def test_a_fault_restarts_every_count():
    m, ref = both(spec())
    step2(m, ref, ok(f=300.0))
    step2(m, ref, ok())
    step2(m, ref, ok())
    step2(m, ref, ok(d=math.nan))  # two clean cycles, then a fault: contact's count is 0 again
    for _ in range(2):
        d = step2(m, ref, ok())
    assert not d.awaiting_release
    d = step2(m, ref, ok())
    assert d.awaiting_release and set(m.latched_rules) == {"contact", "fault"}


def test_risk_rule_release_manual_is_acknowledged_below_tau_minus_delta():
    m, ref = both(ethimon.load_spec_text(BASE.replace("mode: auto", "mode: manual") + OBS, "rp.yaml"))
    step2(m, ref, ok(risk=0.9))
    for _ in range(5):
        d = step2(m, ref, ok(risk=0.47))  # below tau, not below tau - delta: never ready
    assert not d.awaiting_release and not m.acknowledge()
    for _ in range(3):
        d = step2(m, ref, ok(risk=0.2))
    assert d.awaiting_release and m.acknowledge().rules == ("risk",)


def test_release_forces_every_latch():
    m, ref = both(spec())
    step2(m, ref, ok(f=300.0, d=math.nan))
    m.release()
    ref.release()
    assert not m.latched and not step2(m, ref, ok()).override


def test_decision_equality_and_repr_carry_awaiting_release():
    a = ethimon.Decision(True, Response.STOP_0, (), (), 0.1, 3, True, (), True)
    b = ethimon.Decision(True, Response.STOP_0, (), (), 0.1, 3, True, ())
    assert a != b and "awaiting_release=True" in repr(a) and "awaiting_release" not in repr(b)
    assert b.as_dict()["awaiting_release"] is False


def test_step_stays_allocation_free_of_new_objects_per_rule_while_latched():
    """The release pass works in preallocated slots: the latch lists are the same objects."""
    m = ethimon.Monitor(spec())
    lat, run = m._latches.lat, m._latches.run
    m.step(ok(f=300.0, d=0.3))
    for _ in range(50):
        m.step(ok())
    assert m._latches.lat is lat and m._latches.run is run and len(lat) == len(m.obligation_ids) + 5  # + risk, fault, judge, confirm, pending


# -- verify and lint ------------------------------------------------------------------------------

@pytest.mark.slow
def test_lint_warns_on_auto_release_after_a_stop_that_cut_power():
    s = spec("on_fault: {response: stop_1, release: auto}\n",
             obligations='obligations:\n  - {id: contact, require: "f <= 140", response: stop_0, release: auto}\n')
    rep = verify_spec(s)
    warns = [f.message for f in rep.findings if f.name == "lint.release_policy"]
    assert len(warns) == 2 and all(f.status == "warning" for f in rep.findings if f.name == "lint.release_policy")
    assert any("'contact': response stop_0 with release: auto" in w for w in warns)
    assert any("on_fault release: auto" in w and "cut power" in w for w in warns)
    assert rep.finding("release.rule").status == "proved"


@pytest.mark.slow
def test_lint_lists_the_manual_rules_by_default():
    rep = verify_spec(spec())
    f = rep.finding("lint.release_policy")
    assert f.status == "ok" and "manual release for contact, fault" in f.message
    rr = rep.finding("release.rule")
    assert rr.status == "proved" and "manual (Monitor.acknowledge() only): contact, fault" in rr.message
    assert "keep_away after 3 cycles of holding" in rr.message
    assert rep.finding("model.agrees").status == "ok"


def test_lint_warns_on_a_risk_stop_1_that_releases_by_itself():
    s = ethimon.load_spec_text(BASE.replace("threshold: 0.5,", "threshold: 0.5, response: stop_1,"), "rp.yaml")
    rep = verify_spec(s)
    assert any(f.status == "warning" and "risk.response stop_1 with risk.release.mode auto" in f.message
               for f in rep.findings)


@pytest.mark.slow
def test_model_agrees_is_refuted_when_the_monitor_releases_a_manual_rule(monkeypatch):
    """A broken monitor (manual rules releasing by themselves) disagrees with the decision model."""
    from ethimon.runtime._latches import Latches
    orig = Latches.release_pass

    def broken(self, below):
        self.manual = tuple(False for _ in self.manual)
        return orig(self, below)
    monkeypatch.setattr(Latches, "release_pass", broken)
    s = ethimon.load_spec_text(BASE.replace("hold_cycles: 3", "hold_cycles: 1") + OBS, "rp.yaml")
    rep = verify_spec(s)  # hold 1: the model's short sampled traces (2 cycles) reach a release
    f = rep.finding("model.agrees")
    assert f.status == "refuted" and f.counterexample is not None, f


def test_reload_refuses_a_release_made_easier():
    from ethimon.loop._weakenings import weakenings
    old = spec("on_fault: stop_1\n")
    new = spec("on_fault: {response: stop_1, release: auto}\n", obligations=OBS.replace(
        "response: stop_0}", "response: stop_0, release: auto}").replace(
        "response: stop_2}", "response: stop_2, release: {hold_cycles: 1}}"))
    weak, _ = weakenings(old, new)
    assert "obligation contact: release manual -> auto (its latch now releases by itself)" in weak
    assert "obligation keep_away: release hold_cycles lowered 3 -> 1" in weak
    assert "on_fault: release manual -> auto (its latch now releases by itself)" in weak
    assert weakenings(new, old)[0] == []


def test_ethimon_lint_prints_release_policy_warnings(tmp_path, capsys):
    from ethimon.cli import main
    path = tmp_path / "auto_after_stop0.yaml"
    path.write_text(BASE + "on_fault: {response: stop_1, release: auto}\n"
                    + 'obligations:\n  - {id: contact, require: "f <= 140", response: stop_0, release: auto}\n')
    assert main(["lint", str(path)]) == 0  # warnings, not errors
    out = capsys.readouterr().out.splitlines()
    assert out[0].endswith("ok (rp, 1 obligations)")
    assert out[1].startswith(f"{path}: warning: obligation 'contact': response stop_0 with release: auto")
    assert out[2].startswith(f"{path}: warning: on_fault release: auto") and len([o for o in out if "model card" not in o]) == 3
    assert main(["lint", str(tmp_path / "none.yaml")]) == 2


@pytest.mark.slow
def test_json_schema_accepts_the_short_and_long_forms():
    jsonschema = pytest.importorskip("jsonschema")
    schema = ethimon.Spec.model_json_schema()
    base = {"ethimon": 1, "name": "x", "obligations": [{"id": "a", "require": "true"}]}
    for on_fault in ("stop_1", {"response": "stop_0", "release": "auto"},
                     {"response": "stop_0", "release": {"mode": "manual", "hold_cycles": 3}}):
        for release in (None, "manual", {"mode": "auto", "hold_cycles": 2}):
            doc = {**base, "on_fault": on_fault}
            if release is not None:
                doc["obligations"] = [{"id": "a", "require": "true", "release": release}]
            jsonschema.validate(doc, schema)
    for bad in ({**base, "on_fault": "sometimes"},
                {**base, "obligations": [{"id": "a", "require": "true", "release": "later"}]}):
        with pytest.raises(jsonschema.ValidationError):
            jsonschema.validate(bad, schema)
