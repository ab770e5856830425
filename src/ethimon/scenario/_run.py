"""Loading and running scenarios (the library behind ``ethimon check``)."""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from .._api import load_spec
from .._files import find_yaml_files
from ..errors import SpecError
from ..runtime import Decision, Monitor
from ..language._load import validate_document
from ..language import Response, Spec
from ..language._yaml import parse_yaml_text, read_yaml
from ._model import Scenario

if TYPE_CHECKING:  # pragma: no cover
    from ..risk import ProbsEstimator

__all__ = ["load_scenario", "load_scenario_text", "run_scenario", "ScenarioResult", "find_scenarios",
           "check_input_names", "BUILTIN_INPUTS",
           "build_inputs"]

RISK_KEYS = ("risk", "p_unsafe", "p")


def load_scenario(path: str | os.PathLike) -> Scenario:
    """Read and validate a scenario file.

    Raises:
        SpecError: bad YAML or shape, with path:line:column.
    """
    data, smap = read_yaml(path, what="scenario", max_bytes=16 * 1024 * 1024)
    return validate_document(Scenario, data, smap, "scenario")


def load_scenario_text(text: str, path: str = "<string>") -> Scenario:
    """Validate scenario YAML given as text (spec paths resolve against ``path``'s folder)."""
    data, smap = parse_yaml_text(text, path, what="scenario")
    return validate_document(Scenario, data, smap, "scenario")


def find_scenarios(paths: Iterable[str], *, skipped: list[tuple[str, str]] | None = None) -> list[str]:
    """Expand files and folders into a sorted list of scenario files.

    FIFOs, sockets and devices found in a folder are never opened; they are
    appended to ``skipped`` as ``(path, reason)`` when a list is given.

    Raises:
        SpecError: a path that does not exist or is not a regular file or folder
            (a FIFO, ``/dev/stdin``), or a folder with no ``*.yaml``/``*.yml``.
    """
    return find_yaml_files(paths, what="scenario", command="ethimon check", skipped=skipped)


#: step() inputs with a built-in meaning, valid in every scenario besides the spec's signals
BUILTIN_INPUTS = ("risk", "p_unsafe", "p", "risk_age_s", "judge")  # judge: a recorded judge answer (p_unsafe)


def check_input_names(sc: Scenario, spec: Spec) -> None:
    """Every key of ``inputs`` and of each timeline ``set`` must be a signal of ``spec`` or a
    built-in input (:data:`BUILTIN_INPUTS`): a typo would otherwise test nothing.

    Raises:
        SpecError: at the unknown key, with "did you mean ...?".
    """
    import difflib
    known = set(spec.signals) | set(BUILTIN_INPUTS)
    where = [(("inputs",), sc.inputs)] + [(("timeline", i, "set"), e.set) for i, e in enumerate(sc.timeline)]
    for loc, mapping in where:
        for key in mapping:
            if key in known:
                continue
            close = difflib.get_close_matches(key, sorted(known), n=1, cutoff=0.6)
            hint = (f"did you mean {close[0]!r}?" if close else
                    "known inputs: " + ", ".join([*spec.signals, *BUILTIN_INPUTS]))
            shown = key if len(key) <= 80 else key[:77] + "..."
            msg = f"unknown input {shown!r}: spec {spec.name!r} has no signal of that name"
            if sc._source is not None:
                raise sc._source.error(msg, loc + (key,), key=True, hint=hint)
            raise SpecError(msg, hint=hint)


def build_inputs(sc: Scenario) -> list[dict[str, Any]]:
    """The input mapping of every cycle, from ``inputs`` and the piecewise ``timeline``."""
    by_cycle: dict[int, list] = {}
    for entry in sc.timeline:
        by_cycle.setdefault(entry.at, []).append(("set", entry))
        if entry.for_cycles:
            end = entry.at + entry.for_cycles
            if end < sc.cycles:
                by_cycle.setdefault(end, []).append(("revert", entry))
    current: dict[str, Any] = dict(sc.inputs)
    saved: dict[int, dict[str, Any]] = {}
    frames = []
    for t in range(sc.cycles):
        for kind, entry in by_cycle.get(t, ()):  # reverts first would need ordering; keep file order
            if kind == "set":
                saved[id(entry)] = {k: current.get(k, _MISSING) for k in entry.set}
                for k, v in entry.set.items():
                    if v is None:
                        current.pop(k, None)
                    else:
                        current[k] = v
            else:
                for k, v in saved.pop(id(entry), {}).items():
                    if v is _MISSING:
                        current.pop(k, None)
                    else:
                        current[k] = v
        frames.append(dict(current))
    return frames


