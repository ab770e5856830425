"""ethimon ros2 without its extra: `import ethimon.ros2` and the CLI stay light; a missing cyclonedds is a
clear error naming the pip extra, never a traceback."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _run(code: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=str(ROOT))


@pytest.mark.slow
def test_import_ethimon_ros2_does_not_load_cyclonedds_or_rosbags():
    out = _run("import sys, ethimon, ethimon.ros2, ethimon.cli\n"
               "from ethimon.cli import _build_parser\n"
               "_build_parser()\n"
               "print([m for m in ('cyclonedds', 'rosbags', 'torch', 'z3') if m in sys.modules])\n")
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "[]"


@pytest.mark.slow
def test_cli_without_cyclonedds_names_the_extra(tmp_path):
    spec = tmp_path / "s.yaml"
    spec.write_text("ethimon: 1\nname: s\nsignals:\n  v: {unit: m/s, range: [0, 10]}\n")
    mp = tmp_path / "m.yaml"
    mp.write_text("ethimon: 1\nrate_hz: 100\nmax_age_s: 0.1\nsignals:\n"
                  "  v: {topic: /v, type: std_msgs/msg/Float64}\n  p_unsafe: {topic: /p, type: std_msgs/msg/Float64}\n")
    code = ("import sys; sys.modules['cyclonedds'] = None\n"
            "from ethimon.cli import main\n"
            f"sys.exit(main(['ros2', '--spec', {str(spec)!r}, '--map', {str(mp)!r}, '--duration-s', '1']))\n")
    out = _run(code)
    assert out.returncode == 2, out.stderr
    assert "pip install 'ethimon[ros2]'" in out.stderr and "Traceback" not in out.stderr


@pytest.mark.slow
def test_cli_bad_mapping_is_located(tmp_path):
    spec = tmp_path / "s.yaml"
    spec.write_text("ethimon: 1\nname: s\nsignals:\n  v: {unit: m/s, range: [0, 10]}\n")
    mp = tmp_path / "m.yaml"
    mp.write_text("ethimon: 1\nrate_hz: 100\nmax_age_s: 0.1\nsignals:\n"
                  "  v: {topic: /v, type: std_msgs/msg/Float64}\n  p_unsafe: {topic: /p, type: std_msgs/msg/Float64}\n"
                  "ros2: {publisher: 2}\n")
    out = _run(f"import sys\nfrom ethimon.cli import main\nsys.exit(main(['ros2', '--spec', {str(spec)!r}, "
               f"'--map', {str(mp)!r}]))\n")
    assert out.returncode == 2
    assert f"{mp}:7:" in out.stderr and "did you mean 'publishers'" in out.stderr and "Traceback" not in out.stderr


def test_governed_loop_reads_a_sources_own_faults():
    """A signal source may return a mapping with a ``faults`` attribute (ethimon.ros2 reports stale
    topics and foreign publishers there): each fails the cycle closed, with its kind and subject."""
    import ethimon
    from ethimon.loop import GovernedLoop, LoopConfig
    from ethimon.runtime import Fault

    spec = ethimon.load_spec_text("ethimon: 1\nname: s\nsignals:\n  v: {unit: m/s, range: [0, 10]}\n"
                                  "on_fault: {response: stop_1, release: auto}\n")

    class Frame(dict):
        faults = ()

    good = Frame(v=1.0, p_unsafe=0.05)
    loop = GovernedLoop(ethimon.Monitor(spec), signals=lambda: good, config=LoopConfig(period_s=1.0))
    assert not loop.cycle().override
    bad = Frame(v=1.0, p_unsafe=0.05)
    bad.faults = (Fault("stale", "v: stale (last /v message 0.3 s old, max_age_s 0.1)", "v"), "plain text")
    loop2 = GovernedLoop(ethimon.Monitor(spec), signals=lambda: bad, config=LoopConfig(period_s=1.0))
    d = loop2.cycle()
    assert d.override and [(f.kind, f.subject) for f in d.faults] == [("stale", "v"), ("signals", "")]


def test_watchdog_start_does_not_count_the_time_before_it_as_a_stall():
    """Regression (found on `ethimon ros2`, which joins the DDS domain between building its loop and running
    it): Watchdog.start() kicked, so the time since the watchdog was *built* fired a stall ("no cycle for
    411 ms") and faulted the first cycle of every GovernedLoop started later than watchdog_s after it was made."""
    from ethimon.loop import Watchdog

    now = [0.0]
    fired: list[str] = []
    wd = Watchdog(0.05, fired.append, clock=lambda: now[0])
    now[0] = 5.0  # built long before it is started
    wd.start()
    try:
        assert fired == [] and wd.kick() is None
        now[0] = 5.2  # a real stall after the start still fires
        assert wd.kick() is not None and len(fired) == 1
    finally:
        wd.stop()
