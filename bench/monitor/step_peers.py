"""Monitor.step per cycle, side by side in one process with RTAMT and Reelay (S1-S4, one trace).

Run by hand (from the repository root; RTAMT and Reelay are the ``bench`` extra)::

    pip install -e '.[bench]'
    python -m bench.monitor.step_peers [--cycles 20000] [--rounds 9] [--window 10]
                                       [--baseline DIR] [--json bench/results/monitor/step_peers.json]

The four obligations S1-S4 and the trace of ``bench/monitor/offline_check.py`` (speed,
separation distance, contact flag, contact force; window W of S2 and S4), checked online,
one cycle at a time, by:

* ``Monitor.step`` with margins (robustness of every obligation) and without;
* RTAMT's discrete-time online monitor (``StlDiscreteTimeSpecification.update``, one
  specification per obligation; it computes robustness);
* Reelay's discrete-time monitors (``update`` per cycle, one per obligation), with its
  boolean semantics and with its robustness semantics (its C++ core).

Every tool gets its inputs prepared outside the timed loop (dicts of built-in floats/bools
for ethimon and Reelay, lists of ``(name, value)`` for RTAMT). Timing: ``--rounds`` rounds;
in each round every tool runs a fresh monitor over the same ``--cycles`` cycles, the tools'
order rotating from round to round, so load changes on a shared machine hit all of them
alike; the figure is the median over rounds of µs per cycle, and the ratios are taken within
each round and their median reported. ``--baseline DIR`` adds ``Monitor.step`` of another
source tree (``DIR/ethimon``, e.g. ``git archive <commit> src | tar -x -C /tmp/base``, then
``--baseline /tmp/base/src``), loaded as a second package in the same process.

Verdicts are compared on every cycle (all tools agree, as in ``offline_check``). Not a test:
the machine may be shared; the load average is recorded.
"""

from __future__ import annotations

import argparse
import gc
import importlib.util
import json
import os
import statistics
import sys
import time

import numpy as np

import ethimon
from bench import RESULTS, load_baseline
from bench._machine import machine_facts
from bench.monitor.offline_check import D_MIN, F_MAX, IDS, V_MAX, V_SLOW, V_STOP, make_trace, spec_text


def rtamt_formulas(w: int) -> list[str]:
    moving = f"(speed > {V_STOP})"
    return [
        f"speed <= {V_MAX}",
        f"not(historically[0:{w}]{moving} and once[{w}:{w}]({moving} since ((contact >= 0.5) and {moving})))",
        f"(distance >= {D_MIN}) or (speed <= {V_SLOW})",
        f"once[0:{w - 1}](force > {F_MAX}) -> (speed <= {V_SLOW})",
    ]


def reelay_formulas(w: int, robustness: bool) -> list[str]:
    moving = f"{{speed > {V_STOP}}}"
    contact = "{contact > 0.5}" if robustness else "{contact: true}"
    return [
        f"{{speed <= {V_MAX}}}",
        f"not (historically[0:{w}]{moving} and once[{w}:{w}]({moving} since ({contact} and {moving})))",
        f"{{distance >= {D_MIN}}} or {{speed <= {V_SLOW}}}",
        f"(once[0:{w - 1}]{{force > {F_MAX}}}) -> {{speed <= {V_SLOW}}}",
    ]


def _loop_step(make):
    def run(rows):
        step = make().step
        gc.disable()
        t0 = time.perf_counter()
        out = [step(r) for r in rows]
        dt = time.perf_counter() - t0
        gc.enable()
        return dt, out
    return run


def _loop_rtamt(formulas):
    import rtamt

    def run(rows_rt):
        specs = []
        for f in formulas:
            s = rtamt.StlDiscreteTimeSpecification()
            for v in ("speed", "distance", "contact", "force"):
                s.declare_var(v, "float")
            s.spec = f
            s.parse()
            specs.append(s)
        cols = []
        gc.disable()
        t0 = time.perf_counter()
        for s in specs:
            upd = s.update
            cols.append([upd(t, r) for t, r in enumerate(rows_rt)])
        dt = time.perf_counter() - t0
        gc.enable()
        return dt, cols
    return run


def _loop_reelay(formulas, semantics):
    import reelay

    def run(rows):
        mons = [reelay.discrete_timed_monitor(pattern=f, semantics=semantics, condense=False) for f in formulas]
        cols = []
        gc.disable()
        t0 = time.perf_counter()
        for m in mons:
            upd = m.update
            cols.append([upd(r)["value"] for r in rows])
        dt = time.perf_counter() - t0
        gc.enable()
        return dt, cols
    return run


