"""``ethimon verify``: SMT proofs and lints over a spec's compiled plan.

Every spec's decision logic is translated from the same checked
:class:`~ethimon.compiler.Plan` the runtime compiles, unrolled over the
temporal windows, and handed to z3. Refuted properties come with a
counterexample that is replayed in the real :class:`~ethimon.Monitor`.

``import ethimon.verify`` does not import z3; :func:`verify_spec` does, and
raises :class:`~ethimon.errors.DependencyNotInstalled` (``pip install
"ethimon[verify]"``) if it is missing.

Example:
    >>> from ethimon.verify import verify_spec
    >>> report = verify_spec("specs/governor.yaml")  # doctest: +SKIP
    >>> report.exit_code  # doctest: +SKIP
    0
"""

from __future__ import annotations

from ._report import Counterexample, Finding, SpecReport, exit_code, format_table, reports_to_json
from ._verify import (DEFAULT_BUDGET_S, DEFAULT_MAX_UNROLL, DEFAULT_TIMEOUT_S, find_specs, require_z3, verify_paths,
                      verify_spec)

__all__ = ["Counterexample", "Finding", "SpecReport", "verify_paths", "verify_spec"]
