"""The monitor live on ROS 2 over zenoh: ``ethimon ros2 --transport zenoh``, a node that speaks what
``rmw_zenoh`` speaks (a second transport on the :mod:`ethimon.io` seam, beside the Cyclone DDS one).

::

    import ethimon
    from ethimon.zenoh import ZenohMonitor, zenoh_config

    spec = ethimon.load_spec("examples/replay/spec.yaml")
    with ZenohMonitor(spec, "examples/ros2/mapping.yaml", domain_id=0,
                      config=zenoh_config(connect=["tcp/localhost:7447"])) as node:
        node.run(duration_s=60)

The same mapping file as ``ethimon ros2`` and replay; ROS 2 key expressions
(``<domain>/<topic>/<dds type>/<type hash>``), CDR payloads (rosbags' type store) with rmw_zenoh's
attachment (sequence number, source time, publisher GID), liveliness tokens for the node and each of
its publishers and subscriptions. ``zenoh`` is imported only when a node is made
(``pip install 'ethimon[zenoh]'``).
"""

from ._channel import ZenohChannel
from ._keys import topic_key
from ._node import ZenohMonitor, run_zenoh, zenoh_config

__all__ = ["ZenohMonitor", "zenoh_config"]
