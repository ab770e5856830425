"""``ethimon verify`` as composed units (issue 33 item 1): one :class:`Unrolling` per spec, checks
that are each a name and ``run(unrolling) -> findings``, a thin :class:`Verifier`, no mixin bases."""

from __future__ import annotations

import inspect
import time

import pytest

pytest.importorskip("z3")

import ethimon  # noqa: E402
from ethimon.verify import _checks, _encode, _lints, _properties, _tiers, _unrolling, _verifier  # noqa: E402
from ethimon.verify._checks import BUDGET_NOTE, Budget, Check  # noqa: E402
from ethimon.verify._report import OK, SKIPPED, UNKNOWN, Finding  # noqa: E402
from ethimon.verify._unrolling import Unrolling  # noqa: E402
from ethimon.verify._verifier import Verifier  # noqa: E402

SPEC = """
ethimon: 1
name: units
signals: {x: {unit: m, range: [0, 1]}, y: {range: [0, 1]}}
obligations:
  - {id: near, require: x >= 0.1}
  - {id: slow, when: y > 0.5, require: "not held(x > 0.8, 3)", within_cycles: 2}
"""

JUDGED = SPEC + """risk: {threshold: 0.5, confirm_threshold: 0.3}
"""


def _verifier_of(text: str, **kw) -> Verifier:
    return Verifier(ethimon.load_spec_text(text), path="t", timeout_s=20, max_unroll=kw.pop("max_unroll", 32), **kw)


def test_no_mixin_bases_remain():
    """Every class of ``ethimon.verify`` derives only from ``object``, a class of its own module
    (``FloatUnrolled(Unrolled)``) or one outside ``verify`` (the interpreter protocol)."""
    for mod in (_checks, _encode, _lints, _properties, _tiers, _unrolling, _verifier):
        for _, cls in inspect.getmembers(mod, inspect.isclass):
            if cls.__module__ != mod.__name__:
                continue
            for base in cls.__bases__:
                assert (base is object or base.__module__ == mod.__name__
                        or not base.__module__.startswith("ethimon.verify")), (cls, base)
    assert Verifier.__bases__ == (object,) and Unrolling.__bases__ == (object,)


@pytest.mark.slow
def test_the_checks_are_named_units_in_report_order():
    v = _verifier_of(SPEC)
    checks = v.checks()
    assert all(isinstance(c, Check) and c.kind in ("property", "lint") and callable(c.run) for c in checks)
    names = [c.name for c in checks]
    assert names[:7] == ["risk.bounds", "risk.override", "fault.override", "near.defined", "near.response",
                         "slow.defined", "slow.response"]
    assert names[7:10] == ["resume.explained", "release.rule", "model.agrees"]
    assert names[10:] == ["lint.tau_range", "lint.risk_monotone", "lint.release", "lint.release_policy",
                          "lint.vacuous", "lint.contradiction", "lint.unbounded", "lint.fault_gap",
                          "lint.safe_pose_range", "lint.brakes", "lint.retreat_uncapped"]
    assert len(set(names)) == len(names)
    assert [c.name for c in v.checks(lints=False)] == names[:10]
    # the tiers add their properties after the others and their lint last
    judged = [c.name for c in _verifier_of(JUDGED).checks()]
    assert judged[10:13] == ["tier.stop", "tier.band", "tier.adds_only"] and judged[-1] == "lint.confirm_band"


@pytest.mark.slow
def test_the_unrolling_is_built_once_per_spec():
    """The horizon comes from each obligation's look-back; the encoding and decision trace are made
    on first use and then shared by every check (none is made before a check asks)."""
    v = _verifier_of(SPEC)
    u = v.unrolling
    assert u.need == {"near": 1, "slow": 2 + 2 + 1} and v.k == u.k == 5 and not u.truncated
    assert u.window_cycles(["near", "slow"]) == 4 and u.bound_note() == ""
    assert u._enc is None and u._dt is None
    assert u.enc is u.enc and u.dt is u.dt and u.dt.enc is u.enc
    assert u.spec is u.full_spec and v.plan is u.plan
    short = _verifier_of(SPEC, max_unroll=3).unrolling
    assert short.k == 3 and short.truncated and "--max-unroll 3" in short.bound_note()
    tiers = _verifier_of(JUDGED).unrolling
    assert tiers.full_spec.risk.confirm_threshold == 0.3 and tiers.spec.risk.confirm_threshold is None


def test_a_check_runs_alone_over_the_unrolling():
    u = _verifier_of(SPEC).unrolling
    by_name = {c.name: c for c in _lints.lint_checks(u)}
    (f,) = by_name["lint.unbounded"].run(u)
    assert (f.kind, f.name, f.status) == ("lint", "lint.unbounded", OK) and f.seconds == 0.0  # not timed
    (f,) = by_name["lint.tau_range"].run(u)
    assert f.status == OK and f.seconds > 0.0  # timed


def test_a_spent_budget_marks_what_a_check_left_undecided():
    u = _verifier_of(SPEC, budget_s=60).unrolling
    u.budget.deadline = time.perf_counter() - 1.0
    skipped = Check("lint", "lint.x", lambda u: [Finding("lint", "lint.x", SKIPPED, "not run")])
    (f,) = skipped.run(u)
    assert f.status == UNKNOWN and f.message == f"{BUDGET_NOTE}: not run"
    prop = Check("property", "p", lambda u: Finding("property", "p", SKIPPED, "K=3"))
    assert prop.run(u)[0].status == SKIPPED  # a property's own "skipped" is an answer, not a cut
    assert Budget(None, 1.5).check_ms() == 1500 and Budget(10.0, 20.0).check_ms() <= 10_000
    assert u.budget.unreached("lint", "lint.y").message == (f"{BUDGET_NOTE}: not checked; the run's budget "
                                                             f"(--budget-s 60) was spent")


def test_checks_build_no_encoding_of_their_own():
    """Every z3 trace a check uses comes from its unrolling (``enc``/``dt``, or ``trace``,
    ``float_trace``, ``only_trace`` for another horizon), so the plan is translated in one place."""
    for mod in (_properties, _lints, _tiers):
        text = inspect.getsource(mod)
        for made in ("Unrolled(", "FloatUnrolled(", "decision_trace(", "Unrolling("):
            assert made not in text, (mod.__name__, made)
    assert inspect.getsource(_verifier).count("Unrolling(") == 1  # the Verifier builds the one unrolling
