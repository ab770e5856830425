"""YAML numbers written with an exponent and no dot (``1e-3``, ``2e-1``, ``1e3``, ``-5E+2``) are
numbers, as in YAML 1.2: YAML 1.1 reads them as strings, which the strict models refuse (review of
issue 11). A quoted ``'1e-3'`` stays a string and is still refused where a number is needed."""

import math

import pytest

import ethimon
from ethimon.scenario import load_scenario, load_scenario_text
from ethimon.language._yaml import parse_yaml_text

SPEC = """\
ethimon: 1
name: exp
signals:
  x: {unit: m, range: [0, 1e3]}
risk: {alpha: 0.6, beta: 0.2, gamma: 0.2, threshold: 1e-1, max_age_s: 2e-1, response: safe_pose}
obligations:
  - {id: o, require: x < 5e2, response: safe_pose}
"""


@pytest.mark.parametrize("text, value", [("1e-3", 1e-3), ("2e-1", 0.2), ("1e3", 1000.0), ("-5E+2", -500.0),
                                         ("+1E3", 1000.0), (".5e1", 5.0), ("1.0e3", 1000.0)])
def test_plain_exponent_scalars_are_floats(text, value):
    data, _ = parse_yaml_text(f"a: {text}\n")
    assert type(data["a"]) is float and data["a"] == value


@pytest.mark.parametrize("text", ["'1e-3'", '"1e3"', "!!str 1e3", "1e", "e3", "1e-", "1_0e3"])
def test_quoted_tagged_or_malformed_stay_strings(text):
    data, _ = parse_yaml_text(f"a: {text}\n")
    assert type(data["a"]) is str


def test_integers_and_special_floats_are_unchanged():
    data, _ = parse_yaml_text("a: 123\nb: 0x1f\nc: .inf\nd: -.inf\ne: .nan\nf: 1_000\ng: 1.5\n")
    assert data["a"] == 123 and type(data["a"]) is int and data["b"] == 31 and data["f"] == 1000
    assert data["c"] == math.inf and data["d"] == -math.inf and math.isnan(data["e"]) and data["g"] == 1.5


def test_spec_with_exponent_numbers_loads(tmp_path):
    p = tmp_path / "s.yaml"
    p.write_text(SPEC)
    spec = ethimon.load_spec(p)
    assert spec.risk.threshold == 0.1 and spec.risk.max_age_s == 0.2
    assert tuple(spec.signals["x"].range) == (0.0, 1000.0)


def test_quoted_exponent_is_still_refused_where_a_number_is_needed():
    with pytest.raises(ethimon.SpecError, match="number"):
        ethimon.load_spec_text(SPEC.replace("threshold: 1e-1", "threshold: '1e-1'"))


def test_scenario_with_exponent_numbers_loads(tmp_path):
    spec = tmp_path / "s.yaml"
    spec.write_text(SPEC)
    sc = tmp_path / "sc.yaml"
    sc.write_text("ethimon: 1\nname: e\nspec: s.yaml\ncycles: 3\ninputs: {p_unsafe: 1e-2, x: 1e0}\n"
                  "timeline:\n  - {at: 1, set: {x: 2.5e2}}\nexpect: {override: false}\n")
    s = load_scenario(sc)
    assert s.inputs["p_unsafe"] == 0.01 and type(s.inputs["p_unsafe"]) is float and s.inputs["x"] == 1.0
    assert s.timeline[0].set["x"] == 250.0
    with pytest.raises(ethimon.SpecError):
        load_scenario_text("ethimon: 1\nname: e\nspec: s.yaml\ncycles: 3\ninputs: {p_unsafe: '1e-2'}\n",
                           str(sc))