_MISSING = object()


@dataclass
class ScenarioResult:
    """The outcome of one scenario run."""

    name: str
    path: str | None
    passed: bool
    failures: list[str]
    expected: str
    got: str
    first_override_cycle: int | None
    decisions: list[Decision] = field(default_factory=list, repr=False)
    task_probs: tuple[float, ...] | None = None
    mode: str = "timeline"

    def as_dict(self) -> dict:
        return {"name": self.name, "path": self.path, "passed": self.passed, "failures": self.failures,
                "expected": self.expected, "got": self.got, "first_override_cycle": self.first_override_cycle,
                "task_probs": list(self.task_probs) if self.task_probs else None, "mode": self.mode}


def needs_text_risk(sc: Scenario) -> bool:
    """True when no risk input is given anywhere, so the task text must be scored."""
    if any(k in sc.inputs for k in RISK_KEYS):
        return False
    return not any(k in e.set for e in sc.timeline for k in RISK_KEYS)


def run_scenario(sc: Scenario, *, spec: Spec | None = None,
                 estimator: ProbsEstimator | Callable[[], ProbsEstimator] | None = None) -> ScenarioResult:
    """Run a scenario's timeline through a fresh :class:`Monitor` and check ``expect``.

    Args:
        sc: the scenario.
        spec: the spec to use (default: load ``sc.spec_path``).
        estimator: scores ``sc.task`` when the scenario gives no explicit risk
            input: anything :func:`ethimon.risk.as_estimator` takes (an object with
            ``probs(text)``, a zero-argument factory, a function text -> probabilities,
            a model directory).
            Default: the model the spec's ``risk.estimator`` block names
            (``ethimon.risk.load_estimator_for``; the shipped offline model if none).

    Raises:
        SpecError: the spec is missing or invalid, an input name is not a signal
            of the spec (nor a built-in input), or the scenario needs a task text
            it does not have.
    """
    if spec is None:
        spec = load_spec(sc.spec_path)
    check_input_names(sc, spec)
    frames = build_inputs(sc)
    probs = None
    if needs_text_risk(sc):
        if not sc.task:
            raise (sc._source.error("scenario gives no risk input and no task text", (),
                                    hint="add 'task: ...' (scored by the risk model) or 'inputs: {p_unsafe: ...}'")
                   if sc._source is not None else SpecError("scenario gives no risk input and no task text"))
        from ..risk import as_estimator, default_threads  # lazy: torch only when a text must be scored
        est = as_estimator(estimator, spec=spec, num_threads=default_threads(1))  # one text: one thread
        probs = tuple(float(x) for x in est.probs(sc.task))
        for f in frames:
            f["p"] = probs
    monitor = Monitor(spec)
    _check_ids(sc, monitor)
    decisions = [monitor.step(f) for f in frames]
    failures = check_expectations(sc, decisions)
    first = next((d.cycle for d in decisions if d.override), None)
    return ScenarioResult(sc.name, sc.path, not failures, failures, describe_expect(sc), describe_got(decisions),
                          first, decisions, probs)


def describe_expect(sc: Scenario) -> str:
    e = sc.expect
    parts = []
    if e.override is True:
        parts.append("override")
    elif e.override is False:
        parts.append("no override")
    if e.override_by_cycle is not None:
        parts.append(f"by {e.override_by_cycle}")
    if e.no_override_before is not None:
        parts.append(f"not before {e.no_override_before}")
    if e.fired:
        parts.append("fires " + ",".join(e.fired))
    if e.response:
        parts.append(e.response)
    if e.released_by_cycle is not None:
        parts.append(f"release by {e.released_by_cycle}")
    if e.fault is True:
        parts.append("fault")
    return " ".join(parts) or "-"


