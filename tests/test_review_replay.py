"""Review findings on replay (issue 20): 'risk: none' holds R_e at 0 internally; a rule that reads R_e
cannot be checked then, so it is never reported PASS."""

from __future__ import annotations

import pytest

import ethimon

pytest.importorskip("rosbags")

from ethimon.replay import load_mapping_text, replay_bag  # noqa: E402

from test_replay_truth import bag_path, ns, write  # noqa: E402

SPEC = """
ethimon: 1
name: reads_re
signals:
  d: {unit: m, range: [0, 10]}
risk: {threshold: 0.5, confirm_threshold: 0.3}
obligations:
  - {id: far, require: "d >= 0.5"}
  - {id: risky_far, when: "risk >= 0.3", require: "d >= 1.0"}
  - {id: far_or_calm, require: "d >= 1.0 or risk < 0.1"}
"""


def test_rules_reading_re_are_not_checked_under_risk_none(tmp_path):
    # d = 0.6 on every cycle: 'far' holds; whether 'risky_far' and 'far_or_calm' hold depends on R_e,
    # which the bag does not have. Before: R_e held at 0 made them PASS (and 'confirm'), exit 0.
    bag = write(bag_path(tmp_path, "mcap"), "mcap", [(ns(i * 0.05), "/d", "f64", 0.6) for i in range(20)])
    mp = load_mapping_text("ethimon: 1\nrate_hz: 20\nmax_age_s: 0.1\nrisk: none\nsignals:\n  d: {topic: /d}\n")
    res = replay_bag(bag, ethimon.load_spec_text(SPEC), mp)
    assert res.check("far").status == "PASS"
    for rule in ("risk", "risky_far", "far_or_calm", "confirm"):
        c = res.check(rule)
        assert c.status == "NOT CHECKED" and not c.passed, (rule, c)
    assert "R_e" in res.check("risky_far").detail
