"""``ethimon check PATH...``: run scenarios, print a table, exit 0 / 1 / 2."""

from __future__ import annotations

import argparse
import copy
import json
import sys
import time
import xml.etree.ElementTree as ET

from ..errors import DependencyNotInstalled, EthimonError, ModelError, SpecError

__all__ = ["add_check_parser", "cmd_check"]


def add_check_parser(sub) -> None:
    p = sub.add_parser("check", help="run scenario files against their specs",
                       description="Run every scenario; exit 0 all pass, 1 an expectation failed, 2 bad input.")
    p.add_argument("paths", nargs="+", metavar="PATH", help="scenario files or folders")
    p.add_argument("--json", metavar="FILE", help="write results as JSON ('-' for stdout)")
    p.add_argument("--junit", metavar="FILE", help="write a JUnit XML report")
    p.add_argument("--sim", action="store_true", help="also run scenarios with a 'sim:' block in PyBullet")
    p.add_argument("--model", metavar="DIR", help="risk model directory for every scenario "
                   "(default: each spec's risk.estimator.model, else the shipped model)")
    p.add_argument("--quiet", "-q", action="store_true", help="print only problems and the summary")
    p.set_defaults(handler=cmd_check)


class _Estimators:
    """Risk models loaded on first use, one per distinct ``risk.estimator`` block (``--model`` wins)."""

    def __init__(self, model_dir: str | None) -> None:
        self.model_dir = model_dir
        self.loaded: dict[tuple, object] = {}

    def for_spec(self, spec):
        """A zero-argument factory (what ``run_scenario`` accepts) of the spec's estimator."""
        def factory():
            from ..risk import estimator_kwargs, load_estimator_for
            kw = estimator_kwargs(spec)
            if self.model_dir:
                kw["model_dir"] = self.model_dir
            key = tuple(sorted(kw.items()))
            if key not in self.loaded:
                self.loaded[key] = load_estimator_for(spec, model_dir=kw["model_dir"])
            return self.loaded[key]
        return factory


def _expect_line(sc) -> int | None:
    if sc is None or sc._source is None:
        return None
    p = sc._source.pos(("expect",))
    return p.line if p else None


def internal_error(where: str, exc: BaseException) -> str:
    """One line for an unexpected exception from one file: ``where: internal error: Type: text``."""
    text = str(exc)
    if len(text) > 300:
        text = text[:297] + "..."
    what = f"{type(exc).__name__}: {text}" if text else type(exc).__name__
    return f"{where}: internal error: {what} (this file could not be checked; please report this)"


def cmd_check(args: argparse.Namespace) -> int:
    from ..scenario._run import scan_yaml_files

    files = scan_yaml_files(args.paths, what="scenario", command="ethimon check")
    ests = _Estimators(args.model)
    rows, results, problems = [], [], []
    bad_input = failed = False
    specs: dict[str, object] = {}  # spec path -> Spec, or the exception that loading it raised
    t0 = time.perf_counter()
    for path, reason in files:
        if reason is not None:  # a FIFO, socket or device in a folder: never opened
            rows.append((path, "-", "skipped: not a regular file", "-", "SKIP"))
            results.append({"name": path, "path": path, "passed": None, "skipped": reason})
            print(f"{path}: skipped: {reason}", file=sys.stderr)
            continue
        ctx: dict[str, object] = {}
        try:
            failed = _check_one(path, args, ests, specs, rows, results, problems, ctx) or failed
        except Exception as exc:  # one unusable file is one ERROR row; the others still run
            bad_input = True
            if isinstance(exc, SpecError):
                msg = str(exc)
            elif isinstance(exc, (DependencyNotInstalled, ModelError, EthimonError)):
                msg = f"{path}: {exc}"
            else:
                sc = ctx.get("scenario")
                from_spec = sc is not None and bool(ctx.get("from_spec"))
                msg = internal_error(f"{sc.spec_path} (spec of {path})" if from_spec else path, exc)
            problems.append(msg)
            name = ctx["scenario"].name if "scenario" in ctx else path
            rows.append((name, "-", "bad input", "-", "ERROR"))
            results.append({"name": name, "path": path, "passed": False, "error": msg})
    elapsed = time.perf_counter() - t0
    n_pass = sum(1 for r in rows if r[4] == "PASS")
    n_fail = sum(1 for r in rows if r[4] == "FAIL")
    n_err = sum(1 for r in rows if r[4] == "ERROR")
    n_skip = sum(1 for r in rows if r[4] == "SKIP")
    if not args.quiet:
        _print_table(rows)
    for p in problems:
        print(p, file=sys.stderr)
    summary = f"{n_pass} passed, {n_fail} failed, {n_err} errors"
    if n_skip:
        summary += f", {n_skip} skipped"
    print(f"{summary} in {elapsed:.2f}s")
    if args.json:
        doc = json.dumps({"results": results, "passed": n_pass, "failed": n_fail, "errors": n_err,
                          "skipped": n_skip, "seconds": elapsed}, indent=2, default=str)
        if args.json == "-":
            print(doc)
        elif not _report(args.json, doc + "\n", "JSON report"):
            bad_input = True
    if args.junit and not _report(args.junit, _junit_xml(results, elapsed), "JUnit report"):
        bad_input = True
    return 2 if bad_input else (1 if failed else 0)


