"""Test oracles: what the tests and the property suite check the real implementations against.

:class:`ReferenceMonitor` is the reference interpreter: slow, obviously correct,
written straight from the definitions of the spec language (it keeps the whole
history and walks the AST every cycle). The compiled :class:`~ethimon.Monitor`
must agree with it cycle by cycle (``tests/compiler/test_compiled_vs_reference.py``,
``verification/test_prop_equivalence.py``, ``verification/test_prop_stateful.py``).
Never use it to govern an arm: it is O(history) per step.

>>> import ethimon
>>> from ethimon.testing import ReferenceMonitor
>>> spec = ethimon.load_spec("specs/governor.yaml")
>>> m, ref = ethimon.Monitor(spec), ReferenceMonitor(spec)
>>> frame = {"risk": 0.62, "human_distance": 0.4, "ee_speed": 0.1}
>>> m.step(frame) == ref.step(frame)
True
>>> m.step(frame).override
True
"""

from __future__ import annotations

from ._reference import ReferenceMonitor

__all__ = ["ReferenceMonitor"]
