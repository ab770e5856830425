"""``ethimon ros2 --transport zenoh``: the same command, spec and mapping, over zenoh; DDS-only options refused."""

from __future__ import annotations

import json

import pytest

pytest.importorskip("zenoh")
pytest.importorskip("rosbags")

from ethimon.cli import main  # noqa: E402

from tests.zenoh._robot import free_port  # noqa: E402

SPEC = """
ethimon: 1
name: zcli
signals:
  joint_speed_max: {unit: rad/s, range: [0, 100]}
risk: {threshold: 0.5, release: {mode: auto, hysteresis: 0.05, hold_cycles: 2}}
on_fault: {response: stop_1, release: auto}
obligations:
  - {id: joint_speed, require: "joint_speed_max <= 2.0", response: stop_1, release: auto}
"""
MAPPING = """
ethimon: 1
rate_hz: 100
max_age_s: 0.5
signals:
  joint_speed_max: {topic: /joint_states, type: sensor_msgs/msg/JointState, field: velocity, reduce: max_abs}
  p_unsafe: {topic: /zcli/p_unsafe, type: std_msgs/msg/Float64, max_age_s: 5.0}
"""


@pytest.mark.slow  # the node for 0.2 s
def test_ethimon_ros2_transport_zenoh_runs_and_fails_closed_without_inputs(tmp_path, capsys):
    (tmp_path / "s.yaml").write_text(SPEC)
    (tmp_path / "m.yaml").write_text(MAPPING)
    rc = main(["ros2", "--transport", "zenoh", "--spec", str(tmp_path / "s.yaml"), "--map", str(tmp_path / "m.yaml"),
               "--peer", f"tcp/127.0.0.1:{free_port()}", "--duration-s", "0.2", "--json", "-", "-q"])
    assert rc == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["cycles"] >= 5 and doc["override_cycles"] == doc["cycles"]  # no robot: every cycle an override


def test_dds_options_are_refused_over_zenoh(tmp_path, capsys):
    (tmp_path / "s.yaml").write_text(SPEC)
    (tmp_path / "m.yaml").write_text(MAPPING)
    rc = main(["ros2", "--transport", "zenoh", "--spec", str(tmp_path / "s.yaml"), "--map", str(tmp_path / "m.yaml"),
               "--enclave", str(tmp_path), "--duration-s", "0.1"])
    assert rc == 2 and "DDS settings" in capsys.readouterr().err