def write_report(path: str, text: str, what: str) -> None:
    """Write a report file without ever blocking on a FIFO that has no reader
    (:func:`ethimon._files.open_regular`; a FIFO with a reader or ``/dev/null`` is accepted).

    Raises:
        SpecError: the file cannot be written (one line, names the path).
    """
    from .._files import open_regular
    with open_regular(path, "w", what=what, error=SpecError, special_ok=True) as fh:
        try:
            fh.write(text)
        except OSError as exc:
            raise SpecError(f"cannot write the {what}: {exc.strerror or exc}", path=path) from None


def _report(path: str, text: str, what: str) -> bool:
    try:
        write_report(path, text, what)
        return True
    except SpecError as exc:
        print(str(exc), file=sys.stderr)
        return False


def _load_spec_for(sc, path, specs, ctx=None):
    """The scenario's spec, read once per run (a spec that failed fails every scenario using it).

    A failure is cached and raised again as a fresh copy for each scenario (no traceback or
    context chained across scenarios); ``ctx["from_spec"]`` is set when the error is the spec's.
    """
    got = specs.get(sc.spec_path)
    if got is None:
        from .. import _api
        try:
            got = _api.load_spec(sc.spec_path)  # regular files only: a FIFO as spec is a SpecError
        except Exception as exc:  # noqa: BLE001 - a SpecError, or an internal error of this spec, per scenario
            got = exc
        specs[sc.spec_path] = got
    if isinstance(got, BaseException):
        if ctx is not None:
            ctx["from_spec"] = True
        if (isinstance(got, SpecError) and got.path == sc.spec_path
                and ("not found" in got.message or "no such file" in got.message)):
            pos = sc._source.pos(("spec",))
            raise SpecError(f"spec {sc.spec!r} not found (looked at {sc.spec_path})", path=path,
                            line=pos.line if pos else None, column=pos.column if pos else None,
                            hint="'spec:' is relative to the scenario file") from None
        raise _fresh(got) from None
    return got


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


def _check_one(path, args, ests, specs, rows, results, problems, ctx) -> bool:
    """Run one scenario file (timeline, and sim with ``--sim``); returns whether an expectation failed.

    Adds its rows; ``ctx["scenario"]`` is the scenario once it is read (for the error row).
    """
    from ..scenario import check_input_names, load_scenario, run_scenario

    sc = ctx["scenario"] = load_scenario(path)
    spec = _load_spec_for(sc, path, specs, ctx)
    check_input_names(sc, spec)
    failed = False
    # a sim scenario whose signals come from the simulator cannot run as a timeline
    sim_only = sc.sim is not None and any(name not in sc.inputs for name in spec.signals)
    if sim_only and not args.sim:
        rows.append((sc.name, "(sim only)", "skipped: needs --sim", "-", "SKIP"))
        results.append({"name": sc.name, "path": path, "passed": None, "skipped": "needs --sim"})
        return False
    if not sim_only:
        res = run_scenario(sc, spec=spec, estimator=ests.for_spec(spec))
        first = "-" if res.first_override_cycle is None else str(res.first_override_cycle)
        rows.append((res.name, res.expected, res.got, first, "PASS" if res.passed else "FAIL"))
        results.append({**res.as_dict(), "path": path})
        if not res.passed:
            failed = True
            line = _expect_line(sc)
            for f in res.failures:
                problems.append(f"{path}:{line}: {res.name}: {f}" if line else f"{path}: {res.name}: {f}")
    if args.sim and sc.sim is not None:
        sim_row, sim_res, sim_problems = _run_sim(sc, spec, ests.for_spec(spec), path)
        rows.append(sim_row)
        results.append(sim_res)
        problems.extend(sim_problems)
        failed = failed or bool(sim_problems)
    return failed


