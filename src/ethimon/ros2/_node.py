"""The monitor as a node on a ROS 2 robot's own DDS wire (Cyclone DDS, no rclpy).

:class:`Ros2Monitor` is a Cyclone DDS transport (``ros2/_channel.py``, an
:class:`ethimon.io.Channel`) under :class:`ethimon.io.LiveMonitor`: the mapping
file replay reads (each topic also names its ``type:``), the same holds,
reductions, ``derive: rate``, staleness and future-stamp rules as replay
(``ethimon.io``), and the monitor stepped by :class:`~ethimon.loop.GovernedLoop`
at the mapping's ``rate_hz``
(deadline, stall detection, watchdog, audit log, async risk scoring of the
task-text topic). Every cycle it publishes

* ``/ethimon/override`` (``std_msgs/msg/Bool``): the decision's override, and
* ``/ethimon/decision`` (``std_msgs/msg/String``): the decision as JSON
  (cycle, override, response, violations, faults, margins, R_e),

both reliable, keep last 10, with an offered *deadline* of
``ros2.deadline_cycles`` cycles: a robot-side reader that requests a deadline
is told by its own DDS stack (requested-deadline-missed) when the node goes
silent, crashed or not; ``/ethimon/override`` arriving every cycle is the
heartbeat. The watchdog publishes ``override: true`` itself when the loop
stalls.

Fail closed: a topic with no message yet is a missing input; one whose last
message is older than its ``max_age_s`` is a ``stale`` fault; a value that
cannot be formed (NaN, an empty array) is invalid; a second publisher on a
monitored topic (or one replacing the first mid-run) is a ``signals`` fault
naming its writer and participant, and its samples are not used; so is any
other writer on ``/ethimon/override``; a header stamp further ahead than
``future_tolerance_s`` is a ``stale`` fault; a sample replaced before a cycle
read it is a ``signals`` fault under ``samples: every`` (replay refuses such a bag).

Operators acknowledge latched rules on ``/ethimon/acknowledge``
(``std_msgs/msg/String`` holding ``{"operator": ..., "reason": ...}``),
queued and applied by the loop thread between two cycles (audited); the answer is
published on ``/ethimon/acknowledge_result``. Without DDS Security nothing on
the wire is authenticated, so acknowledgements are refused (and audited as
refused) unless the mapping's ``ros2.allow_unauthenticated_acknowledge``
gives a reason to accept them.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from typing import Any

from ..errors import SpecError
from ..io import LiveNode, Mapping
from ..language import Spec
from ..loop import LoopStats
from ..runtime import Decision
from ._channel import (ACK_RESULT_TOPIC, ACK_TOPIC, DECISION_TOPIC, OVERRIDE_TOPIC, DdsChannel, Subscription)
from ._config import cyclone_config
from ._types import MessageTypes

__all__ = ["ACK_RESULT_TOPIC", "ACK_TOPIC", "DECISION_TOPIC", "OVERRIDE_TOPIC", "Ros2Monitor", "run_ros2"]


class Ros2Monitor(LiveNode):
    """A :class:`~ethimon.Monitor` live on a ROS 2 DDS domain (Cyclone DDS; ``pip install 'ethimon[ros2]'``):
    an :class:`ethimon.io.LiveNode` on a Cyclone DDS channel.

    Args:
        spec: the loaded spec (:func:`ethimon.load_spec`).
        mapping: a :class:`~ethimon.io.Mapping` or the path of a mapping file (the replay format;
            each topic needs ``type:``).
        domain_id: the ROS 2 domain (``ROS_DOMAIN_ID``; default 0).
        interface, peers, multicast, enclave: network and DDS Security settings (see
            :func:`~ethimon.ros2.cyclone_config`); none given: Cyclone's own configuration.
        config: Cyclone DDS XML instead of those four.
        msg_files: ``.msg`` files or folders for types outside the ROS 2 Humble type store.
        estimator, estimator_kwargs, audit, watchdog_s, on_decision, record, loop_kwargs: as
            :class:`~ethimon.io.LiveNode` (the task text scored by the spec's estimator in a child process by
            default; a watchdog publishes ``override: true`` when no cycle completes for 5 cycles, at least
            50 ms; ``deadline_s`` & co. go to :class:`~ethimon.loop.LoopConfig`).

    Raises:
        SpecError: the mapping does not fit the spec or the message types (file, line, column).
        Ros2Error: a DDS entity cannot be made, or DDS Security is asked for but not available.
        DependencyNotInstalled: cyclonedds or rosbags is missing.
    """

    def __init__(self, spec: Spec, mapping: Mapping | str | os.PathLike, *, domain_id: int = 0,
                 interface: str | None = None, peers: tuple[str, ...] | list[str] = (),
                 multicast: bool | None = None, enclave: str | os.PathLike | None = None,
                 config: str | None = None, msg_files: list | tuple = (),
                 on_decision: Callable[[Decision], None] | None = None, **kwargs: Any) -> None:
        if not isinstance(spec, Spec):
            raise SpecError(f"Ros2Monitor needs a loaded spec (ethimon.load_spec), got {type(spec).__name__}")
        if not (isinstance(domain_id, int) and 0 <= domain_id <= 232):
            raise ValueError(f"domain_id={domain_id!r}; a ROS 2 domain id is 0..232 (ROS_DOMAIN_ID)")
        self.domain_id = domain_id
        self.secure = enclave is not None

        def open_channel(subs: list[Subscription], period_s: float) -> DdsChannel:
            xml = config if config is not None else cyclone_config(interface=interface, peers=tuple(peers),
                                                                   multicast=multicast, enclave=enclave)
            return DdsChannel(subs, self.types, domain_id, xml, period_s=period_s,
                              deadline_cycles=self.mapping.ros2.deadline_cycles,
                              publishers=self.mapping.ros2.publishers, secure=self.secure)

        super().__init__(spec, mapping, open_channel, types=MessageTypes(msg_files), topic=Subscription,
                         on_decision=on_decision, audit_fields={"domain_id": domain_id, "secure": self.secure},
                         **kwargs)


def run_ros2(spec: Spec | str | os.PathLike, mapping: Mapping | str | os.PathLike, *,
             duration_s: float | None = None, **kwargs: Any) -> LoopStats:
    """Load ``spec`` (a path or a :class:`~ethimon.Spec`) and ``mapping``, govern the domain for
    ``duration_s`` seconds (``None``: until interrupted) and return the loop's statistics.

    Keyword arguments go to :class:`Ros2Monitor`.
    """
    if not isinstance(spec, Spec):
        from .._api import load_spec
        spec = load_spec(spec)
    node = Ros2Monitor(spec, mapping, **kwargs)
    return node.run(duration_s)
