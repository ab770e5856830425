"""The checks of ``ethimon verify`` for one spec: its properties and its lints (imports z3)."""

from __future__ import annotations

from ._lints import Lints
from ._properties import Properties

__all__ = ["Verifier"]


class Verifier(Properties, Lints):
    """Runs every check of one compiled spec (see :func:`ethimon.verify.verify_spec`): the
    properties (``_properties.py``), then the lints (``_lints.py``), while the budget lasts."""
