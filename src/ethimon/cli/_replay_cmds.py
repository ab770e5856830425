"""``ethimon replay BAG... --spec SPEC --map MAP``: ROS bags in, verdicts out.

Prints one table row per obligation (and the risk rule, and the input faults) of
each bag: cycles violated, the first violation's time, the worst margin and
PASS / FAIL / NOT EVALUATED / NOT CHECKED; a bag that cannot be read is one ERROR
row and the others still run. ``--json`` / ``--junit`` as ``ethimon check``;
``--audit`` writes a hash-chained audit log of the decisions; ``--mcap OUT`` the
verdicts as MCAP topics; ``ethimon replay BAG --topics`` lists a bag's topics.
Exit 0 every check passed, 1 a violation or fault, 2 bad input (a bag, spec or
mapping that cannot be used).
"""

from __future__ import annotations

import argparse
import sys
import time
import xml.etree.ElementTree as ET
from typing import Any

from ._common import Progress, add_ray_options, emit_json, emit_report, err, open_audit_log, ray_options

__all__ = ["add_replay_parsers", "cmd_replay"]


def add_replay_parsers(sub) -> None:
    p = sub.add_parser(
        "replay", help="replay ROS bags through a spec's monitor (needs ethimon[ros])",
        description="Replay ROS 2 (sqlite3, MCAP) and ROS 1 bags through the monitor of SPEC, with the "
                    "topics mapped to signals by MAP (resampled to the monitor's rate, zero-order hold, "
                    "stale or missing inputs fail closed). Exit 0 all checks pass, 1 a violation or fault, "
                    "2 bad input.")
    p.add_argument("bags", nargs="*", metavar="BAG",
                   help="ROS 2 bag folders (or .mcap/.db3 files) and ROS 1 .bag files")
    p.add_argument("--spec", metavar="SPEC", help="the spec to check against")
    p.add_argument("--map", dest="mapping", metavar="MAP", help="the mapping file (topics → signals)")
    p.add_argument("--json", metavar="FILE", help="write results as JSON ('-' for stdout: then stdout holds "
                   "only the JSON, the table and summary go to stderr)")
    p.add_argument("--junit", metavar="FILE", help="write a JUnit XML report (one test case per check)")
    p.add_argument("--audit", metavar="FILE", help="write the decisions to a new hash-chained audit log "
                   "(one record per change; 'ethimon audit verify FILE' checks it)")
    p.add_argument("--model", metavar="DIR", help="risk model that scores the task texts "
                   "(default: the spec's risk.estimator.model, else the shipped model)")
    p.add_argument("--mcap", metavar="OUT", help="write each cycle's decision, margins, faults, R_e and inputs as "
                   "MCAP topics on the bag's timeline (for Foxglove); with several bags OUT is a folder")
    p.add_argument("--foxglove", nargs="?", const="127.0.0.1:8765", metavar="[HOST:]PORT",
                   help="serve the verdicts (the --mcap channels) to a live Foxglove view as the bag replays "
                        "(WebSocket; needs ethimon[foxglove]; default 127.0.0.1:8765, loopback unless a host is named)")
    p.add_argument("--foxglove-speed", type=float, default=1.0, metavar="X",
                   help="with --foxglove: X times the bag's own pace (default 1; 0: as fast as it goes)")
    p.add_argument("--foxglove-wait-s", type=float, default=60.0, metavar="S",
                   help="with --foxglove: wait up to S seconds for a client to subscribe before serving (default 60)")
    p.add_argument("--topics", action="store_true", help="list each BAG's topics (type, count, rate, log and header "
                   "time spans, fields, joint names) and exit; needs no --spec or --map")
    p.add_argument("--schema", action="store_true", help="print the JSON Schema of mapping files and exit")
    p.add_argument("--quiet", "-q", action="store_true", help="print only problems and the summary")
    add_ray_options(p, "bags")
    p.set_defaults(handler=cmd_replay)


