"""The risk input of a cycle, an object of its own: R_e from ``risk``, ``p_unsafe`` or ``p`` with the
spec's weights, the range R_e can take, and the one age limit of the estimate."""

from __future__ import annotations

import math
from math import isfinite as _isfinite

from ..compiler import Plan
from ..compiler._risk_formula import risk_from_probs, two_class_risk
from ._fault import Fault
from ._inputs import as_number, as_probs

_NO_RISK = Fault("missing", "no risk input this cycle (give risk, p_unsafe or p)", "risk")


class RiskInput:
    """The R_e formula's weights, its reachable range and the age limit (a part of
    :class:`~ethimon.runtime.Monitor`).

    ``Monitor.step`` inlines the two-class formula for a built-in float ``p_unsafe`` (the common case,
    reading ``alpha``, ``beta``, ``gamma``, ``sample`` and ``p2`` here) and hands every other input to
    :meth:`direct` or :meth:`from_p`. ``max_age`` is the age limit in force (``None``: no limit) and
    ``age_missing`` the fault of a cycle without ``risk_age_s`` under it.
    """

    __slots__ = ("alpha", "beta", "gamma", "sample", "k", "p2", "uidx", "lo", "hi",
                 "spec_age", "max_age", "age_missing")

    def __init__(self, plan: Plan, max_age_s: float | None) -> None:
        r = plan.risk_plan  # the whole risk rule, resolved once (never the spec's risk block)
        self.alpha, self.beta, self.gamma = float(r.alpha), float(r.beta), float(r.gamma)
        self.sample = r.variance == "sample"
        self.k = int(r.classes)
        self.p2 = self.k == 2
        self.uidx = int(r.unsafe_index)
        self.lo, self.hi = r.accepted  # exact, any K: the one place the range is written
        self.spec_age = r.max_age_s
        self.max_age = None
        self.age_missing = None
        self.set_max_age(max_age_s)

    def set_max_age(self, fallback: float | None) -> None:
        """The spec's ``risk.max_age_s`` if it sets one, else ``fallback`` (see :meth:`Monitor.set_max_age`).

        Raises:
            ValueError: ``fallback`` is not a positive, finite number of seconds or ``None``.
        """
        if self.spec_age is not None:
            self.max_age, why = float(self.spec_age), "the spec sets risk.max_age_s"
        elif fallback is not None:
            if not (isinstance(fallback, (int, float)) and not isinstance(fallback, bool) and fallback > 0
                    and math.isfinite(fallback)):
                raise ValueError(f"max_age_s={fallback!r}; expected a positive number of seconds or None")
            self.max_age, why = float(fallback), "an estimate age limit is set"
        else:
            self.max_age, why = None, ""
        self.age_missing = Fault("missing", f"risk_age_s is missing ({why})", "risk_age_s") if why else None

    def read(self, get) -> tuple[float | None, Fault | None]:
        """R_e from a cycle's inputs (``get``: their ``Mapping.get``), converted once at the boundary
        (see ``_inputs``): ``risk`` first, else ``p_unsafe``, else ``p``."""
        r = get("risk")
        if r is not None:
            return self.direct(r)
        return self.from_p(get, get("p_unsafe"))

    def direct(self, r) -> tuple[float | None, Fault | None]:
        """R_e given directly (``risk``, read once by the caller)."""
        f = r if type(r) is float else as_number(r)
        if f is None or not self.lo <= f <= self.hi:
            return None, Fault("invalid" if f is None else "range",
                               f"risk input R_e={r!r} is NaN, not a number or outside "
                               f"[{self.lo:g}, {self.hi:g}]", "risk")
        return f, None

    def from_p(self, get, q) -> tuple[float | None, Fault | None]:
        """R_e from ``p_unsafe`` (``q``, read once by the caller; ``None``: absent) or else ``p``."""
        if q is not None:
            if self.k != 2:
                return None, Fault("invalid",
                                   f"p_unsafe alone needs a 2-class spec (risk.classes is {self.k}); pass p", "p_unsafe")
            f = q if type(q) is float else as_number(q)
            if f is None or not 0.0 <= f <= 1.0:
                return None, Fault("invalid" if f is None or not _isfinite(f) else "range",
                                   f"p_unsafe={q!r} is NaN, not a number or outside [0, 1]", "p_unsafe")
            return two_class_risk(f, self.alpha, self.beta, self.gamma,
                                  "sample" if self.sample else "population"), None
        p = get("p")
        if p is None:
            return None, _NO_RISK
        probs, why = as_probs(p, self.k)
        if why is not None:
            return None, Fault("invalid", why, "p")
        return risk_from_probs(probs, self.alpha, self.beta, self.gamma,
                               "sample" if self.sample else "population", self.uidx), None
