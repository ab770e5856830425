"""One name per concept (issue 24, item 3): YAML keys <-> Python attributes <-> CLI flags <-> JSON keys.

``CONCEPTS`` is the map. Each row is checked layer by layer against the code: a YAML key is written
into a spec or mapping file and read back through the attribute (same value, and the model field is
the key itself: no alias); a CLI flag is found on its command's parser and parses into the dest of
the same words; a JSON key is read out of what the library writes. A rename in one layer that the
others do not follow fails here. The rules beside it: one argparse handler name, a unit in every
flag that carries a quantity (no hidden old spellings), ``run_sim``
takes the monitor's input names, and the two "defaults" of τ stay two named facts.
"""

from __future__ import annotations

import argparse
import inspect
from pathlib import Path

import pytest

import ethimon
from ethimon.cli import _build_parser

# concept: (spec-or-mapping YAML key path, Python attribute path, [(command, flag)], JSON key)
#   the YAML and attribute paths are the same words by rule; a JSON key may be the symbol (tau for
#   risk.threshold: the τ of R_e >= τ) and is then written here, once.
CONCEPTS: dict[str, dict] = {
    "tau": {"yaml": ("spec", "risk.threshold", 0.31), "attr": "risk.threshold", "cli": [],
            "json": "tau"},
    "confirm_threshold": {"yaml": ("spec", "risk.confirm_threshold", 0.12), "attr": "risk.confirm_threshold",
                          "cli": [(("evaluate",), "--confirm-threshold")], "json": "confirm_threshold"},
    "risk_hold_cycles": {"yaml": ("spec", "risk.release.hold_cycles", 7), "attr": "risk.release.hold_cycles",
                         "cli": [], "json": None},
    "hold_cycles": {"yaml": ("spec", "obligations.0.release.hold_cycles", 5),
                    "attr": "obligations.0.release.hold_cycles", "cli": [], "json": None},
    "risk_max_age_s": {"yaml": ("spec", "risk.max_age_s", 0.25), "attr": "risk.max_age_s", "cli": [],
                       "json": None},
    "max_age_s": {"yaml": ("mapping", "max_age_s", 0.08), "attr": "max_age_s", "cli": [], "json": "max_age_s"},
    "rate_hz": {"yaml": ("mapping", "rate_hz", 40), "attr": "rate_hz", "cli": [], "json": "rate_hz"},
    "file_timeout_s": {"yaml": None, "attr": None, "cli": [(("check",), "--file-timeout-s"),
                                                           (("replay",), "--file-timeout-s")], "json": None},
    "duration_s": {"yaml": None, "attr": None, "cli": [(("ros2",), "--duration-s")], "json": None},
    "timeout_s": {"yaml": None, "attr": None, "cli": [(("verify",), "--timeout-s")], "json": None},
    "budget_s": {"yaml": None, "attr": None, "cli": [(("verify",), "--budget-s")], "json": None},
}

#: flags whose dest is not their own words, each for a reason
DEST_EXCEPTIONS = {"--map": "mapping",  # the file is a mapping (replay.load_mapping); --map is its short flag
                   "--int8": "precision", "--fp32": "precision"}  # two switches of one setting

SPEC = """ethimon: 1
name: names
signals:
  d: {unit: m, range: [0, 10]}
risk: {threshold: 0.5, confirm_threshold: 0.2, max_age_s: 0.5, release: {mode: auto, hysteresis: 0.05, hold_cycles: 3}}
obligations:
  - {id: sep, require: "d >= 0.5", release: {mode: auto, hold_cycles: 2}}
"""

MAPPING = """ethimon: 1
rate_hz: 50
max_age_s: 0.1
signals:
  d: {topic: /d}
"""


def _set(doc: dict, path: str, value) -> None:
    *head, last = path.split(".")
    for k in head:
        doc = doc[int(k)] if k.isdigit() else doc[k]
    doc[last] = value


def _get(obj, path: str):
    for k in path.split("."):
        obj = obj[int(k)] if k.isdigit() else getattr(obj, k)
    return obj


