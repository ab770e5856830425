"""The checks of ``ethimon verify`` for one spec, run in order over one unrolling (imports z3)."""

from __future__ import annotations

from ..compiler import Plan
from ..language import Spec
from ._checks import BUDGET_NOTE, Budget, Check
from ._lints import lint_checks
from ._properties import property_checks
from ._report import Finding
from ._unrolling import Unrolling

__all__ = ["Verifier"]


class Verifier:
    """Runs every check of one spec (see :func:`ethimon.verify.verify_spec`) over its
    :class:`~._unrolling.Unrolling`, built once: the properties (``_properties.py``), then the
    lints (``_lints.py``), while the :class:`~._checks.Budget` lasts.

    Args:
        spec: the loaded spec.
        path: its file (for the report).
        timeout_s: z3 time limit per check.
        max_unroll: most cycles of symbolic state to unroll.
        budget_s: total seconds for all checks (``None``: no limit), counted from ``started``.
        started: ``time.perf_counter()`` when the spec's run began (now if ``None``).
    """

    __slots__ = ("path", "budget", "unrolling")

    def __init__(self, spec: Spec, *, path: str, timeout_s: float, max_unroll: int,
                 budget_s: float | None = None, started: float | None = None) -> None:
        self.path = path
        self.budget = Budget(budget_s, timeout_s, started)
        self.unrolling = Unrolling(spec, max_unroll=max_unroll, budget=self.budget)

    @property
    def k(self) -> int:
        """Cycles unrolled."""
        return self.unrolling.k

    @property
    def plan(self) -> Plan:
        """The plan the checks run on (the spec's, without its tiers)."""
        return self.unrolling.plan

    def checks(self, lints: bool = True) -> list[Check]:
        """Every check, in report order: the properties, then (``lints``) the lints."""
        u = self.unrolling
        return property_checks(u) + (lint_checks(u) if lints else [])

    def run(self, lints: bool = True) -> tuple[list[Finding], int]:
        """Every property, then every lint, while the budget lasts.

        Returns:
            The findings and how many checks the budget did not let run or finish (each is
            reported as an ``unknown`` row whose message starts with :data:`~._checks.BUDGET_NOTE`).
        """
        out: list[Finding] = []
        for check in self.checks(lints):
            if self.budget.out_of_budget():
                out.append(self.budget.unreached(check.kind, check.name))
                continue
            out += check.run(self.unrolling)
        return out, sum(f.message.startswith(BUDGET_NOTE) for f in out)
