"""``ethimon.run``: units through an executor, one typed outcome per unit, in order (issue 33 item 5)."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

import ethimon
from ethimon import Outcome, Report, Serial, Unit, run
from ethimon.errors import DependencyNotInstalled


def _boom(x):
    raise RuntimeError(f"bad {x}")


def test_outcomes_in_unit_order_and_one_failure_stops_nothing():
    seen = []
    rep = run([Unit(len, ("abc",), "a"), Unit(_boom, (1,), "b"), Unit(str.upper, ("x",), "c")],
              Serial(), on_progress=lambda done, total, label: seen.append((done, total, label)))
    assert [o.label for o in rep.outcomes] == ["a", "b", "c"]
    assert rep.values() == [3, None, "X"] and rep.errors == 1
    assert rep.outcomes[1].error == "internal error: RuntimeError: bad 1"
    assert seen == [(0, 3, "a"), (1, 3, "b"), (2, 3, "c"), (3, 3, "")]


def test_to_json_and_lines():
    class Found:
        def lines(self):
            return ["x.yaml:1:1: bad (fix it)"]

        def as_dict(self):
            return {"found": 1}

    rep = Report((Outcome("a", Found()), Outcome("b", error="timed out"), Outcome("c", 7)), 1.5)
    assert rep.lines() == ["x.yaml:1:1: bad (fix it)", "b: timed out", "c: ok"]
    doc = rep.to_json()
    assert doc == {"outcomes": [{"label": "a", "ok": True, "value": {"found": 1}},
                                {"label": "b", "ok": False, "error": "timed out"},
                                {"label": "c", "ok": True, "value": 7}], "errors": 1, "seconds": 1.5}
    json.dumps(doc)


def test_a_missing_extra_stops_the_run():
    def needs():
        raise DependencyNotInstalled("pip install 'ethimon[sim]'")
    with pytest.raises(DependencyNotInstalled):
        run([Unit(needs, (), "a"), Unit(len, ("b",), "b")])


def test_default_executor_is_serial_and_empty_runs_are_fine():
    rep = run([])
    assert rep.outcomes == () and rep.errors == 0 and rep.to_json()["outcomes"] == []


def test_plain_is_what_a_json_report_holds():
    import enum

    class E(enum.IntEnum):
        A = 2
    from ethimon.fleet import plain
    assert plain({"a": (1, E.A), 3: None}) == {"a": [1, 2], 3: None}


@pytest.mark.slow
def test_ray_executor_is_served_lazily_without_importing_ray():
    code = ("import sys, ethimon\n"
            "r = ethimon.Ray(num_cpus=1, file_timeout=5)\n"
            "print(type(r).__module__, 'ray' in sys.modules)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["ethimon.fleet._executor", "False"]


def test_ray_executor_checks_its_arguments_at_once():
    from ethimon.errors import EthimonError
    with pytest.raises(EthimonError, match="not a Ray address"):
        ethimon.Ray("nowhere")
    with pytest.raises(EthimonError, match="above 0"):
        ethimon.Ray(file_timeout=0)
