"""``ethimon check --ray`` and ``ethimon replay --ray``: a local Ray instance gives the serial run's results.

One Ray instance (2 CPUs) is started for the module and shut down at its end; the
CLI runs in this process (``ethimon.cli.main``) and uses that instance. One test
runs the CLI in a subprocess, where it starts and stops its own local instance.
Tests that need no Ray (addresses, plain data, rows of failed units) run without it.
"""

from __future__ import annotations

import enum
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from tests._cli import ROOT, run_cli

from ethimon.errors import EthimonError
from ethimon.fleet import Failure, check_address, plain

pytestmark = pytest.mark.slow  # a local Ray instance and CLI subprocesses: seconds each

RAY_MISSING = "ray is not installed (pip install -e '.[fleet]'; CI installs it with .[all,test])"

SPEC = f"{ROOT}/specs/cobot_cell.yaml"
BASE = "{p_unsafe: 0.05, human_distance: 5.0, ee_speed: 0.8, contact_force: 0.0, joint_speed_max: 1.5}"


@pytest.fixture(scope="module")
def ray_local():
    """One local Ray instance with 2 CPUs for the whole module (start-up takes seconds)."""
    try:
        import ray
    except ImportError:
        pytest.skip(RAY_MISSING)
    import logging
    ray.init(num_cpus=2, include_dashboard=False, logging_level=logging.ERROR, log_to_driver=False)
    yield ray
    ray.shutdown()


def _scenarios(d: Path) -> Path:
    """A folder of scenario files: passes, a failed expectation, a broken YAML, a missing spec, a bad spec."""
    d.mkdir()
    for i, speed in enumerate((1.5, 2.6, 0.5, 2.9)):
        fired = "[joint_speed]" if speed > 2.0 else "[]"
        (d / f"s{i}.yaml").write_text(
            f"ethimon: 1\nname: joint speed {speed}\nspec: {SPEC}\ncycles: 30\ninputs: {BASE}\n"
            f"timeline:\n  - {{at: 10, set: {{joint_speed_max: {speed}}}}}\n"
            f"expect: {{override: {str(speed > 2.0).lower()}, fired: {fired}}}\n")
    (d / "t_fail.yaml").write_text(f"ethimon: 1\nname: wrong expectation\nspec: {SPEC}\ncycles: 5\n"
                                   f"inputs: {BASE}\nexpect: {{override: true}}\n")
    (d / "u_broken.yaml").write_text("ethimon: 1\nname: [unclosed\n")
    (d / "v_nospec.yaml").write_text(f"ethimon: 1\nname: no spec\nspec: missing.yaml\ncycles: 5\ninputs: {BASE}\n"
                                     "expect: {override: false}\n")
    (d / "badspec.txt").write_text("ethimon: 1\nname: x\nsignals: {a: {unit: m, range: [0, 1]}}\nobligations: 7\n")
    (d / "w_badspec.yaml").write_text("ethimon: 1\nname: bad spec\nspec: badspec.txt\ncycles: 5\n"
                                      "inputs: {a: 1, p_unsafe: 0.1}\nexpect: {override: false}\n")
    return d


def _main(capsys, *argv: str) -> tuple[int, str, str]:
    from ethimon.cli import main
    rc = main(list(argv))
    got = capsys.readouterr()
    return rc, got.out, got.err


def _no_time(text: str) -> str:
    """A report without its wall times (the summary line's seconds, JUnit time=, JSON "seconds")."""
    import re
    return re.sub(r' in \d+\.\d+s| time="[0-9.]+"|"seconds": [0-9.e+-]+', "", text)


def _same_runs(capsys, monkeypatch, tmp_path, *argv: str, ray_args=("--ray", "--ray-workers", "2")) -> dict:
    from ethimon.fleet import _executor
    calls = []
    real = _executor.map_files
    monkeypatch.setattr(_executor, "map_files", lambda *a, **kw: calls.append(a[2]) or real(*a, **kw))
    outs = []
    for tag, extra in (("serial", ()), ("ray", ray_args)):
        j, x = tmp_path / f"{tag}.json", tmp_path / f"{tag}.xml"
        rc, out, err = _main(capsys, *argv, "--json", str(j), "--junit", str(x), *extra)
        outs.append((rc, _no_time(out), _no_time(err), _no_time(j.read_text()), _no_time(x.read_text())))
    assert len(calls) == 1 and len(calls[0]) >= 4  # the second run went through Ray, one task per file
    assert outs[0] == outs[1]  # same exit code, table, problems, JSON and JUnit (but the wall times)
    return json.loads((tmp_path / "ray.json").read_text())