def _open_view(args: argparse.Namespace, spec: Any) -> tuple[Any, int | None]:
    """``--foxglove``: the live view of the replay's verdicts, once a client subscribed (or the wait ended)."""
    from ..errors import DependencyNotInstalled
    from ..runtime import Monitor
    from ..view import FoxgloveView, VerdictChannels, parse_address
    try:
        address = "%s:%d" % parse_address(args.foxglove)
        view = FoxgloveView(VerdictChannels.of_spec(spec, Monitor(spec).obligation_ids), address,
                            queue=4096, name="ethimon replay")
    except ValueError as exc:
        return None, err(f"--foxglove: {exc}")
    except (DependencyNotInstalled, OSError) as exc:
        return None, err(f"--foxglove: {exc}")
    if not args.quiet:
        print(f"ethimon replay: Foxglove view on {view.url}: open it in Foxglove (Open connection, Foxglove "
              f"WebSocket; layout examples/foxglove/ethimon-layout.json); waiting up to {args.foxglove_wait_s:g} s "
              "for a subscriber", file=sys.stderr, flush=True)
    if args.foxglove_wait_s > 0 and not view.wait_subscribed(1, args.foxglove_wait_s, settle_s=0.3) and not args.quiet:
        print("ethimon replay: no Foxglove client subscribed; replaying anyway", file=sys.stderr, flush=True)
    return view, None


def cmd_replay(args: argparse.Namespace) -> int:
    from ..errors import EthimonError
    from ..io import lint_mapping, mapping_json_schema

    if args.schema:
        emit_json("-", mapping_json_schema(), "JSON Schema")
        return 0
    if args.topics:
        return _cmd_topics(args)
    try:
        ray, file_timeout = ray_options(args, "bags")  # ray None: serial; else (address, workers)
    except EthimonError as exc:
        return err(str(exc))
    refused = _refusal(args, ray)
    if refused is not None:
        return err(refused)
    spec, mapping = _load(args)  # a SpecError: printed located by main, exit 2
    view, audit, rc = _sinks(args, spec)
    if rc is not None:
        return rc
    out = sys.stderr if args.json == "-" else sys.stdout  # stdout is the JSON's alone
    t0 = time.perf_counter()
    try:
        report = _replay(args, spec, mapping, ray, file_timeout, audit, view)
    except OSError as exc:
        return err(f"--mcap {args.mcap}: {exc.strerror or exc}")
    finally:
        if audit is not None:
            audit.close()
        if view is not None:
            view.close(timeout=10.0)  # what is queued goes out first
    rows, problems, notes = [], [], [f"{args.mapping}: lint: {w}" for w in lint_mapping(mapping, spec)]
    for bag, rec in zip(args.bags, report.results):
        _bag_lines(bag, rec, rows, problems, notes)
    return _finish(args, report, rows, problems, notes, time.perf_counter() - t0, out)


def _refusal(args: argparse.Namespace, ray: Any) -> str | None:
    """Why these arguments cannot run (one line), or ``None``."""
    if not args.bags:
        return "ethimon replay: give at least one BAG (and --spec SPEC --map MAP)"
    if ray is not None and args.audit:
        return ("ethimon replay: --audit cannot be used with --ray (the audit log is one hash chain, "
                "written in bag order by one process); run without --ray to write it")
    if ray is not None and args.mcap:
        return "ethimon replay: --mcap cannot be used with --ray; run without --ray to write it"
    if ray is not None and args.foxglove is not None:
        return "ethimon replay: --foxglove cannot be used with --ray; run without --ray to serve it"
    if args.foxglove is not None:
        from ..view import parse_address
        try:
            parse_address(args.foxglove)
        except ValueError as exc:
            return f"--foxglove: {exc}"
    if not (args.foxglove_speed >= 0 and args.foxglove_speed != float("inf")):
        return f"--foxglove-speed {args.foxglove_speed:g}: expected a number >= 0 (0: no pacing)"
    if not (args.foxglove_wait_s >= 0 and args.foxglove_wait_s != float("inf")):
        return f"--foxglove-wait-s {args.foxglove_wait_s:g}: expected a number of seconds >= 0"
    if not args.spec or not args.mapping:
        return ("ethimon replay: --spec SPEC and --map MAP are required (ethimon replay BAG --topics lists "
                "a bag's topics to write the mapping from)")
    return None


