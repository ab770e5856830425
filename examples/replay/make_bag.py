"""Write the example bag ``examples/replay/cell/`` (ROS 2, MCAP storage) with rosbags.

A 10 s recording of a Panda cell at a conveyor (bag time starts at 1,700,000,000 s):

* ``/joint_states`` (sensor_msgs/JointState, 50 Hz): 7 joints, velocities about 0.5 rad/s;
* ``/ee/twist`` (geometry_msgs/TwistStamped, 50 Hz): end-effector speed 0.5 m/s, slowed to
  0.2 m/s when a person comes near -- 0.2 s after they cross the 1.5 m line, too late for the
  3-cycle bounded response of ``slow_near_human`` at 100 Hz;
* ``/ee/wrench`` (geometry_msgs/WrenchStamped, 50 Hz): small contact forces;
* ``/human/range`` (sensor_msgs/Range, 20 Hz): a person walks from 4 m to 0.9 m and back; the
  sensor drops out for 0.3 s at t = 8 s (longer than the mapping's 0.1 s staleness limit);
* ``/task`` (std_msgs/String): the task text, published once at t = 0.

Run from the repository root: ``python examples/replay/make_bag.py`` (replaces the folder).
Deterministic: the same bytes every run.
"""

from __future__ import annotations

import math
import shutil
import sys
from pathlib import Path

import numpy as np

try:
    from rosbags.rosbag2 import StoragePlugin, Writer
    from rosbags.typesys import Stores, get_typestore
except ImportError:  # pragma: no cover
    sys.exit("needs rosbags: pip install 'ethimon[ros]'")

OUT = Path(__file__).resolve().parent / "cell"
T0 = 1_700_000_000 * 10**9  # bag time of the first message (ns)
DURATION_S = 10.0
TASK = "Move the boxes from the conveyor to the pallet."


def human_distance(t: float) -> float:
    """4 m, walking in from t = 3 s to 0.9 m at t = 5.5 s, staying until 6.5 s, leaving by 9 s."""
    if t < 3.0:
        return 4.0
    if t < 5.5:
        return 4.0 - (t - 3.0) / 2.5 * 3.1
    if t < 6.5:
        return 0.9
    if t < 9.0:
        return 0.9 + (t - 6.5) / 2.5 * 3.1
    return 4.0


def first_near() -> float:
    """When the person first comes within 1.5 m."""
    return 3.0 + (4.0 - 1.5) / 3.1 * 2.5


def ee_speed(t: float) -> float:
    """0.5 m/s; 0.2 m/s from 0.2 s after the person is within 1.5 m until they are 2 m away again."""
    near_from = first_near() + 0.2
    far_again = 6.5 + (2.0 - 0.9) / 3.1 * 2.5
    return 0.2 if near_from <= t < far_again else 0.5


def main() -> None:
    ts = get_typestore(Stores.ROS2_HUMBLE)
    T = ts.types
    Time, Header = T["builtin_interfaces/msg/Time"], T["std_msgs/msg/Header"]
    JointState, String = T["sensor_msgs/msg/JointState"], T["std_msgs/msg/String"]
    Range = T["sensor_msgs/msg/Range"]
    Vector3, Twist, TwistStamped = (T["geometry_msgs/msg/Vector3"], T["geometry_msgs/msg/Twist"],
                                    T["geometry_msgs/msg/TwistStamped"])
    Wrench, WrenchStamped = T["geometry_msgs/msg/Wrench"], T["geometry_msgs/msg/WrenchStamped"]

    def header(t_ns: int, frame: str) -> object:
        return Header(stamp=Time(sec=t_ns // 10**9, nanosec=t_ns % 10**9), frame_id=frame)

    if OUT.exists():
        shutil.rmtree(OUT)
    joints = [f"panda_joint{i}" for i in range(1, 8)]
    with Writer(OUT, version=9, storage_plugin=StoragePlugin.MCAP) as w:
        c_js = w.add_connection("/joint_states", JointState.__msgtype__, typestore=ts)
        c_tw = w.add_connection("/ee/twist", TwistStamped.__msgtype__, typestore=ts)
        c_wr = w.add_connection("/ee/wrench", WrenchStamped.__msgtype__, typestore=ts)
        c_hr = w.add_connection("/human/range", Range.__msgtype__, typestore=ts)
        c_task = w.add_connection("/task", String.__msgtype__, typestore=ts)
        msgs: list[tuple[int, int, object, object]] = []  # (time, order, connection, message)
        msgs.append((T0, 0, c_task, String(data=TASK)))
        for i in range(int(DURATION_S * 50) + 1):  # 50 Hz
            t_ns = T0 + i * 20_000_000
            t = i / 50
            vel = np.array([0.5 * math.sin(0.8 * t + j) for j in range(7)])
            pos = np.array([0.3 * math.cos(0.8 * t + j) for j in range(7)])
            msgs.append((t_ns, 1, c_js, JointState(header=header(t_ns, ""), name=joints, position=pos,
                                                     velocity=vel, effort=np.zeros(7))))
            v = ee_speed(t)
            msgs.append((t_ns, 2, c_tw, TwistStamped(header=header(t_ns, "panda_hand"), twist=Twist(
                linear=Vector3(x=0.8 * v, y=0.6 * v, z=0.0), angular=Vector3(x=0.0, y=0.0, z=0.1)))))
            f = 4.0 + 2.0 * math.sin(3.0 * t)
            msgs.append((t_ns, 3, c_wr, WrenchStamped(header=header(t_ns, "panda_hand"), wrench=Wrench(
                force=Vector3(x=0.0, y=0.0, z=f), torque=Vector3(x=0.0, y=0.0, z=0.0)))))
        for i in range(int(DURATION_S * 20) + 1):  # 20 Hz, dropout 8.0 s <= t < 8.3 s
            t = i / 20
            if 8.0 <= t < 8.3:
                continue
            t_ns = T0 + i * 50_000_000
            msgs.append((t_ns, 4, c_hr, Range(header=header(t_ns, "lidar"), radiation_type=1, field_of_view=3.1,
                                              min_range=0.05, max_range=10.0, range=human_distance(t))))
        for t_ns, _, conn, msg in sorted(msgs, key=lambda m: (m[0], m[1])):
            w.write(conn, t_ns, ts.serialize_cdr(msg, conn.msgtype))
    size = sum(f.stat().st_size for f in OUT.iterdir())
    print(f"wrote {OUT} ({len(msgs)} messages, {size / 1024:.0f} KiB)")


if __name__ == "__main__":
    main()
