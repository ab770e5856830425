"""The R_e formula, re-exported where it has always been importable.

The formula is spec semantics (the monitor, the reference interpreter and the
z3 encoder all use it), so it lives on the compiler floor:
:mod:`ethimon.compiler._risk_formula`. ``ethimon.risk`` keeps the same names.
"""

from __future__ import annotations

from ..compiler._risk_formula import (DEFAULT_ALPHA, DEFAULT_BETA, DEFAULT_GAMMA, VARIANCE_MODES,  # noqa: F401
                                      _risk_range_exact, release_bound, risk_bounds, risk_from_p_unsafe,
                                      risk_from_probs, risk_range, OUTCOMES, judge_verdict, tier_outcome)

__all__ = ["DEFAULT_ALPHA", "DEFAULT_BETA", "DEFAULT_GAMMA", "risk_from_p_unsafe", "risk_from_probs", "risk_bounds",
           "release_bound", "risk_range", "VARIANCE_MODES", "OUTCOMES", "judge_verdict", "tier_outcome"]