# ----------------------------------------------------------------------------------------- check --ray
def test_check_on_ray_is_the_serial_run(ray_local, tmp_path, capsys, monkeypatch):
    d = _scenarios(tmp_path / "sc")
    doc = _same_runs(capsys, monkeypatch, tmp_path, "check", str(d))
    assert [r["path"] for r in doc["results"]] == [str(p) for p in sorted(d.glob("*.yaml"))]
    assert (doc["passed"], doc["failed"], doc["errors"]) == (4, 1, 3)
    errors = {Path(r["path"]).name: r["error"] for r in doc["results"] if "error" in r}
    assert "missing.yaml" in errors["v_nospec.yaml"] and errors["w_badspec.yaml"].startswith(str(d / "badspec.txt"))
    assert errors["u_broken.yaml"].startswith(str(d / "u_broken.yaml"))


def test_check_report_in_the_library(ray_local, tmp_path):
    from ethimon import fleet, scenario
    d = _scenarios(tmp_path / "sc")
    seen = []
    serial = scenario.check_paths([str(d)])
    on_ray = fleet.check_paths([str(d)], on_progress=lambda done, total, path: seen.append((done, total)))
    assert [o.record for o in on_ray.outcomes] == json.loads(json.dumps([o.record for o in serial.outcomes]))
    assert [(o.name, o.status, o.messages) for o in on_ray.outcomes] == \
        [(o.name, o.status, o.messages) for o in serial.outcomes]
    assert all(o.result is None for o in on_ray.outcomes)  # workers send plain data, not objects
    assert seen[0] == (0, 8) and seen[-1] == (8, 8) and [d for d, _ in seen] == sorted(d for d, _ in seen)


# ----------------------------------------------------------------------------------------- replay --ray
REPLAY_SPEC = """
ethimon: 1
name: fleet_test
signals:
  human_distance: {unit: m,   range: [0, 10]}
  ee_speed:       {unit: m/s, range: [0, 3]}
risk: {threshold: 0.5}
on_fault: stop_1
obligations:
  - {id: separation, require: human_distance >= 0.5, response: stop_2}
  - {id: slow_near, when: human_distance < 1.5, require: ee_speed <= 0.25, within_cycles: 3}
"""

REPLAY_MAP = """
ethimon: 1
rate_hz: 50
max_age_s: 0.1
signals:
  human_distance: {topic: /human/distance, field: data}
  ee_speed:       {topic: /ee/speed, field: data}
  p_unsafe:       {topic: /risk/p_unsafe, field: data, stale: false}
"""


def _bag(path: Path, fmt: str, seed: int) -> Path:
    """A 3 s recording (ROS 2 MCAP or ROS 1): a person walks in; the arm slows down late on some seeds."""
    from rosbags.rosbag1 import Writer as Writer1
    from rosbags.rosbag2 import StoragePlugin, Writer
    from rosbags.typesys import Stores, get_typestore
    ts = get_typestore(Stores.ROS1_NOETIC if fmt == "ros1" else Stores.ROS2_HUMBLE)
    F64 = ts.types["std_msgs/msg/Float64"]
    ser = ts.serialize_ros1 if fmt == "ros1" else ts.serialize_cdr
    rng = np.random.default_rng(seed)
    t0 = 1_000 * 10**9
    msgs = [(t0, "/risk/p_unsafe", 0.1)]
    for i in range(150):
        t = 0.02 * i + rng.uniform(0, 0.005)
        d = 3.0 - 2.0 * min(t, 1.5) / 1.5
        msgs += [(int(t0 + t * 1e9), "/human/distance", d),
                 (int(t0 + t * 1e9) + 1000, "/ee/speed", 0.2 if t > 0.6 + 0.1 * seed else 0.5)]
    msgs.sort()
    w = Writer1(path) if fmt == "ros1" else Writer(path, version=9, storage_plugin=StoragePlugin.MCAP)
    with w:
        conns = {}
        for t, topic, v in msgs:
            if topic not in conns:
                conns[topic] = w.add_connection(topic, "std_msgs/msg/Float64", typestore=ts)
            w.write(conns[topic], t, ser(F64(data=float(v)), "std_msgs/msg/Float64"))
    return path


