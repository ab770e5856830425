"""Checking many scenario files in one run: the library behind ``ethimon check`` and ``ethimon simulate``.

One :class:`ScenarioSession` reads each spec once (a spec that fails fails every
scenario using it, each with its own fresh exception), loads each risk model
once (only when a scenario's task text must be scored: no torch otherwise) and
imports the simulator only for ``sim:`` runs. :func:`check_paths` and
:func:`simulate_paths` turn files and folders into a :class:`CheckReport`; one
unusable file is one ERROR outcome, the others still run.
"""

from __future__ import annotations

import copy
import functools
import os
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any

from ..errors import DependencyNotInstalled, EthimonError, SimError, SpecError
from ._model import Scenario
from .._files import scan_yaml_files
from ._run import RISK_KEYS, needs_text_risk, override_expectations

__all__ = ["CheckOutcome", "CheckReport", "ScenarioSession", "check_paths", "check_unit", "simulate_paths",
           "error_line", "internal_error", "sim_risk_inputs"]

#: ``on_progress(done, total, path)``: ``ethimon.run``'s one progress callback: before each file (``path`` is
#: starting, ``done`` files are finished) and once at the end with ``done == total`` and ``path == ""``
ProgressCallback = Callable[[int, int, str], None]


def internal_error(where: str, exc: BaseException) -> str:
    """One line for an unexpected exception from one file: ``where: internal error: Type: text``."""
    text = str(exc)
    if len(text) > 300:
        text = text[:297] + "..."
    what = f"{type(exc).__name__}: {text}" if text else type(exc).__name__
    return f"{where}: internal error: {what} (this file could not be checked; please report this)"


def error_line(path: str, exc: BaseException, *, where: str | None = None) -> str:
    """The one line that reports ``exc`` raised while using the file ``path``.

    A :class:`SpecError` names its own location; another ethimon error (or an
    ``OSError``) is prefixed with ``path``; anything else is an internal error
    at ``where`` (default ``path``).
    """
    if isinstance(exc, SpecError):
        return str(exc)
    if isinstance(exc, (EthimonError, OSError)):
        return f"{path}: {exc}"
    return internal_error(where or path, exc)


@dataclass
class CheckOutcome:
    """One row of a run: a scenario's timeline, its ``sim:`` block, a skipped file or an unusable one.

    Attributes:
        name: the scenario's name (``"<name> [sim]"`` for a sim row of ``check``; the path when
            the file could not be read).
        path: the scenario file.
        status: ``"PASS"``, ``"FAIL"``, ``"ERROR"`` (bad input) or ``"SKIP"``.
        expected, got: short descriptions for the table.
        first_override_cycle: first cycle with an override (``None``: never, or no run).
        messages: one-line messages: the failed expectations (located at the file), the error, or
            why the file was skipped.
        record: the JSON-ready record of this row.
        result: the :class:`~ethimon.scenario.ScenarioResult` or ``ethimon.sim.SimResult``
            (``None`` for SKIP and ERROR).
    """

    name: str
    path: str
    status: str
    expected: str = "-"
    got: str = "-"
    first_override_cycle: int | None = None
    messages: list[str] = field(default_factory=list)
    record: dict[str, Any] = field(default_factory=dict)
    result: Any = field(default=None, repr=False)

    @property
    def mode(self) -> str:
        return self.record.get("mode", "timeline")


