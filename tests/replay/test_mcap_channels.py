"""``--mcap`` and ``--foxglove`` write the same verdict channels as the live view (issue 34): the latched
rules by name, margins by rule id, R_e against τ and τ_confirm, one schema per topic."""

from __future__ import annotations

import json

import pytest

import ethimon

pytest.importorskip("rosbags")
pytest.importorskip("mcap")

from ethimon.replay import load_mapping_text, replay_bag, write_mcap  # noqa: E402
from tests.replay.test_replay_bags import ns, write  # noqa: E402

SPEC = """
ethimon: 1
name: ab
signals:
  a: {unit: m, range: [0, 10]}
obligations:
  - {id: oa, require: a >= 1, release: {hold_cycles: 3}}
risk: {threshold: 0.5, confirm_threshold: 0.2}
"""
MAP = "ethimon: 1\nrate_hz: 20\nmax_age_s: 0.1\nrisk: none\nsignals:\n  a: {topic: /a}\n"


def _replay(tmp_path):
    spec = ethimon.load_spec_text(SPEC)
    write(tmp_path / "b", "mcap", [(ns(i * 0.05), "/a", "f64", 0.5 if i == 10 else 2.0) for i in range(20)])
    return spec, replay_bag(tmp_path / "b", spec, load_mapping_text(MAP), keep_trace=True)


def _read(path):
    from mcap.reader import make_reader
    got, schemas = {}, {}
    with open(path, "rb") as f:
        reader = make_reader(f)
        summary = reader.get_summary()
        for ch in summary.channels.values():  # every channel, a message on it or not
            sc = summary.schemas[ch.schema_id]
            assert ch.message_encoding == "json" and sc.encoding == "jsonschema"
            schemas[ch.topic] = (sc.name, json.loads(sc.data))
        for schema, channel, message in reader.iter_messages():
            got.setdefault(channel.topic, []).append(json.loads(message.data))
    return got, schemas


def test_mcap_names_the_latched_rules_and_tau_confirm(tmp_path):
    spec, res = _replay(tmp_path)
    write_mcap(res, tmp_path / "v.mcap", spec)
    got, _ = _read(tmp_path / "v.mcap")
    dec = got["/ethimon/decision"]
    assert dec[10]["violations"] == ["oa"] and dec[10]["latched_rules"] == ["oa"]
    assert dec[11]["latched"] and dec[11]["latched_rules"] == ["oa"]  # held by the release rule
    assert dec[9]["latched_rules"] == [] and not dec[14]["override"]
    assert got["/ethimon/risk"][0]["tau_confirm"] == 0.2 and got["/ethimon/risk"][0]["tau"] == 0.5
    assert got["/ethimon/margins"][10] == {"oa": -0.5}


def test_mcap_and_the_live_view_share_names_and_schemas(tmp_path):
    from ethimon.view import VerdictChannels
    spec, res = _replay(tmp_path)
    write_mcap(res, tmp_path / "v.mcap", spec)
    _, schemas = _read(tmp_path / "v.mcap")
    live = VerdictChannels.of_spec(spec, ethimon.Monitor(spec).obligation_ids).schemas()
    assert {t: (name, json.loads(data)) for t, name, data in live} == schemas


def test_replay_verdicts_served_to_a_view_paced_on_the_bag_timeline(tmp_path):
    from ethimon.replay._mcap import serve_verdicts
    spec, res = _replay(tmp_path)
    got, waits = [], []

    class View:
        def put_messages(self, msgs, t):
            got.append((t, dict(msgs)))

    now = [0.0]
    n = serve_verdicts(res, View(), spec, speed=2.0, clock=lambda: now[0],
                       sleep=lambda s: (waits.append(s), now.__setitem__(0, now[0] + s)))
    assert n == 20 and [t for t, _ in got] == res.grid.tolist()
    assert got[10][1]["/ethimon/decision"]["latched_rules"] == ["oa"]
    assert waits == pytest.approx([0.025] * 19)  # 50 ms cycles at twice the bag's pace
    with pytest.raises(ValueError, match="speed"):
        serve_verdicts(res, View(), spec, speed=-1)
