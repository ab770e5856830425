"""Bad input: every case is one clear SpecError (API) / one line and exit 2 (CLI)."""

import time

import pytest

import ethimon
from ethimon.scenario import load_scenario

from tests._cli import call_cli, run_cli

GOOD_HEAD = "ethimon: 1\nname: x\n"
SIGS = "signals:\n  ee_speed: {unit: m/s, range: [0, 3]}\n  human_distance: {unit: m, range: [0, 10]}\n"

CASES = {
    # name: (file bytes, expected message fragment, line, column)
    "broken_yaml": (b"ethimon: 1\nname: x\nsignals:\n  a: {unit: m\n", "invalid YAML", 5, 1),
    "tabs": (b"ethimon: 1\nname: x\nsignals:\n\ta: {}\n", "invalid YAML", 4, 1),
    "wrong_type": (b"ethimon: 1\nname: x\nrisk: {threshold: high}\n", "risk.threshold", 3, 19),
    "unknown_key": (b"ethimon: 1\nname: x\nrisk: {treshold: 0.4}\n", "unknown key 'treshold'", 3, 8),
    "estimator_quantize": (b"ethimon: 1\nname: x\nrisk:\n  estimator: {quantize: int4}\n",
                           "risk.estimator.quantize", 4, 25),
    "estimator_temperature": (b"ethimon: 1\nname: x\nrisk:\n  estimator:\n    temperature: 0\n",
                              "risk.estimator.temperature", 5, 18),
    "estimator_typo": (b"ethimon: 1\nname: x\nrisk:\n  estimator: {temprature: 1.2}\n",
                       "unknown key 'temprature'", 4, 15),
    "unknown_top_key": (b"ethimon: 1\nname: x\nobligation: []\n", "unknown key 'obligation'", 3, 1),
    "unknown_signal": ((GOOD_HEAD + SIGS + "obligations:\n  - id: a\n    require: ee_sped < 1\n").encode(),
                       "unknown signal 'ee_sped'", 8, 14),
    "empty": (b"", "empty", 1, 1),
    "only_comments": (b"# nothing\n# here\n", "empty", 1, 1),
    "binary": (b"ethimon: 1\n\x00\x01\x02\xff", "binary", 2, 1),
    "non_utf8": (b"ethimon: 1\nname: caf\xe9\n", "not valid UTF-8", 2, 10),
    "duplicate_key": (b"ethimon: 1\nname: x\nname: y\n", "duplicate key 'name'", 3, 1),
    "version": (b"ethimon: 2\nname: x\n", "unsupported format version 2", 1, 10),
    "no_version": (b"name: x\n", "missing format version", 1, 1),
    "python_tag": (b"ethimon: 1\nname: !!python/object/apply:os.system ['touch /tmp/ethimon_pwned']\n",
                   "not allowed", 2, 7),
    "custom_tag": (b"ethimon: 1\nname: !Thing x\n", "not allowed", 2, 7),
    "not_mapping": (b"- a\n- b\n", "must be a mapping", 1, 1),
    "number_as_condition": ((GOOD_HEAD + SIGS + "obligations:\n  - id: a\n    require: ee_speed * 2\n").encode(),
                            "must be a condition", 8, 14),
    "bool_as_number": ((GOOD_HEAD + SIGS + "obligations:\n  - id: a\n    require: (ee_speed > 1) + 1 > 0\n").encode(),
                       "needs a number", 8, 15),
    "unit_mismatch": ((GOOD_HEAD + SIGS + "obligations:\n  - id: a\n    require: ee_speed < human_distance\n").encode(),
                      "unit mismatch", 8, 14),
    "zero_window": ((GOOD_HEAD + SIGS + "obligations:\n  - id: a\n    require: held(ee_speed < 1, 0)\n").encode(),
                    "makes no sense", 8, 33),
    "fractional_window": ((GOOD_HEAD + SIGS + "obligations:\n  - id: a\n    require: once(ee_speed < 1, 2.5)\n").encode(),
                          "whole number", 8, 33),
    "signal_window": ((GOOD_HEAD + SIGS + "obligations:\n  - id: a\n    require: once(ee_speed < 1, ee_speed)\n").encode(),
                      "whole number", 8, 33),
    "unknown_function": ((GOOD_HEAD + "obligations:\n  - id: a\n    require: hold(risk < 1, 3)\n").encode(),
                         "unknown function 'hold'", 5, 14),
    "syntax": ((GOOD_HEAD + "obligations:\n  - id: a\n    require: 'risk < 1 && true'\n").encode(),
               "syntax error", 5, 24),
    "duplicate_id": ((GOOD_HEAD + "obligations:\n  - {id: a, require: 'true'}\n  - {id: a, require: 'true'}\n").encode(),
                     "duplicate obligation id", 5, 10),
    "reserved_signal": ((GOOD_HEAD + "signals:\n  risk: {unit: '1'}\n").encode(), "built-in name", 4, 9),
    "nan_threshold": (b"ethimon: 1\nname: x\nrisk: {threshold: .nan}\n", "finite", 3, 19),
    "empty_range": ((GOOD_HEAD + "signals:\n  a: {range: [5, 1]}\n").encode(), "empty", 4, 6),
    "bad_response": ((GOOD_HEAD + "obligations:\n  - {id: a, require: 'true', response: stop_3}\n").encode(),
                     "response", 4, 40),
    "bad_unit_text": ((GOOD_HEAD + "signals:\n  a: {unit: 'm//s'}\n").encode(), "unit", 4, 13),
    "merge_key": (b"ethimon: 1\nname: x\nbase: &b {a: 1}\nrisk:\n  <<: *b\n", "merge keys", 5, 3),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_api_raises_spec_error_with_position(tmp_path, name):
    data, fragment, line, column = CASES[name]
    path = tmp_path / f"{name}.yaml"
    path.write_bytes(data)
    with pytest.raises(ethimon.SpecError) as info:
        ethimon.load_spec(path)
    err = info.value
    assert fragment in err.message, str(err)
    assert err.path == str(path)
    assert (err.line, err.column) == (line, column), str(err)


@pytest.mark.slow
@pytest.mark.parametrize("name", ["broken_yaml", "python_tag", "unknown_signal", "binary", "version"])
def test_cli_exit_2_one_line_no_traceback(tmp_path, name):
    data, fragment, line, column = CASES[name]
    spec = tmp_path / "spec.yaml"
    spec.write_bytes(data)
    sc = tmp_path / "sc.yaml"
    sc.write_text("ethimon: 1\nname: s\nspec: spec.yaml\ninputs: {risk: 0.2}\n")
    r = run_cli("check", str(sc))
    assert r.returncode == 2
    assert "Traceback" not in r.stderr + r.stdout
    assert f"{spec}:{line}:{column}: " in r.stderr
    assert fragment in r.stderr


def test_python_tag_executes_nothing(tmp_path):
    import os
    marker = "/tmp/ethimon_pwned"
    if os.path.exists(marker):
        os.remove(marker)
    path = tmp_path / "t.yaml"
    path.write_bytes(CASES["python_tag"][0])
    with pytest.raises(ethimon.SpecError):
        ethimon.load_spec(path)
    assert not os.path.exists(marker)


@pytest.mark.slow
def test_alias_bomb_is_refused_quickly(tmp_path):
    lines = ["ethimon: 1", "name: x", 'a: &a ["lol","lol","lol","lol","lol","lol","lol","lol","lol"]']
    prev = "a"
    for name in "bcdefghij":
        lines.append(f"{name}: &{name} [" + ",".join([f"*{prev}"] * 9) + "]")
        prev = name
    path = tmp_path / "bomb.yaml"
    path.write_text("\n".join(lines) + "\n")
    t0 = time.perf_counter()
    with pytest.raises(ethimon.SpecError) as info:
        ethimon.load_spec(path)
    assert time.perf_counter() - t0 < 10
    assert "expands to more than" in info.value.message and info.value.line is not None


@pytest.mark.slow
def test_deep_nesting_is_refused(tmp_path):
    path = tmp_path / "deep.yaml"
    path.write_text("ethimon: 1\nname: x\ndescription: " + "[" * 5000 + "]" * 5000 + "\n")
    with pytest.raises(ethimon.SpecError) as info:
        ethimon.load_spec(path)
    assert "nested too deeply" in info.value.message
    assert info.value.line == 3  # located by the scanner, before the composer recurses (was unlocated, ~3 s)


def test_huge_file_is_refused_without_reading_it_all(tmp_path):
    path = tmp_path / "huge.yaml"
    with open(path, "wb") as fh:
        fh.write(b"ethimon: 1\nname: x\ndescription: '")
        fh.seek(5 * 1024 * 1024)
        fh.write(b"'\n")
    with pytest.raises(ethimon.SpecError) as info:
        ethimon.load_spec(path)
    assert "too large" in info.value.message


def test_missing_file_and_directory(tmp_path):
    with pytest.raises(ethimon.SpecError, match="not found"):
        ethimon.load_spec(tmp_path / "nope.yaml")
    with pytest.raises(ethimon.SpecError, match="directory"):
        ethimon.load_spec(tmp_path)


def test_block_scalar_errors_point_into_the_block(tmp_path):
    path = tmp_path / "b.yaml"
    path.write_text(GOOD_HEAD + "obligations:\n  - id: a\n    require: >-\n      risk < 0.3 and\n"
                    "      hold(risk < 0.2, 3)\n")
    with pytest.raises(ethimon.SpecError) as info:
        ethimon.load_spec(path)
    assert (info.value.line, info.value.column) == (7, 7)


@pytest.mark.slow
def test_scenario_missing_spec_and_empty_dir(tmp_path):
    sc = tmp_path / "sc.yaml"
    sc.write_text("ethimon: 1\nname: s\nspec: nowhere.yaml\ninputs: {risk: 0.1}\n")
    r = run_cli("check", str(sc))
    assert r.returncode == 2 and f"{sc}:3:7: spec 'nowhere.yaml' not found" in r.stderr
    empty = tmp_path / "empty"
    empty.mkdir()
    r = run_cli("check", str(empty))
    assert r.returncode == 2 and "no scenario files" in r.stderr and "Traceback" not in r.stderr


@pytest.mark.slow
def test_scenario_bad_expectation_id_has_hint(tmp_path, root):
    sc = tmp_path / "sc.yaml"
    sc.write_text(f"ethimon: 1\nname: s\nspec: {root}/specs/cobot_cell.yaml\n"
                  "inputs: {p_unsafe: 0.1, human_distance: 3, ee_speed: 0, contact_force: 0, joint_speed_max: 0}\n"
                  "expect: {fired: [seperation]}\n")
    r = call_cli("check", str(sc))
    assert r.returncode == 2
    assert "did you mean 'separation'?" in r.stderr and f"{sc}:5:" in r.stderr


def test_scenario_timeline_past_end(tmp_path, root):
    sc = tmp_path / "sc.yaml"
    sc.write_text(f"ethimon: 1\nname: s\nspec: {root}/specs/governor.yaml\ncycles: 5\n"
                  "inputs: {risk: 0.1}\ntimeline:\n  - {at: 9, set: {risk: 0.2}}\n")
    with pytest.raises(ethimon.SpecError) as info:
        load_scenario(sc)
    assert info.value.line == 7 and "past the end" in info.value.message
