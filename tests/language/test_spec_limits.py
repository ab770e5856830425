"""Specs at and past the size limits, and specs that load but could not work (issue 11).

Every case is one SpecError with file:line:column and a hint, never a
RecursionError, OverflowError or ValueError, and never a spec that loads and
then faults on every cycle or never fires its risk rule.
"""

from __future__ import annotations

import os
import stat
import subprocess
import sys
import threading

import pytest

import ethimon
from ethimon.testing import ReferenceMonitor
from ethimon.scenario import load_scenario
from ethimon.language._expr import MAX_CHAIN_TERMS, MAX_EXPR_CHARS, MAX_TREE_DEPTH

from tests._cli import call_cli

HEAD = "ethimon: 1\nname: x\n"
COL0 = len("    require: '") + 1  # column of the first character of a spec_with() expression
SIGS = "signals:\n  x: {range: [0, 1]}\n  b: {type: bool}\n"
INPUT = {"x": 0.5, "b": True, "risk": 0.1}


def spec_with(require: str, extra: str = "") -> str:
    return HEAD + SIGS + extra + f"obligations:\n  - id: o\n    require: '{require}'\n"


def load_error(text: str) -> ethimon.SpecError:
    with pytest.raises(ethimon.SpecError) as info:
        ethimon.load_spec_text(text, "t.yaml")
    err = info.value
    assert err.path == "t.yaml" and err.line is not None and err.column is not None, str(err)
    assert err.hint, str(err)
    return err


def runs_clean(spec) -> None:
    """Monitor and reference interpreter agree and raise/fault on nothing for a few cycles."""
    m, r = ethimon.Monitor(spec), ReferenceMonitor(spec)
    for _ in range(3):
        d, e = m.step(INPUT), r.step(INPUT)
        assert not d.faults and not e.faults, (d, e)
        assert (d.override, d.violations) == (e.override, e.violations)


# -- long chains: handled, or a clear SpecError -------------------------------------------------


@pytest.mark.slow
@pytest.mark.parametrize("op,n", [("and", 400), ("or", 600), ("and", 1000), ("or", 2500)])
def test_long_and_or_chains_load_and_run(op, n):
    terms = ["b", "x < 2", "not b", "x > -1"] if op == "and" else ["not b", "x > 2", "b"]
    src = f" {op} ".join(terms[i % len(terms)] for i in range(n))
    assert len(src) <= MAX_EXPR_CHARS
    spec = ethimon.load_spec_text(spec_with(src), "t.yaml")
    runs_clean(spec)
    d = ethimon.Monitor(spec).step(INPUT)
    assert d.violations == (("o",) if op == "and" else ())  # 'not b' is false / 'b' is true


def test_and_chain_short_circuits_left_to_right():
    # the right-hand division would fail if evaluated; a balanced tree must not change that
    text = spec_with(" and ".join(["x > 2"] + ["x / x > 0"] * 300))
    spec = ethimon.load_spec_text(text, "t.yaml")
    d = ethimon.Monitor(spec).step({"x": 0.0, "b": True, "risk": 0.1})
    assert not d.faults and d.violations == ("o",)


@pytest.mark.parametrize("op,n", [("+", 400), ("*", 600), ("-", 1300), ("/", 700)])
def test_long_arithmetic_chains_are_spec_errors(op, n):
    src = op.join(["x"] * n) + " > -1"
    err = load_error(spec_with(src))
    assert f"too long: {n} terms, the limit is {MAX_CHAIN_TERMS}" in err.message
    assert err.line == 8
    # points at the first operator past the limit: column of "require: '" + (limit terms)
    assert err.column == len("    require: '") + 1 + (2 * MAX_CHAIN_TERMS - 1)


@pytest.mark.parametrize("op", ["+", "-", "*", "/"])
def test_arithmetic_chain_at_the_limit_works(op):
    src = op.join(["x"] * MAX_CHAIN_TERMS) + " > -1e300"
    spec = ethimon.load_spec_text(spec_with(src), "t.yaml")
    runs_clean(spec)


def test_tree_depth_limit_through_parentheses():
    inner = "+".join(["x"] * 60)
    deep = f"(({inner}) * " + " * ".join(["x"] * 60) + ")"  # 59 + 60 levels: fine
    runs_clean(ethimon.load_spec_text(spec_with(" - ".join([deep] * 2) + " > -1"), "t.yaml"))
    too_deep = "((" + "(" + inner + ") + " + inner + ") + " + inner + ") > 0"  # 3 * 59 + 3 levels
    err = load_error(spec_with(too_deep))
    assert f"nested or chained too deeply (more than {MAX_TREE_DEPTH} levels)" in err.message


