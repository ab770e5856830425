"""Issue 5 (found by verification/test_prop_encoding.py): robustness margins are computed
without short-circuiting, so a guarded division such as ``y <= 0 or x / y < 2`` raised
ZeroDivisionError in its *margin* at y = 0 and the monitor failed closed (a spurious stop)
although the verdict is well defined. Margins that cannot be computed are now NaN."""

import math

import ethimon
from ethimon.testing import ReferenceMonitor

SPEC = """
ethimon: 1
name: guarded
signals: {x: {range: [0, 1]}, y: {range: [0, 1]}}
obligations:
  - {id: rate, require: y <= 0 or x / y < 2}
  - {id: gated, when: y > 0, require: x / y < 2}
"""


def test_guarded_division_is_not_a_fault():
    spec = ethimon.load_spec_text(SPEC)
    frame = {"x": 1.0, "y": 0.0, "risk": 0.2}
    d = ethimon.Monitor(spec).step(frame)
    assert not d.override and not d.faults
    assert d == ReferenceMonitor(spec).step(frame)
    assert all(math.isnan(m) for m in d.margins)
    d = ethimon.Monitor(spec).step({"x": 1.0, "y": 0.25, "risk": 0.2})
    assert d.override and d.violations == ("rate", "gated") and not any(math.isnan(m) for m in d.margins)
