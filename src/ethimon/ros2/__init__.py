"""The monitor live on ROS 2: ``ethimon ros2``, a node on the robot's own DDS wire.

::

    import ethimon
    from ethimon.ros2 import Ros2Monitor

    spec = ethimon.load_spec("examples/ros2/spec.yaml")
    with Ros2Monitor(spec, "examples/ros2/mapping.yaml", domain_id=0) as node:
        node.run(duration_s=60)

No rclpy: ROS 2 nodes talk DDS-RTPS, and this node is a plain Cyclone DDS
participant that follows ROS 2's wire conventions (topic ``rt/<name>``, type
``<pkg>::msg::dds_::<Name>_``, XCDR1 payloads, the ROS 2 QoS profiles). It reads
the replay mapping format (one file for live monitoring and bag replay),
steps the monitor with :class:`~ethimon.loop.GovernedLoop` and publishes
``/ethimon/override`` (``std_msgs/msg/Bool``) and ``/ethimon/decision``
(``std_msgs/msg/String``, JSON) every cycle. ``cyclonedds`` is imported only
when a node is made (``pip install 'ethimon[ros2]'``).
"""

from ._config import ENCLAVE_FILES, cyclone_config, security_available
from ._names import dds_topic, dds_type, normalize_type, ros_topic
from ._node import ACK_RESULT_TOPIC, ACK_TOPIC, DECISION_TOPIC, OVERRIDE_TOPIC, Ros2Monitor, run_ros2
from ._qos import DEFAULT, SENSOR_DATA, QosProfile, to_cyclone
from ._types import MessageTypes

__all__ = ["DEFAULT", "MessageTypes", "Ros2Monitor", "SENSOR_DATA"]
