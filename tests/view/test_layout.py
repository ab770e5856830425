"""The shipped Foxglove layout reads only channels and fields the verdict channels have (for the example
spec), holds the panels it promises, and its mosaic places every panel it configures."""

from __future__ import annotations

import json

import ethimon
from ethimon.view import VerdictChannels
from tests._cli import ROOT

LAYOUT = ROOT / "examples" / "foxglove" / "ethimon-layout.json"


def _leaves(node):
    if isinstance(node, str):
        yield node
    else:
        yield from _leaves(node["first"])
        yield from _leaves(node["second"])


def test_layout_paths_are_channels_and_fields_of_the_example_spec() -> None:
    doc = json.loads(LAYOUT.read_text(encoding="utf-8"))
    spec = ethimon.load_spec(ROOT / "examples" / "replay" / "spec.yaml")
    fields = {topic: set(json.loads(data)["properties"])
              for topic, _, data in VerdictChannels.of_spec(spec, ethimon.Monitor(spec).obligation_ids).schemas()}
    paths = []
    for pid, cfg in doc["configById"].items():
        if "topicPath" in cfg:
            assert cfg["topicPath"] in fields, pid
        for s in cfg.get("paths", []):
            topic, _, field = s["value"].partition(".")
            assert topic in fields and field in fields[topic], (pid, s["value"])
            paths.append((pid.split("!")[0], s["value"]))
    assert sorted(_leaves(doc["layout"])) == sorted(doc["configById"])
    assert {("Plot", "/ethimon/risk.R_e"), ("Plot", "/ethimon/risk.tau"), ("Plot", "/ethimon/risk.tau_confirm"),
            ("StateTransitions", "/ethimon/decision.override")} <= set(paths)
    assert {f"/ethimon/margins.{oid}" for oid in ethimon.Monitor(spec).obligation_ids} <= {p for _, p in paths}
    assert doc["configById"]["RawMessages!ethimon-decision"]["topicPath"] == "/ethimon/decision"
