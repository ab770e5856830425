"""Offline checking of a recorded trace, side by side: ethimon.offline vs the step loop vs RTAMT vs Reelay.

Run by hand (from the repository root; RTAMT and Reelay are the ``bench`` extra)::

    pip install -e '.[bench]'
    python -m bench.monitor.offline_check [--cycles 100000] [--windows 10 100 1000]
                                          [--json bench/results/monitor/offline_check.json]

Four obligations over one synthetic trace (a cobot cell: speed, separation
distance, contact flag, contact force), the window W of S2 and S4 growing from
10 to 1000 cycles:

* S1 invariant: ``speed <= 1.5``
* S2 bounded response: after a contact the arm is stopped (``speed <= 0.1``)
  within W cycles
* S3 separation: ``distance >= 0.5 or speed <= 0.25``
* S4 once: for W cycles after a contact force above 140 N, ``speed <= 0.25``

Timed, each from columns or rows already in memory: ``ethimon.offline.check_trace``
(with and without margins), ``Monitor.step`` over the rows, RTAMT's discrete-time
offline ``evaluate`` (one specification per obligation), and Reelay's discrete-time
monitors (one per obligation, ``update`` per cycle). Every tool's verdict of every
obligation on every cycle is compared.

Conventions aligned (documented in the JSON too):

* ethimon's ``once(e, W)`` counts the current cycle: it is ``once[0:W-1]`` in RTAMT/Reelay.
* A bounded response has no future operator here; the violation at ``t`` (some
  contact at ``j <= t - W`` with the arm moving at every cycle of ``j..t``) is the
  past-time formula ``historically[0:W](moving) and once[W:W](moving since (contact and moving))``,
  and the obligation holds where that is false. Before cycle W nothing is due (all three).
* RTAMT gives robustness: an obligation is violated where it is < 0. The trace is
  continuous-valued so that no cycle sits exactly on a threshold (robustness 0).
* ethimon also checks its built-in risk rule; the trace keeps R_e low and only the
  four obligations are compared. No input is missing or NaN (the peers have no fault
  semantics to compare with).

Not a test: the machine may be shared (the load average is recorded).
"""

from __future__ import annotations

import argparse
import gc
import json
import os
import statistics
import sys
import time

import numpy as np

import ethimon
from bench import RESULTS
from bench._machine import machine_facts
from ethimon.offline import check_trace

IDS = ("s1_speed", "s2_stop_after_contact", "s3_separation", "s4_slow_after_force")
V_MAX, V_STOP, V_SLOW, D_MIN, F_MAX = 1.5, 0.1, 0.25, 0.5, 140.0


def spec_text(w: int) -> str:
    """The S1-S4 spec with window ``w`` as YAML text (also parsed by another tree's ethimon in
    ``step_peers --baseline``)."""
    return f"""
ethimon: 1
name: s1_s4_w{w}
signals:
  speed:    {{unit: m/s, range: [0, 10]}}
  distance: {{unit: m, range: [0, 20]}}
  contact:  {{type: bool}}
  force:    {{unit: N, range: [0, 1000]}}
constants:
  v_max: {{value: {V_MAX}, unit: m/s}}
  v_stop: {{value: {V_STOP}, unit: m/s}}
  v_slow: {{value: {V_SLOW}, unit: m/s}}
  d_min: {{value: {D_MIN}, unit: m}}
  f_max: {{value: {F_MAX}, unit: N}}
obligations:
  - {{id: {IDS[0]}, require: "speed <= v_max"}}
  - {{id: {IDS[1]}, when: "contact", require: "speed <= v_stop", within_cycles: {w}}}
  - {{id: {IDS[2]}, require: "distance >= d_min or speed <= v_slow"}}
  - {{id: {IDS[3]}, require: "once(force > f_max, {w}) implies speed <= v_slow"}}
"""


def ethimon_spec(w: int) -> ethimon.Spec:
    return ethimon.load_spec_text(spec_text(w), f"<s1_s4_w{w}>")