def test_replay_on_ray_is_the_serial_run(ray_local, tmp_path, capsys, monkeypatch):
    pytest.importorskip("rosbags", reason="needs rosbags (pip install -e '.[ros]')")
    (tmp_path / "spec.yaml").write_text(REPLAY_SPEC)
    (tmp_path / "map.yaml").write_text(REPLAY_MAP)
    bags = [_bag(tmp_path / "a", "mcap", 0), _bag(tmp_path / "b.bag", "ros1", 7), tmp_path / "broken.bag",
            _bag(tmp_path / "c", "mcap", 9)]
    bags[2].write_bytes(b"not a bag at all")
    doc = _same_runs(capsys, monkeypatch, tmp_path, "replay", *map(str, bags), "--spec", str(tmp_path / "spec.yaml"),
                     "--map", str(tmp_path / "map.yaml"), ray_args=("--ray", "--file-timeout-s", "300"))
    assert [r["path"] for r in doc["results"]] == [str(b) for b in bags]
    assert doc["errors"] == 1 and doc["results"][2]["error"].startswith(f"{bags[2]}: cannot open the bag")
    slow = [next(c for c in r["checks"] if c["id"] == "slow_near") for r in doc["results"] if "checks" in r]
    assert [c["passed"] for c in slow] == [True, False, False]  # the data differ per bag, so does the order


def test_replay_ray_refuses_audit_and_bad_address(tmp_path, capsys):
    rc, _, err = _main(capsys, "replay", "x.bag", "--spec", "s", "--map", "m", "--audit", str(tmp_path / "a"),
                       "--ray")
    assert rc == 2 and "--audit cannot be used with --ray" in err and not (tmp_path / "a").exists()
    rc, _, err = _main(capsys, "replay", "--ray", "no-such-place", "x.bag", "--spec", "s", "--map", "m")
    assert rc == 2 and "'no-such-place' is not a Ray address" in err and "--ray=ADDRESS" in err
    rc, _, err = _main(capsys, "check", str(ROOT / "scenarios"), "--ray-workers", "2")
    assert rc == 2 and "--ray-workers needs --ray" in err
    rc, _, err = _main(capsys, "check", str(ROOT / "scenarios"), "--ray=auto", "--ray-workers", "2")
    assert rc == 2 and "local Ray instance" in err


# ----------------------------------------------------------------------------------------- failures
def _unit(label: str, pid_dir: str | None = None) -> int:
    if label == "raises":
        raise ValueError("bad file content")
    if label == "dies":
        os._exit(3)  # the worker process dies (a segfault in a parser, the OOM killer)
    if label == "hangs":  # a parser stuck in a loop (or in C code that never returns)
        Path(pid_dir, "hangs.pid").write_text(str(os.getpid()))
        time.sleep(60)
    return len(label)


def _gone(pid: int, within_s: float = 15.0) -> bool:
    """Whether process ``pid`` has ended (or ends within ``within_s``)."""
    end = time.monotonic() + within_s
    while time.monotonic() < end:
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            return True
        time.sleep(0.1)
    return False


def test_a_worker_that_raises_or_dies_is_one_failure(ray_local):
    import ray.cloudpickle
    from ethimon.fleet import map_files
    ray.cloudpickle.register_pickle_by_value(sys.modules[__name__])  # workers cannot import this test module
    labels = ["aa", "raises", "bbb", "dies", "c"]
    seen = []
    got = map_files(_unit, [(x,) for x in labels], labels, max_retries=0,
                    on_done=lambda *a: seen.append(a + (sys.stdout is sys.stderr,)))
    assert got[0] == 2 and got[2] == 3 and got[4] == 1
    assert isinstance(got[1], Failure) and got[1].what == "ValueError: bad file content"
    assert isinstance(got[3], Failure) and "worker checking this file died" in got[3].what
    assert len(seen) == 6 and seen[-1][:2] == (5, 5)
    # Ray's driver prints "a worker died" to sys.stdout from a thread: during the run that is stderr
    assert all(s[-1] for s in seen[1:]) and sys.stdout is not sys.stderr