def describe_got(decisions: list[Decision]) -> str:
    fired: list[str] = []
    worst = Response.NONE
    faults = 0
    for d in decisions:
        for v in d.violations:
            if v not in fired:
                fired.append(v)
        if d.override and d.response.severity > worst.severity:
            worst = d.response
        faults += bool(d.faults)
    if worst is Response.NONE:
        return "no override"
    out = f"{worst.value}"
    if fired:
        out += " [" + ",".join(fired) + "]"
    if faults:
        out += f" faults:{faults}"
    return out


def override_expectations(e, first: int | None, why: str = "") -> list[str]:
    """The ``expect.override`` check alone, given the first override cycle (shared with the sim)."""
    if e.override is True and first is None:
        return ["expected an override, none happened"]
    if e.override is False and first is not None:
        return [f"expected no override, got one at cycle {first}" + (f" ({why})" if why else "")]
    return []


def check_expectations(sc: Scenario, decisions: list[Decision]) -> list[str]:
    """Compare a run with ``sc.expect``; returns the failed expectations (empty: pass)."""
    e = sc.expect
    overrides = [d.cycle for d in decisions if d.override]
    first = overrides[0] if overrides else None
    fired = {v for d in decisions for v in d.violations}
    fails = override_expectations(e, first, "; ".join(decisions[first].reasons) if first is not None else "")
    if e.override_by_cycle is not None and (first is None or first > e.override_by_cycle):
        fails.append(f"expected the first override by cycle {e.override_by_cycle}, got "
                     f"{'none' if first is None else first}")
    if e.no_override_before is not None and first is not None and first < e.no_override_before:
        fails.append(f"expected no override before cycle {e.no_override_before}, got one at {first}")
    for oid in e.fired:
        if oid not in fired:
            fails.append(f"expected {oid!r} to fire, it never did")
    for oid in e.not_fired:
        if oid in fired:
            c = next(d.cycle for d in decisions if oid in d.violations)
            fails.append(f"expected {oid!r} never to fire, it fired at cycle {c}")
    if e.response is not None:
        worst = max((d.response for d in decisions if d.override), key=lambda r: r.severity,
                    default=Response.NONE)
        if worst.value != e.response:
            fails.append(f"expected response {e.response}, got {worst.value}")
    if e.released_by_cycle is not None:
        released = first is not None and any(
            not d.override for d in decisions[first:e.released_by_cycle + 1])
        if not released:
            fails.append(f"expected the override to be released by cycle {e.released_by_cycle}")
    if e.final_override is not None and decisions and decisions[-1].override != e.final_override:
        fails.append(f"expected final override={e.final_override}, got {decisions[-1].override}")
    if e.fault is not None:
        has = any(d.faults for d in decisions)
        if has != e.fault:
            fails.append("expected a fail-closed fault, none happened" if e.fault
                         else "expected no fault, got: " + str(next(f for d in decisions for f in d.faults)))
    return fails


def _check_ids(sc: Scenario, monitor: Monitor) -> None:
    import difflib
    known = set(monitor.obligation_ids) | {"risk"}
    tiers = monitor.plan.tiers
    if tiers.judges:
        known.add("judge")
    if tiers.confirm_threshold is not None or tiers.hold_ceiling is not None:
        known.add("confirm")
    for key in ("fired", "not_fired"):
        for i, oid in enumerate(getattr(sc.expect, key)):
            if oid not in known:
                close = difflib.get_close_matches(oid, sorted(known), n=1)
                hint = f"did you mean {close[0]!r}?" if close else f"known: {', '.join(sorted(known))}"
                msg = f"expect.{key} names {oid!r}, which is not an obligation of spec {monitor.spec.name!r}"
                if sc._source is not None:
                    raise sc._source.error(msg, ("expect", key, i), hint=hint)
                raise SpecError(msg, hint=hint)
