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


@pytest.mark.parametrize("value", ["1e300", "1e7"])
def test_a_signals_own_max_age_is_bounded_like_the_mappings(tmp_path, value):
    # Before: the top-level max_age_s was capped at 1e6 s but a signal's own was not: 'max_age_s: 1e300'
    # on one signal made it never stale (replay and live) with no error.
    from ethimon.errors import SpecError
    from ethimon.replay import load_mapping
    f = tmp_path / "m.yaml"
    f.write_text(f"ethimon: 1\nrate_hz: 10\nmax_age_s: 0.1\nsignals:\n  d: {{topic: /d, max_age_s: {value}}}\n")
    with pytest.raises(SpecError) as ei:
        load_mapping(f)
    e = ei.value
    assert (e.path, e.line, e.column) == (str(f), 5, 29), str(e)
    assert "1000000" in str(e)
