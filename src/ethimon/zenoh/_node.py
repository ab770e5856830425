"""The monitor as a node on a ROS 2 robot that runs ``rmw_zenoh``: a zenoh transport (``_channel.py``) under
:class:`ethimon.io.LiveMonitor`, made from the same spec and mapping file as ``ethimon ros2`` over DDS.

Everything that is not the wire comes from :class:`ethimon.io.LiveNode` and ``ethimon.loop``: the holds,
reductions, ``derive: rate``, staleness and future-stamp rules (as replay), the decision JSON, the
acknowledgements (applied in the loop thread), the loop's deadline, watchdog and audit log. The mapping's
``ros2:`` block applies as it is (``publishers``, ``allow_unauthenticated_acknowledge``; ``deadline_cycles``
is DDS only: zenoh has no deadline QoS to offer, the override every cycle is the heartbeat).
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable
from typing import Any

from ..errors import Ros2Error, SpecError
from ..io import LiveNode, Mapping
from ..language import Spec
from ..loop import LoopStats
from ..runtime import Decision
from ._channel import Topic, ZenohChannel, zenoh_module

__all__ = ["ZenohMonitor", "run_zenoh", "zenoh_config"]


def zenoh_config(connect: tuple[str, ...] | list[str] = (), listen: tuple[str, ...] | list[str] = (), *,
                 mode: str = "peer", multicast: bool = False, config_file: str | os.PathLike | None = None) -> Any:
    """A ``zenoh.Config``: rmw_zenoh's session defaults (peer, multicast scouting off, connect to the router on
    ``tcp/localhost:7447``) unless ``connect`` / ``listen`` endpoints are given; ``config_file``: a zenoh
    JSON5 configuration instead (``ZENOH_SESSION_CONFIG_URI`` in rmw_zenoh)."""
    zenoh = zenoh_module()
    try:
        if config_file is not None:
            return zenoh.Config.from_file(os.fspath(config_file))
        c = zenoh.Config()
        c.insert_json5("mode", json.dumps(mode))
        c.insert_json5("scouting/multicast/enabled", "true" if multicast else "false")
        c.insert_json5("connect/endpoints", json.dumps(list(connect) if connect or listen
                                                       else ["tcp/localhost:7447"]))
        c.insert_json5("listen/endpoints", json.dumps(list(listen)))
        return c
    except Exception as exc:  # noqa: BLE001 - ZError: a bad endpoint or file
        raise Ros2Error(f"zenoh configuration: {exc}"[:600]) from None


class ZenohMonitor(LiveNode):
    """A :class:`~ethimon.Monitor` live on a ROS 2 system over zenoh (``rmw_zenoh``; ``pip install
    'ethimon[zenoh]'``): an :class:`ethimon.io.LiveNode` on a zenoh channel.

    Args:
        spec: the loaded spec.
        mapping: a :class:`~ethimon.io.Mapping` or a mapping file's path (each topic names its ``type:``).
        domain_id: the ROS 2 domain (``ROS_DOMAIN_ID``).
        config: a ``zenoh.Config`` (:func:`zenoh_config`; default: connect to ``tcp/localhost:7447``).
        type_hash: ``"rihs01"`` (Jazzy and later) or ``"none"`` (Humble): the hash chunk of the keys written.
        msg_files: ``.msg`` files or folders for types outside the ROS 2 Humble type store.
        clock: one clock for the loop and the channel (tests).
        estimator, estimator_kwargs, audit, watchdog_s, on_decision, record, loop_kwargs: as
            :class:`~ethimon.io.LiveNode`.

    Raises:
        SpecError: the mapping does not fit the spec or the message types (file, line, column).
        Ros2Error: the zenoh session or its publishers and subscribers cannot be made.
        DependencyNotInstalled: eclipse-zenoh or rosbags is missing.
    """

    def __init__(self, spec: Spec, mapping: Mapping | str | os.PathLike, *, domain_id: int = 0,
                 config: Any = None, type_hash: str = "rihs01", msg_files: list | tuple = (),
                 on_decision: Callable[[Decision], None] | None = None,
                 clock: Callable[[], float] | None = None, **kwargs: Any) -> None:
        from ..ros2 import MessageTypes
        if not isinstance(spec, Spec):
            raise SpecError(f"ZenohMonitor needs a loaded spec (ethimon.load_spec), got {type(spec).__name__}")
        if not (isinstance(domain_id, int) and 0 <= domain_id <= 232):
            raise ValueError(f"domain_id={domain_id!r}; a ROS 2 domain id is 0..232 (ROS_DOMAIN_ID)")
        self.domain_id = domain_id
        if clock is not None:
            kwargs.setdefault("clock", clock)

        def open_channel(topics: list[Topic], period_s: float) -> ZenohChannel:
            return ZenohChannel(topics, self.types, domain_id, config if config is not None else zenoh_config(),
                                publishers=self.mapping.ros2.publishers, period_s=period_s, type_hash=type_hash,
                                clock=clock)

        super().__init__(spec, mapping, open_channel, types=MessageTypes(msg_files), topic=Topic,
                         on_decision=on_decision,
                         audit_fields={"transport": "zenoh", "domain_id": domain_id, "secure": False}, **kwargs)


def run_zenoh(spec: Spec | str | os.PathLike, mapping: Mapping | str | os.PathLike, *,
              duration_s: float | None = None, **kwargs: Any) -> LoopStats:
    """Load ``spec`` and ``mapping``, govern over zenoh for ``duration_s`` seconds (``None``: until
    interrupted) and return the loop's statistics. Keyword arguments go to :class:`ZenohMonitor`."""
    if not isinstance(spec, Spec):
        from .._api import load_spec
        spec = load_spec(spec)
    return ZenohMonitor(spec, mapping, **kwargs).run(duration_s)