def test_deepest_accepted_tree_compiles_and_runs_in_a_deep_caller():
    # a spec the parser accepts must not hit the recursion limit downstream (codegen, step,
    # reference interpreter), even when loaded and run from code that already uses 200 frames
    inner = "+".join(["x"] * 79)
    src = f"(({inner}) + {inner}) > -1"
    text = spec_with(src)

    def nest(k):
        if k:
            return nest(k - 1)
        runs_clean(ethimon.load_spec_text(text, "t.yaml"))
    nest(200)


@pytest.mark.slow
def test_thousand_term_chain_passes_ethimon_check(tmp_path):
    src = " and ".join(["b"] * 1000)
    (tmp_path / "s.yaml").write_text(spec_with(src))
    (tmp_path / "sc.yaml").write_text("ethimon: 1\nname: sc\nspec: s.yaml\ncycles: 5\n"
                                      "inputs: {x: 0.5, b: true, risk: 0.1}\nexpect: {override: false}\n")
    r = call_cli("check", str(tmp_path / "sc.yaml"))
    assert r.returncode == 0, r.stdout + r.stderr
    assert "Traceback" not in r.stdout + r.stderr


@pytest.mark.slow
def test_long_chain_in_cli_is_exit_2_not_internal_error(tmp_path):
    (tmp_path / "s.yaml").write_text(spec_with("+".join(["x"] * 500) + " > 0"))
    (tmp_path / "sc.yaml").write_text("ethimon: 1\nname: sc\nspec: s.yaml\ninputs: {x: 0.5, b: true, risk: 0.1}\n")
    r = call_cli("check", str(tmp_path / "sc.yaml"))
    assert r.returncode == 2, r.stdout + r.stderr
    assert "Traceback" not in r.stderr and "too long: 500 terms" in r.stderr


# -- huge numbers -------------------------------------------------------------------------------


@pytest.mark.parametrize("window", ["1e400", "9" * 3000, "1" + "0" * 400])
def test_huge_windows_are_spec_errors(window):
    err = load_error(spec_with(f"held(x < 1, {window})"))
    assert "too large" in err.message or "too long" in err.message
    assert (err.line, err.column) == (8, 27)
    assert len(str(err)) < 400  # the 3,000 digits are not echoed


def test_huge_constant_window_is_a_spec_error():
    err = load_error(spec_with("held(x < 1, n)", "constants:\n  n: 1.0e+300\n"))
    assert "too long" in err.message and (err.line, err.column) == (10, 27)


def test_huge_number_literals_in_expressions():
    err = load_error(spec_with("x < 1e309"))
    assert "too large" in err.message and (err.line, err.column) == (8, COL0 + 4)
    err = load_error(spec_with("x < 1e200 * 1e200"))
    assert "not a finite number" in err.message


# (YAML 1.1, which PyYAML reads, has no 0o prefix: "0o777" is text; its octal is "0777")
BIG = {"hex": "0x" + "f" * 4000, "bin": "0b" + "1" * 15000, "dec": "9" * 5000, "octal": "0" + "7" * 5000}


@pytest.mark.parametrize("kind", sorted(BIG))
@pytest.mark.parametrize("where", ["constant", "classes", "hold_cycles", "version"])
def test_huge_integers_in_specs(kind, where):
    n = BIG[kind]
    text = {"constant": HEAD + f"constants:\n  c: {n}\n",
            "classes": HEAD + f"risk: {{classes: {n}}}\n",
            "hold_cycles": HEAD + f"risk:\n  release:\n    hold_cycles: {n}\n",
            "version": f"ethimon: {n}\nname: x\n"}[where]
    err = load_error(text)
    assert "too long" in err.message and len(str(err)) < 300, str(err)


@pytest.mark.parametrize("key", ["at", "for_cycles", "cycles"])
def test_huge_integers_in_scenarios(tmp_path, root, key):
    n = BIG["hex"]
    entry = {"at": f"{{at: {n}, set: {{risk: 0.2}}}}", "for_cycles": f"{{at: 1, for_cycles: {n}, set: {{risk: 0.2}}}}",
             "cycles": "{at: 1, set: {risk: 0.2}}"}[key]
    cycles = n if key == "cycles" else "10"
    sc = tmp_path / "sc.yaml"
    sc.write_text(f"ethimon: 1\nname: s\nspec: {root}/specs/governor.yaml\ncycles: {cycles}\n"
                  f"inputs: {{risk: 0.1}}\ntimeline:\n  - {entry}\n")
    with pytest.raises(ethimon.SpecError) as info:
        load_scenario(sc)
    assert "too long" in info.value.message and info.value.line is not None