def _key(d) -> tuple:
    """A Decision as plain values (the two trees' Decision classes differ, so == between them is False)."""
    return (d.cycle, d.override, d.response.value, d.violations, d.risk, d.latched,
            tuple((f.kind, f.message) for f in d.faults), d.awaiting_release)


def _viol_ethimon(ds) -> np.ndarray:
    index = {oid: k for k, oid in enumerate(IDS)}
    viol = np.zeros((len(ds), len(IDS)), bool)
    for t, d in enumerate(ds):
        for v in d.violations:
            if v in index:
                viol[t, index[v]] = True
    return viol


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cycles", type=int, default=20_000)
    ap.add_argument("--rounds", type=int, default=9)
    ap.add_argument("--window", type=int, default=10)
    ap.add_argument("--baseline", default=None, help="a src/ directory of another tree (its ethimon, timed too)")
    ap.add_argument("--baseline-label", default=None, help="what the baseline is (a commit), for the JSON")
    ap.add_argument("--json", default=str(RESULTS / "monitor" / "step_peers.json"))
    args = ap.parse_args()
    load_start = [round(x, 2) for x in os.getloadavg()]
    n, w = args.cycles, args.window
    spec = ethimon.load_spec_text(spec_text(w), f"<s1_s4_w{w}>")
    cols = make_trace(n, w)
    rows = [{"speed": float(a), "distance": float(b), "contact": bool(c), "force": float(d), "p_unsafe": 0.05}
            for a, b, c, d in zip(cols["speed"], cols["distance"], cols["contact"], cols["force"])]
    rows_rt = [[("speed", r["speed"]), ("distance", r["distance"]), ("contact", float(r["contact"])),
                ("force", r["force"])] for r in rows]
    rows_rb = [{"speed": r["speed"], "distance": r["distance"], "contact": float(r["contact"]),
                "force": r["force"]} for r in rows]
    tools = {
        "step_margins": (_loop_step(lambda: ethimon.Monitor(spec, margins=True)), rows),
        "step_no_margins": (_loop_step(lambda: ethimon.Monitor(spec, margins=False)), rows),
    }
    missing = [p for p in ("rtamt", "reelay") if importlib.util.find_spec(p) is None]
    if missing:  # a peer not installed is left out (said in the output and the JSON), never faked
        print(f"not installed, left out: {', '.join(missing)} (pip install -e '.[bench]')", flush=True)
    if "rtamt" not in missing:
        tools["rtamt_online"] = (_loop_rtamt(rtamt_formulas(w)), rows_rt)
    if "reelay" not in missing:
        tools["reelay_boolean"] = (_loop_reelay(reelay_formulas(w, False), "boolean"), rows)
        tools["reelay_robustness"] = (_loop_reelay(reelay_formulas(w, True), "robustness"), rows_rb)
    if args.baseline:
        base = load_baseline(args.baseline)
        bspec = base.load_spec_text(spec_text(w), f"<s1_s4_w{w}>")
        tools["baseline_step_margins"] = (_loop_step(lambda: base.Monitor(bspec, margins=True)), rows)
        tools["baseline_step_no_margins"] = (_loop_step(lambda: base.Monitor(bspec, margins=False)), rows)
    names = list(tools)
    times: dict[str, list[float]] = {k: [] for k in names}
    outs: dict[str, object] = {}
    for rnd in range(args.rounds):
        order = names[rnd % len(names):] + names[:rnd % len(names)]
        for k in order:
            fn, data = tools[k]
            gc.collect()
            dt, out = fn(data)
            times[k].append(dt / n * 1e6)
            if rnd == 0:
                outs[k] = out
        print(f"round {rnd + 1}/{args.rounds}: " + ", ".join(f"{k} {times[k][-1]:.2f}" for k in names), flush=True)

    # verdicts: every tool, every obligation, every cycle
    v_step = _viol_ethimon(outs["step_margins"])
    agree = {}
    for k in names:
        if k.startswith(("step", "baseline")):
            v = _viol_ethimon(outs[k])
        elif k == "rtamt_online":
            v = np.array(outs[k], dtype=float).T < 0
        elif k == "reelay_robustness":
            v = np.array(outs[k], dtype=float).T < 0
        else:
            v = ~np.array(outs[k], dtype=bool).T
        agree[k] = int((v == v_step).sum())
    if "baseline_step_margins" in outs:  # the same Decision on every cycle, margins bit for bit
        agree["baseline_decisions_identical"] = all(
            _key(a) == _key(b) and len(a.margins) == len(b.margins) and all(
                (x != x and y != y) or (x == y and str(x) == str(y)) for x, y in zip(a.margins, b.margins))
            for a, b in zip(outs["baseline_step_margins"], outs["step_margins"]))

    med = {k: statistics.median(v) for k, v in times.items()}

    def ratio(peer: str, ours: str) -> float:  # > 1: ours is faster; median of per-round ratios
        return statistics.median(p / o for p, o in zip(times[peer], times[ours]))

    ratios = {}
    if "rtamt_online" in times:
        ratios["rtamt_over_step_margins"] = ratio("rtamt_online", "step_margins")
    if "reelay_boolean" in times:
        ratios["reelay_robustness_over_step_margins"] = ratio("reelay_robustness", "step_margins")
        ratios["reelay_boolean_over_step_margins"] = ratio("reelay_boolean", "step_margins")
        ratios["reelay_boolean_over_step_no_margins"] = ratio("reelay_boolean", "step_no_margins")
    if args.baseline:
        ratios["baseline_over_step_margins"] = ratio("baseline_step_margins", "step_margins")
        ratios["baseline_over_step_no_margins"] = ratio("baseline_step_no_margins", "step_no_margins")
    targets = {f"{k} >= {v:g}": ratios[k] >= v for k, v in (
        ("rtamt_over_step_margins", 10), ("reelay_robustness_over_step_margins", 1.2),
        ("reelay_boolean_over_step_no_margins", 2)) if k in ratios}

    print(f"\n{n:,} cycles x {args.rounds} rounds, S1-S4, window {w}; µs per cycle (median over rounds), "
          "agreement with Monitor.step's verdicts")
    for k in names:
        print(f"  {k:<26} {med[k]:>8.2f} µs   min {min(times[k]):>7.2f}   agree {agree[k]:,}/{v_step.size:,}")
    if "baseline_decisions_identical" in agree:
        print(f"  baseline and this tree: the same Decision (margins bit for bit) on every cycle: "
              f"{agree['baseline_decisions_identical']}")
    print("ratios (peer time / ethimon time, median of per-round ratios; > 1: ethimon faster):")
    for k, v in ratios.items():
        print(f"  {k:<44} {v:>6.2f}")
    for k, ok in targets.items():
        print(f"  target {k}: {'met' if ok else 'MISSED'}")
    result = {
        "benchmark": "step_peers", "cycles": n, "rounds": args.rounds, "window": w,
        "obligations": {"S1": "speed <= 1.5", "S2": "contact => speed <= 0.1 within W cycles",
                        "S3": "distance >= 0.5 or speed <= 0.25", "S4": "once(force > 140, W) implies speed <= 0.25"},
        "formulas": {"rtamt": rtamt_formulas(w), "reelay_boolean": reelay_formulas(w, False),
                     "reelay_robustness": reelay_formulas(w, True)},
        "timing": "each round: every tool once, fresh monitor, same cycles, order rotating; "
                  "µs per cycle = loop time / cycles; median over rounds; ratios: median of per-round ratios",
        "us_per_cycle_median": med, "us_per_cycle_rounds": times, "ratios": ratios, "targets_met": targets,
        "agreement": agree, "obligation_cycles": int(v_step.size),
        "baseline": {"dir": args.baseline, "label": args.baseline_label} if args.baseline else None,
        "peers_not_installed": missing,
        "versions": _versions(),
        "machine": machine_facts(loadavg_start=load_start),
    }
    os.makedirs(os.path.dirname(args.json), exist_ok=True)
    with open(args.json, "w", encoding="utf-8") as fh:
        json.dump(result, fh, indent=2)
    print(f"\nload average {result['machine']['loadavg']} (start {load_start}); wrote {args.json}")
    return 0


def _versions() -> dict:
    out = {}
    from importlib.metadata import version
    for name in ("rtamt", "reelay"):
        try:
            out[name] = version(name)
        except Exception:  # noqa: BLE001 - not installed
            out[name] = None
    return out


if __name__ == "__main__":
    sys.exit(main())