def _load(kind: str, path: str, value):
    import yaml
    doc = yaml.safe_load(SPEC if kind == "spec" else MAPPING)
    _set(doc, path, value)
    text = yaml.safe_dump(doc, sort_keys=False)
    if kind == "spec":
        return ethimon.load_spec_text(text)
    from ethimon.replay import load_mapping_text
    return load_mapping_text(text)


def _field_owner(obj, path: str):
    """The pydantic model holding the last key of ``path``, and that key."""
    *head, last = path.split(".")
    return (_get(obj, ".".join(head)) if head else obj), last


@pytest.mark.parametrize("concept", [c for c, row in CONCEPTS.items() if row["yaml"]])
def test_yaml_key_is_the_attribute(concept):
    row = CONCEPTS[concept]
    kind, key, value = row["yaml"]
    obj = _load(kind, key, value)
    assert _get(obj, row["attr"]) == value, (concept, key, row["attr"])
    owner, last = _field_owner(obj, row["attr"])
    field = type(owner).model_fields[last]  # the Python field is the YAML key itself
    assert field.alias in (None, last) and key.split(".")[-1] == last, (concept, field.alias)


def _leaves(p: argparse.ArgumentParser, path: tuple[str, ...] = ()):
    subs = [a for a in p._actions if isinstance(a, argparse._SubParsersAction)]
    if not subs:
        yield path, p
        return
    for a in subs:
        for name, sp in a.choices.items():
            yield from _leaves(sp, path + (name,))


LEAVES = dict(_leaves(_build_parser()))


@pytest.mark.parametrize("concept", [c for c, row in CONCEPTS.items() if row["cli"]])
def test_cli_flag_is_the_concept(concept):
    for command, flag in CONCEPTS[concept]["cli"]:
        parser = LEAVES[command]
        action = next((a for a in parser._actions if flag in a.option_strings), None)
        assert action is not None, (concept, command, flag)
        assert action.dest == flag.lstrip("-").replace("-", "_") == concept.removeprefix("risk_"), (flag, action.dest)


def test_every_flag_parses_into_its_own_words():
    for command, parser in LEAVES.items():
        for a in parser._actions:
            for o in a.option_strings:
                if o.startswith("--") and o not in ("--help", "--version"):
                    want = DEST_EXCEPTIONS.get(o, o.lstrip("-").replace("-", "_"))
                    assert a.dest == want, (command, o, a.dest)


def test_a_unit_in_every_flag_that_carries_seconds():
    seen = 0
    for command, parser in LEAVES.items():
        for a in parser._actions:
            if a.help == argparse.SUPPRESS:
                continue
            if a.metavar == "S" or "seconds" in (a.help or "") and a.type is float:
                seen += 1
                assert all(o.endswith("-s") for o in a.option_strings if o.startswith("--")), (command, a.option_strings)
    assert seen >= 4  # --file-timeout-s (check, replay), --duration-s, --timeout-s, --budget-s


def test_one_handler_name_on_every_leaf_command():
    for command, parser in LEAVES.items():
        assert callable(parser.get_default("handler")), command
        assert parser.get_default("func") is None, command


def test_json_keys_of_tau_and_confirm_threshold():
    from ethimon.risk._evaluate import tier_metrics
    spec = _load("spec", "risk.confirm_threshold", 0.12)
    m = tier_metrics([0, 1], [0.1, 0.6], spec.risk.threshold, spec.risk.confirm_threshold)
    assert m[CONCEPTS["tau"]["json"]] == spec.risk.threshold
    assert m[CONCEPTS["confirm_threshold"]["json"]] == spec.risk.confirm_threshold