def _load(args: argparse.Namespace) -> tuple[Any, Any]:
    """The spec and the mapping, checked against each other (a ``SpecError`` otherwise)."""
    from .. import _api
    from ..io import check_against_spec, load_mapping
    spec = _api.load_spec(args.spec)
    mapping = load_mapping(args.mapping)
    check_against_spec(mapping, spec)
    return spec, mapping


def _sinks(args: argparse.Namespace, spec: Any) -> tuple[Any, Any, int | None]:
    """``(live view, audit log, exit code if one could not open)``."""
    view = audit = None
    if args.foxglove is not None:
        view, rc = _open_view(args, spec)
        if rc is not None:
            return None, None, rc
    if args.audit:
        audit, rc = open_audit_log(args.audit, spec, tool="ethimon replay", spec=args.spec, mapping=args.mapping,
                                   bags=list(args.bags))
        if rc is not None:
            return view, None, rc
    return view, audit, None


def _replay(args: argparse.Namespace, spec: Any, mapping: Any, ray: Any, file_timeout: float | None,
            audit: Any, view: Any) -> Any:
    """The bags replayed here (``replay_paths``) or each on a Ray worker (``replay_records``): a report."""
    from ..replay import TaskScorer
    from ..replay._record import ReplayReport, replay_paths, replay_records
    json_to_stdout = args.json == "-"
    with Progress("replay", enabled=not json_to_stdout) as progress, _MessageBar(enabled=not json_to_stdout) as bar:
        if ray is None:
            scorer = TaskScorer(spec, model_dir=args.model)
            return replay_paths(args.bags, spec, mapping, score=scorer, audit=audit, mcap=args.mcap,
                                on_progress=lambda i, n, b: (bar.new(b), progress(i, n, b)),
                                on_messages=bar, foxglove=view, foxglove_speed=args.foxglove_speed)
        from ..fleet import Ray  # the same records, each bag on a Ray worker
        return ReplayReport(replay_records(args.bags, spec=args.spec, mapping=args.mapping, model_dir=args.model,
                                           on_progress=progress,
                                           executor=Ray(ray[0], num_cpus=ray[1], file_timeout=file_timeout)))


def _bag_lines(bag: str, rec: dict, rows: list, problems: list, notes: list) -> None:
    """One bag's table rows, problems (stderr) and notes (stderr unless ``--quiet``)."""
    if "error" in rec:
        rows.append((bag, "-", "-", "-", "-", "ERROR"))
        problems.append(rec["error"])
        return
    for c in rec["checks"]:
        fv = c["first_violation"]
        first = "-" if fv is None else f"{fv['t_s']:.3f} s (cycle {fv['cycle']})"
        status = c.get("status") or ("PASS" if c["passed"] else "FAIL")
        rows.append((bag, c["id"], str(c["cycles_violated"]), first, _margin(c["worst_margin"]), status))
        if status == "FAIL":
            what = "failed closed" if c["kind"] == "faults" else "violated"
            line = (f"{bag}: {c['id']}: {what} on {c['cycles_violated']} of {rec['cycles']} cycles, first at "
                    f"t = {fv['t_s']:.3f} s (bag time {_stamp(fv['bag_time_ns'])}, cycle {fv['cycle']})")
            if c["worst_margin"] is not None:
                line += f", worst margin {_margin(c['worst_margin'])}"
            if c["detail"]:
                line += f": {c['detail']}"
            problems.append(line)
        elif status != "PASS":
            notes.append(f"{bag}: {c['id']}: {status}: {c['detail']}")
    problems.extend(_run_lines(bag, rec))
    for task in rec.get("tasks", []):
        if "outcome" in task:
            text = task["text"] if len(task["text"]) <= 80 else task["text"][:77] + "..."
            r_e = "-" if task.get("r_e") is None else f"{task['r_e']:.3f}"
            at = "" if task.get("t_s") is None else f" at t = {task['t_s']:.3f} s"
            notes.append(f"{bag}: task{at}: {text!r}: R_e {r_e}: {task['outcome']}")
    if rec.get("started", {}).get("note"):
        notes.append(f"{bag}: {rec['started']['note']}")
    for w in rec.get("warnings", []):
        notes.append(f"{bag}: warning: {w}")
    for name, sg in rec.get("signals", {}).items():
        if "judged" in sg and sg.get("samples", sg["messages"]) != sg["judged"]:
            notes.append(f"{bag}: {name} ({sg['topic']}): read {sg['messages']:,} messages, judged "
                         f"{sg['judged']:,} of {sg.get('samples', sg['messages']):,} samples")
    if "mcap" in rec:
        notes.append(f"{bag}: wrote {rec['mcap']['messages']:,} MCAP messages to {rec['mcap']['path']}")
    if "foxglove" in rec:
        notes.append(f"{bag}: served {rec['foxglove']['cycles']:,} cycles to {rec['foxglove']['url']}")