def test_a_hanging_worker_times_out_and_its_task_is_cancelled(ray_local, tmp_path):
    import ray.cloudpickle
    from ethimon.fleet import map_files
    ray.cloudpickle.register_pickle_by_value(sys.modules[__name__])
    labels = ["aa", "raises", "hangs", "bbb", "dies", "c"]
    seen = []
    t0 = time.monotonic()
    got = map_files(_unit, [(x, str(tmp_path)) for x in labels], labels, max_retries=0, file_timeout=6,
                    on_done=lambda *a: seen.append(a))
    took = time.monotonic() - t0
    assert [got[i] for i in (0, 3, 5)] == [2, 3, 1]  # the others are reported
    assert isinstance(got[1], Failure) and got[1].what == "ValueError: bad file content"
    assert isinstance(got[4], Failure) and "worker checking this file died" in got[4].what
    assert isinstance(got[2], Failure) and got[2].what == "timed out after 6 s; its Ray task was cancelled"
    assert took < 45  # not the hanging unit's 60 s: the run went on without it
    assert _gone(int((tmp_path / "hangs.pid").read_text()))  # cancelled with force: its worker was killed
    assert len(seen) == 7 and seen[-1][:2] == (6, 6) and sorted(s[2] for s in seen[1:]) == sorted(labels)


def _hang_on_s1(run_id: str, path: str, sim: bool, model_dir: str | None):
    """``check_unit``, but the file s1.yaml never finishes."""
    from ethimon.scenario._session import check_unit
    if path.endswith("s1.yaml"):
        time.sleep(60)
    return check_unit(run_id, path, sim, model_dir)


def test_check_file_timeout_is_one_error_row(ray_local, tmp_path, capsys, monkeypatch):
    import ray.cloudpickle
    from ethimon.scenario import _session
    ray.cloudpickle.register_pickle_by_value(sys.modules[__name__])
    monkeypatch.setattr(_session, "check_unit", _hang_on_s1)
    d = _scenarios(tmp_path / "sc")
    rc_serial, _, _ = _main(capsys, "check", str(d), "--json", str(tmp_path / "serial.json"))
    rc, _, err = _main(capsys, "check", str(d), "--json", str(tmp_path / "ray.json"), "--ray", "--file-timeout-s", "8")
    serial, on_ray = (json.loads((tmp_path / f"{t}.json").read_text()) for t in ("serial", "ray"))
    line = f"{d / 's1.yaml'}: timed out after 8 s; its Ray task was cancelled (this file could not be checked; " \
           "the other files were)"
    assert on_ray["results"][1] == {"name": str(d / "s1.yaml"), "path": str(d / "s1.yaml"), "passed": False,
                                    "error": line}
    assert line in err.splitlines()
    assert on_ray["results"][:1] + on_ray["results"][2:] == serial["results"][:1] + serial["results"][2:]
    assert (on_ray["passed"], on_ray["errors"]) == (serial["passed"] - 1, serial["errors"] + 1)
    assert rc == rc_serial == 2


def test_file_timeout_needs_ray_and_seconds_above_0(capsys):
    for cmd in (["check", str(ROOT / "scenarios")], ["replay", "x.bag", "--spec", "s", "--map", "m"]):
        rc, _, err = _main(capsys, *cmd, "--file-timeout-s", "5")
        assert rc == 2 and "--file-timeout-s needs --ray" in err
        for bad in ("0", "-1", "nan", "inf"):
            rc, _, err = _main(capsys, *cmd, "--ray", "--file-timeout-s", bad)
            assert rc == 2 and "--file-timeout-s must be a number of seconds above 0" in err, (cmd, bad, err)