def test_large_but_readable_integer_is_a_range_error_not_a_crash():
    err = load_error(HEAD + "risk: {classes: 0x" + "f" * 300 + "}\n")
    assert "risk.classes" in err.message and "less than or equal to 1000" in err.message


# -- constant folding: a spec that would fault on every cycle is refused -------------------------


@pytest.mark.parametrize("require,consts,fragment,at", [
    ("x / 0 < 1", "", "division by zero", "0"),
    ("x / (1 - 1) < 1", "", "division by zero", "1 -"),
    ("x / z < 1", "constants:\n  z: 0\n", "division by zero: 'z' is always 0.0", "z"),
    ("x / (z * 3) < 1", "constants:\n  z: {value: 0.0, unit: m}\n", "division by zero", "z"),
    ("x / -z < 1", "constants:\n  z: 0\n", "division by zero", "-z"),
    ("x / min(1, z) < 1", "constants:\n  z: 0\n", "division by zero", "min"),
    ("sqrt(-1) < x", "", "square root of a negative constant", "-1"),
    ("sqrt(0 - 2) < x", "", "square root of a negative constant", "0 -"),
    ("sqrt(n) < x", "constants:\n  n: -4\n", "'n' is always -4.0", "n)"),
    ("b and sqrt(abs(n) - 5) < x", "constants:\n  n: -4\n", "square root of a negative constant", "abs"),
    ("held(x / (2 - 2) < 1, 3)", "", "division by zero", "2 -"),
])
def test_constant_faults_are_spec_errors(require, consts, fragment, at):
    err = load_error(spec_with(require, consts))
    assert fragment in err.message, str(err)
    line = 8 + consts.count("\n")
    assert (err.line, err.column) == (line, COL0 + require.index(at)), str(err)


@pytest.mark.parametrize("require,consts", [
    ("x / 2 < 1", ""), ("sqrt(4) > x", ""), ("sqrt(abs(n)) > x", "constants:\n  n: -4\n"),
    ("x / (z + 1) < 1", "constants:\n  z: 0\n"), ("x / (x + 1) < 1", ""), ("sqrt(x) >= 0", ""),
    ("x * 0 <= 0", ""), ("max(-1, -2) < x", ""),
])
def test_constants_that_are_fine_still_load(require, consts):
    runs_clean(ethimon.load_spec_text(spec_with(require, consts), "t.yaml"))


# -- τ and the risk weights -------------------------------------------------------------------


@pytest.mark.parametrize("risk,fragment,key_col", [
    ("{threshold: 2}", "outside (0, 1]", 19),
    ("{threshold: 1.5}", "outside (0, 1]", 19),
    ("{threshold: -0.1}", "outside (0, 1]", 19),
    ("{threshold: 0}", "outside (0, 1]", 19),
    ("{alpha: 0, beta: 0, gamma: 0}", "all 0", 7),
    ("{alpha: -0.5, beta: 0.5, gamma: 0}", "negative", 15),
    ("{alpha: 0.6, beta: 0.2, gamma: -0.2}", "negative", 38),
    ("{alpha: 0.0, beta: 0.0, gamma: 0.0, threshold: 0.5}", "all 0", 7),
])
def test_risk_rule_that_cannot_work_is_a_spec_error(risk, fragment, key_col):
    err = load_error(HEAD + f"risk: {risk}\n")
    assert fragment in err.message and "allow" in err.hint, str(err)
    assert (err.line, err.column) == (3, key_col), str(err)


def test_risk_opt_out_needs_a_reason():
    s = ethimon.load_spec_text(HEAD + "risk:\n  threshold: 10\n  alpha: 0\n  beta: 0\n  gamma: 0\n"
                               "  allow: {threshold: 'R_e formation test', weights: 'R_e = 0 edge case'}\n")
    assert s.risk.threshold == 10 and set(s.risk.allow) == {"threshold", "weights"}
    err = load_error(HEAD + "risk:\n  threshold: 10\n  allow: {threshold: ''}\n")
    assert "risk.allow.threshold" in err.message
    err = load_error(HEAD + "risk:\n  threshold: 10\n  allow: {weights: 'only weights'}\n")
    assert "outside (0, 1]" in err.message
    err = load_error(HEAD + "risk:\n  allow: {tau: 'typo'}\n")
    assert "risk.allow" in err.message


@pytest.mark.parametrize("risk", ["{threshold: 1}", "{threshold: 0.001}", "{alpha: 0, beta: 1, gamma: 0}",
                                  "{alpha: 1, beta: 0, gamma: 0}"])