def test_json_keys_of_a_replay(tmp_path):
    pytest.importorskip("rosbags", reason="needs rosbags (pip install -e '.[ros]')")
    from rosbags.rosbag2 import StoragePlugin, Writer
    from rosbags.typesys import Stores, get_typestore
    from ethimon.replay import load_mapping_text, replay_bag
    ts = get_typestore(Stores.ROS2_HUMBLE)
    f64 = ts.types["std_msgs/msg/Float64"]
    bag = tmp_path / "b"
    with Writer(bag, version=9, storage_plugin=StoragePlugin.MCAP) as w:
        c = w.add_connection("/d", "std_msgs/msg/Float64", typestore=ts)
        for i in range(40):
            w.write(c, 10**12 + i * 50_000_000, ts.serialize_cdr(f64(data=2.0), "std_msgs/msg/Float64"))
    mapping = load_mapping_text(MAPPING.replace("rate_hz: 50", "rate_hz: 40").replace("max_age_s: 0.1", "max_age_s: 0.08"))
    doc = replay_bag(bag, ethimon.load_spec_text(SPEC), mapping, p=(1.0, 0.0)).as_dict()
    assert doc[CONCEPTS["rate_hz"]["json"]] == _get(mapping, CONCEPTS["rate_hz"]["attr"]) == 40
    assert doc["signals"]["d"][CONCEPTS["max_age_s"]["json"]] == _get(mapping, CONCEPTS["max_age_s"]["attr"]) == 0.08


def test_run_sim_takes_the_monitor_input_names():
    from ethimon.sim import run_sim
    kws = set(inspect.signature(run_sim).parameters)
    assert {"p", "p_unsafe", "risk"} <= kws
    from ethimon.scenario._run import RISK_KEYS
    assert set(RISK_KEYS) <= kws  # what sim_risk_inputs returns is what run_sim takes

    class Stop(Exception):
        pass

    class Probe:
        def reset(self):
            raise Stop  # run_sim resets the monitor right after reading its inputs: no simulation runs

    with pytest.raises(TypeError, match="probs"):  # the old spelling is gone (issue 33)
        run_sim({}, Probe(), probs=(0.9, 0.1))
    with pytest.raises(Stop):
        run_sim({}, Probe(), p=(0.9, 0.1))


def test_the_two_defaults_of_tau_are_two_named_facts():
    """The spec language's default τ (a spec that writes no threshold) and the shipped model's
    calibrated τ are different numbers with different names; the shipped specs write the latter."""
    from ethimon.risk import DEFAULT_TAU
    from ethimon.language import RiskConfig
    spec_default = RiskConfig.model_fields["threshold"].default
    assert (spec_default, DEFAULT_TAU) == (0.5, 0.606)
    assert ethimon.load_spec_text("ethimon: 1\nname: t\nsignals: {}\n").risk.threshold == spec_default
    root = Path(__file__).resolve().parents[2]
    for name in ("governor.yaml", "cobot_cell.yaml"):
        assert ethimon.load_spec(str(root / "specs" / name)).risk.threshold == DEFAULT_TAU, name


def test_tau_and_the_release_cut_have_one_name_in_the_monitor_and_offline():
    """τ is ``tau`` (``Monitor._tau``), the float cut of the release bound τ − δ is ``release_cut``
    (``Plan.release_cut``, which the monitor and offline read, ``Monitor._release_cut``): the same number
    under one name."""
    from ethimon.compiler._risk_formula import release_bound
    spec = ethimon.load_spec_text(SPEC.replace("hysteresis: 0.05", "hysteresis: 0.07"))
    mon = ethimon.Monitor(spec)
    cut = release_bound(spec.risk.threshold, spec.risk.release.hysteresis)[1]
    assert mon._tau == spec.risk.threshold and mon._release_cut == cut == mon.plan.release_cut
    assert not hasattr(mon, "_below")


def test_result_report_outcome_follow_the_glossary_rule() -> None:
    """Every class named ``…Result``/``…Report``/``…Outcome`` is named in ARCHITECTURE.md's rule."""
    import ast
    import re
    root = Path(__file__).resolve().parents[2]
    doc = (root / "ARCHITECTURE.md").read_text(encoding="utf-8")
    rule = doc[doc.index("**Result / Report / Outcome**"):]
    rule = rule[:rule.index("\n- **", 1)]
    found = set()
    for path in (root / "src" / "ethimon").rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ClassDef) and re.search(r"(Result|Report|Outcome)$", node.name):
                found.add(node.name)
    assert found, "the scan found no class"
    assert sorted(n for n in found if f"`{n}`" not in rule) == []