def _finish(args: argparse.Namespace, report: Any, rows: list, problems: list, notes: list, elapsed: float,
            out: Any) -> int:
    """Print the table, the inputs, the problems, the notes and the summary; write the reports; the exit code."""
    results = report.results
    if not args.quiet:
        _print_table(rows, out)
        for rec in results:
            if "error" not in rec and rec.get("signals"):
                _print_inputs(rec, out)
    for msg in problems:
        print(msg, file=sys.stderr)
    if not args.quiet:
        for msg in notes:
            print(msg, file=sys.stderr)
    n_pass, n_fail, n_err = report.passed, report.failed, report.errors
    print(f"{n_pass} passed, {n_fail} failed, {n_err} errors in {elapsed:.2f}s "
          f"({len(args.bags)} bag{'s' if len(args.bags) != 1 else ''})", file=out)
    rc = 2 if n_err else (1 if n_fail else 0)
    doc = {"results": results, "passed": n_pass, "failed": n_fail, "errors": n_err, "seconds": elapsed,
           "spec": args.spec, "mapping": args.mapping}
    if args.json and not emit_json(args.json, doc):
        rc = 2
    if args.junit and not emit_report(args.junit, _junit_xml(results, elapsed), "JUnit report",
                                      dash_is_stdout=False):
        rc = 2
    return rc


#: how many override runs the text lists per bag (the JSON lists more; the one to the end always shows)
SHOWN_RUNS = 10


def _run_lines(bag: str, rec: dict) -> list[str]:
    """The override of one bag as a person reads it: the cycle total, every run (or the first
    :data:`SHOWN_RUNS`, "... N more" and the one that lasts to the end of the bag), why each began,
    which latch held it and how that latch is released."""
    runs = rec.get("latches", [])
    n_over, n = rec.get("override_cycles", 0), rec["cycles"]
    if not n_over:
        return []
    total = rec.get("override_runs", len(runs))
    lines = [f"{bag}: override on {n_over:,} of {n:,} cycles ({100.0 * n_over / max(n, 1):.1f} %), "
             f"in {total:,} run{'s' if total != 1 else ''}"]
    shown = runs[:SHOWN_RUNS]
    last = runs[-1] if runs and runs[-1]["until_end"] else None
    for run in shown:
        lines.append(_run_line(bag, run))
    hidden = total - len(shown) - (1 if last is not None and last not in shown else 0)
    if hidden > 0:
        lines.append(f"{bag}: ... {hidden:,} more override run{'s' if hidden != 1 else ''} (--json lists up to "
                     f"{len(runs):,})")
    if last is not None and last not in shown:
        lines.append(_run_line(bag, last))
    return lines


