"""Results of ``ethimon verify``: findings, counterexamples, tables and JSON (no z3 here)."""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from typing import Any

__all__ = ["Counterexample", "Finding", "SpecReport", "format_table", "reports_to_json", "exit_code",
           "PROVED", "PROVED_REAL", "REFUTED", "UNKNOWN", "WARNING", "OK", "SKIPPED"]

PROVED, REFUTED, UNKNOWN = "proved", "refuted", "unknown"
#: proved over the reals, but the monitor's doubles can leave the reals on this spec's in-range inputs
#: (an overflow to inf, an underflow to 0 or a subnormal): the message names the term and an input
PROVED_REAL = "proved (real arithmetic)"
WARNING, OK, SKIPPED = "warning", "ok", "skipped"


@dataclass
class Counterexample:
    """Concrete inputs, cycle by cycle, that break a property; replayed in :class:`~ethimon.Monitor`.

    Attributes:
        property: the refuted property's name.
        frames: the ``step`` inputs of cycles ``0 .. cycle``.
        cycle: the cycle at which the property fails.
        expect: the property as a scenario ``expect`` block (replaying it fails while the spec is unchanged).
        replay: ``Decision.as_dict()`` of every replayed cycle.
        confirmed: the real monitor shows the failure at ``cycle``.
        note: what the replay showed.
    """

    property: str
    frames: list[dict[str, Any]]
    cycle: int
    expect: dict[str, Any]
    replay: list[dict[str, Any]] = field(default_factory=list)
    confirmed: bool = False
    note: str = ""

    def as_dict(self) -> dict[str, Any]:
        return {"property": self.property, "cycle": self.cycle, "frames": [_jsonable(f) for f in self.frames],
                "expect": self.expect, "confirmed": self.confirmed, "note": self.note,
                "replay": [_jsonable(d) for d in self.replay]}


@dataclass
class Finding:
    """One row of a spec's report: a property (proved/refuted/unknown) or a lint (ok/warning).

    Attributes:
        kind: ``"property"`` or ``"lint"``.
        name: e.g. ``risk.override``, ``separation.response``, ``lint.vacuous``.
        status: ``proved``, ``proved (real arithmetic)``, ``refuted``, ``unknown``, ``skipped`` (properties)
            or ``ok``, ``warning`` (lints).
        message: one line saying what was shown.
        seconds: solver wall time.
        counterexample: for a refuted property, the replayed counterexample.
        scenario: the scenario file written for it (``--counterexamples``).
    """

    kind: str
    name: str
    status: str
    message: str
    seconds: float = 0.0
    counterexample: Counterexample | None = None
    scenario: str | None = None

    def as_dict(self) -> dict[str, Any]:
        d = {"kind": self.kind, "name": self.name, "status": self.status, "message": self.message,
             "seconds": round(self.seconds, 6)}
        if self.counterexample is not None:
            d["counterexample"] = self.counterexample.as_dict()
        if self.scenario is not None:
            d["scenario"] = self.scenario
        return d


