"""ROS 2's names on the DDS wire (the conventions rmw implementations share).

A ROS 2 topic ``/joint_states`` is the DDS topic ``rt/joint_states`` ("ROS
topic"; services use ``rq/``/``rr/``), and the message type
``sensor_msgs/msg/JointState`` is the DDS type
``sensor_msgs::msg::dds_::JointState_``. A node and a plain DDS participant
find each other when both names match.
"""

from __future__ import annotations

import re

__all__ = ["dds_topic", "dds_type", "normalize_type", "ros_topic"]

_TYPE = re.compile(r"^([A-Za-z][A-Za-z0-9_]*)/(?:(msg)/)?([A-Za-z][A-Za-z0-9_]*)$")


def normalize_type(msgtype: str) -> str:
    """``sensor_msgs/JointState`` or ``sensor_msgs/msg/JointState`` → ``sensor_msgs/msg/JointState``."""
    m = _TYPE.match(msgtype)
    if m is None:
        raise ValueError(f"not a ROS 2 message type: {msgtype!r} (expected pkg/msg/Name)")
    return f"{m.group(1)}/msg/{m.group(3)}"


def dds_type(msgtype: str) -> str:
    """``sensor_msgs/msg/JointState`` → ``sensor_msgs::msg::dds_::JointState_``."""
    pkg, kind, name = normalize_type(msgtype).split("/")
    return f"{pkg}::{kind}::dds_::{name}_"


def dds_topic(topic: str) -> str:
    """``/joint_states`` → ``rt/joint_states`` (a relative name is taken as in the root namespace)."""
    name = topic.lstrip("/")
    if not name:
        raise ValueError(f"not a ROS 2 topic name: {topic!r}")
    return "rt/" + name


def ros_topic(dds_name: str) -> str:
    """``rt/joint_states`` → ``/joint_states`` (any other DDS name is returned as it is)."""
    return "/" + dds_name[3:] if dds_name.startswith("rt/") else dds_name