def _run_line(bag: str, run: dict) -> str:
    held = run.get("held_by") or []
    how = "; ".join(f"{h}: released {run['released_by'].get(h) or 'by its release rule'}" for h in held)
    end = {"end_of_bag": "and lasted to the end of the bag",
           "fresh_start": "then every input had been seen and the monitor started fresh"}.get(
        run.get("ended", "end_of_bag" if run["until_end"] else ""), "then the arm was released")
    text = (f"{bag}: override from t = {run['t_s']:.3f} s (cycle {run['from_cycle']}) for {run['cycles']:,} cycles "
            f"({run['seconds']:.3f} s), begun by {run['cause']}")
    if held:
        text += f"; held at its end by the latch{'es' if len(held) != 1 else ''} of {', '.join(held)} ({how})"
    return f"{text}, {end}"


def _print_inputs(rec: dict, out) -> None:
    """Per input: messages read and samples judged (a cycle held it), missing and stale cycles."""
    print(f"inputs of {rec['path']} ({rec['cycles']:,} cycles at {rec['rate_hz']:g} Hz, "
          f"{rec['duration_s']:.3f} s):", file=out)
    for name, sg in rec["signals"].items():
        judged = sg.get("judged")
        extra = "" if judged is None else f", judged {judged:,} of {sg.get('samples', sg['messages']):,} samples"
        print(f"  {name:<20} {sg['topic']:<28} read {sg['messages']:,}{extra}, missing {sg['missing_cycles']:,} / "
              f"stale {sg.get('stale_cycles', 0):,} cycles", file=out)


class _MessageBar:
    """A message-count progress bar on stderr for long bags (TTY only, tqdm if installed)."""

    def __init__(self, *, enabled: bool) -> None:
        self.enabled = enabled and _tty()
        self.bar = None
        self.desc = ""

    def __enter__(self) -> "_MessageBar":
        return self

    def new(self, bag: str) -> None:
        self.close()
        self.desc = bag[-30:]

    def __call__(self, done: int, total: int) -> None:
        if not self.enabled or total < 100_000:
            return
        if self.bar is None:
            try:
                from tqdm import tqdm
            except ImportError:
                self.enabled = False
                return
            self.bar = tqdm(total=total, desc=self.desc, unit="msg", unit_scale=True, file=sys.stderr, leave=False,
                            dynamic_ncols=True)
        self.bar.update(min(done, total) - self.bar.n)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
            self.bar = None

    def __exit__(self, *exc) -> None:
        self.close()


def _tty() -> bool:
    try:
        return bool(sys.stdout.isatty() and sys.stderr.isatty())
    except (AttributeError, ValueError):
        return False


