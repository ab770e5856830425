"""Proofs and lints over a spec's compiled :class:`~ethimon.compiler.Plan`, with z3.

Nothing here imports z3 at module import time: :func:`verify_spec` imports it
(and :mod:`._encode`) on first use and raises
:class:`~ethimon.errors.DependencyNotInstalled` if it is missing.
"""

from __future__ import annotations

import os
import time
from collections.abc import Iterable
from typing import Any

from .._files import find_yaml_files
from ..errors import DependencyNotInstalled, SpecError
from ..language import Spec
from ._report import WARNING, Finding, SpecReport

__all__ = ["verify_spec", "verify_paths", "find_specs", "require_z3", "DEFAULT_TIMEOUT_S", "DEFAULT_MAX_UNROLL",
           "DEFAULT_BUDGET_S"]

DEFAULT_TIMEOUT_S = 20.0
DEFAULT_MAX_UNROLL = 32
#: total seconds for all checks of one spec; checks not reached in time are "unknown (budget)"
DEFAULT_BUDGET_S = 120.0


def require_z3():
    """Import z3, or raise :class:`DependencyNotInstalled` naming the pip command."""
    try:
        import z3  # noqa: F401
    except ImportError:
        raise DependencyNotInstalled(
            'ethimon verify needs the z3 SMT solver: pip install "ethimon[verify]"') from None
    return z3


def find_specs(paths: Iterable[str]) -> list[str]:
    """Expand files and folders into a sorted list of ``*.yaml``/``*.yml`` files (the one discovery rule,
    :func:`ethimon._files.scan_yaml_files`: a FIFO, socket or device in a folder is passed over, never opened).

    Raises:
        SpecError: a path that does not exist or is not a regular file or folder, or a folder without YAML files.
    """
    return find_yaml_files(paths, what="spec", command="ethimon verify")


def verify_paths(paths: Iterable[str], **kw: Any) -> list[SpecReport]:
    """:func:`verify_spec` for every spec file under ``paths`` (see :func:`find_specs`)."""
    return [verify_spec(p, **kw) for p in find_specs(paths)]


def _is_unit_error(exc: SpecError) -> bool:
    m = exc.message
    return "unit mismatch" in m or m.startswith("unit ") or "[" in m and "unit" in m


def verify_spec(spec: str | os.PathLike | Spec, *, timeout_s: float = DEFAULT_TIMEOUT_S,
                max_unroll: int = DEFAULT_MAX_UNROLL, lints: bool = True,
                counterexamples: str | os.PathLike | None = None,
                budget_s: float | None = DEFAULT_BUDGET_S) -> SpecReport:
    """Prove the decision-logic invariants of one spec, lint it, and replay counterexamples.

    Args:
        spec: a spec file, or a :class:`Spec` from :func:`ethimon.load_spec`.
        timeout_s: z3 time limit per check (a check that runs out is ``unknown``).
        budget_s: total time for this spec (``None``: no limit). When it is spent, the check
            running is cut short and the rest are not started; each is reported as ``unknown``
            with a message starting ``unknown (budget)``, ``report.not_reached`` counts them and
            the exit code is 1. Each check's z3 limit is also cut to what the budget has left.
        max_unroll: most cycles of symbolic state to unroll.
        lints: also run the lints.
        counterexamples: a folder to write each counterexample into as a scenario file.

    Returns:
        A :class:`SpecReport`; a spec that cannot be read has ``error`` set (and a
        ``lint.unit_mismatch`` warning when the reason is a unit error).

    Raises:
        DependencyNotInstalled: z3 is missing.

    Example:
        >>> report = verify_spec("specs/governor.yaml")  # doctest: +SKIP
        >>> report.finding("risk.override").status  # doctest: +SKIP
        'proved'
    """
    require_z3()
    from ._verifier import Verifier  # imports z3

    t0 = time.perf_counter()
    if isinstance(spec, Spec):
        path = spec.path or "<spec>"
    else:
        path = os.fspath(spec)
        from .._api import load_spec
        try:
            spec = load_spec(path)
        except SpecError as exc:
            rep = SpecReport(path=path, error=str(exc))
            if _is_unit_error(exc):
                rep.findings.append(Finding("lint", "lint.unit_mismatch", WARNING, str(exc)))
            rep.seconds = time.perf_counter() - t0
            return rep
    v = Verifier(spec, path=path, timeout_s=timeout_s, max_unroll=max_unroll, budget_s=budget_s, started=t0)
    rep = SpecReport(path=path, name=spec.name, unroll=v.k, budget_s=budget_s)
    found, rep.not_reached = v.run(lints=lints)
    rep.findings += found
    if counterexamples is not None:
        from ._scenario import write_counterexample
        for f in rep.findings:
            if f.counterexample is not None and spec.path:
                f.scenario = write_counterexample(f.counterexample, spec, counterexamples)
    rep.seconds = time.perf_counter() - t0
    return rep