@dataclass
class CheckReport:
    """Every outcome of a run, in file order, and its wall time."""

    outcomes: list[CheckOutcome] = field(default_factory=list)
    seconds: float = 0.0

    def count(self, status: str) -> int:
        return sum(1 for o in self.outcomes if o.status == status)

    @property
    def passed(self) -> int:
        return self.count("PASS")

    @property
    def failed(self) -> int:
        return self.count("FAIL")

    @property
    def errors(self) -> int:
        return self.count("ERROR")

    @property
    def skipped(self) -> int:
        return self.count("SKIP")

    @property
    def exit_code(self) -> int:
        """0 every run passed, 1 an expectation failed, 2 a file was unusable."""
        return 2 if self.errors else (1 if self.failed else 0)

    def summary(self) -> str:
        """``"3 passed, 1 failed, 0 errors[, 2 skipped] in 1.23s"``."""
        text = f"{self.passed} passed, {self.failed} failed, {self.errors} errors"
        if self.skipped:
            text += f", {self.skipped} skipped"
        return f"{text} in {self.seconds:.2f}s"

    def as_dict(self) -> dict[str, Any]:
        """The JSON report of ``ethimon check``."""
        return {"results": [o.record for o in self.outcomes], "passed": self.passed, "failed": self.failed,
                "errors": self.errors, "skipped": self.skipped, "seconds": self.seconds}

    def junit_xml(self) -> str:
        """The JUnit XML report (one test case per outcome)."""
        import xml.etree.ElementTree as ET
        results = [o.record for o in self.outcomes]
        suite = ET.Element("testsuite", name="ethimon check", tests=str(len(results)),
                           failures=str(self.failed), errors=str(self.errors), skipped=str(self.skipped),
                           time=f"{self.seconds:.3f}")
        for o in self.outcomes:
            case = ET.SubElement(suite, "testcase", classname=str(o.path), name=str(o.name))
            if o.status == "ERROR":
                ET.SubElement(case, "error", message=str(o.record.get("error", "; ".join(o.messages))))
            elif o.status == "SKIP":
                ET.SubElement(case, "skipped", message=str(o.record.get("skipped", "")))
            elif o.status == "FAIL":
                fails = [str(f) for f in o.record.get("failures", o.record.get("problems", []))]
                el = ET.SubElement(case, "failure", message="; ".join(fails))
                el.text = "\n".join(fails)
        return "<?xml version='1.0' encoding='utf-8'?>\n" + ET.tostring(suite, encoding="unicode") + "\n"


def _fresh(exc: BaseException) -> BaseException:
    """A new exception equal to ``exc`` (same type, message and fields), without its traceback."""
    try:
        new = copy.copy(exc)
    except Exception:  # noqa: BLE001 - a type that cannot be rebuilt from its args
        new = None
    if new is None or new is exc or type(new) is not type(exc) or str(new) != str(exc):
        new = RuntimeError(f"{type(exc).__name__}: {exc}")
    new.__traceback__ = new.__context__ = new.__cause__ = None
    return new


class _SpecLoadError(Exception):
    """Internal: wraps an unexpected exception raised by a scenario's spec (the row names the spec)."""

    def __init__(self, spec_path: str, exc: BaseException) -> None:
        super().__init__(str(exc))
        self.spec_path = spec_path
        self.exc = exc


def _missing(path: str) -> bool:
    """``path`` does not exist (a dangling link included); other stat errors are the loader's to say."""
    try:
        os.stat(path)
    except FileNotFoundError:
        return True
    except OSError:
        return False
    return False


def sim_risk_inputs(sc: Scenario, estimator: Callable[[], Any] | Any) -> dict[str, Any]:
    """The constant risk input of a scenario's ``sim:`` run (the one rule of ``simulate`` and ``check --sim``).

    The first of ``risk``, ``p_unsafe``, ``p`` in ``inputs``; else the first value of one of them in
    the timeline; else the task text scored by ``estimator`` (an object with ``probs(text)`` or a
    zero-argument factory of one), fed as ``p``.

    Raises:
        SpecError: no risk input and no task text (located at the scenario).
    """
    if not needs_text_risk(sc):
        for key in RISK_KEYS:
            if key in sc.inputs:
                return {key: sc.inputs[key]}
        for entry in sc.timeline:  # risk given only in the timeline: use its first value
            for key in RISK_KEYS:
                if key in entry.set:
                    return {key: entry.set[key]}
        return {}  # pragma: no cover - needs_text_risk is False only when one of the above holds
    if not sc.task:
        hint = "add 'task: ...' (scored by the risk model) or 'inputs: {p_unsafe: ...}'"
        msg = "scenario gives no risk input and no task text"
        raise sc._source.error(msg, (), hint=hint) if sc._source is not None else SpecError(msg, hint=hint)
    from ..risk import as_estimator
    est = as_estimator(estimator)
    return {"p": tuple(float(x) for x in est.probs(sc.task))}


