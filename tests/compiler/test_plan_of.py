"""A Spec never points at its Plan: the compiler finds (or compiles) it; Monitor takes either."""

from __future__ import annotations

import ethimon
from ethimon.compiler import Plan, compile_plan, plan_of, stateless_slots

SPEC = """
ethimon: 1
name: p
signals: {d: {unit: m, range: [0, 10]}, v: {unit: m/s}}
obligations:
  - {id: near, require: "d >= 0.5"}
  - {id: slow, require: "held(v <= 1, 3)"}
  - {id: fast, require: "v <= 2 or risk < 0.2"}
"""


def test_spec_is_plain_data_and_plan_of_finds_the_compiled_plan():
    spec = ethimon.load_spec_text(SPEC)
    assert not hasattr(spec, "_program")
    plan = plan_of(spec)
    assert isinstance(plan, Plan) and plan.spec is spec and plan_of(spec) is plan and plan_of(plan) is plan
    other = ethimon.load_spec_text(SPEC)  # an equal spec is another object: its own plan
    assert plan_of(other) is not plan and plan_of(other).spec is other


def test_monitor_takes_a_plan_or_a_spec():
    spec = ethimon.load_spec_text(SPEC)
    frame = {"d": 0.2, "v": 0.1, "p_unsafe": 0.05}
    a = ethimon.Monitor(compile_plan(spec)).step(frame)
    b = ethimon.Monitor(spec).step(frame)
    assert a == b and "near" in a.violations
    assert ethimon.Monitor(spec).plan is plan_of(spec)


def test_slot_map_is_built_once_at_compile_time():
    plan = plan_of(ethimon.load_spec_text(SPEC))
    assert plan.slots == {"d": 0, "v": 1, "risk": 2}
    near, slow, fast = plan.obligations
    assert stateless_slots(plan, near) == frozenset({0})
    assert stateless_slots(plan, slow) is None  # temporal: keeps state
    assert stateless_slots(plan, fast) == frozenset({1, 2})
    assert not hasattr(plan, "risk") and plan.on_fault is ethimon.Response.SAFE_POSE  # the rule: plan.risk_plan


def test_a_loaded_spec_carries_its_plan_none_recompiled(monkeypatch):
    """No hidden cache by the spec's address: 100 live specs each carry their plan (issue 24)."""
    from ethimon.compiler import _plans

    specs = [ethimon.load_spec_text(SPEC) for _ in range(100)]
    plans = [plan_of(s) for s in specs]
    calls = []
    real = _plans.compile_plan
    monkeypatch.setattr(_plans, "compile_plan", lambda spec: calls.append(spec) or real(spec))
    for spec, plan in zip(specs, plans):
        assert ethimon.Monitor(spec).plan is plan and plan_of(spec) is plan and plan.spec is spec
    assert calls == []  # none recompiled, however many specs are alive


def test_the_carried_plan_is_no_part_of_the_specs_value():
    import copy
    import pickle

    a, b = ethimon.load_spec_text(SPEC), ethimon.load_spec_text(SPEC)
    assert a == b and plan_of(a) is not plan_of(b)
    c = a.model_copy()  # a copy is another spec: it gets its own plan, the original keeps its own
    assert plan_of(c).spec is c and plan_of(a).spec is a
    d = copy.deepcopy(a)
    assert d == a and plan_of(d).spec is d
    e = pickle.loads(pickle.dumps(a))  # the plan does not travel in a pickle; it is compiled again
    assert e == a and plan_of(e).spec is e


def test_every_consumer_reads_the_releases_resolved_in_the_plan():
    """Holds, manual flags, τ and the release cut are resolved once in the plan: a plan whose risk
    rule holds 2 cycles (the spec says 10) is followed by the monitor, the reference and offline."""
    import dataclasses

    import numpy as np

    from ethimon.offline import check_trace
    from ethimon.testing import ReferenceMonitor

    assert [r.name for r in plan_of(ethimon.load_spec_text(SPEC)).rules()] == [
        "near", "slow", "fast", "risk", "fault", "judge", "confirm"]
    spec = ethimon.load_spec_text(SPEC.replace('held(v <= 1, 3)', 'v <= 1'))  # no start-up window
    plan = plan_of(spec)
    assert plan.risk_rule.hold == 10 and not plan.risk_rule.manual and plan.fault_rule.manual
    assert (plan.threshold, plan.release_cut) == (spec.risk.threshold, float(plan.release_exact))
    short = dataclasses.replace(plan, risk_rule=dataclasses.replace(plan.risk_rule, hold=2))
    qs = [0.99] + [0.0] * 12
    frames = [{"d": 1.0, "v": 0.1, "p_unsafe": q} for q in qs]
    for make in (ethimon.Monitor, ReferenceMonitor):
        for p, hold in ((plan, 10), (short, 2)):  # fired at 0, released on the hold-th good cycle
            m = make(p)
            held = [m.step(f).override for f in frames]
            assert held == [True] * hold + [False] * (len(qs) - hold), (make, p.risk_rule)
    cols = {"d": np.ones(len(qs)), "v": np.full(len(qs), 0.1), "p_unsafe": np.array(qs)}
    for p, hold in ((plan, 10), (short, 2)):
        for method in ("vector", "step"):
            res = check_trace(p, cols, method=method)
            assert list(res.override) == [True] * hold + [False] * (len(qs) - hold), (method, hold)
    try:
        dataclasses.replace(plan, threshold=None)
    except TypeError as exc:
        assert "compile_plan" in str(exc)
    else:
        raise AssertionError("a plan without its resolved rules was accepted")


def test_the_hot_path_copy_of_r_e_equals_the_one_definition():
    """Monitor.step inlines the two-class R_e (hot path): bit for bit the value of two_class_risk,
    which the slow path, offline (numpy), risk_from_p_unsafe and verify (z3) all call."""
    import numpy as np

    from ethimon.compiler._risk_formula import risk_from_p_unsafe, two_class_risk
    from ethimon.offline import check_trace

    qs = sorted({i / 200 for i in range(201)} | {0.5 - 1e-12, 0.5 + 1e-12, 1e-300, 1.0 - 1e-16, 0.3, 0.7})
    for alpha, beta, gamma in ((0.6, 0.2, 0.2), (0.9, 0.05, 0.05), (0.3, 0.5, 0.4), (1.0, 0.0, 0.0)):
        for variance in ("sample", "population"):
            spec = ethimon.load_spec_text(
                "ethimon: 1\nname: r\nrisk: {threshold: 1.0, alpha: %r, beta: %r, gamma: %r, variance: %s}\n"
                % (alpha, beta, gamma, variance))
            m = ethimon.Monitor(spec)
            want = [two_class_risk(q, alpha, beta, gamma, variance) for q in qs]
            hot = [m.step({"p_unsafe": q}).risk for q in qs]  # built-in floats: the inlined copy
            slow = [m.step({"p_unsafe": np.float64(q)}).risk for q in qs]  # not a float: _risk_p
            vec = check_trace(spec, {"p_unsafe": np.array(qs)}).risk.tolist()
            assert hot == want and slow == want and vec == want, (alpha, beta, gamma, variance)
            assert [risk_from_p_unsafe(q, alpha, beta, gamma, variance) for q in qs] == want
