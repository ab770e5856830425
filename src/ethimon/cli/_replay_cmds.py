"""``ethimon replay BAG... --spec SPEC --map MAP``: ROS bags in, verdicts out.

Prints one table row per obligation (and the risk rule, and the input faults) of
each bag: cycles violated, the first violation's time, the worst margin and
PASS/FAIL; a bag that cannot be read is one ERROR row and the others still run.
``--json`` / ``--junit`` as ``ethimon check``; ``--audit`` writes a hash-chained
audit log of the decisions. Exit 0 every check passed, 1 a violation or fault,
2 bad input (a bag, spec or mapping that cannot be used).
"""

from __future__ import annotations

import argparse
import sys
import time
import xml.etree.ElementTree as ET

from ._common import Progress, add_ray_options, emit_json, emit_report, err, ray_options

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
    p.add_argument("--schema", action="store_true", help="print the JSON Schema of mapping files and exit")
    p.add_argument("--quiet", "-q", action="store_true", help="print only problems and the summary")
    add_ray_options(p, "bags")
    p.set_defaults(handler=cmd_replay)


def cmd_replay(args: argparse.Namespace) -> int:
    from .. import _api
    from ..errors import EthimonError, SpecError
    from ..replay import TaskScorer, check_against_spec, load_mapping, mapping_json_schema
    from ..replay._record import bag_record

    if args.schema:
        emit_json("-", mapping_json_schema(), "JSON Schema")
        return 0
    try:
        ray, file_timeout = ray_options(args, "bags")  # ray None: serial; else (address, workers)
    except EthimonError as exc:
        return err(str(exc))
    if not args.bags:
        return err("ethimon replay: give at least one BAG (and --spec SPEC --map MAP)")
    if ray is not None and args.audit:
        return err("ethimon replay: --audit cannot be used with --ray (the audit log is one hash chain, "
                   "written in bag order by one process); run without --ray to write it")
    if not args.spec or not args.mapping:
        return err("ethimon replay: --spec SPEC and --map MAP are required")
    try:
        spec = _api.load_spec(args.spec)
        mapping = load_mapping(args.mapping)
        check_against_spec(mapping, spec)
    except SpecError as exc:
        print(str(exc), file=sys.stderr)
        return 2
    audit = None
    if args.audit:
        from ..audit import AuditLog, spec_hash
        try:
            audit = AuditLog(args.audit, fsync="interval", meta={
                "tool": "ethimon replay", "spec": args.spec, "spec_sha256": spec_hash(spec),
                "mapping": args.mapping, "bags": list(args.bags)})
        except FileExistsError:
            return err(f"{args.audit}: the audit log exists already (a log is never appended to; pick a new name)")
        except OSError as exc:
            return err(f"{args.audit}: cannot write the audit log: {exc.strerror or exc}")
    json_to_stdout = args.json == "-"
    out = sys.stderr if json_to_stdout else sys.stdout  # stdout is the JSON's alone
    results: list[dict] = []
    t0 = time.perf_counter()
    try:
        with Progress("replay", enabled=not json_to_stdout) as progress:
            if ray is None:
                scorer = TaskScorer(spec, model_dir=args.model)
                for i, bag in enumerate(args.bags):
                    progress(i, len(args.bags), bag)
                    results.append(bag_record(bag, spec, mapping, score=scorer, audit=audit))
                progress(len(args.bags), len(args.bags), "")
            else:  # the same records, each bag on a Ray worker
                from ..fleet import replay_records
                results = replay_records(args.bags, spec=args.spec, mapping=args.mapping, model_dir=args.model,
                                         on_bag=progress, address=ray[0], num_cpus=ray[1],
                                         file_timeout=file_timeout)
    finally:
        if audit is not None:
            audit.close()
    rows, problems = [], []
    n_pass = n_fail = n_err = 0
    for bag, rec in zip(args.bags, results):
        if "error" in rec:
            n_err += 1
            rows.append((bag, "-", "-", "-", "-", "ERROR"))
            problems.append(rec["error"])
            continue
        if rec["passed"]:
            n_pass += 1
        else:
            n_fail += 1
        for c in rec["checks"]:
            fv = c["first_violation"]
            first = "-" if fv is None else f"{fv['t_s']:.3f} s (cycle {fv['cycle']})"
            rows.append((bag, c["id"], str(c["cycles_violated"]), first, _margin(c["worst_margin"]),
                         "PASS" if c["passed"] else "FAIL"))
            if not c["passed"]:
                what = "failed closed" if c["kind"] == "faults" else "violated"
                line = (f"{bag}: {c['id']}: {what} on {c['cycles_violated']} of {rec['cycles']} cycles, first at "
                        f"t = {fv['t_s']:.3f} s (bag time {_stamp(fv['bag_time_ns'])}, cycle {fv['cycle']})")
                if c["worst_margin"] is not None:
                    line += f", worst margin {_margin(c['worst_margin'])}"
                if c["detail"]:
                    line += f": {c['detail']}"
                problems.append(line)
    elapsed = time.perf_counter() - t0
    if not args.quiet:
        _print_table(rows, out)
    for msg in problems:
        print(msg, file=sys.stderr)
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
            if c["passed"]:
                cases.append((r["path"], c["id"], None, ""))
            else:
                fv = c["first_violation"] or {}
                msg = (f"{c['id']}: {c['cycles_violated']} cycles, first at t = {fv.get('t_s')} s "
                       f"(bag time {fv.get('bag_time_ns')} ns, cycle {fv.get('cycle')}), worst margin "
                       f"{c['worst_margin']}" + (f": {c['detail']}" if c["detail"] else ""))
                cases.append((r["path"], c["id"], "failure", msg))
    suite = ET.Element("testsuite", name="ethimon replay", tests=str(len(cases)),
                       failures=str(sum(1 for c in cases if c[2] == "failure")),
                       errors=str(sum(1 for c in cases if c[2] == "error")), time=f"{elapsed:.3f}")
    for path, name, kind, msg in cases:
        case = ET.SubElement(suite, "testcase", classname=str(path), name=str(name))
        if kind is not None:
            el = ET.SubElement(case, kind, message=msg)
            el.text = msg
    return "<?xml version='1.0' encoding='utf-8'?>\n" + ET.tostring(suite, encoding="unicode") + "\n"
