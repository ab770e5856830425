"""The z3 encoding that ``ethimon verify`` proves things about ≡ the real Monitor.

A proof is only as good as the translation it runs on. Here the translation
of random specs (``ethimon.verify._encode``: expressions, temporal operators
unrolled, bounded response, severity, latch and hysteresis release) is
evaluated on concrete random traces and compared, cycle by cycle, with
:class:`ethimon.Monitor` on the same inputs: violations, override and response.
The definedness condition must be true exactly on the cycles where the
monitor does not report an internal error.
"""

from __future__ import annotations

import pytest
from hypothesis import assume, given, note
from hypothesis import strategies as st

import ethimon

z3 = pytest.importorskip("z3")

import yaml  # noqa: E402

from ethimon.language._expr import Binary, Call, Name, Num, to_source  # noqa: E402
from ethimon.verify._encode import Unrolled, decision_trace, real  # noqa: E402
from ethimon_strategies import (NUM_SIGNALS, GenSpec, _n, _no_risk, _nonneg, _nonzero, bool_expr,  # noqa: E402
                                num_expr, spec_doc, specs)


def dyadic(lo: float, hi: float) -> st.SearchStrategy:
    # multiples of 1/8: sums and products stay exact in floating point, so float and
    # rational arithmetic agree (no rounding ties at comparison boundaries)
    return st.integers(int(lo * 8), int(hi * 8)).map(lambda i: i / 8)


@st.composite
def valid_trace(draw, n_max: int = 7):
    n = draw(st.integers(1, n_max))
    frames = []
    for _ in range(n):
        f = {name: draw(dyadic(lo, hi)) for name, (lo, hi) in NUM_SIGNALS.items()}
        f["b"] = draw(st.booleans())
        f["risk"] = draw(st.integers(0, 64).map(lambda i: i / 64))
        frames.append(f)
        if draw(st.integers(0, 2)) == 0 and len(frames) < n:  # hold inputs
            frames.append(dict(f))
    return frames[:n]


@pytest.mark.slow
@given(specs(max_obligations=2, depth=2), valid_trace())
def test_encoding_agrees_with_the_monitor(gen, frames):
    assume("sqrt" not in gen.text and "/" not in gen.text and "separation_distance" not in gen.text)
    spec = gen.spec
    if spec.risk.max_age_s is not None:
        for f in frames:
            f["risk_age_s"] = 0.0
    note(gen.text)
    m = ethimon.Monitor(spec)
    decisions = [m.step(f) for f in frames]
    assert not any(d.faults for d in decisions)
    plan = m.plan
    enc = Unrolled(plan, len(frames))
    dt = decision_trace(enc, fresh=True)
    s = z3.Solver()
    s.add(*enc.constraints, *dt.init)
    for t, f in enumerate(frames):
        for sig in plan.signals:
            v = enc.sig[t][sig.name]
            s.add(v == (z3.BoolVal(bool(f[sig.name])) if sig.kind == "bool" else real(f[sig.name])))
        s.add(enc.R[t] == real(f["risk"]))
    assert s.check() == z3.sat
    model = s.model()

    def val(e):
        return model.eval(e, model_completion=True)

    for t, d in enumerate(decisions):
        got_v = [ob.id for ob, v in zip(plan.obligations, dt.violated[t]) if z3.is_true(val(v))]
        if z3.is_true(val(dt.risk_fires[t])):
            got_v.append("risk")
        note(f"cycle {t}: {frames[t]} -> {d!r}; encoding: {got_v}")
        assert got_v == list(d.violations)
        assert z3.is_true(val(dt.override[t])) == d.override
        assert val(dt.response[t]).as_long() == d.response.severity
        assert all(z3.is_true(val(enc.obligation_defined(ob, t))) for ob in plan.obligations)


@st.composite
def partial_specs(draw):
    """Specs whose one obligation divides, takes a square root or a separation distance somewhere (maybe under a short circuit)."""
    a, b = draw(num_expr(1)), draw(num_expr(1))
    risky = draw(st.sampled_from((
        _n(Binary, "/", a, _nonzero(b)),
        _n(Call, "sqrt", (_nonneg(a),)),  # a constant negative argument is a SpecError
        _n(Call, "separation_distance", (_nonneg(_no_risk(a)), _n(Name, "y"), _nonneg(_no_risk(b)),
                                         _n(Num, 0.1), _n(Name, "y"), _n(Num, 0.0), _nonneg(_no_risk(b)),
                                         _n(Num, 0.05))))))
    other_side = draw(num_expr(0))
    if isinstance(risky, Call) and risky.func == "separation_distance":  # [m]: never compared with risk [1]
        other_side = _no_risk(other_side)
    cond = _n(Binary, draw(st.sampled_from(("<", ">=", "=="))), risky, other_side)
    other = draw(bool_expr(1))
    shape = draw(st.sampled_from(("alone", "and", "or", "implies", "rand", "held", "prev")))
    if shape in ("and", "or", "implies"):
        cond = _n(Binary, shape, other, cond)
    elif shape == "rand":
        cond = _n(Binary, "and", cond, other)
    elif shape == "held":
        cond = _n(Call, "held", (cond, _n(Num, 2.0)))
    elif shape == "prev":
        cond = _n(Binary, "or", _n(Call, "prev", (cond,)), other)
    doc = spec_doc(draw, max_obligations=0, depth=1)
    doc["obligations"] = [{"id": "partial", "require": to_source(cond)}]
    if draw(st.booleans()):
        doc["obligations"][0]["when"] = to_source(draw(bool_expr(1)))
    text = yaml.safe_dump(doc, sort_keys=False)
    return GenSpec(text, ethimon.load_spec_text(text, "<generated>"), doc)


@pytest.mark.slow
@given(partial_specs(), valid_trace(n_max=4))
def test_definedness_matches_the_monitors_internal_errors(gen, frames):
    spec = gen.spec
    if spec.risk.max_age_s is not None:
        for f in frames:
            f["risk_age_s"] = 0.0
    note(gen.text)
    m = ethimon.Monitor(spec)
    plan = m.plan
    # the first error ends the comparison (a fault clears the history, the unrolled trace does not)
    enc = Unrolled(plan, len(frames))
    ob = plan.obligations[0]
    defined = [enc.obligation_defined(ob, t) for t in range(len(frames))]  # before reading constraints
    s = z3.Solver()
    s.add(*enc.constraints)
    for t, f in enumerate(frames):
        for sig in plan.signals:
            v = enc.sig[t][sig.name]
            s.add(v == (z3.BoolVal(bool(f[sig.name])) if sig.kind == "bool" else real(f[sig.name])))
        s.add(enc.R[t] == real(f["risk"]))
    assert s.check() == z3.sat
    model = s.model()
    for t, f in enumerate(frames):
        d = m.step(f)
        error = any(x.kind == "internal" for x in d.faults)
        ok = z3.is_true(model.eval(defined[t], model_completion=True))
        note(f"cycle {t}: {f} -> {d!r}; defined={ok}")
        assert ok == (not error)
        if error:
            break