@dataclass
class SpecReport:
    """Everything ``ethimon verify`` found for one spec file.

    Attributes:
        path: the spec file.
        name: the spec's name (``None`` if it could not be read).
        findings: property and lint rows, in report order.
        error: a one-line error when the spec could not be read or compiled.
        unroll: cycles of symbolic state unrolled for the temporal proofs.
        seconds: total wall time for this spec.
        budget_s: the run's total budget for this spec (``None``: unlimited).
        not_reached: checks the budget cut short or never started (``unknown (budget)`` rows).
    """

    path: str
    name: str | None = None
    findings: list[Finding] = field(default_factory=list)
    error: str | None = None
    unroll: int | None = None
    seconds: float = 0.0
    budget_s: float | None = None
    not_reached: int = 0

    @property
    def refuted(self) -> list[Finding]:
        return [f for f in self.findings if f.status == REFUTED]

    @property
    def unknown(self) -> list[Finding]:
        """Findings left undecided (solver limits, unrolling limits, or the budget)."""
        return [f for f in self.findings if f.status == UNKNOWN]

    def counts(self) -> dict[str, int]:
        """How many properties were proved, refuted, left unknown; lint warnings; checks the budget cut."""
        props = [f for f in self.findings if f.kind == "property"]
        return {"proved": sum(f.status == PROVED for f in props),
                "proved_real_arithmetic": sum(f.status == PROVED_REAL for f in props),
                "refuted": sum(f.status == REFUTED for f in props),
                "unknown": sum(f.status == UNKNOWN for f in props),
                "lint_warnings": sum(f.status == WARNING for f in self.findings),
                "lint_unknown": sum(f.kind == "lint" and f.status == UNKNOWN for f in self.findings),
                "not_reached": self.not_reached}

    @property
    def warnings(self) -> list[Finding]:
        return [f for f in self.findings if f.status == WARNING]

    def finding(self, name: str) -> Finding | None:
        """The first finding called ``name`` (``None`` if absent)."""
        return next((f for f in self.findings if f.name == name), None)

    @property
    def exit_code(self) -> int:
        """0 every property proved and every check run, 1 something refuted, unproved or cut by the budget, 2 unusable.

        A lint's warning, or a lint the solver could not decide, does not change the code; a lint
        the budget did not let run does (the run is incomplete).
        """
        if self.error is not None:
            return 2
        if any(f.kind == "property" and f.status in (REFUTED, UNKNOWN) for f in self.findings):
            return 1
        if self.not_reached:
            return 1
        return 0

    def as_dict(self) -> dict[str, Any]:
        return {"path": self.path, "name": self.name, "error": self.error, "unroll_cycles": self.unroll,
                "seconds": round(self.seconds, 6), "budget_s": self.budget_s, "complete": not self.not_reached,
                "exit_code": self.exit_code, "counts": self.counts(), "findings": [f.as_dict() for f in self.findings]}


def exit_code(reports: list[SpecReport]) -> int:
    """The CLI exit code: 2 any spec unusable, else 1 anything refuted/unproved/cut by the budget, else 0."""
    codes = [r.exit_code for r in reports]
    return 2 if 2 in codes else (1 if 1 in codes else 0)


def _jsonable(x: Any) -> Any:
    if isinstance(x, float):
        if math.isnan(x):
            return "nan"
        if math.isinf(x):
            return "inf" if x > 0 else "-inf"
        return x
    if isinstance(x, dict):
        return {str(k): _jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_jsonable(v) for v in x]
    return x


def reports_to_json(reports: list[SpecReport], settings: dict[str, Any] | None = None) -> dict[str, Any]:
    """The ``--json`` document (``settings``: versions and limits the run used)."""
    out: dict[str, Any] = {"ethimon_verify": 1, "exit_code": exit_code(reports),
                           "specs": [r.as_dict() for r in reports]}
    if settings:
        out["settings"] = settings
    return out


def format_table(report: SpecReport) -> str:
    """A plain-text table of one spec's findings."""
    head = f"{report.path}"
    if report.name:
        head += f"  (spec {report.name!r}"
        if report.unroll is not None:
            head += f", unrolled {report.unroll} cycles"
        head += f", {report.seconds:.2f} s)"
    lines = [head]
    if report.error is not None:
        lines.append(f"  error: {report.error}")
    if report.findings:
        w = max(len("check"), *(len(f.name) for f in report.findings))
        lines.append(f"  {'check':<{w}}  {'result':<8}  {'time':>8}  note")
        for f in report.findings:
            note = f.message
            if f.counterexample is not None:
                note += f" [counterexample at cycle {f.counterexample.cycle}, " + (
                    "replayed in Monitor" if f.counterexample.confirmed else "NOT confirmed by replay") + "]"
            if f.scenario:
                note += f" -> {os.path.normpath(f.scenario)}"
            lines.append(f"  {f.name:<{w}}  {f.status:<8}  {f.seconds:>7.3f}s  {note}")
    if report.not_reached:
        c = report.counts()
        lines.append(f"  budget of {report.budget_s:g} s spent: {c['proved']} properties proved, {c['refuted']} "
                     f"refuted, {c['unknown']} unknown; {report.not_reached} check(s) cut short or not reached "
                     f"(unknown (budget))")
    return "\n".join(lines)
