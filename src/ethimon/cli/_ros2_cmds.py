"""``ethimon ros2 --spec SPEC --map MAP``: the monitor live on a ROS 2 robot's DDS domain.

Subscribes to the mapping's topics, steps the monitor at its ``rate_hz`` and
publishes ``/ethimon/override`` and ``/ethimon/decision`` every cycle, until
``--duration-s`` has passed or Ctrl-C. Prints the loop's statistics at the end
(``--json`` for a machine-readable summary). Exit 0 it ran, 2 bad input (a spec
or mapping that cannot be used, a DDS domain that cannot be joined), 3 internal error.
"""

from __future__ import annotations

import argparse
import signal
import sys
import threading
from typing import Any

from ._common import emit_json, err, open_audit_log

__all__ = ["add_ros2_parsers", "cmd_ros2"]


def add_ros2_parsers(sub) -> None:
    p = sub.add_parser(
        "ros2", help="run the monitor live as a node on a ROS 2 DDS domain (needs ethimon[ros2])",
        description="Run SPEC's monitor live on a ROS 2 robot: the topics of MAP (the replay mapping format, "
                    "each with its 'type:') in, /ethimon/override (std_msgs/msg/Bool) and /ethimon/decision "
                    "(std_msgs/msg/String, JSON) out every cycle. Stale, missing or foreign inputs fail closed. "
                    "Exit 0 it ran, 2 bad input, 3 internal error.")
    p.add_argument("--spec", metavar="SPEC", required=True, help="the spec to monitor")
    p.add_argument("--map", dest="mapping", metavar="MAP", required=True, help="the mapping file (topics → signals)")
    p.add_argument("--domain", type=int, default=None, metavar="N",
                   help="ROS 2 domain id (default: $ROS_DOMAIN_ID, else 0)")
    p.add_argument("--duration-s", type=float, default=None, metavar="S", help="stop after S seconds (default: "
                   "run until Ctrl-C / SIGTERM)")
    p.add_argument("--transport", choices=("dds", "zenoh"), default="dds",
                   help="dds (default): a Cyclone DDS participant; zenoh: speak rmw_zenoh (needs ethimon[zenoh]; "
                        "--peer then names zenoh endpoints, default the router on tcp/localhost:7447)")
    p.add_argument("--interface", metavar="NAME|ADDR", help="network interface for DDS (e.g. eth0, lo, or its "
                   "address); default: Cyclone's configuration (CYCLONEDDS_URI)")
    p.add_argument("--peer", action="append", default=[], metavar="ADDR",
                   help="unicast discovery peer (repeatable); with peers multicast is off")
    p.add_argument("--enclave", metavar="DIR", help="SROS2 enclave folder for DDS Security (needs a Cyclone "
                   "DDS build with security)")
    p.add_argument("--msg", action="append", default=[], metavar="PATH",
                   help=".msg file or folder for types outside the ROS 2 Humble type store (repeatable)")
    p.add_argument("--audit", metavar="FILE", help="write a new hash-chained audit log")
    p.add_argument("--model", metavar="DIR", help="risk model for the task text (default: the spec's)")
    p.add_argument("--foxglove", nargs="?", const="127.0.0.1:8765", metavar="[HOST:]PORT",
                   help="serve a live Foxglove view (WebSocket; needs ethimon[foxglove]): the decision, margins by "
                        "rule, R_e against tau and tau_confirm, every input, the channels of 'ethimon replay --mcap' "
                        "(default 127.0.0.1:8765; loopback unless a host is named)")
    p.add_argument("--json", metavar="FILE", help="write the run's statistics as JSON ('-': stdout)")
    p.add_argument("--quiet", "-q", action="store_true", help="print nothing but problems")
    p.set_defaults(handler=cmd_ros2)


def cmd_ros2(args: argparse.Namespace) -> int:
    from .. import _api
    from ..replay import load_mapping

    domain, refused = _domain(args)
    if refused is None:
        refused = _refusal(args)
    if refused is not None:
        return err(refused)
    kwargs = _node_kwargs(args)
    spec = _api.load_spec(args.spec)  # a SpecError: printed located by main, exit 2
    mapping = load_mapping(args.mapping)
    audit = None
    if args.audit:
        audit, rc = open_audit_log(args.audit, spec, tool="ethimon ros2", spec=args.spec, mapping=args.mapping,
                                   domain_id=domain)
        if rc is not None:
            return rc
    try:
        try:
            node = _start(args, spec, mapping, domain, audit, kwargs)  # SpecError, EthimonError: main prints them
        except OSError as exc:  # the Foxglove port is taken
            return err(f"--foxglove: {exc}")
        try:
            stats = node.run(args.duration_s)
        except KeyboardInterrupt:
            node.close()
            stats = node.stats
    finally:
        if audit is not None:
            audit.close()
    return _finish(args, spec, mapping, domain, node, stats)


