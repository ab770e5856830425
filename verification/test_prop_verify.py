"""``ethimon verify`` on random specs: it never crashes, its model agrees with the Monitor,
and every refuted property comes with a counterexample that replays in the Monitor."""

from __future__ import annotations

import pytest
from hypothesis import given, note, settings

pytest.importorskip("z3")

from ethimon.verify import format_table, verify_spec  # noqa: E402
from ethimon_strategies import specs  # noqa: E402


@pytest.mark.slow
@settings(max_examples=max(6, settings.default.max_examples // 4))
@given(specs(max_obligations=2, depth=2))
def test_verify_random_specs(gen):
    note(gen.text)
    rep = verify_spec(gen.spec, timeout_s=10, max_unroll=12)
    note(format_table(rep))
    assert rep.error is None
    assert rep.finding("model.agrees").status == "ok"
    for f in rep.findings:
        assert f.status in ("proved", "refuted", "unknown", "skipped", "ok", "warning")
        if f.status == "refuted":
            # the only built-in property a spec can break is definedness (a division by zero or the
            # square root of a negative on in-range input); the decision-logic properties always hold
            assert f.name.endswith(".defined"), f.name
            assert f.counterexample is not None and f.counterexample.confirmed, f.counterexample
    for name in ("risk.override", "fault.override", "resume.explained", "release.rule"):
        assert rep.finding(name).status == "proved"
