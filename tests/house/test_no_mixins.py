"""No mixin bases for the four classes issue 33 cut by state (item 1): ``Monitor``, ``GovernedLoop``,
``ArmSim`` and ``Verifier`` each compose objects that own their state, so each class's MRO is itself
and ``object``. A base class that shares one ``self`` across files would come back here first.

Importing the classes imports no PyBullet, z3 or torch (``ArmSim`` imports PyBullet when built)."""

from __future__ import annotations

import importlib

import pytest

CLASSES = [
    ("ethimon.runtime", "Monitor"),
    ("ethimon.loop", "GovernedLoop"),
    ("ethimon.sim._arm", "ArmSim"),
    ("ethimon.verify._verifier", "Verifier"),
]


@pytest.mark.parametrize("module, name", CLASSES)
def test_the_class_has_no_bases(module, name):
    cls = getattr(importlib.import_module(module), name)
    assert cls.__mro__ == (cls, object), (
        f"{module}.{name} has bases {[c.__qualname__ for c in cls.__mro__[1:-1]]}: compose parts that own "
        f"their state (issue 33), do not mix them into one self")
