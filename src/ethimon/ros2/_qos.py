"""QoS profiles, named as in ROS 2 (``rmw_qos_profile_*``), and their Cyclone DDS form.

=================  ===========  ==============  ===========  =====================================
profile            reliability  history         durability   used here for
=================  ===========  ==============  ===========  =====================================
``DEFAULT``        reliable     keep last 10    volatile     /ethimon/override, /ethimon/decision
                                                             (plus a deadline), /ethimon/acknowledge,
                                                             the task-text topic
``SENSOR_DATA``    best effort  keep last 5     volatile     every mapped signal topic
=================  ===========  ==============  ===========  =====================================

Matching (DDS request/offer): a best-effort reader matches reliable *and*
best-effort writers, a volatile reader matches volatile and transient-local
writers, so signal subscriptions with ``SENSOR_DATA`` see every publisher a
robot may use; a lost sample only ages the held value (and a stale one fails
closed). The task text is read reliably (``DEFAULT``): a lost text would
leave the previous, possibly harmless one being scored; a best-effort task
publisher does not match, so no text arrives and the risk rule fails closed.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["DEFAULT", "SENSOR_DATA", "QosProfile", "to_cyclone"]


@dataclass(frozen=True)
class QosProfile:
    """A ROS 2 QoS profile (the policies ethimon sets; the rest keep their DDS defaults)."""

    name: str
    reliable: bool
    depth: int
    transient_local: bool = False


#: ``rmw_qos_profile_default``: reliable, keep last 10, volatile
DEFAULT = QosProfile("default", reliable=True, depth=10)
#: ``rmw_qos_profile_sensor_data``: best effort, keep last 5, volatile
SENSOR_DATA = QosProfile("sensor_data", reliable=False, depth=5)


def to_cyclone(profile: QosProfile, *, deadline_s: float | None = None, lease_s: float | None = None):
    """The :class:`cyclonedds.qos.Qos` of ``profile`` (optionally with a deadline and a liveliness lease)."""
    from cyclonedds.qos import Policy, Qos  # lazy: cyclonedds only for a live node
    from cyclonedds.util import duration

    pol = [Policy.Reliability.Reliable(duration(milliseconds=100)) if profile.reliable
           else Policy.Reliability.BestEffort,
           Policy.History.KeepLast(profile.depth),
           Policy.Durability.TransientLocal if profile.transient_local else Policy.Durability.Volatile,
           # XCDR1 (plain CDR, encapsulation CDR_LE): what ROS 2 bags store and rmw_cyclonedds sends
           Policy.DataRepresentation(use_cdrv0_representation=True)]
    if deadline_s is not None:
        pol.append(Policy.Deadline(duration(seconds=deadline_s)))
    if lease_s is not None:
        pol.append(Policy.Liveliness.Automatic(duration(seconds=lease_s)))
    return Qos(*pol)
