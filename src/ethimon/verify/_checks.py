"""The two small units every check of ``ethimon verify`` is built from (imports z3): the run's
:class:`Budget` (its deadline, the per-check z3 limit and the solvers it limits) and a
:class:`Check` (a name and ``run(unrolling) -> findings``)."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Union

import z3

from ..language import Response
from ._report import SKIPPED, UNKNOWN, Finding

if TYPE_CHECKING:  # pragma: no cover
    from ._encode import Unrolled

__all__ = ["Budget", "Check", "BUDGET_NOTE"]

_SEV_NAME = {r.severity: r.value for r in Response}
#: how a check that the run's total budget did not let finish is reported
BUDGET_NOTE = "unknown (budget)"


def _fmt(x: float) -> str:
    return f"{x:.6g}"


class Budget:
    """The run's time: a deadline for all checks of one spec (``budget_s``; ``None``: no limit), the
    z3 limit of one check (``timeout_s``, cut to what the budget has left) and the solvers under it.

    Args:
        budget_s: total seconds for the spec's checks, counted from ``started``.
        timeout_s: z3 time limit per check.
        started: ``time.perf_counter()`` when the spec's run began (now if ``None``).
    """

    __slots__ = ("budget_s", "deadline", "timeout_ms")

    def __init__(self, budget_s: float | None, timeout_s: float, started: float | None = None) -> None:
        self.budget_s = budget_s
        t0 = time.perf_counter() if started is None else started
        self.deadline = None if budget_s is None else t0 + budget_s
        self.timeout_ms = max(1, int(timeout_s * 1000))

    def left_s(self) -> float:
        return math.inf if self.deadline is None else self.deadline - time.perf_counter()

    def out_of_budget(self) -> bool:
        return self.left_s() <= 0

    def check_ms(self) -> int:
        """The z3 time limit for the next check: ``--timeout-s``, or less if the budget has less left."""
        left = self.left_s()
        if left == math.inf:
            return self.timeout_ms
        return min(self.timeout_ms, int(left * 1000))

    def unreached(self, kind: str, name: str, what: str = "") -> Finding:
        """The row of a check (or part of one) that the budget did not let run."""
        return Finding(kind, name, UNKNOWN, f"{BUDGET_NOTE}: {what or 'not checked'}; the run's budget "
                                            f"(--budget-s {self.budget_s:g}) was spent")

    # -- solvers -------------------------------------------------------------------------
    def solve(self, *constraints, enc: Unrolled | None = None) -> tuple[str, z3.ModelRef | None, str]:
        """``sat`` (with a model), ``unsat`` or ``unknown`` (with the reason).

        ``enc``'s domain and auxiliary constraints are added last, after every goal term
        was built (building a term can define an auxiliary variable, e.g. for ``sqrt``).
        """
        ms = self.check_ms()
        if ms <= 0:
            return "unknown", None, "the run's budget is spent"
        s = z3.Solver()
        s.set("timeout", ms)
        # incremental mode (push first): z3's SMT core with its nonlinear arithmetic module, which is
        # ~20x faster here than the one-shot tactic the default solver picks for these problems
        s.push()
        for c in constraints:
            s.add(c)
        if enc is not None:
            s.add(*enc.constraints)
        return self.outcome(s)

    def solve_fp(self, *constraints, enc: Unrolled) -> tuple[str, z3.ModelRef | None, str]:
        """:meth:`solve` for IEEE-754 (``FloatUnrolled``) problems: z3's QF_FP solver (bit-blasting),
        which decides these in a second where the incremental core used for the reals gives up."""
        ms = self.check_ms()
        if ms <= 0:
            return "unknown", None, "the run's budget is spent"
        s = z3.SolverFor("QF_FP")
        s.set("timeout", ms)
        for c in constraints:
            s.add(c)
        s.add(*enc.constraints)
        return self.outcome(s)

    def outcome(self, s: z3.Solver) -> tuple[str, z3.ModelRef | None, str]:
        """Check ``s`` as it stands: ``sat`` with its model, ``unsat``, or ``unknown`` with the reason."""
        r = s.check()
        if r == z3.sat:
            return "sat", s.model(), ""
        if r == z3.unsat:
            return "unsat", None, ""
        if self.out_of_budget():
            return "unknown", None, "the run's budget is spent"
        return "unknown", None, s.reason_unknown()


#: ``fn(unrolling)`` of a :class:`Check` (an :class:`~._unrolling.Unrolling`, which imports this module)
CheckFn = Callable[[Any], Union[Finding, list[Finding]]]


class Check:
    """One check of ``ethimon verify``: its ``kind`` (``"property"`` or ``"lint"``), its report
    ``name``, and :meth:`run` over a spec's :class:`~._unrolling.Unrolling`.

    Args:
        kind: ``"property"`` (one finding) or ``"lint"`` (one or more).
        name: the row's name (a lint that reports per obligation names its rows itself).
        fn: ``fn(unrolling)`` -> a finding or a list of findings.
        timed: set the finding's ``seconds`` to ``fn``'s wall time (else ``fn`` sets it, or it stays 0).
    """

    __slots__ = ("kind", "name", "fn", "timed")

    def __init__(self, kind: str, name: str, fn: CheckFn, *, timed: bool = True) -> None:
        self.kind, self.name, self.fn, self.timed = kind, name, fn, timed

    def __repr__(self) -> str:
        return f"Check({self.kind!r}, {self.name!r})"

    def run(self, u: Any) -> list[Finding]:
        """The findings of this check over ``u``; when the budget ran out while it ran, an
        undecided finding says so (its message starts with :data:`BUDGET_NOTE`)."""
        t0 = time.perf_counter()
        got = self.fn(u)
        found = [got] if isinstance(got, Finding) else got
        if self.timed:
            for f in found:
                f.seconds = time.perf_counter() - t0
        undecided = (UNKNOWN,) if self.kind == "property" else (UNKNOWN, SKIPPED)
        for f in found:
            if f.status in undecided and u.budget.out_of_budget() and not f.message.startswith(BUDGET_NOTE):
                f.status, f.message = UNKNOWN, f"{BUDGET_NOTE}: {f.message}"
        return found
