"""Drive :class:`ethimon.io.LiveMonitor` through a :class:`MemoryChannel` on a fake clock, then replay its
recording; the two verdicts side by side, cycle by cycle (issue 31's differential test)."""

from __future__ import annotations

import ethimon
from ethimon.io import LiveMonitor, MemoryChannel, Recording, Sample
from ethimon.loop import GovernedLoop, LoopConfig
from ethimon.replay import recorded_data, replay_data

from tests._estimators import FakeClock

SPEC = """
ethimon: 1
name: io_diff
signals:
  speed: {unit: rad/s, range: [-1000, 1000]}
  dist: {unit: m, range: [0, 100]}
  estop: {type: bool}
risk: {threshold: 0.5, release: {mode: auto, hysteresis: 0.05, hold_cycles: 2}}
on_fault: {response: stop_1, release: {mode: auto, hold_cycles: 2}}
obligations:
  - {id: slow, require: "speed <= 2.0", response: stop_1, release: {mode: auto, hold_cycles: 2}}
  - {id: clear, require: "dist >= 0.5", response: stop_2, release: {mode: auto, hold_cycles: 3}}
  - {id: no_estop, require: "not estop", response: stop_0, release: {mode: auto, hold_cycles: 1}}
"""

MAPPING = """
ethimon: 1
rate_hz: 100
max_age_s: 0.0355
samples: latest
signals:
  speed: {topic: /js, field: position, derive: rate, reduce: max_abs}
  dist: {topic: /range, field: range, time: header}
  estop: {topic: /estop, field: data, max_age_s: 0.0505}
  p_unsafe: {topic: /p, field: data, max_age_s: 0.2}
"""


def spec():
    return ethimon.load_spec_text(SPEC)


def replay_of(samples, spec_, mapping):
    """Replay a :class:`Recording` (or bare samples: as if each were taken at its own time)."""
    rec = samples if isinstance(samples, Recording) else Recording(samples=list(samples))
    return replay_data(recorded_data(rec, mapping), spec_, mapping, keep_trace=True, engine="step")


def live_on_grid(samples, spec_, mapping, grid_ns, s0):
    """The live loop stepped at ``grid_ns[s0:]`` (a fake clock on both the log and the header clock), each
    sample delivered once its receive time has come; its decisions and the LiveMonitor."""
    clock = FakeClock(grid_ns[s0] / 1e9)
    ch = MemoryChannel(clock=clock)
    loop = GovernedLoop(ethimon.Monitor(spec_), clock=clock,
                        config=LoopConfig(period_s=1.0 / float(mapping.rate_hz), deadline_s=1e6, stall_s=1e6))
    live = LiveMonitor(loop, mapping, ch, record=True)
    todo = sorted(samples, key=lambda s: s.t_log)
    i, out = 0, []
    for k in range(s0, len(grid_ns)):
        now = grid_ns[k] / 1e9
        while i < len(todo) and int(round(todo[i].t_log * 1e9)) <= grid_ns[k]:
            s = todo[i]
            ch.publish(s.signal, s.value, s.t_log, s.t_header)
            i += 1
        clock.t = now
        out.append(loop.cycle())
    return out, live


def verdicts(samples, mapping_text=MAPPING):
    """(live, replay) verdicts per cycle from the replay's start cycle on: (override, severity, latched, fault,
    violations) each; and both runs."""
    from ethimon.io import load_mapping_text
    mapping = load_mapping_text(mapping_text)
    sp = spec()
    res = replay_of(samples, sp, mapping)
    grid = [int(x) for x in res.grid]
    s0 = res.started["cycle"]
    decisions, live = live_on_grid(samples, sp, mapping, grid, s0)
    # the live run's own recording, replayed, is what is compared (the recording is what a robot keeps)
    res2 = replay_of(live.recording, sp, mapping)
    assert [int(x) for x in res2.grid] == grid
    tr, ids = res2.trace, res2.trace.ids
    rep = [(bool(tr.override[k]), int(tr.severity[k]), bool(tr.latched[k]), bool(tr.fault[k]),
            frozenset(ids[j] for j in range(len(ids)) if tr.violated[k, j])) for k in range(s0, len(grid))]
    liv = [(d.override, d.response.severity, d.latched, bool(d.faults), frozenset(d.violations) - {"fault"})
           for d in decisions]
    return liv, rep, live, res2


def S(t, signal, value, header=None):
    return Sample(signal, value, t, header)