class ScenarioSession:
    """Shared state of one run over many scenario files: specs read once, risk models loaded once.

    Args:
        model_dir: risk model directory for every scenario (default: each spec's
            ``risk.estimator.model``, else the shipped model).
    """

    def __init__(self, *, model_dir: str | None = None) -> None:
        self.model_dir = model_dir
        self._specs: dict[str, Any] = {}       # spec path -> Spec, or the exception loading it raised
        self._estimators: dict[tuple, Any] = {}

    # -- shared resources ----------------------------------------------------------------------------

    def spec_for(self, sc: Scenario) -> Any:
        """The scenario's spec, read once per session.

        Raises:
            SpecError: the spec is missing (located at the scenario's ``spec:``) or invalid; a failure
                is cached and raised again as a fresh copy for each scenario.
            _SpecLoadError: an unexpected exception of the spec (wrapping a fresh copy).
        """
        spath = sc.spec_path
        got = self._specs.get(spath)
        if got is None:
            if _missing(spath):  # said at the scenario's 'spec:' key, where the fix goes
                pos = sc._source.pos(("spec",)) if sc._source is not None else None
                raise SpecError(f"spec {sc.spec!r} not found (looked at {spath})", path=sc.path,
                                line=pos.line if pos else None, column=pos.column if pos else None,
                                hint="'spec:' is relative to the scenario file")
            from .. import _api
            try:
                got = _api.load_spec(spath)  # regular files only: a FIFO as spec is a SpecError
            except Exception as exc:  # noqa: BLE001 - a SpecError, or an internal error of this spec
                got = exc
            self._specs[spath] = got
        if isinstance(got, SpecError):
            raise _fresh(got) from None
        if isinstance(got, BaseException):
            raise _SpecLoadError(spath, _fresh(got)) from None
        return got

    def estimator_for(self, spec: Any) -> Callable[[], Any]:
        """A zero-argument factory of the spec's risk estimator (loaded on first call, then shared)."""
        def factory():
            # lazy: torch only when a text is scored
            from ..risk import as_estimator, default_threads, estimator_kwargs
            kw = estimator_kwargs(spec)
            if self.model_dir:
                kw["model_dir"] = self.model_dir
            key = tuple(sorted(kw.items()))
            if key not in self._estimators:
                # one task text per scenario: one thread (torch's default of 2 spins on busy cores)
                self._estimators[key] = as_estimator(kw["model_dir"], spec=spec, num_threads=default_threads(1))
            return self._estimators[key]
        return factory

    def sim_inputs(self, sc: Scenario, spec: Any) -> dict[str, Any]:
        """:func:`sim_risk_inputs` with this session's estimator of ``spec``."""
        return sim_risk_inputs(sc, self.estimator_for(spec))

    def run_sim(self, sc: Scenario, spec: Any, *, record_dir: str | None = None, gui: bool = False,
                inputs: dict[str, Any] | None = None):
        """Run the scenario's ``sim:`` block; returns ``(block, SimResult, sim problems)``.

        ``inputs``: the constant risk input, already worked out (:meth:`sim_inputs`; a pool worker
        is given the parent's, so that the risk model is loaded once, in the parent).

        Raises:
            DependencyNotInstalled: the simulator cannot be loaded.
        """
        try:
            from ..sim import SimBlock, check_sim_expectations, run_sim
        except ImportError as exc:
            raise DependencyNotInstalled(f"the simulator cannot be loaded: {exc}") from None
        from ..runtime import Monitor
        block = sc.sim if isinstance(sc.sim, SimBlock) else SimBlock.model_validate(sc.sim)
        try:
            fixed = self.sim_inputs(sc, spec) if inputs is None else inputs
            res = run_sim(block, Monitor(spec), record_dir=record_dir, gui=gui, **fixed)
        except SimError as exc:  # a sim: block that cannot be simulated, located where it says
            loc = getattr(exc, "loc", None)
            if loc is None or sc._source is None:
                raise
            raise sc._source.error(str(exc), loc, key=True, hint=getattr(exc, "hint", None)) from None
        return block, res, check_sim_expectations(block, res)

    # -- one file ------------------------------------------------------------------------------------

    def check_file(self, path: str, *, sim: bool = False, defer_sim: bool = False) -> list[CheckOutcome]:
        """``ethimon check`` of one scenario file: its timeline row, and its sim row with ``sim``.

        Never raises for a bad file: the problem is one ERROR outcome (its message names the file).
        ``defer_sim``: the sim row is not run here but returned as a ``"PENDING"`` outcome whose
        ``record["sim_inputs"]`` holds its risk input (:func:`check_paths` runs it in a worker).
        """
        from . import _run, load_scenario  # the package's name, looked up per call
        sc = None
        where = None
        try:
            sc = load_scenario(path)
            try:
                spec = self.spec_for(sc)
            except _SpecLoadError as exc:
                where = f"{exc.spec_path} (spec of {path})"
                raise exc.exc from None
            _run.check_input_names(sc, spec)
            out: list[CheckOutcome] = []
            # a sim scenario whose signals come from the simulator cannot run as a timeline
            sim_only = sc.sim is not None and any(name not in sc.inputs for name in spec.signals)
            if sim_only and not sim:
                return [CheckOutcome(sc.name, path, "SKIP", "(sim only)", "skipped: needs --sim",
                                     record={"name": sc.name, "path": path, "passed": None,
                                             "skipped": "needs --sim"})]
            if not sim_only:
                out.append(self._timeline_outcome(sc, spec, path))
            if sim and sc.sim is not None:
                if defer_sim:
                    out.append(CheckOutcome(f"{sc.name} [sim]", path, "PENDING",
                                            record={"sim_inputs": self.sim_inputs(sc, spec)}))
                else:
                    out.append(self._sim_outcome(sc, spec, path))
            return out
        except Exception as exc:  # noqa: BLE001 - one unusable file is one ERROR row; the others still run
            msg = error_line(path, exc, where=where)
            name = sc.name if sc is not None else path
            return [CheckOutcome(name, path, "ERROR", "-", "bad input", messages=[msg],
                                 record={"name": name, "path": path, "passed": False, "error": msg})]

    def _timeline_outcome(self, sc: Scenario, spec: Any, path: str) -> CheckOutcome:
        from ._run import run_scenario
        res = run_scenario(sc, spec=spec, estimator=self.estimator_for(spec))
        msgs = []
        if not res.passed:
            pos = sc._source.pos(("expect",)) if sc._source is not None else None
            line = pos.line if pos else None
            msgs = [f"{path}:{line}: {res.name}: {f}" if line else f"{path}: {res.name}: {f}"
                    for f in res.failures]
        return CheckOutcome(res.name, path, "PASS" if res.passed else "FAIL", res.expected, res.got,
                            res.first_override_cycle, msgs, {**res.as_dict(), "path": path}, res)

    def sim_row(self, path: str, inputs: dict[str, Any]) -> list[CheckOutcome]:
        """The sim row of ``check`` for one file whose timeline row has already been made (a pool
        worker's job): ``[sim outcome]``, or ``[ERROR outcome]`` that replaces the file's rows, as
        the serial :meth:`check_file` would have."""
        from . import load_scenario
        sc = None
        try:
            sc = load_scenario(path)
            try:
                spec = self.spec_for(sc)
            except _SpecLoadError as exc:
                raise exc.exc from None
            return [self._sim_outcome(sc, spec, path, inputs=inputs)]
        except Exception as exc:  # noqa: BLE001 - as check_file: one unusable file is one ERROR row
            msg = error_line(path, exc)
            name = sc.name if sc is not None else path
            return [CheckOutcome(name, path, "ERROR", "-", "bad input", messages=[msg],
                                 record={"name": name, "path": path, "passed": False, "error": msg})]

    def _sim_outcome(self, sc: Scenario, spec: Any, path: str, *,
                     inputs: dict[str, Any] | None = None) -> CheckOutcome:
        block, res, problems = self.run_sim(sc, spec, inputs=inputs)
        problems = problems + override_expectations(sc.expect, res.first_override_cycle)
        name = f"{sc.name} [sim]"
        record = {"name": name, "path": path, "passed": not problems, "failures": problems,
                  "first_override_cycle": res.first_override_cycle, "mode": "sim",
                  "time_to_safe_pose_s": res.time_to_safe_pose_s, "min_separation_m": res.min_separation_m,
                  "realtime_factor": res.realtime_factor}
        return CheckOutcome(name, path, "FAIL" if problems else "PASS", "sim expectations",
                            "no override" if res.first_override_cycle is None else "override",
                            res.first_override_cycle, [f"{path}: {name}: {p}" for p in problems], record, res)

    def simulate_file(self, path: str, *, record_dir: str | None = None, gui: bool = False,
                      require_sim: bool = True) -> CheckOutcome | None:
        """``ethimon simulate`` of one scenario file (its ``sim:`` block only).

        Returns ``None`` for a scenario without a ``sim:`` block when ``require_sim`` is false.
        ``record_dir`` is the folder above the recording: it goes to ``record_dir/<scenario name>/``.

        Raises:
            DependencyNotInstalled: the simulator cannot be loaded (no file can run).
        """
        from . import _run, load_scenario
        try:
            sc = load_scenario(path)
            if sc.sim is None:
                if not require_sim:
                    return None
                raise SpecError("the scenario has no 'sim:' block", path=path)
            spec = self.spec_for(sc)
            _run.check_input_names(sc, spec)
            rec = os.path.join(record_dir, sc.name) if record_dir else None
            block, res, problems = self.run_sim(sc, spec, record_dir=rec, gui=gui)
        except DependencyNotInstalled:
            raise
        except _SpecLoadError as exc:
            msg = error_line(path, exc.exc, where=f"{exc.spec_path} (spec of {path})")
            return CheckOutcome(path, path, "ERROR", messages=[msg], record={"path": path, "error": msg})
        except Exception as exc:  # noqa: BLE001 - one unusable file is one line; the others still run
            msg = error_line(path, exc)
            return CheckOutcome(path, path, "ERROR", messages=[msg], record={"path": path, "error": msg})
        return CheckOutcome(sc.name, path, "FAIL" if problems else "PASS", "sim expectations",
                            res.executed_response, res.first_override_cycle,
                            [f"{path}: {sc.name}: {p}" for p in problems],
                            {"name": sc.name, "path": path, "passed": not problems, "problems": problems,
                             **res.summary()}, res)