def _run_sim(sc, spec, estimator, path):
    try:
        from ..sim import check_sim_expectations, run_sim
        from ..sim._model import SimBlock
    except ImportError as exc:
        raise DependencyNotInstalled(f"--sim needs the simulator: {exc}") from None
    from ..runtime import Monitor
    from ..scenario._run import RISK_KEYS, needs_text_risk, override_expectations
    block = SimBlock.model_validate(sc.sim)
    kwargs = {}
    if needs_text_risk(sc):
        kwargs["probs"] = tuple(estimator().probs(sc.task))
    else:
        for key in RISK_KEYS:
            if key in sc.inputs:
                kwargs[key] = sc.inputs[key]
                break
    res = run_sim(block, Monitor(spec), **kwargs)
    problems = check_sim_expectations(block, res)
    problems += override_expectations(sc.expect, res.first_override_cycle)
    first = "-" if res.first_override_cycle is None else str(res.first_override_cycle)
    got = "no override" if res.first_override_cycle is None else "override"
    row = (f"{sc.name} [sim]", "sim expectations", got, first, "FAIL" if problems else "PASS")
    out = {"name": f"{sc.name} [sim]", "path": path, "passed": not problems, "failures": problems,
           "first_override_cycle": res.first_override_cycle, "mode": "sim",
           "time_to_safe_pose_s": getattr(res, "time_to_safe_pose_s", None),
           "min_separation_m": getattr(res, "min_separation_m", None),
           "realtime_factor": getattr(res, "realtime_factor", None)}
    return row, out, [f"{path}: {sc.name} [sim]: {p}" for p in problems]


def _print_table(rows) -> None:
    header = ("scenario", "expected", "got", "first override", "result")
    table = [header] + [tuple(str(c) for c in r) for r in rows]
    widths = [min(max(len(r[i]) for r in table), 44) for i in range(len(header))]

    def fmt(r):
        cells = []
        for c, w in zip(r, widths):
            c = c if len(c) <= w else c[: w - 1] + "…"
            cells.append(c.ljust(w))
        return "  ".join(cells).rstrip()
    print(fmt(header))
    print("  ".join("-" * w for w in widths))
    for r in table[1:]:
        print(fmt(r))


def _junit_xml(results: list[dict], elapsed: float) -> str:
    suite = ET.Element("testsuite", name="ethimon check", tests=str(len(results)),
                       failures=str(sum(1 for r in results if r.get("passed") is False and "error" not in r)),
                       errors=str(sum(1 for r in results if "error" in r)),
                       skipped=str(sum(1 for r in results if r.get("skipped"))), time=f"{elapsed:.3f}")
    for r in results:
        case = ET.SubElement(suite, "testcase", classname=str(r.get("path")), name=str(r.get("name")))
        if "error" in r:
            ET.SubElement(case, "error", message=str(r["error"]))
        elif r.get("skipped"):
            ET.SubElement(case, "skipped", message=str(r["skipped"]))
        elif r.get("passed") is False:
            el = ET.SubElement(case, "failure", message="; ".join(r.get("failures", [])))
            el.text = "\n".join(r.get("failures", []))
    return "<?xml version='1.0' encoding='utf-8'?>\n" + ET.tostring(suite, encoding="unicode") + "\n"
