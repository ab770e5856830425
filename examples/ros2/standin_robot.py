"""A stand-in robot for trying `ethimon ros2` on one machine (no ROS 2 needed).

It publishes healthy values on the topics of examples/ros2/mapping.yaml over Cyclone DDS (the ROS 2
wire: rt/ topics, XCDR1) and a task text on /task, at --rate-hz, for --duration-s seconds:

    python examples/ros2/standin_robot.py --domain 0 --duration-s 60
    python examples/ros2/standin_robot.py --unsafe-after-s 5      # joint speed 9 rad/s from 5 s on

`--config` (or CYCLONEDDS_URI) picks the network; `--loopback` keeps it on 127.0.0.1.
"""

from __future__ import annotations

import argparse
import os
import sys
import time


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--domain", type=int, default=int(os.environ.get("ROS_DOMAIN_ID", "0") or 0))
    p.add_argument("--duration-s", type=float, default=60.0)
    p.add_argument("--rate-hz", type=float, default=50.0)
    p.add_argument("--text", default="Place the red box on the second shelf.")
    p.add_argument("--unsafe-after-s", type=float, default=None,
                   help="from then on publish a joint speed of 9 rad/s (the spec's limit is 2)")
    p.add_argument("--loopback", action="store_true", help="Cyclone DDS on the loopback interface only")
    args = p.parse_args(argv)

    from cyclonedds.domain import Domain, DomainParticipant
    from cyclonedds.pub import DataWriter
    from cyclonedds.topic import Topic
    from ethimon.ros2 import DEFAULT, SENSOR_DATA, MessageTypes, cyclone_config, dds_topic, to_cyclone

    types = MessageTypes()
    domain = Domain(args.domain, cyclone_config(interface="lo", peers=["127.0.0.1"])) if args.loopback else None
    dp = DomainParticipant(args.domain)

    def writer(topic, msgtype, profile):
        return DataWriter(dp, Topic(dp, dds_topic(topic), types.idl(msgtype)), to_cyclone(profile))

    T = types.idl
    Time, Header, Vector3 = T("builtin_interfaces/msg/Time"), T("std_msgs/msg/Header"), T("geometry_msgs/msg/Vector3")
    w_joints = writer("/joint_states", "sensor_msgs/msg/JointState", SENSOR_DATA)
    w_twist = writer("/ee/twist", "geometry_msgs/msg/TwistStamped", SENSOR_DATA)
    w_wrench = writer("/ee/wrench", "geometry_msgs/msg/WrenchStamped", SENSOR_DATA)
    w_range = writer("/human/range", "sensor_msgs/msg/Range", SENSOR_DATA)
    w_task = writer("/task", "std_msgs/msg/String", DEFAULT)

    def header():
        now = time.time()
        return Header(stamp=Time(sec=int(now), nanosec=int((now % 1) * 1e9)), frame_id="base")

    zero = Vector3(x=0.0, y=0.0, z=0.0)
    t0 = time.monotonic()
    period = 1.0 / args.rate_hz
    n = 0
    print(f"standin robot: domain {args.domain}, {args.rate_hz:g} Hz, task {args.text!r}", file=sys.stderr, flush=True)
    while time.monotonic() - t0 < args.duration_s:
        unsafe = args.unsafe_after_s is not None and time.monotonic() - t0 >= args.unsafe_after_s
        speed = 9.0 if unsafe else 0.5
        w_joints.write(T("sensor_msgs/msg/JointState")(header=header(), name=[f"j{i}" for i in range(7)],
                                                       position=[0.0] * 7, velocity=[speed] + [0.1] * 6, effort=[]))
        w_twist.write(T("geometry_msgs/msg/TwistStamped")(header=header(), twist=T("geometry_msgs/msg/Twist")(
            linear=Vector3(x=0.1, y=0.0, z=0.0), angular=zero)))
        w_wrench.write(T("geometry_msgs/msg/WrenchStamped")(header=header(), wrench=T("geometry_msgs/msg/Wrench")(
            force=Vector3(x=0.0, y=0.0, z=5.0), torque=zero)))
        w_range.write(T("sensor_msgs/msg/Range")(header=header(), radiation_type=0, field_of_view=0.5,
                                                 min_range=0.05, max_range=8.0, range=3.0))
        if n % max(1, int(args.rate_hz)) == 0:  # the task text once a second (reliable; late joiners get it too)
            w_task.write(T("std_msgs/msg/String")(data=args.text))
        n += 1
        time.sleep(max(0.0, t0 + n * period - time.monotonic()))
    del domain
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
