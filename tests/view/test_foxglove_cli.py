"""``ethimon replay --foxglove`` and ``ethimon ros2 --foxglove``, watched by a Foxglove protocol client
(loopback, a free port, every wait bounded)."""

from __future__ import annotations

import os
import socket
import subprocess
import sys
import threading
import time

import pytest

pytest.importorskip("foxglove")
pytest.importorskip("websockets")

from tests._cli import ROOT, call_cli  # noqa: E402

from ._client import FoxgloveClient  # noqa: E402


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def connect(url: str, timeout: float = 10.0) -> FoxgloveClient:
    end = time.monotonic() + timeout
    while True:
        try:
            return FoxgloveClient(url)
        except OSError:
            if time.monotonic() > end:
                raise
            time.sleep(0.05)


@pytest.mark.parametrize("cmd", [["replay", "b", "--spec", "s.yaml", "--map", "m.yaml"],
                                 ["ros2", "--spec", "s.yaml", "--map", "m.yaml"]])
def test_a_bad_address_is_a_located_error_not_a_traceback(cmd) -> None:
    r = call_cli(*cmd, "--foxglove", "localhost:99999")
    assert r.returncode == 2 and "ethimon: error: --foxglove: " in r.stderr and "[HOST:]PORT" in r.stderr
    assert "Traceback" not in r.stderr


@pytest.mark.slow
def test_replay_serves_the_bags_verdicts_to_a_client(tmp_path) -> None:
    pytest.importorskip("rosbags")
    from tests.replay.test_replay_bags import ns, write
    write(tmp_path / "b", "mcap", [(ns(i * 0.05), "/a", "f64", 0.5 if i == 10 else 2.0) for i in range(20)])
    (tmp_path / "s.yaml").write_text("ethimon: 1\nname: ab\nsignals:\n  a: {unit: m, range: [0, 10]}\n"
                                     "obligations:\n  - {id: oa, require: a >= 1, release: {hold_cycles: 3}}\n")
    (tmp_path / "m.yaml").write_text("ethimon: 1\nrate_hz: 20\nmax_age_s: 0.1\nrisk: none\nsignals:\n"
                                     "  a: {topic: /a}\n")
    port = free_port()
    out: dict = {}
    cli = threading.Thread(target=lambda: out.update(r=call_cli(
        "replay", tmp_path / "b", "--spec", tmp_path / "s.yaml", "--map", tmp_path / "m.yaml",
        "--foxglove", str(port), "--foxglove-speed", "0", "--foxglove-wait-s", "20")), daemon=True)
    cli.start()
    client = connect(f"ws://127.0.0.1:{port}")
    try:
        client.handshake({"/ethimon/decision", "/ethimon/margins"})
        client.subscribe(["/ethimon/decision", "/ethimon/margins"])  # the replay starts on the subscription
        got = client.messages(40)
    finally:
        client.close()
    cli.join(20)
    assert not cli.is_alive() and out["r"].returncode == 1, out
    dec = [m for topic, _, m in got if topic == "/ethimon/decision"]
    assert [d["cycle"] for d in dec] == list(range(20))
    assert dec[10]["latched_rules"] == ["oa"] and dec[12]["latched"] and not dec[13]["override"]
    assert [m for topic, _, m in got if topic == "/ethimon/margins"][10] == {"oa": -0.5}
    assert f"served 20 cycles to ws://127.0.0.1:{port}" in out["r"].stdout + out["r"].stderr


@pytest.mark.slow
def test_ros2_node_watched_live_in_foxglove(tmp_path) -> None:
    """A stand-in robot on loopback DDS, ``ethimon ros2 --foxglove`` in a child process, a Foxglove client:
    named margins, R_e against τ, and the override lane as the robot goes too fast."""
    pytest.importorskip("cyclonedds")
    from tests.ros2.test_ros2 import DOMAIN, LOOPBACK, MAPPING, SPEC, Peer
    (tmp_path / "spec.yaml").write_text(SPEC)
    (tmp_path / "map.yaml").write_text(MAPPING)
    port = free_port()
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"), CYCLONEDDS_URI=LOOPBACK)
    proc = subprocess.Popen([sys.executable, "-m", "ethimon.cli", "ros2", "--spec", str(tmp_path / "spec.yaml"),
                             "--map", str(tmp_path / "map.yaml"), "--domain", str(DOMAIN), "--duration-s", "20",
                             "--interface", "lo", "--peer", "127.0.0.1", "--foxglove", f"127.0.0.1:{port}"],
                            env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    peer = Peer()
    stop = threading.Event()
    speed = [0.5]
    client = None
    try:
        js = peer.writer("/joint_states", "sensor_msgs/msg/JointState")
        pu = peer.writer("/ethimon_test/p_unsafe", "std_msgs/msg/Float64")
        F64 = peer.types.idl("std_msgs/msg/Float64")

        def robot():
            while not stop.is_set():
                js.write(peer.joint_state(speed[0]))
                pu.write(F64(data=0.05))
                time.sleep(0.01)
        threading.Thread(target=robot, daemon=True).start()
        client = connect(f"ws://127.0.0.1:{port}", timeout=15.0)
        topics = ["/ethimon/decision", "/ethimon/margins", "/ethimon/risk", "/ethimon/inputs/joint_speed_max"]
        client.handshake(set(topics))
        client.subscribe(topics)

        def until(pred, n: int = 3000):
            for topic, _, m in (client.messages(1)[0] for _ in range(n)):
                if pred(topic, m):
                    return m
            pytest.fail("not seen within the bound")

        m = until(lambda t, m: t == "/ethimon/margins" and m.get("joint_speed") == pytest.approx(1.5))
        r = until(lambda t, m: t == "/ethimon/risk" and m["R_e"] is not None)
        assert r["tau"] == 0.5 and r["band"] == "below"
        until(lambda t, m: t == "/ethimon/decision" and not m["override"])
        speed[0] = 3.0  # too fast: the override lane turns on, held by joint_speed by name
        d = until(lambda t, m: t == "/ethimon/decision" and m["override"])
        assert "joint_speed" in d["latched_rules"] and d["response"] == "stop_1"
        v = until(lambda t, m: t == "/ethimon/inputs/joint_speed_max")
        assert v["value"] == pytest.approx(3.0)
        assert m["joint_speed"] == pytest.approx(1.5)
    finally:
        stop.set()
        if client is not None:
            client.close()
        proc.terminate()
        try:
            proc.communicate(timeout=15)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.communicate()
        peer.close()
