"""Issue 31 item 7: replay reports a person reads cannot mislead.

Each test failed on the code before the fix: an override that ran to the end of the bag was
reported as "held ... then released" and named the last rule that fired, not the latch that held;
only five runs printed with no "more" line; task texts and their R_e showed only in ``--json``; a
text-only bag could not be checked against the shipped governor; ``replay_bag`` took no spec path;
a 30 Hz recording's jitter was an ERROR whose first suggestion was a rate of 100,000 Hz."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("rosbags")

import ethimon  # noqa: E402
from ethimon.replay import BagError, load_mapping_text, replay_bag  # noqa: E402
from tests._cli import ROOT, call_cli  # noqa: E402
from tests.replay.test_replay import MAPPING, SPEC, T0, _score, make_messages, write_bag  # noqa: E402

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def cell(tmp_path_factory):
    d = tmp_path_factory.mktemp("cell")
    (d / "spec.yaml").write_text(SPEC, encoding="utf-8")
    (d / "map.yaml").write_text(MAPPING, encoding="utf-8")
    write_bag(d / "bag", "mcap", make_messages())
    return d


def test_an_override_to_the_end_of_the_bag_is_never_called_released(cell):
    res = replay_bag(cell / "bag", ethimon.load_spec(cell / "spec.yaml"), cell / "map.yaml", score=_score)
    last = res.latches[-1]
    assert last["until_end"] and last["ended"] == "end_of_bag"
    # joint_speed (stop_1, release manual) fired at 1.06 s and its latch holds the arm to the end
    assert "joint_speed" in last["held_by"]
    assert "acknowledgement" in last["released_by"]["joint_speed"]
    assert sum(r["cycles"] for r in res.latches) == res.override_cycles  # every override cycle is in a run


def test_the_text_names_the_holding_latch_the_totals_and_each_task(cell, monkeypatch):
    monkeypatch.setattr("ethimon.replay._scoring._Lazy.score", lambda self, text, k: (_score(text), None))
    r = call_cli("replay", "bag", "--spec", "spec.yaml", "--map", "map.yaml", cwd=cell)
    out = r.stdout + r.stderr
    assert "then released" not in out
    assert "override on 149 of 201 cycles" in out
    assert "held at its end by the latches of joint_speed" in out and "lasted to the end of the bag" in out
    assert "'Throw the box at the person.': R_e 0.556: stopped: R_e ≥ τ = 0.5" in out
    assert "'Stack the boxes.': R_e 0.144: executes" in out


def test_many_runs_say_how_many_more_and_show_the_last(cell, tmp_path):
    from ethimon.cli._replay_cmds import SHOWN_RUNS, _run_lines
    runs = [{"from_cycle": 10 * i, "cycles": 2, "seconds": 0.04, "t_s": 0.2 * i, "until_end": False,
             "ended": "released", "cause": "separation", "held_by": ["separation"],
             "released_by": {"separation": "by itself after 10 cycles of holding"}} for i in range(30)]
    runs[-1].update(until_end=True, ended="end_of_bag")
    lines = _run_lines("b", {"latches": runs, "override_runs": 30, "override_cycles": 60, "cycles": 400})
    assert lines[0] == "b: override on 60 of 400 cycles (15.0 %), in 30 runs"
    assert len(lines) == 1 + SHOWN_RUNS + 2
    assert lines[-2] == "b: ... 19 more override runs (--json lists up to 30)"
    assert "lasted to the end of the bag" in lines[-1]


def test_both_engines_name_the_same_holding_latches(cell):
    spec = ethimon.load_spec(cell / "spec.yaml")
    a = replay_bag(cell / "bag", spec, cell / "map.yaml", score=_score, engine="offline", keep_trace=True)
    b = replay_bag(cell / "bag", spec, cell / "map.yaml", score=_score, engine="step", keep_trace=True)
    assert a.latches == b.latches
    for k in range(a.cycles):
        assert a.trace.holding_at(k) == b.trace.holding_at(k), k


def test_replay_bag_takes_a_spec_path(cell):
    res = replay_bag(cell / "bag", cell / "spec.yaml", cell / "map.yaml", score=_score)
    assert res.cycles == 201 and not res.passed


def test_a_text_only_bag_checks_against_the_shipped_governor(tmp_path):
    msgs = [(T0, "/task", "str", "Stack the boxes."), (T0 + 2 * 10**9, "/task", "str", "Throw the box at the person."),
            (T0 + 4 * 10**9, "/task", "str", "Stack the boxes.")]
    write_bag(tmp_path / "bag", "mcap", msgs)
    m = load_mapping_text("ethimon: 1\nrate_hz: 10\nmax_age_s: null\ntask: {topic: /task}\n")
    p = {"Stack the boxes.": (0.95, 0.05), "Throw the box at the person.": (0.05, 0.95)}
    res = replay_bag(tmp_path / "bag", ROOT / "specs" / "governor.yaml", m, score=p.__getitem__)
    assert [t["outcome"].split(":")[0] for t in res.tasks] == ["executes (below the risk tiers)", "stopped"]
    assert res.check("risk").first_t_s == pytest.approx(2.0)


def test_a_mapping_with_neither_signals_nor_task_is_refused():
    with pytest.raises(Exception, match="map at least one signal, or a task topic"):
        load_mapping_text("ethimon: 1\nrate_hz: 10\nmax_age_s: null\n")


def test_a_30_hz_recordings_jitter_says_plainly_that_samples_latest_is_the_fix(tmp_path):
    rng = np.random.default_rng(3)
    msgs = [(int(T0 + (i / 30 + rng.uniform(-0.004, 0.004)) * 1e9), "/human/distance_cm", "f64", 300.0)
            for i in range(300)]
    msgs += [(T0, "/task", "str", "Stack the boxes.")]
    msgs.sort(key=lambda m: m[0])
    write_bag(tmp_path / "bag", "mcap", msgs)
    (tmp_path / "s.yaml").write_text(
        "ethimon: 1\nname: j\nsignals:\n  human_distance: {unit: m, range: [0, 10]}\nrisk: {threshold: 0.5}\n"
        "obligations:\n  - {id: sep, require: human_distance >= 0.5, response: stop_2}\n", encoding="utf-8")
    m = load_mapping_text("ethimon: 1\nrate_hz: 30\nmax_age_s: 0.2\nsignals:\n  human_distance: "
                          "{topic: /human/distance_cm, field: data, scale: 0.01}\ntask: {topic: /task}\n")
    with pytest.raises(BagError) as exc:
        replay_bag(tmp_path / "bag", tmp_path / "s.yaml", m, score=_score)
    text = str(exc.value) + " " + str(getattr(exc.value, "hint", ""))
    assert "ordinary jitter" in text
    assert getattr(exc.value, "hint", "").startswith("write 'samples: latest'")
    assert "100000" not in text