def _skipped(path: str, reason: str) -> CheckOutcome:
    return CheckOutcome(path, path, "SKIP", "-", "skipped: " + reason.split(",")[0].split(":")[0],
                        messages=[f"{path}: skipped: {reason}"],
                        record={"name": path, "path": path, "passed": None, "skipped": reason})


def check_paths(paths: Iterable[str], *, sim: bool = False, model_dir: str | None = None,
                on_progress: ProgressCallback | None = None, jobs: int = 1, executor: Any = None) -> CheckReport:
    """Run every scenario file under ``paths`` (files and folders): what ``ethimon check`` reports.

    One file is one unit of :func:`ethimon.run`: here (``executor`` ``None`` or ``ethimon.Serial()``), or
    one Ray task per file (``ethimon.fleet.Ray(...)``: the same outcomes in the same order, each with
    ``result`` ``None``, as workers return plain data; a file whose task raised, died or timed out is
    one ERROR outcome).

    Args:
        paths: scenario files or folders (``*.yaml``/``*.yml``, sorted; FIFOs, sockets and devices
            found in a folder are SKIP outcomes, never opened).
        sim: also run each ``sim:`` block in PyBullet (scenarios whose signals come from the
            simulator are SKIP outcomes without it).
        model_dir: the risk model of every scenario (default: each spec's).
        on_progress: ``on_progress(done, total, path)`` (see :data:`ProgressCallback`).
        jobs: serially with ``sim``, run the ``sim:`` blocks in a pool of this many worker processes
            (each its own PyBullet); the timelines, specs and risk model stay in this process. The
            outcomes, their order and every figure are the serial run's (``1``: serial, the default;
            a single sim row always runs in this process).
        executor: where the files run (see above).

    Raises:
        SpecError: a path given that does not exist or is not a regular file or folder, or a folder
            without YAML files (nothing can run).
    """
    from .._batch import Serial, Unit, run
    files = scan_yaml_files(paths, what="scenario", command="ethimon check")
    t0 = time.perf_counter()
    if executor is None or isinstance(executor, Serial):
        session = ScenarioSession(model_dir=model_dir)
        check = functools.partial(session.check_file, sim=sim, defer_sim=sim and jobs > 1)
        units = [Unit(check, (path,), path) if reason is None else Unit(_skipped, (path, reason), path)
                 for path, reason in files]
        rows = [_rows_of(o, list) for o in run(units, executor, on_progress).outcomes]
        _run_pending_sims(rows, session, jobs, model_dir)
    else:
        rows = _check_elsewhere(files, sim, model_dir, executor, on_progress)
    return CheckReport([o for out in rows for o in out], time.perf_counter() - t0)