def rtamt_formulas(w: int) -> list[str]:
    """Formulas that hold where the obligation holds (violated where robustness < 0)."""
    moving = f"(speed > {V_STOP})"
    return [
        f"speed <= {V_MAX}",
        f"not(historically[0:{w}]{moving} and once[{w}:{w}]({moving} since ((contact >= 0.5) and {moving})))",
        f"(distance >= {D_MIN}) or (speed <= {V_SLOW})",
        f"once[0:{w - 1}](force > {F_MAX}) -> (speed <= {V_SLOW})",
    ]


def reelay_formulas(w: int) -> list[str]:
    moving = f"{{speed > {V_STOP}}}"
    return [
        f"{{speed <= {V_MAX}}}",
        f"not (historically[0:{w}]{moving} and once[{w}:{w}]({moving} since ({{contact: true}} and {moving})))",
        f"{{distance >= {D_MIN}}} or {{speed <= {V_SLOW}}}",
        f"(once[0:{w - 1}]{{force > {F_MAX}}}) -> {{speed <= {V_SLOW}}}",
    ]


def make_trace(n: int, w: int, seed: int = 0) -> dict[str, np.ndarray]:
    """Speed with overspeed spells, contacts followed by a stop after 0..2W cycles, people walking
    in and out, force spikes; continuous values (no cycle exactly on a threshold)."""
    rng = np.random.default_rng(seed)
    t = np.arange(n)
    speed = 0.2 + 0.6 * (1 + np.sin(t / 700.0 + rng.uniform(0, 6))) + rng.uniform(0.001, 0.05, n)
    over = np.repeat(rng.random(n // 100 + 1) < 0.03, 100)[:n]
    speed = np.where(over, speed + 0.9, speed)
    contact = np.zeros(n, bool)
    for j in np.flatnonzero(rng.random(n) < 1 / 3000):
        contact[j] = True
        d = int(rng.integers(0, 2 * w + 1))
        speed[j + d: j + d + 300] = rng.uniform(0.0, 0.09)  # stopped (below v_stop)
    distance = 2.0 + 1.5 * np.sin(t / 1100.0) + rng.uniform(-0.05, 0.05, n)
    distance = np.clip(distance, 0.05, 19.0)
    force = rng.uniform(0.0, 40.0, n)
    force[rng.random(n) < 1 / 2500] = rng.uniform(150.0, 300.0)
    slow_after = np.zeros(n, bool)
    for j in np.flatnonzero(force > F_MAX):  # mostly slowed down after a force spike
        if rng.random() < 0.7:
            slow_after[j: j + w + 50] = True
    speed = np.where(slow_after, np.minimum(speed, rng.uniform(0.0, 0.24, n)), speed)
    speed = np.clip(speed, 0.0, 9.0)
    return {"speed": speed, "distance": distance, "contact": contact, "force": force,
            "p_unsafe": np.full(n, 0.05)}


def timed(fn, repeat: int) -> tuple[list[float], object]:
    out, times = None, []
    for _ in range(repeat):
        gc.collect()
        gc.disable()
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
        gc.enable()
    return times, out


def run_rtamt(formulas: list[str], cols: dict[str, np.ndarray], n: int) -> tuple[float, np.ndarray]:
    import rtamt
    data = {"time": list(range(n)), "speed": cols["speed"][:n].tolist(), "distance": cols["distance"][:n].tolist(),
            "contact": cols["contact"][:n].astype(float).tolist(), "force": cols["force"][:n].tolist()}
    specs = []
    for f in formulas:
        s = rtamt.StlDiscreteTimeOfflineSpecification()
        for v in ("speed", "distance", "contact", "force"):
            s.declare_var(v, "float")
        s.spec = f
        s.parse()
        specs.append(s)
    viol = np.zeros((n, len(formulas)), bool)
    total = 0.0
    gc.collect()
    for k, s in enumerate(specs):
        t0 = time.perf_counter()
        out = s.evaluate(data)
        total += time.perf_counter() - t0
        rob = np.array([r for _, r in out], dtype=float)
        viol[:, k] = rob < 0
    return total, viol


def run_reelay(formulas: list[str], rows: list[dict], n: int) -> tuple[float, np.ndarray]:
    import reelay
    mons = [reelay.discrete_timed_monitor(pattern=f, condense=False) for f in formulas]
    ok = np.zeros((n, len(formulas)), bool)
    gc.collect()
    gc.disable()
    t0 = time.perf_counter()
    cols = []
    for m in mons:
        upd = m.update
        cols.append([upd(r)["value"] for r in rows[:n]])
    dt = time.perf_counter() - t0
    gc.enable()
    for k, c in enumerate(cols):
        ok[:, k] = c
    return dt, ~ok


def run_step(spec, rows: list[dict], margins: bool, repeat: int) -> tuple[float, np.ndarray]:
    """The fastest of ``repeat`` runs of a fresh Monitor over the rows, and its verdicts."""
    best = float("inf")
    for _ in range(repeat):
        m = ethimon.Monitor(spec, margins=margins)
        step = m.step
        gc.collect()
        gc.disable()
        t0 = time.perf_counter()
        ds = [step(r) for r in rows]
        best = min(best, time.perf_counter() - t0)
        gc.enable()
    dt = best
    index = {oid: k for k, oid in enumerate(IDS)}
    viol = np.zeros((len(rows), len(IDS)), bool)
    for t, d in enumerate(ds):
        for v in d.violations:
            if v in index:
                viol[t, index[v]] = True
    return dt, viol


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--cycles", type=int, default=100_000)
    ap.add_argument("--windows", type=int, nargs="+", default=[10, 100, 1000])
    ap.add_argument("--repeat", type=int, default=15, help="repetitions of the offline check (min and median)")
    ap.add_argument("--step-repeat", type=int, default=3, help="repetitions of the step loop (the fastest counts)")
    ap.add_argument("--peer-cycles", type=int, default=None,
                    help="cycles given to RTAMT and Reelay (default: all; their rate is cycles/s either way)")
    ap.add_argument("--no-peers", action="store_true", help="ethimon only (RTAMT/Reelay not installed)")
    ap.add_argument("--json", default=str(RESULTS / "monitor" / "offline_check.json"))
    args = ap.parse_args()
    load_start = os.getloadavg()
    n = args.cycles
    rows_out = []
    for w in args.windows:
        spec = ethimon_spec(w)
        cols = make_trace(n, w)
        rows = [{"speed": float(a), "distance": float(b), "contact": bool(c), "force": float(d), "p_unsafe": 0.05}
                for a, b, c, d in zip(cols["speed"], cols["distance"], cols["contact"], cols["force"])]
        t_off, res = timed(lambda: check_trace(spec, cols), args.repeat)
        t_off_nm, res_nm = timed(lambda: check_trace(spec, cols, margins=False), args.repeat)
        assert res.fallback_cycles == 0
        t_step, v_step = run_step(spec, rows, True, args.step_repeat)
        t_step_nm, _ = run_step(spec, rows, False, args.step_repeat)
        v_off = res.violated
        entry = {
            "window": w, "cycles": n,
            "violations_per_obligation": dict(zip(IDS, v_off.sum(axis=0).tolist())),
            "ethimon_offline_s": {"min": min(t_off), "median": statistics.median(t_off), "runs": len(t_off)},
            "ethimon_offline_no_margins_s": {"min": min(t_off_nm), "median": statistics.median(t_off_nm)},
            "ethimon_step_loop_s": t_step, "ethimon_step_loop_no_margins_s": t_step_nm,
            "agree_offline_step": int((v_off == v_step).sum()),
            "obligation_cycles": int(v_off.size),
        }
        assert np.array_equal(res_nm.violated, v_off)
        if not args.no_peers:
            pn = min(n, args.peer_cycles or n)
            t_rt, v_rt = run_rtamt(rtamt_formulas(w), cols, pn)
            t_re, v_re = run_reelay(reelay_formulas(w), rows, pn)
            sub = v_off[:pn]
            entry.update({
                "peer_cycles": pn, "rtamt_evaluate_s": t_rt, "reelay_s": t_re,
                "agree_offline_rtamt": int((sub == v_rt).sum()), "agree_offline_reelay": int((sub == v_re).sum()),
                "agree_all_four": int(((sub == v_rt) & (sub == v_re) & (v_step[:pn] == sub)).sum()),
                "peer_obligation_cycles": int(sub.size),
            })
        rows_out.append(entry)
        print(f"window {w}: done", flush=True)

    def rate(cycles, s):
        return cycles / s if s else float("inf")

    print(f"\n{n:,} cycles, 4 obligations (S1-S4); cycles per second (higher is better); ratio: ethimon offline "
          "(with margins) / the other; 'no m.': both without margins")
    head = f"{'W':>5} | {'offline':>10} | {'step loop':>9} {'ratio':>6} | {'no m.':>10} {'no m.':>9} {'ratio':>6} | " \
           f"{'RTAMT':>7} {'ratio':>6} | {'Reelay':>8} {'ratio':>6} | agreement"
    print(head)
    print("-" * len(head))
    for e in rows_out:
        off = rate(n, e["ethimon_offline_s"]["min"])
        off_nm = rate(n, e["ethimon_offline_no_margins_s"]["min"])
        st = rate(n, e["ethimon_step_loop_s"])
        st_nm = rate(n, e["ethimon_step_loop_no_margins_s"])
        line = f"{e['window']:>5} | {off:>10,.0f} | {st:>9,.0f} {off / st:>5.0f}x | {off_nm:>10,.0f} {st_nm:>9,.0f} " \
               f"{off_nm / st_nm:>5.0f}x | "
        e["rates_cycles_per_s"] = {"offline": off, "offline_no_margins": off_nm, "step_loop": st,
                                   "step_loop_no_margins": st_nm}
        e["ratios"] = {"offline_vs_step_loop": off / st, "offline_vs_step_loop_no_margins": off_nm / st_nm}
        if "rtamt_evaluate_s" in e:
            rt, re_ = rate(e["peer_cycles"], e["rtamt_evaluate_s"]), rate(e["peer_cycles"], e["reelay_s"])
            e["rates_cycles_per_s"].update({"rtamt_evaluate": rt, "reelay": re_})
            e["ratios"].update({"offline_vs_rtamt": off / rt, "offline_vs_reelay": off / re_})
            line += f"{rt:>7,.0f} {off / rt:>5.0f}x | {re_:>8,.0f} {off / re_:>5.0f}x | " \
                    f"{e['agree_all_four']:,}/{e['peer_obligation_cycles']:,}"
        else:
            line += f"{'-':>7} {'-':>6} | {'-':>8} {'-':>6} | {e['agree_offline_step']:,}/{e['obligation_cycles']:,}"
        print(line)
    result = {
        "benchmark": "offline_check", "cycles": n, "windows": args.windows, "repeat": args.repeat,
        "step_repeat": args.step_repeat,
        "timing": "offline: fastest of --repeat runs; step loop: fastest of --step-repeat runs; RTAMT, Reelay: one run",
        "obligations": {"S1": "speed <= 1.5", "S2": "contact => speed <= 0.1 within W cycles",
                        "S3": "distance >= 0.5 or speed <= 0.25", "S4": "once(force > 140, W) implies speed <= 0.25"},
        "formulas_w10": {"rtamt": rtamt_formulas(10), "reelay": reelay_formulas(10)},
        "conventions": [
            "ethimon once(e, W) covers the current cycle: once[0:W-1] in RTAMT/Reelay",
            "bounded response as past time: violated = historically[0:W](moving) and "
            "once[W:W](moving since (contact and moving)); nothing due before cycle W",
            "RTAMT: violated where robustness < 0; no cycle lies exactly on a threshold",
            "only the four obligations are compared (ethimon's risk rule is not), no missing/NaN input",
            "times exclude building the columns/rows; RTAMT and Reelay get lists/dicts of built-in floats",
        ],
        "results": rows_out,
        "versions": _versions(),
        "machine": machine_facts(loadavg_start=[round(x, 2) for x in load_start]),
    }
    os.makedirs(os.path.dirname(args.json), exist_ok=True)
    with open(args.json, "w", encoding="utf-8") as fh:
        json.dump(result, fh, indent=2)
    print(f"\nload average {result['machine']['loadavg']} (start {result['machine']['loadavg_start']}); "
          f"wrote {args.json}")
    return 0


def _versions() -> dict:
    out = {}
    for name in ("rtamt", "reelay"):
        try:
            from importlib.metadata import version
            out[name] = version(name)
        except Exception:  # noqa: BLE001 - not installed
            out[name] = None
    return out


if __name__ == "__main__":
    sys.exit(main())
