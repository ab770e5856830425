"""Issue 5 (found by the verification suite's Monitor == ReferenceMonitor property): a non-numeric
risk input (``risk: "high"``, a string ``p_unsafe`` or ``risk_age_s``) raised inside ``Monitor._risk``
and took the internal-error path, which skips judging the stateless obligations on a fault cycle:
a garbage risk value could hide a stop 0 the reference interpreter reports."""

import pytest

import ethimon
from ethimon.testing import ReferenceMonitor

SPEC = """
ethimon: 1
name: t
signals: {contact_force: {unit: N, range: [0, 1000]}}
risk: {max_age_s: 0.5}
on_fault: safe_pose
obligations:
  - {id: transient_contact, require: contact_force <= 140, response: stop_0}
"""


@pytest.mark.parametrize("bad", [{"risk": "high"}, {"p_unsafe": "0.9"}, {"risk": [0.5]},
                                 {"p_unsafe": 0.1, "risk_age_s": "old"}])
def test_non_numeric_risk_input_still_judges_stateless_obligations(bad):
    spec = ethimon.load_spec_text(SPEC)
    frame = {"contact_force": 500.0, "risk_age_s": 0.0, **bad}
    for m in (ethimon.Monitor(spec), ReferenceMonitor(spec)):
        d = m.step(frame)
        assert d.override and d.faults
        assert d.violations == ("transient_contact",)
        assert d.response is ethimon.Response.STOP_0
    assert not any(f.kind == "internal" for f in ethimon.Monitor(spec).step(frame).faults)
