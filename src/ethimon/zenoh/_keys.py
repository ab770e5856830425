"""What ``rmw_zenoh`` puts on the wire, as data: topic key expressions, the per-sample attachment, the
liveliness tokens of the ROS 2 graph. No zenoh import here.

The formats are those of ``rmw_zenoh_cpp``'s design document (ros2/rmw_zenoh, ``docs/design.md``, sections
"Topic and Service name mapping to Zenoh key expressions", "Graph Cache" and "Publishers"):

* a topic's key expression is ``<domain_id>/<fully_qualified_name>/<type_name>/<type_hash>``: the topic name
  without its leading ``/`` (inner ``/`` kept), the type as DDS names it (``std_msgs::msg::dds_::String_``),
  the REP-2016 type hash (``RIHS01_<sha256 hex>``), e.g.
  ``0/chatter/std_msgs::msg::dds_::String_/RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18``;
  ROS 2 Humble has no type hashes (its ``rmw_zenoh`` writes ``TypeHashNotSupported``);
* the payload is CDR with its 4-byte encapsulation header (the bytes rosbags' ``serialize_cdr`` gives);
* each published sample carries an attachment: the sequence number (int64, little endian), the source
  time (int64 ns since the Unix epoch, little endian), one byte with the publisher GID's length (16) and
  the GID;
* each entity declares a liveliness token
  ``@ros2_lv/<domain_id>/<session_id>/<node_id>/<entity_id>/<kind>/<enclave>/<namespace>/<node>[/<topic>/<type>/<hash>/<qos>]``
  (``kind``: ``NN`` node, ``MP`` publisher, ``MS`` subscription; ``/`` inside a name replaced by ``%``,
  an empty enclave or namespace written ``%``).
"""

from __future__ import annotations

import struct
from dataclasses import dataclass

__all__ = ["ADMIN_SPACE", "HASH_NOT_SUPPORTED", "Attachment", "TokenInfo", "liveliness_token", "mangle",
           "pack_attachment", "parse_token", "topic_key", "unpack_attachment"]

#: the hermetic prefix of rmw_zenoh's liveliness tokens
ADMIN_SPACE = "@ros2_lv"
#: the type hash rmw_zenoh writes on ROS 2 Humble, which has none
HASH_NOT_SUPPORTED = "TypeHashNotSupported"
#: rmw_zenoh's QoS chunk for the ROS 2 default profile, depth 10 (design.md's ``listener`` example)
DEFAULT_QOS = "::,10:,:,:,,"
_ATT = struct.Struct("<qqB")


def topic_key(domain_id: int, topic: str, dds_type: str, type_hash: str) -> str:
    """``topic_key(0, "/chatter", "std_msgs::msg::dds_::String_", "RIHS01_df66...")`` →
    ``0/chatter/std_msgs::msg::dds_::String_/RIHS01_df66...`` (``type_hash`` may be ``*``: any)."""
    name = topic.strip("/")
    if not name or "//" in name or any(c in name for c in "*$?#"):
        raise ValueError(f"not a ROS 2 topic name: {topic!r}")
    return f"{int(domain_id)}/{name}/{dds_type}/{type_hash}"


def mangle(name: str) -> str:
    """A name as one key chunk: each ``/`` → ``%`` (``""`` → ``%``)."""
    return name.replace("/", "%") if name else "%"


def liveliness_token(domain_id: int, session_id: str, node_id: int, entity_id: int, kind: str, node: str,
                     topic: str | None = None, dds_type: str | None = None, type_hash: str | None = None,
                     qos: str = DEFAULT_QOS) -> str:
    """The liveliness token of a node (``kind="NN"``) or of one of its publishers / subscriptions."""
    key = f"{ADMIN_SPACE}/{int(domain_id)}/{session_id}/{node_id}/{entity_id}/{kind}/%/%/{node}"
    if topic is not None:
        key += f"/{mangle(topic)}/{dds_type}/{type_hash}/{qos}"
    return key


@dataclass(frozen=True)
class TokenInfo:
    """A parsed endpoint token: who (session, node, entity, node name), what (``MP``/``MS``), on which topic."""

    session_id: str
    node_id: str
    entity_id: str
    kind: str
    node: str
    topic: str
    dds_type: str
    type_hash: str

    @property
    def who(self) -> str:
        return f"publisher {self.entity_id} of node {self.node!r} ({self.node_id}) in zenoh session {self.session_id}"


def parse_token(key: str) -> TokenInfo | None:
    """An endpoint token's parts (``None`` for a node's token or anything else)."""
    parts = key.split("/")
    if len(parts) != 13 or parts[0] != ADMIN_SPACE:
        return None
    topic = parts[9].replace("%", "/")
    return TokenInfo(parts[2], parts[3], parts[4], parts[5], parts[8], topic if topic.startswith("/") else "/" + topic,
                     parts[10], parts[11])


@dataclass(frozen=True)
class Attachment:
    """An rmw_zenoh sample attachment: sequence number, source time (ns since the epoch), publisher GID."""

    seq: int
    t_ns: int
    gid: bytes

    @property
    def gid_hex(self) -> str:
        return self.gid.hex()


def pack_attachment(seq: int, t_ns: int, gid: bytes) -> bytes:
    """The 33 bytes (for a 16-byte GID) rmw_zenoh attaches to a published sample."""
    return _ATT.pack(int(seq), int(t_ns), len(gid)) + bytes(gid)


def unpack_attachment(data: bytes | None) -> Attachment | None:
    """The attachment's fields, or ``None`` when it is missing or not in rmw_zenoh's form."""
    if data is None or len(data) < _ATT.size:
        return None
    seq, t_ns, n = _ATT.unpack_from(data)
    gid = bytes(data[_ATT.size:])
    if n == 0 or len(gid) != n:
        return None
    return Attachment(seq, t_ns, gid)