def test_edge_risk_configs_still_load(risk):
    ethimon.load_spec_text(HEAD + f"risk: {risk}\n")


# -- ASCII-only expressions ------------------------------------------------------------------


@pytest.mark.parametrize("require,bad,hint", [
    ("x < 1\u0665", "\u0665", "ASCII digits"),      # ARABIC-INDIC DIGIT FIVE: was read as 15
    ("x < \uff11", "\uff11", "ASCII digits"),       # FULLWIDTH DIGIT ONE
    ("x <\u00a01", "\u00a0", "plain space"),        # NO-BREAK SPACE
    ("x\u2009< 1", "\u2009", "plain space"),        # THIN SPACE
    ("x \u2264 1", "\u2264", "<="),                 # LESS-THAN OR EQUAL TO
    ("\u00e9 < 1", "\u00e9", "ASCII"),
])
def test_non_ascii_in_expressions_is_a_spec_error(require, bad, hint):
    err = load_error(spec_with(require))
    assert "unexpected character" in err.message and f"U+{ord(bad):04X}" in err.message
    assert (err.line, err.column) == (8, COL0 + require.index(bad)), str(err)
    assert hint in err.hint


# -- obligation id 'risk' --------------------------------------------------------------------------


def test_obligation_id_risk_is_reserved():
    err = load_error(HEAD + "obligations:\n  - {id: a, require: 'true'}\n  - {id: risk, require: 'true'}\n")
    assert "'risk' is reserved" in err.message and (err.line, err.column) == (5, 10)
    ethimon.load_spec_text(HEAD + "obligations:\n  - {id: risk_limit, require: 'true'}\n")


# -- strict types ----------------------------------------------------------------------------------


@pytest.mark.parametrize("text,fragment,at", [
    (HEAD + "risk: {threshold: true}\n", "risk.threshold", "true"),
    (HEAD + "risk: {threshold: !!bool maybe}\n", "cannot read boolean 'maybe'", "!!bool"),
    (HEAD + "risk: {threshold: '0.5'}\n", "risk.threshold", "'0.5'"),
    (HEAD + "risk: {classes: '2'}\n", "risk.classes", "'2'"),
    (HEAD + "risk: {classes: 2.0}\n", "risk.classes", "2.0"),
    (HEAD + "risk: {unsafe_index: true}\n", "risk.unsafe_index", "true"),
    (HEAD + "risk:\n  release: {hold_cycles: '10'}\n", "risk.release.hold_cycles", "'10'"),
    (HEAD + "signals:\n  a: {range: [0, true]}\n", "signals.a.range[1]", "true"),
    (HEAD + "signals:\n  a: {range: ['0', 1]}\n", "signals.a.range[0]", "'0'"),
    (HEAD + "constants:\n  c: true\n", "constants.c", "true"),
    (HEAD + "obligations:\n  - {id: a, require: 'true', within_cycles: '3'}\n", "within_cycles", "'3'"),
    (HEAD + "safe_pose: {joints_rad: [0, '1']}\n", "safe_pose.joints_rad[1]", "'1'"),
    ("ethimon: 1.0\nname: x\n", "unsupported format version 1.0", "1.0"),
    ("ethimon: true\nname: x\n", "unsupported format version True", "true"),
    ("ethimon: '1'\nname: x\n", "unsupported format version '1'", "'1'"),
])
def test_strict_types_in_specs(text, fragment, at):
    err = load_error(text)
    assert fragment in err.message, str(err)
    lines = text.splitlines()
    line = max(i for i, ln in enumerate(lines) if at in ln)
    assert (err.line, err.column) == (line + 1, lines[line].rindex(at) + 1), str(err)


def test_yaml_booleans_and_integers_still_read():
    s = ethimon.load_spec_text(HEAD + "risk: {threshold: 1, classes: 0x3, unsafe_index: -1}\n"
                               "signals:\n  a: {range: [0, 0b11]}\n")
    assert s.risk.threshold == 1.0 and s.risk.classes == 3 and s.signals["a"].range == (0.0, 3.0)


@pytest.mark.parametrize("line,fragment", [
    ("cycles: '1000'", "cycles"),
    ("cycles: 10.0", "cycles"),
    ("cycles: true", "cycles"),
    ("expect: {override: 1}", "expect.override"),
    ("expect: {override_by_cycle: '3'}", "expect.override_by_cycle"),
    ("timeline:\n  - {at: '2', set: {risk: 0.2}}", "timeline[0].at"),
    ("timeline:\n  - {at: 2, for_cycles: true, set: {risk: 0.2}}", "timeline[0].for_cycles"),
])
def test_strict_types_in_scenarios(tmp_path, root, line, fragment):
    sc = tmp_path / "sc.yaml"
    sc.write_text(f"ethimon: 1\nname: s\nspec: {root}/specs/governor.yaml\ninputs: {{risk: 0.1}}\n{line}\n")
    with pytest.raises(ethimon.SpecError) as info:
        load_scenario(sc)
    assert fragment in info.value.message and info.value.line is not None, str(info.value)