def _rows_of(outcome: Any, rows: Callable[[Any], Any]) -> list[CheckOutcome]:
    """A unit's rows (a SKIP row is one outcome), or the one ERROR row of a unit that did not return."""
    if outcome.ok:
        v = outcome.value
        return [v] if isinstance(v, CheckOutcome) else list(rows(v))
    path = outcome.label
    msg = f"{path}: {outcome.error}"
    return [CheckOutcome(path, path, "ERROR", "-", "bad input", messages=[msg],
                         record={"name": path, "path": path, "passed": False, "error": msg})]


def _check_elsewhere(files, sim: bool, model_dir: str | None, executor: Any,
                     on_progress: ProgressCallback | None) -> list[list[CheckOutcome]]:
    """The files' rows with each readable file a unit on ``executor`` (plain data back)."""
    import uuid

    from .._batch import Unit, run
    todo = [path for path, reason in files if reason is None]
    skipped = len(files) - len(todo)

    def progress(done: int, total: int, label: str) -> None:
        if on_progress is not None:
            on_progress(done + skipped if done else 0, len(files), label)

    run_id = uuid.uuid4().hex
    got = iter(run([Unit(check_unit, (run_id, p, sim, model_dir), p) for p in todo], executor, progress).outcomes)
    return [[_skipped(path, reason)] if reason is not None
            else _rows_of(next(got), lambda v: [CheckOutcome(**d) for d in v]) for path, reason in files]


