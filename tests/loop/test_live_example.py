"""Issue 31, item 2: the docs' live example end to end, as written in docs/ros2.md: the stand-in robot
(examples/ros2/standin_robot.py) and `ethimon ros2` with the example spec and mapping, two processes
over loopback. The arm moves after the safe text's estimate and stops on the unsafe joint speed."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("cyclonedds")
pytest.importorskip("rosbags")

ROOT = Path(__file__).resolve().parents[2]
DOMAIN = 71


@pytest.mark.slow
def test_docs_live_example_moves_then_stops(tmp_path):
    from ethimon.ros2 import cyclone_config
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"), CYCLONEDDS_URI=cyclone_config(interface="lo",
                                                                                       peers=["127.0.0.1"]))
    robot = subprocess.Popen([sys.executable, str(ROOT / "examples" / "ros2" / "standin_robot.py"), "--domain",
                              str(DOMAIN), "--duration-s", "40", "--unsafe-after-s", "30"], env=env, cwd=ROOT,
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        out = subprocess.run([sys.executable, "-m", "ethimon.cli", "ros2", "--spec", "examples/replay/spec.yaml",
                              "--map", "examples/ros2/mapping.yaml", "--domain", str(DOMAIN), "--duration-s", "6",
                              "--audit", str(tmp_path / "run.jsonl"), "--json", "-"],
                             env=env, cwd=ROOT, capture_output=True, text=True, timeout=120)
    finally:
        robot.kill()
        robot.wait(10)
    assert out.returncode == 0, out.stderr[-2000:]
    doc = json.loads(out.stdout)
    recs = [json.loads(line) for line in (tmp_path / "run.jsonl").read_text().splitlines()]
    decisions = [r for r in recs if r.get("kind") == "decision"]
    off = [r for r in decisions if r["event"] == "override_off"]
    if not off and any(k in ("deadline", "stall") for r in decisions for k in r["fault_kinds"]):
        pytest.skip("this machine missed a control deadline before the release (it fails closed, manual)")
    assert off, (doc, decisions[:5])
    # the arm may move within 1 s (100 cycles at 100 Hz) of the start: the pending hold released by itself
    assert off[0]["loop_cycle"] <= 100, decisions[:5]
    assert doc["pending_cycles"] == off[0]["loop_cycle"], doc
    # nothing but the load of a shared machine (a missed deadline fails closed) holds it afterwards
    assert {k for r in decisions for k in r["fault_kinds"]} <= {"deadline", "stall"}, decisions[:8]