def _cmd_topics(args: argparse.Namespace) -> int:
    """``ethimon replay BAG... --topics``: what each bag holds, to write a mapping from."""
    from ..errors import DependencyNotInstalled
    from ..replay import BagError, list_topics
    if not args.bags:
        return err("ethimon replay --topics: give at least one BAG")
    rc = 0
    docs = []
    for bag in args.bags:
        try:
            with _MessageBar(enabled=args.json != "-") as bar:
                bar.new(bag)
                storage, topics = list_topics(bag, on_progress=bar)
        except (BagError, DependencyNotInstalled) as exc:
            print(f"{bag}: {exc}" if isinstance(exc, DependencyNotInstalled) else str(exc), file=sys.stderr)
            docs.append({"path": bag, "error": str(exc)})
            rc = 2
            continue
        docs.append({"path": bag, "storage": storage, "topics": [t.as_dict() for t in topics]})
        if args.json == "-":
            continue
        print(f"{bag} ({storage}, {len(topics)} topics)")
        rows = [("topic", "type", "count", "rate", "log time (s)", "header time (s)")]
        for t in topics:
            rate = "-" if t.rate_hz is None else f"{t.rate_hz:.1f} Hz"
            log = "-" if t.log_first is None else f"{_sec(t.log_first)} .. {_sec(t.log_last)}"
            if t.header_first is not None:
                hdr = f"{_sec(t.header_first)} .. {_sec(t.header_last)}"
                if t.header_zero:
                    hdr += f" ({t.header_zero:,} unset)"
            else:
                hdr = f"unset on all {t.header_zero:,}" if t.header_zero else "-"
            rows.append((t.topic, t.type, f"{t.count:,}", rate, log, hdr))
        widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
        for r in rows:
            print("  " + "  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip())
        for t in topics:
            if t.error:
                print(f"  {t.topic}: cannot deserialise: {t.error}")
            elif t.fields:
                line = f"  {t.topic} fields: {', '.join(t.fields)}"
                if t.names:
                    line += f"; names: {', '.join(t.names)} (select one: field: position[{t.names[0]}])"
                print(line)
    if args.json:
        if not emit_json(args.json, {"bags": docs}):
            rc = 2
    return rc


def _sec(t_ns: int | None) -> str:
    return "-" if t_ns is None else f"{t_ns / 1e9:.3f}"


def _margin(m: float | str | None) -> str:
    if m is None:
        return "-"
    if isinstance(m, str):  # a record's infinite margin: "inf" / "-inf"
        return m
    if m != m:
        return "nan"
    if m in (float("inf"), float("-inf")):
        return "inf" if m > 0 else "-inf"
    return f"{m:.4g}"


def _stamp(t_ns: int | None) -> str:
    if t_ns is None:
        return "-"
    return f"{t_ns // 1_000_000_000}.{t_ns % 1_000_000_000:09d}"


def _print_table(rows, out) -> None:
    header = ("bag", "check", "cycles violated", "first", "worst margin", "result")
    table = [header] + [tuple(str(c) for c in r) for r in rows]
    widths = [min(max(len(r[i]) for r in table), 44) for i in range(len(header))]

    def fmt(r):
        cells = []
        for i, (c, w) in enumerate(zip(r, widths)):
            if len(c) > w:  # a long bag path keeps its end, other cells their start
                c = "…" + c[-(w - 1):] if i == 0 else c[: w - 1] + "…"
            cells.append(c.ljust(w))
        return "  ".join(cells).rstrip()
    print(fmt(header), file=out)
    print("  ".join("-" * w for w in widths), file=out)
    for r in table[1:]:
        print(fmt(r), file=out)


def _junit_xml(results: list[dict], elapsed: float) -> str:
    cases = []
    for r in results:
        if "error" in r:
            cases.append((r["path"], "replay", "error", r["error"]))
            continue
        for c in r["checks"]:
            status = c.get("status") or ("PASS" if c["passed"] else "FAIL")
            if status == "PASS":
                cases.append((r["path"], c["id"], None, ""))
            elif status in ("NOT EVALUATED", "NOT CHECKED"):
                cases.append((r["path"], c["id"], "skipped", f"{status}: {c['detail']}"))
            else:
                fv = c["first_violation"] or {}
                msg = (f"{c['id']}: {c['cycles_violated']} cycles, first at t = {fv.get('t_s')} s "
                       f"(bag time {fv.get('bag_time_ns')} ns, cycle {fv.get('cycle')}), worst margin "
                       f"{c['worst_margin']}" + (f": {c['detail']}" if c["detail"] else ""))
                cases.append((r["path"], c["id"], "failure", msg))
    suite = ET.Element("testsuite", name="ethimon replay", tests=str(len(cases)),
                       failures=str(sum(1 for c in cases if c[2] == "failure")),
                       skipped=str(sum(1 for c in cases if c[2] == "skipped")),
                       errors=str(sum(1 for c in cases if c[2] == "error")), time=f"{elapsed:.3f}")
    for path, name, kind, msg in cases:
        case = ET.SubElement(suite, "testcase", classname=str(path), name=str(name))
        if kind is not None:
            el = ET.SubElement(case, kind, message=msg)
            el.text = msg
    return "<?xml version='1.0' encoding='utf-8'?>\n" + ET.tostring(suite, encoding="unicode") + "\n"