def _run_pending_sims(rows: list[list[CheckOutcome]], session: ScenarioSession, jobs: int,
                      model_dir: str | None) -> None:
    """``check --sim -j N``: the deferred sim rows (``PENDING``) in a pool of ``jobs`` processes (one
    alone runs here), put in place; an ERROR replaces the file's rows, as serially."""
    pending = [(i, out[-1].path, out[-1].record["sim_inputs"]) for i, out in enumerate(rows)
               if out and out[-1].status == "PENDING"]
    if not pending:
        return
    pool: _SimPool | None = _SimPool(jobs, model_dir) if len(pending) >= 2 else None
    try:
        if pool is None:
            done = [(i, session.sim_row(path, inputs)) for i, path, inputs in pending]
        else:
            for job in pending:
                pool.submit(*job)
            done = pool.results()
        for i, sim_rows in done:
            if sim_rows[0].status == "ERROR":
                rows[i] = sim_rows
            else:
                rows[i][-1:] = sim_rows
    finally:
        if pool is not None:
            pool.close()


_STATE: dict[str, Any] = {}  # "check" -> (key, session) of the run this process works for now


def outcome_as_plain(o: CheckOutcome) -> dict[str, Any]:
    """A :class:`CheckOutcome` as plain data (its ``result`` object is left out)."""
    from .._batch import plain
    return plain({"name": o.name, "path": o.path, "status": o.status, "expected": o.expected, "got": o.got,
                  "first_override_cycle": o.first_override_cycle, "messages": list(o.messages),
                  "record": o.record})


