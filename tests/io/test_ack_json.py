"""One parser for an operator's acknowledgement as JSON text (``AckRequest.from_json``), used by every
transport (Cyclone DDS and zenoh): the same request is accepted or refused the same way on each, and a
refusal says what is wrong with it (the key, the type, where the JSON breaks).

Before (issue 33 item 3): each transport parsed the JSON itself, refused every malformed request with
one fixed message, and took a misspelt key (``"task_sha"``) or an empty ``task_sha256`` as "no task
named", so an acknowledgement meant to bind to the text the operator was shown was applied unbound."""

from __future__ import annotations

import json
from types import SimpleNamespace

import pytest

from ethimon.io import AckRequest


def test_a_well_formed_request_is_read_with_its_bounds():
    req = AckRequest.from_json(json.dumps({"operator": "ops-1", "reason": "cleared the cell",
                                           "task_sha256": "ab" * 32}), sender="w1", authenticated=True)
    assert (req.operator, req.reason, req.task_sha256, req.sender, req.authenticated, req.error) == \
        ("ops-1", "cleared the cell", "ab" * 32, "w1", True, None)
    long = AckRequest.from_json(json.dumps({"operator": "o" * 500, "reason": "r" * 5000}), sender="w")
    assert len(long.operator) == 200 and len(long.reason) == 2000 and long.task_sha256 is None


@pytest.mark.parametrize("text, says", [
    ("not json", "not JSON (line 1, column 1"),
    ("[1, 2]", "a JSON object"),
    ('{"reason": "x"}', "'operator' is missing"),
    ('{"operator": "  "}', "'operator' is empty"),
    ('{"operator": 7}', "'operator' is a number, not text"),
    ('{"operator": "a", "reason": ["x"]}', "'reason' is a list, not text"),
    ('{"operator": "a", "task_sha256": 5}', "'task_sha256' is a number, not text"),
    ('{"operator": "a", "task_sha256": ""}', "'task_sha256' is empty"),
    ('{"operator": "a", "task_sha": "ab"}', "unknown key 'task_sha' (did you mean 'task_sha256'?)"),
    (b'\xff\xfe', "not UTF-8 text"),
])
def test_a_malformed_request_is_refused_saying_what_is_wrong(text, says):
    req = AckRequest.from_json(text, sender="w2")
    assert req.operator is None and req.error is not None and req.error.startswith("refused: ")
    assert says in req.error, req.error
    assert '{"operator": "<name>", "reason": "<text>"' in req.error  # the expected shape, always
    assert req.sender == "w2"


def _dds_parse(text: str) -> AckRequest:
    pytest.importorskip("cyclonedds")
    from ethimon.ros2._channel import DdsChannel
    return DdsChannel._parse_ack(SimpleNamespace(secure=False), SimpleNamespace(data=text), "writer w")


def _zenoh_parse(text: str) -> AckRequest:
    pytest.importorskip("zenoh")
    from ethimon.ros2 import MessageTypes
    from ethimon.zenoh._channel import ZenohChannel
    types = MessageTypes()
    St = types.store.types["std_msgs/msg/String"]
    payload = bytes(types.store.serialize_cdr(St(data=text), "std_msgs/msg/String"))
    return ZenohChannel._parse_ack(SimpleNamespace(types=types), payload, "publisher p")


@pytest.mark.parametrize("parse", [_dds_parse, _zenoh_parse], ids=["dds", "zenoh"])
@pytest.mark.parametrize("text", ['{"operator": "a", "task_sha": "ab"}', '{"operator": "a", "task_sha256": ""}',
                                  '{"operator": 3}', "{"])
def test_every_transport_refuses_what_the_one_parser_refuses(parse, text):
    got, want = parse(text), AckRequest.from_json(text, sender="x")
    assert got.operator is None and got.error == want.error


@pytest.mark.parametrize("parse", [_dds_parse, _zenoh_parse], ids=["dds", "zenoh"])
def test_every_transport_reads_a_good_request_as_the_one_parser_does(parse):
    text = json.dumps({"operator": "ops-1", "reason": "ok", "task_sha256": "cd" * 32})
    got, want = parse(text), AckRequest.from_json(text, sender="x")
    assert (got.operator, got.reason, got.task_sha256, got.error) == (want.operator, want.reason,
                                                                      want.task_sha256, None)
    assert "/ethimon/acknowledge" in got.sender and got.authenticated is False