def test_failed_units_are_error_rows_in_place(tmp_path, monkeypatch):
    """The driver's side without Ray: a unit that failed is an ERROR row at its file's place."""
    from ethimon.fleet import _executor, _run
    d = _scenarios(tmp_path / "sc")

    def fake_map(fn, calls, labels, **kw):
        return [Failure("the Ray worker checking this file died (WorkerCrashedError)") if lab.endswith("s1.yaml")
                else fn(*args) for args, lab in zip(calls, labels)]
    monkeypatch.setattr(_executor, "map_files", fake_map)
    rep = _run.check_paths([str(d)])
    assert [o.path for o in rep.outcomes] == [str(p) for p in sorted(d.glob("*.yaml"))]
    row = rep.outcomes[1]
    assert row.status == "ERROR" and row.record["error"] == (
        f"{d / 's1.yaml'}: the Ray worker checking this file died (WorkerCrashedError) "
        "(this file could not be checked; the other files were)")
    assert rep.passed == 3 and rep.errors == 4 and rep.exit_code == 2


# ----------------------------------------------------------------------------------------- no Ray needed
def test_addresses():
    assert check_address(None) is None and check_address("local") is None
    for a in ("auto", "ray://head:10001", "10.0.0.5:6379", "head.cluster:6379"):
        assert check_address(a) == a
    for bad in ("scenarios/", "ray", "http://x", ""):
        with pytest.raises(EthimonError, match="not a Ray address"):
            check_address(bad)


def test_ray_before_a_path_takes_the_path_back():
    import argparse

    from ethimon.cli._common import ray_target
    args = argparse.Namespace(ray=str(ROOT / "scenarios"), ray_workers=None, paths=["b.yaml"])
    assert ray_target(args, "paths") == (None, None) and args.paths == [str(ROOT / "scenarios"), "b.yaml"]


def test_check_needs_a_path(capsys):
    rc, _, err = _main(capsys, "check")
    assert rc == 2 and "give at least one PATH" in err


class _Color(str, enum.Enum):
    RED = "red"


class _Level(enum.IntEnum):
    HIGH = 3


def test_plain_data_is_what_the_json_report_holds():
    obj = {"a": (1, np.float64(0.25), np.int64(7)), "b": [_Color.RED, _Level.HIGH, True, None],
           "c": {"d": float("inf"), 3: Path("x/y")}, "e": np.bool_(True)}
    got = plain(obj)
    assert json.dumps(got) == json.dumps(obj, default=str)
    types = set()

    def walk(o):
        types.add(type(o))
        if isinstance(o, dict):
            [walk(v) for v in o.values()]
        elif isinstance(o, list):
            [walk(v) for v in o]
    walk(got)
    assert types <= {dict, list, str, int, float, bool, type(None)}


def test_import_ethimon_does_not_import_ray():
    code = "import sys, ethimon, ethimon.fleet, ethimon.cli; print('ray' in sys.modules)"
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert r.returncode == 0 and r.stdout.strip() == "False", r.stderr


# ----------------------------------------------------------------------------------------- the CLI as run
def test_cli_starts_and_stops_its_own_local_instance(tmp_path):
    pytest.importorskip("ray", reason=RAY_MISSING)
    d = _scenarios(tmp_path / "sc")
    serial = run_cli("check", str(d), "--json", "-")
    on_ray = run_cli("check", str(d), "--json", "-", "--ray", "--ray-workers", "1", timeout=120)
    assert on_ray.returncode == serial.returncode == 2, on_ray.stderr
    errors = [r.get("error") for r in json.loads(on_ray.stdout)["results"]]
    assert _no_time(on_ray.stdout) == _no_time(serial.stdout), errors
    assert _no_time(on_ray.stderr) == _no_time(serial.stderr)  # no Ray chatter, no traceback


def test_without_ray_the_cli_says_what_to_install(tmp_path):
    d = _scenarios(tmp_path / "sc")
    code = ("import sys; sys.modules['ray'] = None; from ethimon.cli import main; "
            "sys.exit(main(sys.argv[1:]))")
    r = subprocess.run([sys.executable, "-c", code, "check", str(d), "--ray"], capture_output=True, text=True,
                       cwd=ROOT)
    assert r.returncode == 2 and "pip install 'ethimon[fleet]'" in r.stderr and "Traceback" not in r.stderr