def check_unit(run_id: str, path: str, sim: bool, model_dir: str | None) -> list[dict[str, Any]]:
    """The unit of ``ethimon check`` on another process (``ethimon.run`` with ``fleet.Ray``): one file's
    outcomes as plain dicts (never raises for a bad file). A process keeps the specs and risk model of the
    run it works for (``run_id``), so a model loads once per worker, not once per file."""
    got = _STATE.get("check")
    if got is None or got[0] != (run_id, model_dir):  # a new run: drop the previous run's specs and models
        got = _STATE["check"] = ((run_id, model_dir), ScenarioSession(model_dir=model_dir))
    return [outcome_as_plain(o) for o in got[1].check_file(path, sim=sim)]


_WORKER_SESSION: ScenarioSession | None = None


def _worker_sim_row(path: str, inputs: dict[str, Any], model_dir: str | None) -> list[dict[str, Any]]:
    """A pool worker's job: the sim row of one file, as plain data (no result object, no trace)."""
    global _WORKER_SESSION
    if _WORKER_SESSION is None or _WORKER_SESSION.model_dir != model_dir:
        _WORKER_SESSION = ScenarioSession(model_dir=model_dir)  # specs read once per worker
    return [{"name": o.name, "path": o.path, "status": o.status, "expected": o.expected, "got": o.got,
             "first_override_cycle": o.first_override_cycle, "messages": list(o.messages),
             "record": dict(o.record)} for o in _WORKER_SESSION.sim_row(path, inputs)]


class _SimPool:
    """``check --sim -j N``: the sim rows in ``N`` spawned worker processes, collected in file order."""

    def __init__(self, jobs: int, model_dir: str | None) -> None:
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor
        # spawn: a fresh interpreter per worker (no forked PyBullet, ONNX or torch state)
        self._ex = ProcessPoolExecutor(max_workers=jobs, mp_context=multiprocessing.get_context("spawn"))
        self._model_dir = model_dir
        self._futures: list[tuple[int, str, Any]] = []

    def submit(self, index: int, path: str, inputs: dict[str, Any]) -> None:
        self._futures.append((index, path, self._ex.submit(_worker_sim_row, path, inputs, self._model_dir)))

    def results(self):
        """``(row index, [CheckOutcome])`` in submission order; a worker that died is an ERROR row."""
        for index, path, fut in self._futures:
            try:
                rows = [CheckOutcome(**d) for d in fut.result()]
            except Exception as exc:  # noqa: BLE001 - a crashed worker fails its file, not the run
                msg = internal_error(path, exc)
                rows = [CheckOutcome(path, path, "ERROR", "-", "bad input", messages=[msg],
                                     record={"name": path, "path": path, "passed": False, "error": msg})]
            yield index, rows

    def close(self) -> None:
        self._ex.shutdown(wait=True, cancel_futures=True)


def simulate_paths(paths: Iterable[str], *, model_dir: str | None = None, record_dir: str | None = None,
                   gui: bool = False, on_progress: ProgressCallback | None = None) -> CheckReport:
    """Run the ``sim:`` block of every scenario file under ``paths``: what ``ethimon simulate`` reports.

    Files passed over (FIFOs, sockets, devices in a folder) are SKIP outcomes; scenarios without a
    ``sim:`` block are left out, or an ERROR when a single file is given. Each file is one unit of
    :func:`ethimon.run`, here.

    Raises:
        SpecError: a bad path, or no scenario files at all.
        DependencyNotInstalled: the simulator cannot be loaded.
    """
    from .._batch import Unit, run
    paths = list(paths)
    scanned = scan_yaml_files(paths, what="scenario", command="ethimon simulate")
    readable = [p for p, reason in scanned if reason is None]
    if not readable:
        raise EthimonError(f"no scenario files under {' '.join(paths)}")
    session = ScenarioSession(model_dir=model_dir)
    one = functools.partial(session.simulate_file, record_dir=record_dir, gui=gui, require_sim=len(readable) == 1)
    t0 = time.perf_counter()
    got = run([Unit(one, (path,), path) if reason is None else Unit(_skipped, (path, reason), path)
               for path, reason in scanned], None, on_progress)
    rows = [r for o in got.outcomes for r in _rows_of(o, lambda v: []) if r is not None]
    return CheckReport(rows, time.perf_counter() - t0)
