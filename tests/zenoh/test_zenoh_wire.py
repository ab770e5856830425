"""What the zenoh node puts on the wire is what rmw_zenoh puts there (ros2/rmw_zenoh docs/design.md: the key
expressions' examples, the attachment's layout, the liveliness tokens), and what it refuses to use."""

from __future__ import annotations

import pytest

from ethimon.zenoh import topic_key
from ethimon.zenoh._keys import liveliness_token, pack_attachment, parse_token, unpack_attachment

CHATTER_HASH = "RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18"


def test_topic_keys_are_rmw_zenohs():
    # design.md's examples, word for word
    assert topic_key(0, "/chatter", "std_msgs::msg::dds_::String_", CHATTER_HASH) == \
        f"0/chatter/std_msgs::msg::dds_::String_/{CHATTER_HASH}"
    assert topic_key(0, "/robot1/chatter", "std_msgs::msg::dds_::String_", CHATTER_HASH) == \
        f"0/robot1/chatter/std_msgs::msg::dds_::String_/{CHATTER_HASH}"
    for bad in ("/", "", "/a//b", "/a/*", "/a/**"):
        with pytest.raises(ValueError):
            topic_key(0, bad, "T", "H")


def test_the_type_hash_is_rep_2016s():
    pytest.importorskip("rosbags")
    from ethimon.ros2 import MessageTypes
    assert MessageTypes().store.hash_rihs01("std_msgs/msg/String") == CHATTER_HASH


def test_the_attachment_is_sequence_time_and_gid_little_endian():
    gid = bytes(range(16))
    raw = pack_attachment(7, 1_700_000_000_123_456_789, gid)
    assert len(raw) == 33 and raw[:8] == (7).to_bytes(8, "little") and raw[16] == 16 and raw[17:] == gid
    att = unpack_attachment(raw)
    assert (att.seq, att.t_ns, att.gid) == (7, 1_700_000_000_123_456_789, gid)
    assert unpack_attachment(None) is None and unpack_attachment(raw[:20]) is None
    assert unpack_attachment(raw[:17] + gid[:8]) is None  # a GID shorter than it says


def test_liveliness_tokens_are_rmw_zenohs_and_parse_back():
    # design.md's talker example: session, node 0, entity 10, a publisher on /chatter
    key = liveliness_token(2, "8b20917502ee955ac4476e0266340d5c", 0, 10, "MP", "talker", "/chatter",
                           "std_msgs::msg::dds_::String_", CHATTER_HASH, qos="::,7:,:,:,,")
    assert key == ("@ros2_lv/2/8b20917502ee955ac4476e0266340d5c/0/10/MP/%/%/talker/%chatter/"
                   f"std_msgs::msg::dds_::String_/{CHATTER_HASH}/::,7:,:,:,,")
    info = parse_token(key)
    assert (info.kind, info.topic, info.node, info.session_id) == ("MP", "/chatter", "talker",
                                                                  "8b20917502ee955ac4476e0266340d5c")
    assert parse_token(liveliness_token(2, "s", 0, 0, "NN", "listener")) is None
    assert parse_token("0/chatter/x/y") is None
