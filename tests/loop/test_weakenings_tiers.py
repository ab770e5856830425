"""A reload's weakenings of the tiers, the judges and the estimator, judged from the two plans
(issue 33: ``loop/_weakenings.py`` reads ``Plan.tiers`` / ``Plan.estimator``, not ``spec.risk``).

These pin what :func:`weakenings` and :func:`unmapped_latches` said when they read the specs' risk
blocks (they pass on that code too): the move to the plans changed no message.
"""

from __future__ import annotations

import ethimon
from ethimon.loop._weakenings import unmapped_latches, weakenings

BASE = """ethimon: 1
name: tiers
signals:
  d: {unit: m, range: [0, 10]}
risk:
  threshold: 0.5
  confirm_threshold: 0.3
JUDGE
obligations:
  - {id: keep_away, require: "d >= 0.5"}
"""
ONE = "  judge: {url: 'http://127.0.0.1:9/v1', model: m, safe_below: 0.2, unsafe_from: 0.8}\n"
PANEL = ("  judges:\n    - {url: 'http://127.0.0.1:9/v1', model: a}\n"
         "    - {url: 'http://127.0.0.1:8/v1', model: b}\n")


def _spec(judge: str = ONE, extra: str = "") -> ethimon.Spec:
    return ethimon.load_spec_text(BASE.replace("JUDGE\n", judge + extra))


def test_the_same_tiers_are_no_weakening():
    for j in (ONE, PANEL, ""):
        assert weakenings(_spec(j), _spec(j)) == ([], [])


def test_a_judge_removed_or_added_and_its_settings():
    w, _ = weakenings(_spec(ONE), _spec(""))
    assert "risk.judge removed (no unsafe verdict can stop a text below tau_confirm)" in w
    w, _ = weakenings(_spec(""), _spec(ONE))
    assert "risk.judge added (its safe verdict executes texts in the confirm band)" in w
    _, u = weakenings(_spec(ONE), _spec(ONE.replace("model: m", "model: m2")))
    assert u == ["risk.judge settings changed: cannot tell whether this change weakens monitoring"]
    assert weakenings(_spec(ONE), _spec(ONE.replace("safe_below: 0.2", "safe_below: 0.1"))) == ([], [])


def test_a_panel_changed_and_a_hold_ceiling_added_or_raised():
    _, u = weakenings(_spec(PANEL), _spec(PANEL.replace("model: b", "model: c")))
    assert u == ["risk.judges changed: cannot tell whether this change weakens monitoring"]
    _, u = weakenings(_spec(ONE), _spec(PANEL))
    assert "risk.judges changed: cannot tell whether this change weakens monitoring" in u
    hold = "  judge_may_hold_above_tau: {ceiling: 0.7}\n"
    w, _ = weakenings(_spec(ONE), _spec(ONE, hold))
    assert any(x.startswith("risk.judge_may_hold_above_tau added or its ceiling raised") for x in w)
    w, _ = weakenings(_spec(ONE, hold), _spec(ONE, hold.replace("0.7", "0.8")))
    assert any(x.startswith("risk.judge_may_hold_above_tau added or its ceiling raised") for x in w)
    assert weakenings(_spec(ONE, hold.replace("0.7", "0.8")), _spec(ONE, hold))[0] == []


def test_the_band_and_the_estimator():
    w, _ = weakenings(_spec(), ethimon.load_spec_text(BASE.replace("JUDGE\n", ONE).replace(
        "  confirm_threshold: 0.3\n", "  confirm_threshold: 0.4\n")))
    assert "risk.confirm_threshold 0.3 -> 0.4 (fewer texts held for a confirmation)" in w
    _, u = weakenings(_spec(), _spec(ONE, "  estimator: {backend: onnx}\n"))
    assert u == ["risk.estimator settings changed: cannot tell whether this change weakens monitoring"]
    assert weakenings(_spec(), _spec(ONE, "  estimator: {backend: auto}\n")) == ([], [])


def test_latched_tier_rules_carry_by_identity():
    assert unmapped_latches(_spec(), _spec(), ("judge", "confirm")) == []
    out = unmapped_latches(_spec(), _spec(ONE.replace("model: m", "model: m2")), ("judge", "confirm"))
    assert [x.split(":")[0] for x in out] == ["judge", "confirm"]
    assert "judge http://127.0.0.1:9/v1" in out[0]
    assert unmapped_latches(_spec(), _spec(""), ("judge",)) == ["judge: latched, and the new spec has no such rule"]


def test_a_panels_latched_judge_and_confirm_carry_to_the_same_panel():
    """Defect found moving the reads to the plan: with ``risk.judges`` (a panel) the rule identity read
    only ``risk.judge``, so a latched ``judge`` could not be carried even to the identical spec (the
    reload was refused), and a changed panel did not stop a latched ``confirm`` from being carried."""
    assert unmapped_latches(_spec(PANEL), _spec(PANEL), ("judge", "confirm")) == []
    out = unmapped_latches(_spec(PANEL), _spec(PANEL.replace("model: b", "model: c")), ("judge", "confirm"))
    assert [x.split(":")[0] for x in out] == ["judge", "confirm"]
    assert "judges http://127.0.0.1:9/v1+http://127.0.0.1:8/v1" in out[0]
