"""A stateful model of the monitor's life: step, reset, release, spec reload, late risk.

The machine drives :class:`ethimon.Monitor` and :class:`ethimon.ReferenceMonitor`
side by side and keeps its own model of the latch (written from the contract).
"""

from __future__ import annotations

import math
import os

import yaml

from hypothesis import strategies as st
from hypothesis.stateful import RuleBasedStateMachine, initialize, invariant, precondition, rule

import ethimon
from ethimon.spec._model import Response
from ethimon_strategies import decision_key, frame, specs

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
    """Invariants: monitor ≡ reference; a latched override stays latched until its release rule,
    ``release()`` or ``reset()``; replaying the trace since the last reset gives the same verdicts."""

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
        self.ref = ethimon.ReferenceMonitor(self.spec)
        self.log: list = []  # ops since the last reset/reload, with the decisions they produced
        self.last = None
        self.clean = 0
        self.explicit = False

    def _step(self, f) -> None:
        d, e = self.m.step(f), self.ref.step(f)
        assert decision_key(d) == decision_key(e), (f, d, e)
        rel = self.spec.risk.release
        r = self.spec.risk
        if d.faults:
            assert d.override and d.response.severity >= Response(self.spec.on_fault).severity
            self.clean = 0
        elif d.violations or d.risk >= r.threshold - rel.hysteresis:
            self.clean = 0
        else:
            self.clean += 1
        if self.last is not None and self.last.override and not d.override and not self.explicit:
            assert rel.mode == "auto" and self.clean >= rel.hold_cycles
        if not d.override:
            assert not d.violations and not d.faults and d.risk < r.threshold
        self.log.append(("step", f, d))
        self.last, self.explicit = d, False

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
        self.clean = 0
        self.explicit = True
        self.last = None
        assert self.m.cycle == 0 and not self.m.latched

    @rule()
    def release(self):
        self.m.release()
        self.ref.release()
        self.log.append(("release",))
        self.clean = 0
        self.explicit = True
        assert not self.m.latched

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
            else:
                assert decision_key(fresh.step(op[1])) == decision_key(op[2])

    @invariant()
    def agree_on_state(self):
        if hasattr(self, "m"):
            assert self.m.latched == (self.ref.latched > 0)
            assert self.m.cycle == self.ref.cycle


TestMonitorLife = MonitorLife.TestCase
