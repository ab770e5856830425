"""Hardening of the governed loop and the audit trail (issue 11).

Hangs and unbounded memory: ``audit verify`` on a FIFO / ``/dev/stdin`` / an
over-long line; a writer that falls behind (records, bytes, age); a log closed
or a writer dead mid-run; an estimator that holds the GIL. And reloads that
weaken monitoring.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import threading
import time
import tracemalloc
from pathlib import Path

import pytest

import ethimon
from ethimon.audit import AuditFormatError, AuditLog, read_log, verify_log
from ethimon.audit import _log
from ethimon.audit._log import GENESIS, canonical, record_hash
from ethimon.loop import AsyncRiskSource, GovernedLoop, LoopConfig, ProcessEstimator, Watchdog

from tests._estimators import FakeClock, ScriptedEstimator, run_in_thread, wait_for
from tests.loop.test_loop import CELL, SAFE

ROOT = Path(__file__).resolve().parents[2]
MAX_RECORD_BYTES = getattr(_log, "MAX_RECORD_BYTES", 1 << 20)  # the documented cap: 1 MiB


def _loop(clock=None, spec=CELL, **kw):
    clock = clock or FakeClock()
    if "risk" not in kw:
        src = AsyncRiskSource(ScriptedEstimator(), text="wipe the table", clock=clock, start=False)
        src.poll_once()
        kw["risk"] = src
    return GovernedLoop(ethimon.Monitor(ethimon.load_spec_text(spec)), clock=clock,
                        config=LoopConfig(period_s=0.001), **kw), clock


def _gate_writer(log):
    """Hold the writer thread inside its next write until the returned event is set."""
    gate = threading.Event()
    real = log._write

    def slow(records, force_sync=False):
        gate.wait(10.0)
        real(records, force_sync)

    log._write = slow
    return gate


# ================================================================ audit verify: hangs and memory


def test_verify_refuses_a_fifo_without_blocking(tmp_path):
    fifo = tmp_path / "log.fifo"
    os.mkfifo(fifo)
    hung, out = run_in_thread(lambda: verify_log(fifo))
    if hung:  # unblock the stuck open() so the thread can end, then fail
        fd = os.open(fifo, os.O_WRONLY | os.O_NONBLOCK)
        os.close(fd)
    assert not hung, "verify_log blocked on a FIFO"
    assert isinstance(out.get("exc"), AuditFormatError) and "not a regular file" in str(out["exc"])


@pytest.mark.slow
def test_cli_verify_refuses_dev_stdin_pipe_without_blocking():
    # stdin is a pipe nobody writes to: reading it would block forever
    proc = subprocess.Popen([sys.executable, "-m", "ethimon.cli._audit_cmds", "audit", "verify", "/dev/stdin"],
                            stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            cwd=ROOT)
    try:
        out, err = proc.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()
        pytest.fail("audit verify /dev/stdin blocked")
    assert proc.returncode == 2 and "regular file" in err and "Traceback" not in err


def _record(seq: int, prev: str, **fields) -> tuple[bytes, str]:
    rec = {"kind": fields.pop("kind", "decision"), "t": 1.0, "seq": seq, "prev": prev, **fields}
    h = record_hash(rec)
    body = canonical(rec)
    return body[:-1] + b',"hash":"' + h.encode() + b'"}\n', h


def _log_with_line3(payload: str) -> bytes:
    l0, h0 = _record(0, GENESIS, kind="open", format="ethimon-audit/1", log_id="x")
    l1, h1 = _record(1, h0, cycle=0)
    l2, _ = _record(2, h1, cycle=1, inputs={"blob": payload})
    return l0 + l1 + l2


def test_verify_refuses_an_over_long_record_naming_its_line(tmp_path):
    p = tmp_path / "big.jsonl"
    p.write_bytes(_log_with_line3("x" * (MAX_RECORD_BYTES + 10)))  # a correctly hashed, but huge, record
    rep = verify_log(p)
    assert not rep.ok and rep.line == 3 and rep.records == 2
    assert "longer than" in rep.error and str(MAX_RECORD_BYTES) in rep.error
    # just under the cap still verifies
    p2 = tmp_path / "ok.jsonl"
    p2.write_bytes(_log_with_line3("x" * (MAX_RECORD_BYTES - 400)))
    assert verify_log(p2).ok


def test_verify_memory_is_bounded_on_a_huge_line(tmp_path):
    p = tmp_path / "huge.jsonl"
    head = _log_with_line3("y")
    with open(p, "wb") as fh:
        fh.write(head)
        chunk = b"z" * (1 << 20)
        for _ in range(24):  # a 24 MiB line without a newline
            fh.write(chunk)
    tracemalloc.start()
    try:
        rep = verify_log(p)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert not rep.ok and rep.line == 4 and "longer than" in rep.error
    assert peak < 8 * MAX_RECORD_BYTES, f"peak {peak / 2**20:.1f} MiB"


def test_over_long_first_line_is_not_an_audit_log(tmp_path):
    p = tmp_path / "blob.jsonl"
    p.write_bytes(b"x" * (MAX_RECORD_BYTES + 5) + b"\n")
    with pytest.raises(AuditFormatError, match="line 1 is longer than"):
        verify_log(p)


# ================================================================ audit writer: lag bounds
def test_close_does_not_hang_when_the_writer_died_with_a_full_queue(tmp_path):
    log = AuditLog(tmp_path / "z.jsonl", queue_size=2)
    gate = threading.Event()

    def failing(records, force_sync=False):
        gate.wait(10.0)
        raise OSError(5, "Input/output error")

    log._write = failing
    assert log.append("decision", cycle=0)
    assert wait_for(lambda: log.pending() == 0)
    assert log.append("decision", cycle=1) and log.append("decision", cycle=2)  # the queue is full
    gate.set()
    assert wait_for(lambda: not log._thread.is_alive())
    hung, out = run_in_thread(lambda: log.close(timeout=1.0))
    assert not hung, "close() blocked on the full queue of a dead writer"
    assert isinstance(out.get("exc"), OSError) and "Input/output error" in str(out["exc"])

def test_append_refuses_past_the_pending_records_bound(tmp_path):
    log = AuditLog(tmp_path / "a.jsonl", max_pending=5)
    gate = _gate_writer(log)
    try:
        assert log.append("decision", cycle=-1)
        assert wait_for(lambda: log.pending() == 0)  # the writer holds record -1 inside its write
        results = [log.append("decision", cycle=i) for i in range(10)]
        assert results.count(True) == 4 and results.count(False) == 6  # -1 plus 4 = 5 pending
        lag = log.lag()
        assert lag.records == 5 and lag.bytes > 0
        assert log.fault is None  # at the bound, not past it; the refusals are the fault
    finally:
        gate.set()
    log.close()
    recs = read_log(tmp_path / "a.jsonl")
    assert sum(r["count"] for r in recs if r["kind"] == "dropped") == 6 == log.dropped


def test_append_refuses_past_the_pending_bytes_bound(tmp_path):
    log = AuditLog(tmp_path / "b.jsonl", max_pending_bytes=20_000, max_record_bytes=4096)
    gate = _gate_writer(log)
    try:
        results = [log.append("decision", inputs={"blob": "x" * 3000}) for _ in range(12)]
        assert 4 <= results.count(True) <= 6 and not results[-1]
        assert log.lag().bytes <= 20_000
    finally:
        gate.set()
    log.close()
    assert verify_log(tmp_path / "b.jsonl", require_closed=True).ok


def test_old_pending_record_is_a_fault_and_refuses_appends(tmp_path):
    clock = FakeClock()
    log = AuditLog(tmp_path / "c.jsonl", max_lag_s=0.5, clock=clock)
    gate = _gate_writer(log)
    try:
        assert log.append("decision", cycle=0)
        clock.advance(0.4)
        assert log.fault is None and log.lag().age_s == pytest.approx(0.4)
        clock.advance(0.2)
        assert "0.600 s" in log.fault and "max_lag_s 0.5" in log.fault
        assert not log.append("decision", cycle=1)
    finally:
        gate.set()
    assert wait_for(lambda: log.lag().records == 0)
    assert log.fault is None and log.append("decision", cycle=2)
    log.close()


def test_loop_overrides_every_cycle_while_the_writer_lags_without_a_full_queue(tmp_path):
    alog_clock = FakeClock()
    log = AuditLog(tmp_path / "d.jsonl", max_lag_s=0.5, clock=alog_clock)
    loop, clock = _loop(audit=log)
    assert not loop.cycle(SAFE).override
    gate = _gate_writer(log)
    try:
        assert log.append("note", text="stuck in the writer")  # e.g. an fsync that takes seconds
        alog_clock.advance(1.0)  # one record a second old; the queue is nearly empty
        for _ in range(5):  # no state change, nothing appended: every cycle must still override
            clock.advance(0.001)
            d = loop.cycle(SAFE)
            assert d.override and any(f.kind == "audit" and "audit log is behind" in f.message
                                      for f in d.faults), d.faults
    finally:
        gate.set()
    assert wait_for(lambda: log.fault is None)
    for _ in range(3):  # the writer caught up: the fault latch (manual, the default) becomes ready
        clock.advance(0.001)
        d = loop.cycle(SAFE)
    assert d.override and d.awaiting_release and not d.faults
    assert loop.monitor.acknowledge()
    clock.advance(0.001)
    assert not loop.cycle(SAFE).override
    log.close()
    assert verify_log(tmp_path / "d.jsonl", require_closed=True).ok


def test_a_huge_record_is_capped_not_queued_whole(tmp_path):
    log = AuditLog(tmp_path / "e.jsonl")
    big = {f"s{i}": "v" * 1000 for i in range(3000)}  # ~3 MB of signals
    assert log.append("decision", override=True, faults=["x"], inputs=big)
    assert log.lag().bytes <= MAX_RECORD_BYTES
    log.close()
    assert verify_log(tmp_path / "e.jsonl", require_closed=True).ok
    rec = [r for r in read_log(tmp_path / "e.jsonl") if r["kind"] == "decision"][0]
    assert rec["override"] is True and rec["faults"] == ["x"]  # the decision itself is kept
    assert rec["inputs"]["omitted"].startswith("field too large") and rec["truncated"] == ["inputs"]
    assert log.oversize == 1
    line = [ln for ln in (tmp_path / "e.jsonl").read_bytes().splitlines() if b'"decision"' in ln][0]
    assert len(line) < MAX_RECORD_BYTES


def test_append_takes_a_snapshot_of_its_fields(tmp_path):
    log = AuditLog(tmp_path / "f.jsonl")
    gate = _gate_writer(log)
    inputs = {"x": 1.0}
    log.append("decision", inputs=inputs)
    inputs["x"] = 99.0  # the caller reuses its dict
    gate.set()
    log.close()
    assert [r for r in read_log(tmp_path / "f.jsonl") if r["kind"] == "decision"][0]["inputs"] == {"x": 1.0}


def test_serialised_records_stay_canonical_with_odd_keys_and_values(tmp_path):
    log = AuditLog(tmp_path / "k.jsonl")
    assert log.append("decision", inputs={10: 1, 9: 2, "n": {2: float("nan"), 1: float("-inf")}}, p=(0.5, 0.5),
                      seq=99, prev="forged", hash="forged", obj=object())
    log.close()
    assert verify_log(tmp_path / "k.jsonl", require_closed=True).ok
    rec = read_log(tmp_path / "k.jsonl")[1]
    assert rec["inputs"] == {"10": 1, "9": 2, "n": {"2": "nan", "1": "-inf"}} and rec["seq"] == 1


def test_loop_overrides_every_cycle_after_the_log_is_closed_mid_run(tmp_path):
    log = AuditLog(tmp_path / "g.jsonl")
    loop, clock = _loop(audit=log)
    for _ in range(3):
        clock.advance(0.001)
        assert not loop.cycle(SAFE).override
    log.close()
    for _ in range(10):  # same inputs, no state change: every cycle must still override
        clock.advance(0.001)
        d = loop.cycle(SAFE)
        assert d.override and any(f.kind == "audit" and "audit log is closed" in f.message for f in d.faults), d.faults


def test_loop_overrides_every_cycle_after_the_writer_thread_died(tmp_path):
    log = AuditLog(tmp_path / "h.jsonl")
    loop, clock = _loop(audit=log)
    assert not loop.cycle(SAFE).override

    def boom(records, force_sync=False):
        raise OSError(28, "No space left on device")

    log._write = boom
    assert log.append("note", text="the write of this record fails")
    assert wait_for(lambda: not log._thread.is_alive())
    for _ in range(10):
        clock.advance(0.001)
        d = loop.cycle(SAFE)
        assert d.override and any(f.kind == "audit" and "audit writer failed" in f.message for f in d.faults), d.faults


# ================================================================ estimator holding the GIL
def test_stall_between_cycles_is_a_fault_and_counted():
    loop, clock = _loop(risk=None)
    inputs = {**SAFE, "p_unsafe": 0.05, "risk_age_s": 0.0}
    assert not loop.cycle(inputs).override
    clock.advance(0.001)
    assert not loop.cycle(inputs).override
    clock.advance(9.6)  # the whole interpreter was frozen (e.g. a regex holding the GIL)
    d = loop.cycle(inputs)
    assert d.override and any(f.kind == "stall" and "control loop stalled for 9600" in f.message
                              for f in d.faults), d.faults
    assert loop.stats.stalls == 1 and loop.stats.max_gap_s == pytest.approx(9.6, abs=0.01)


def test_watchdog_reports_a_stall_it_could_not_see_when_the_loop_resumes():
    clock = FakeClock()
    fired = []
    wd = Watchdog(0.02, fired.append, clock=clock)
    wd.kick()
    clock.advance(5.0)  # the watchdog thread was starved as well: it never checked
    wd.kick()           # the loop resumes first
    assert len(fired) == 1 and "detected after it ended" in fired[0] and wd.fired_count == 1
    clock.advance(0.001)
    wd.kick()
    assert len(fired) == 1


def _gil_hog_seconds(target: float = 0.15) -> int:
    """Smallest n for which a catastrophic regex on 'a' * n + '!' takes >= target seconds here."""
    n = 16
    while True:
        t0 = time.perf_counter()
        re.match(r"(a+)+$", "a" * n + "!")
        if time.perf_counter() - t0 >= target or n >= 30:
            return n
        n += 1


class _RegexEstimator:
    model_id = "regex-hog"

    def __init__(self, n: int) -> None:
        self.n = n
        self.calls = 0

    def probs(self, text):
        self.calls += 1
        if self.calls == 3:
            re.match(r"(a+)+$", "a" * self.n + "!")  # holds the GIL for the whole match
        return (0.95, 0.05)


@pytest.mark.slow
def test_an_estimator_holding_the_gil_is_reported_as_a_stall():
    n = _gil_hog_seconds()
    est = _RegexEstimator(n)
    src = AsyncRiskSource(est, text="t", rate_hz=50.0)
    stalls = []
    try:
        assert wait_for(lambda: src.fault is None)
        loop = GovernedLoop(ethimon.Monitor(ethimon.load_spec_text(CELL)), risk=src,
                            on_stall=stalls.append,
                            signals=lambda: SAFE,
                            config=LoopConfig(period_s=0.002, deadline_s=0.02, max_risk_age_s=None, watchdog_s=0.05))
        decisions = []
        loop._on_decision = decisions.append
        loop.start()
        assert wait_for(lambda: est.calls >= 4, timeout=20.0)
        time.sleep(0.05)
        loop.stop()
    finally:
        src.stop()
    assert loop.stats.stalls >= 1 and loop.stats.max_gap_s >= 0.1
    assert any(any(f.kind == "stall" and "control loop stalled for" in f.message for f in d.faults)
               for d in decisions if d.override)
    assert stalls, "the on_stall callback (hardware stop) was never called"


@pytest.mark.slow
def test_a_factory_string_runs_the_estimator_in_a_child_process(tmp_path):
    env = {"PYTHONPATH": str(ROOT / "tests")}
    log = AuditLog(tmp_path / "p.jsonl")
    loop = GovernedLoop(ethimon.load_spec_text(CELL), audit=log,
                        risk=ProcessEstimator("_estimators:ScriptedEstimator", {"probs": [0.9, 0.1]}, env=env),
                        config=LoopConfig(period_s=0.001, deadline_s=1e6, stall_s=1e6))  # cycles called by hand, seconds apart
    try:
        assert isinstance(loop.risk, AsyncRiskSource) and isinstance(loop.risk.estimator, ProcessEstimator)
        assert loop.risk.isolated and loop.risk.text is None
        d = loop.cycle(SAFE)  # no task text yet: the pending hold (stop 2), not a fault, nothing latched
        assert d.override and d.response.value == "stop_2" and d.violations == ("pending",)
        assert not d.faults and loop.monitor.latched_rules == ("pending",)
        loop.risk.set_text("wipe the table")  # scored in the child process
        # its first answer is as old as the child's start (stale); the source re-scores it at 20 Hz: a fresh one
        assert wait_for(lambda: loop.risk.fault is None and loop.risk.latest()[1] < 0.05, timeout=30.0)
        d = loop.cycle(SAFE)  # the estimate arrived within its age: released by itself, no acknowledgement
        assert not d.override and not d.violations and loop.monitor.latched_rules == ()
        proc = loop.risk.estimator._proc
        assert proc is not None and proc.pid != os.getpid() and proc.poll() is None  # a live child process
    finally:
        loop.risk.stop()
        loop.risk.estimator.close()
        log.close()
    start = read_log(tmp_path / "p.jsonl")[1]
    assert start["kind"] == "start" and start["estimator_isolation"] == "process"


def test_an_in_process_estimator_is_recorded_as_not_isolated(tmp_path):
    log = AuditLog(tmp_path / "q.jsonl")
    loop, _ = _loop(audit=log)
    log.close()
    assert not loop.risk.isolated
    assert read_log(tmp_path / "q.jsonl")[1]["estimator_isolation"] == "thread"


# ================================================================ reload must not weaken silently
WEAKER = [
    ("no obligations and τ 0.99", lambda s: s.replace("threshold: 0.5", "threshold: 0.99")
     .replace('  - {id: keep_away, require: "human_distance >= 0.5", response: stop_2}\n', "")
     .replace("obligations:\n", "obligations: []\n"), ["keep_away removed", "threshold raised"]),
    ("τ raised", lambda s: s.replace("threshold: 0.5", "threshold: 0.6"), ["threshold raised"]),
    ("smaller hysteresis", lambda s: s.replace("hysteresis: 0.05", "hysteresis: 0.01"), ["release bound"]),
    ("shorter hold", lambda s: s.replace("hold_cycles: 2", "hold_cycles: 1"), ["hold_cycles lowered"]),
    ("weaker obligation response", lambda s: s.replace("response: stop_2", "response: safe_pose"),
     ["keep_away: response stop_2 -> safe_pose"]),
    ("max_age removed", lambda s: s.replace(", max_age_s: 0.2", ""), ["max_age_s"]),
    ("max_age larger", lambda s: s.replace("max_age_s: 0.2", "max_age_s: 0.5"), ["max_age_s"]),
    ("within added", lambda s: s.replace("response: stop_2}", "response: stop_2, within_cycles: 3}"),
     ["within_cycles"]),
    ("when added", lambda s: s.replace('require: "human_distance >= 0.5"',
                                       'when: "human_distance < 5", require: "human_distance >= 0.5"'),
     ["when"]),
    ("range widened", lambda s: s.replace("range: [0, 10]", "range: [0, 100]"), ["range"]),
    ("weight lowered", lambda s: s.replace("threshold: 0.5,", "threshold: 0.5, alpha: 0.3,"), ["alpha"]),
]


@pytest.mark.parametrize("name, edit, needles", WEAKER, ids=[w[0] for w in WEAKER])
def test_a_weakening_reload_is_refused_unless_allowed(tmp_path, name, edit, needles):
    log = AuditLog(tmp_path / "r.jsonl")
    loop, clock = _loop(audit=log)
    before = loop.spec_sha256
    weak = ethimon.load_spec_text(edit(CELL))
    res = loop.reload(weak)
    assert not res.ok and "weakens monitoring" in res.error and "allow_weaker=True" in res.error
    for needle in needles:
        assert any(needle in w for w in res.weakened), (needle, res.weakened)
    clock.advance(0.001)
    d = loop.cycle({"human_distance": 0.1})
    assert loop.spec_sha256 == before and d.violations == ("keep_away",)  # the old spec still runs
    assert loop.stats.reloads_rejected == 1
    loop.monitor.release()  # keep_away is latched: a reload that removes or changes it is refused (issue 25)
    ok = loop.reload(weak, allow_weaker=True)
    assert ok.ok and ok.weakened == res.weakened
    log.close()
    recs = [r for r in read_log(tmp_path / "r.jsonl") if r["kind"] == "reload"]
    assert recs[0]["status"] == "rejected" and recs[0]["weakened"] == list(res.weakened)
    assert recs[1]["status"] == "accepted" and recs[1]["allow_weaker"] is True and recs[1]["weakened"]


def test_weaker_responses_release_mode_and_on_fault_are_refused():
    strict = CELL.replace("mode: auto", "mode: manual").replace("on_fault: safe_pose", "on_fault: stop_1") \
        .replace("threshold: 0.5,", "threshold: 0.5, response: stop_2,")
    loop, _ = _loop(spec=strict)
    res = loop.reload(ethimon.load_spec_text(CELL))
    assert not res.ok
    text = " | ".join(res.weakened)
    assert "release mode manual -> auto" in text and "on_fault stop_1 -> safe_pose" in text
    assert "risk.response stop_2 -> safe_pose" in text


def test_a_stronger_or_equal_reload_is_accepted():
    loop, _ = _loop()
    stronger = CELL.replace("threshold: 0.5", "threshold: 0.4").replace("hold_cycles: 2", "hold_cycles: 5") \
        .replace("response: stop_2}", "response: stop_0}")
    res = loop.reload(ethimon.load_spec_text(stronger))
    assert res.ok and res.weakened == () and res.unjudged == ()
    # the same condition up to whitespace is the same condition
    res = loop.reload(ethimon.load_spec_text(CELL.replace('"human_distance >= 0.5"',
                                                          '"  human_distance  >=   0.5 "')))
    assert res.ok and res.weakened == () and res.unjudged == ()


CONST_CELL = CELL.replace("obligations:\n", "constants: {min_d: 0.5}\nobligations:\n") \
    .replace('"human_distance >= 0.5"', '"human_distance >= min_d"')
CANNOT_TELL = "cannot tell whether this change weakens monitoring"
UNJUDGED = [
    ("require true", CELL, lambda s: s.replace('"human_distance >= 0.5"', "'true'"), "keep_away: require changed"),
    ("require stricter text", CELL, lambda s: s.replace(">= 0.5", ">= 3.0"), "keep_away: require changed"),
    ("constant lowered", CONST_CELL, lambda s: s.replace("min_d: 0.5", "min_d: -1"), "constant min_d"),
    ("when changed", CELL.replace('require: "human', 'when: "human_distance < 5", require: "human'),
     lambda s: s.replace("human_distance < 5", "human_distance < 0.1"), "keep_away: when changed"),
    ("signal type", CELL.replace("obligations:\n", "obligations:\n  - {id: b, require: \"x > 0\"}\n")
     .replace("signals:\n", "signals:\n  x: {unit: m}\n"),
     lambda s: s.replace("x: {unit: m}", "x: {type: bool}").replace('"x > 0"', "x"), "signal x: type"),
]


@pytest.mark.parametrize("name, base, edit, needle", UNJUDGED, ids=[u[0] for u in UNJUDGED])
def test_a_change_that_cannot_be_judged_is_refused_unless_allowed(tmp_path, name, base, edit, needle):
    log = AuditLog(tmp_path / "u.jsonl")
    loop, clock = _loop(spec=base, audit=log)
    before = loop.spec_sha256
    new = ethimon.load_spec_text(edit(base))
    res = loop.reload(new)  # default flags: a change of unknown direction may weaken monitoring
    assert not res.ok and "weakens monitoring" in res.error and "allow_weaker=True" in res.error
    hits = [w for w in res.weakened if needle in w]
    assert hits and all(w.endswith(CANNOT_TELL) for w in hits), res.weakened
    assert set(res.unjudged) <= set(res.weakened) and any(needle in u for u in res.unjudged)
    clock.advance(0.001)
    loop.cycle(SAFE)
    assert loop.spec_sha256 == before  # the old spec still runs
    ok = loop.reload(new, allow_weaker=True)
    assert ok.ok and ok.weakened == res.weakened
    log.close()
    recs = [r for r in read_log(tmp_path / "u.jsonl") if r["kind"] == "reload"]
    assert recs[0]["status"] == "rejected" and any(CANNOT_TELL in w for w in recs[0]["weakened"])
    assert recs[1]["status"] == "accepted" and recs[1]["allow_weaker"] is True
