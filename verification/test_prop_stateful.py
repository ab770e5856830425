"""A stateful model of the monitor's life: step, reset, release, spec reload, late risk.

The machine drives :class:`ethimon.Monitor` and :class:`ethimon.testing.ReferenceMonitor`
side by side and keeps its own model of the latch (written from the contract).
"""

from __future__ import annotations

import math
import os

import pytest
import yaml

from hypothesis import strategies as st
from hypothesis.stateful import RuleBasedStateMachine, initialize, invariant, precondition, rule

from fractions import Fraction

import ethimon
from ethimon.testing import ReferenceMonitor
from ethimon.compiler._risk_formula import release_bound
from ethimon.language._model import Response
from ethimon_strategies import decision_key, frame, specs

pytestmark = pytest.mark.slow  # a stateful Hypothesis run: ~4 s

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def _cobot_with_max_age() -> str:
    """The shipped cobot cell, with a risk age limit and a short release hold."""
    with open(os.path.join(ROOT, "specs", "cobot_cell.yaml"), encoding="utf-8") as fh:
        doc = yaml.safe_load(fh)
    doc["risk"]["max_age_s"] = 0.2
    doc["risk"].setdefault("release", {})["hold_cycles"] = 3
    return yaml.safe_dump(doc, sort_keys=False)


COBOT = _cobot_with_max_age()


class MonitorLife(RuleBasedStateMachine):
    """Invariants: monitor ≡ reference; each rule's latch (obligations, risk, fault) stays set until
    its own release rule (auto: its condition held hold_cycles cycles in a row), an accepted
    ``acknowledge()`` (manual), ``release()`` or ``reset()``; the override is on exactly while
    some latch is set, with the most severe latched response; replaying the trace since the
    last reset gives the same verdicts."""

    @initialize(data=st.data())
    def load(self, data):
        if data.draw(st.booleans(), label="shipped"):
            self.text = COBOT
        else:
            self.text = data.draw(specs(max_obligations=2, depth=2)).text
        self.new_monitors()

    def new_monitors(self) -> None:
        self.spec = ethimon.load_spec_text(self.text, "<stateful>")
        self.m = ethimon.Monitor(self.spec)
        self.ref = ReferenceMonitor(self.spec)
        self.log: list = []  # ops since the last reset/reload, with the decisions they produced
        self.last = None
        self.model: dict[str, int] = {}  # this test's own latch model: rule -> clean cycles since it fired
        spec = self.spec
        self.rules = {ob.id: (Response(ob.response).severity, *spec.obligation_release(ob))
                      for ob in spec.obligations}
        rel = spec.risk.release
        self.rules["risk"] = (Response(spec.risk.response).severity, rel.mode, rel.hold_cycles)
        self.rules["fault"] = (Response(spec.on_fault).severity, *spec.fault_release())
        self.bound = release_bound(spec.risk.threshold, rel.hysteresis)[0]

    def _model_step(self, d) -> None:
        model, rules = self.model, self.rules
        if d.faults:
            for k in (*d.violations, "fault"):
                model[k] = 0
            for k in model:
                model[k] = 0
            return
        for k in list(model):
            if k in d.violations or (k == "risk" and not Fraction(repr(d.risk)) < self.bound):
                model[k] = 0
                continue
            _, mode, hold = rules[k]
            model[k] = min(model[k] + 1, hold)
            if mode == "auto" and model[k] >= hold:
                del model[k]
        for k in d.violations:
            model[k] = 0

    def _step(self, f) -> None:
        d, e = self.m.step(f), self.ref.step(f)
        assert decision_key(d) == decision_key(e), (f, d, e)
        r = self.spec.risk
        if d.faults:
            assert d.override and d.response.severity >= Response(self.spec.on_fault).severity
        self._model_step(d)
        model, rules = self.model, self.rules
        assert d.override == bool(model), (d, model)
        if model:
            assert d.response.severity == max(rules[k][0] for k in model), (d, model)
        manual = [k for k in model if rules[k][1] == "manual"]
        assert d.awaiting_release == (bool(manual) and all(model[k] >= rules[k][2] for k in manual)), (d, model)
        assert self.m.latched_rules == self.ref.latched_rules
        assert set(self.m.latched_rules) == set(model)
        if not d.override:
            assert not d.violations and not d.faults and d.risk < r.threshold
        self.log.append(("step", f, d))
        self.last = d

    @rule(data=st.data())
    def step(self, data):
        self._step(data.draw(frame(self.spec, p_bad=0.03, late_risk=False)))

    @rule(data=st.data(), n=st.integers(1, 6))
    def hold_inputs(self, data, n):
        f = data.draw(frame(self.spec, p_bad=0.0, late_risk=False))
        for _ in range(n):
            self._step(f)

    @precondition(lambda self: self.spec.risk.max_age_s is not None)
    @rule(data=st.data(), late=st.sampled_from((1.0001, 2.0, 100.0)))
    def late_risk(self, data, late):
        f = data.draw(frame(self.spec, p_bad=0.0, late_risk=False))
        f["risk_age_s"] = self.spec.risk.max_age_s * late
        self._step(f)
        d = self.last
        assert d.override and any(x.kind == "stale" for x in d.faults)

    @rule()
    def missing_risk(self):
        f = {k: v for k, v in (self.log[-1][1] if self.log and self.log[-1][0] == "step" else {}).items()
             if k not in ("risk", "p_unsafe", "p")}
        self._step(f)
        assert self.last.override and self.last.faults

    @rule()
    def reset(self):
        self.m.reset()
        self.ref.reset()
        self.log = []
        self.model = {}
        self.last = None
        assert self.m.cycle == 0 and not self.m.latched

    @rule()
    def release(self):
        self.m.release()
        self.ref.release()
        self.log.append(("release",))
        self.model = {}
        assert not self.m.latched

    @rule()
    def acknowledge(self):
        a, b = self.m.acknowledge(), self.ref.acknowledge()
        assert a == b, (a, b)
        manual = [k for k in self.model if self.rules[k][1] == "manual"]
        ready = bool(manual) and all(self.model[k] >= self.rules[k][2] for k in manual)
        assert a.released == ready, (a, self.model)
        if ready:
            assert set(a.rules) == set(manual)
            for k in manual:
                del self.model[k]
        else:
            assert set(a.rules) == {k for k in manual if self.model[k] < self.rules[k][2]}
            assert ("still fails" in a.message) or ("has held" in a.message) or not manual
        self.log.append(("acknowledge", a))
        assert set(self.m.latched_rules) == set(self.model)

    @rule()
    def reload(self):
        """Spec reload: a new Monitor from the same text starts fresh."""
        self.new_monitors()
        assert self.m.cycle == 0 and not self.m.latched

    @rule()
    def replay_after_reset(self):
        """Replaying the trace since the last reset on a reset monitor gives the same verdicts."""
        fresh = ethimon.Monitor(self.spec)
        fresh.step({"nonsense": math.nan})  # dirty it, then reset
        fresh.reset()
        for op in self.log:
            if op[0] == "release":
                fresh.release()
            elif op[0] == "acknowledge":
                assert fresh.acknowledge() == op[1]
            else:
                assert decision_key(fresh.step(op[1])) == decision_key(op[2])

    @invariant()
    def agree_on_state(self):
        if hasattr(self, "m"):
            assert self.m.latched == (self.ref.latched > 0)
            assert self.m.cycle == self.ref.cycle


TestMonitorLife = MonitorLife.TestCase