def test_scenario_version_must_be_the_integer_1(tmp_path, root):
    sc = tmp_path / "sc.yaml"
    sc.write_text(f"ethimon: 1.0\nname: s\nspec: {root}/specs/governor.yaml\ninputs: {{risk: 0.1}}\n")
    with pytest.raises(ethimon.SpecError, match="unsupported format version 1.0"):
        load_scenario(sc)


# -- read_yaml: regular files only, never blocking -----------------------------------------------


def _load_in_thread(path, loader=ethimon.load_spec, timeout=10.0):
    out: list = []
    t = threading.Thread(target=lambda: out.append(_catch(loader, path)), daemon=True)
    t.start()
    t.join(timeout)
    assert not t.is_alive(), f"loading {path} blocked"
    return out[0]


def _catch(loader, path):
    try:
        loader(path)
    except ethimon.SpecError as exc:
        return exc
    return None


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs here")
@pytest.mark.parametrize("loader", [ethimon.load_spec, load_scenario])
def test_fifo_is_refused_without_blocking(tmp_path, loader):
    fifo = tmp_path / "spec.yaml"
    os.mkfifo(fifo)  # nobody ever writes to it: opening it for reading without O_NONBLOCK blocks
    err = _load_in_thread(fifo, loader)
    assert err is not None and "named pipe" in err.message and "regular file" in err.message
    assert err.path == str(fifo) and err.hint


@pytest.mark.skipif(not os.path.exists("/dev/null"), reason="no /dev/null")
def test_devices_and_directories_are_refused(tmp_path):
    for path in ("/dev/null", "/dev/zero"):
        err = _load_in_thread(path)
        assert err is not None and "character device" in err.message
    err = _load_in_thread(tmp_path)
    assert err is not None and "directory" in err.message


@pytest.mark.slow
@pytest.mark.skipif(not os.path.exists("/dev/stdin") or not hasattr(os, "pipe"), reason="no /dev/stdin")
@pytest.mark.parametrize("how", ["api", "cli"])
def test_dev_stdin_pipe_does_not_hang(how):
    code = ("import ethimon\ntry:\n    ethimon.load_spec('/dev/stdin')\nexcept ethimon.SpecError as e:\n"
            "    print(e)\n")
    args = ["-c", code] if how == "api" else ["-m", "ethimon.cli", "check", "/dev/stdin"]
    r_fd, w_fd = os.pipe()  # stdin is a pipe that stays open and empty: reading it would block forever
    try:
        r = subprocess.run([sys.executable, *args], stdin=r_fd, capture_output=True, text=True, timeout=60)
    finally:
        os.close(r_fd)
        os.close(w_fd)
    assert "named pipe" in r.stdout + r.stderr, r.stdout + r.stderr
    assert "Traceback" not in r.stderr
    if how == "cli":
        assert r.returncode == 2


def test_regular_file_still_reads_and_size_limit_holds(tmp_path):
    p = tmp_path / "s.yaml"
    p.write_text(HEAD)
    assert ethimon.load_spec(p).name == "x"
    p.chmod(stat.S_IRUSR | stat.S_IWUSR)
    assert ethimon.load_spec(str(p)).name == "x"


# -- YAML indentation errors in plain words ---------------------------------------------------


@pytest.mark.parametrize("text,line,col,words", [
    (HEAD + "risk:\n    threshold: 0.5\n  alpha: 0.6\n", 5, 3, "does not line up with the mapping that starts at line 1"),
    ("ethimon: 1\nobligations:\n  - id: a\n    require: 'true'\n   - id: b\n", 5, 4,
     "does not line up with the list that starts at line 3"),
    (HEAD + "risk:\n  threshold: 0.5\n    alpha: 0.6\n", 5, 10, "unexpected ':'"),
    (HEAD + "description: 'open\n", 4, 1, "quote is not closed (opened at line 3, column 14)"),
])
def test_bad_indentation_gets_a_plain_hint(text, line, col, words):
    with pytest.raises(ethimon.SpecError) as info:
        ethimon.load_spec_text(text, "t.yaml")
    err = info.value
    assert words in err.message, str(err)
    assert (err.line, err.column) == (line, col)
    assert err.hint and ("indent" in err.hint or "quote" in err.hint)