def _domain(args: argparse.Namespace) -> tuple[int, str | None]:
    """The DDS domain (``--domain``, else ``ROS_DOMAIN_ID``, else 0), or why it is unusable."""
    import os
    domain = args.domain
    if domain is None:
        env = os.environ.get("ROS_DOMAIN_ID", "").strip()
        try:
            domain = int(env) if env else 0
        except ValueError:
            return 0, f"ROS_DOMAIN_ID={env!r} is not a number; pass --domain N"
    if not 0 <= domain <= 232:
        return domain, f"--domain {domain}: a ROS 2 domain id is 0..232"
    return domain, None


def _refusal(args: argparse.Namespace) -> str | None:
    if args.duration_s is not None and not args.duration_s > 0:
        return f"--duration-s {args.duration_s:g}: expected a positive number of seconds"
    if args.transport == "zenoh" and (args.interface or args.enclave):
        return "--interface and --enclave are DDS settings; over zenoh name endpoints with --peer"
    if args.foxglove is not None:
        from ..view import parse_address
        try:
            parse_address(args.foxglove)
        except ValueError as exc:
            return f"--foxglove: {exc}"
    return None


def _node_kwargs(args: argparse.Namespace) -> dict:
    """``Ros2Monitor``'s keywords from ``--foxglove`` and ``--model``."""
    import os

    from ..view import parse_address
    kwargs: dict = {} if args.foxglove is None else {"foxglove": "%s:%d" % parse_address(args.foxglove)}
    if args.model:
        kwargs["estimator_kwargs"] = {"model_dir": os.path.abspath(args.model)}
        kwargs["estimator"] = "ethimon.risk:load_estimator"
    return kwargs


def _start(args: argparse.Namespace, spec: Any, mapping: Any, domain: int, audit: Any, kwargs: dict) -> Any:
    """The node, with SIGTERM stopping it, announced on stderr (unless ``--quiet``)."""
    if args.transport == "zenoh":
        from ..zenoh import ZenohMonitor, zenoh_config
        node = ZenohMonitor(spec, mapping, domain_id=domain, audit=audit, config=zenoh_config(connect=args.peer),
                            msg_files=args.msg, **kwargs)
    else:
        from ..ros2 import Ros2Monitor
        node = Ros2Monitor(spec, mapping, domain_id=domain, audit=audit, interface=args.interface,
                           peers=args.peer, enclave=args.enclave, msg_files=args.msg, **kwargs)
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGTERM, lambda *_: node.stop())
    if not args.quiet:
        print(f"ethimon ros2: spec {spec.name!r} on domain {domain} at {float(mapping.rate_hz):g} Hz; "
              f"publishing /ethimon/override and /ethimon/decision", file=sys.stderr, flush=True)
        if node.loop.foxglove is not None:
            print(f"ethimon ros2: Foxglove view on {node.loop.foxglove.url} (open it in Foxglove: Open "
                  "connection, Foxglove WebSocket; layout examples/foxglove/ethimon-layout.json)",
                  file=sys.stderr, flush=True)
    return node


def _finish(args: argparse.Namespace, spec: Any, mapping: Any, domain: int, node: Any, stats: Any) -> int:
    """The run's JSON summary and its lines on stdout; the exit code."""
    doc = {"spec": spec.name, "domain_id": domain, "rate_hz": float(mapping.rate_hz), "cycles": stats.cycles,
           "override_cycles": stats.overrides, "fault_cycles": stats.fault_cycles,
           "deadline_misses": stats.deadline_misses, "stalls": stats.stalls, "max_late_ms": stats.max_late_s * 1e3,
           "acknowledgements_refused": node.acks_refused, "pending_cycles": stats.pending_cycles,
           "held_by": stats.held_by}
    view = node.loop.foxglove
    if view is not None:
        doc["foxglove"] = {"url": view.url, "cycles": view.cycles, "messages": view.messages,
                           "dropped_cycles": view.dropped}
    if args.json and not emit_json(args.json, doc, "JSON summary"):
        return 2
    if not args.quiet and args.json != "-":
        print(f"ethimon ros2: {stats.cycles} cycles, {stats.overrides} with override, {stats.fault_cycles} with "
              f"faults, {stats.deadline_misses} deadline misses, {stats.stalls} stalls, max late "
              f"{stats.max_late_s * 1e3:.2f} ms")
        print(f"ethimon ros2: {stats.pending_cycles} cycles held awaiting an input (start, new task text); "
              + (f"at the end the arm was held by {stats.held_by}" if stats.held_by else "the arm was free at the end"))
        if view is not None:
            print(f"ethimon ros2: {view.summary()}")
    return 0
