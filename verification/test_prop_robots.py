"""Robot descriptions are data (issue 34 item 4): any edit of a shipped description either reads
as a robot whose every number is finite and cited, or is refused with a SpecError; never another
exception, never a robot with a limit out of order."""

from __future__ import annotations

import copy
import math

import yaml
from hypothesis import given
from hypothesis import strategies as st

from ethimon._robot import ROBOTS_DIR, robot_from_data
from ethimon.errors import SpecError

SHIPPED = {n: yaml.safe_load((ROBOTS_DIR / f"{n}.yaml").read_text(encoding="utf-8")) for n in ("panda", "ur5e")}
VALUES = st.one_of(st.none(), st.booleans(), st.integers(-10, 10), st.floats(allow_nan=True, allow_infinity=True),
                   st.text(max_size=5), st.lists(st.floats(-7, 7), max_size=8), st.dictionaries(st.text(max_size=3),
                                                                                                st.integers(), max_size=2))


def _paths(d, prefix=()):
    if isinstance(d, dict):
        for k, v in d.items():
            yield prefix + (k,)
            yield from _paths(v, prefix + (k,))
    elif isinstance(d, list):
        for i, v in enumerate(d):
            yield prefix + (i,)
            yield from _paths(v, prefix + (i,))


@given(st.sampled_from(sorted(SHIPPED)), st.data(), VALUES, st.booleans())
def test_any_edit_reads_as_a_cited_robot_or_a_spec_error(name, data, value, delete) -> None:
    doc = copy.deepcopy(SHIPPED[name])
    paths = list(_paths(doc))
    path = data.draw(st.sampled_from(paths))
    parent = doc
    for k in path[:-1]:
        parent = parent[k]
    if delete and isinstance(parent, dict):
        del parent[path[-1]]
    else:
        parent[path[-1]] = value
    try:
        robot = robot_from_data(doc, "<edited>")
    except SpecError:
        return
    assert all(lo < hi for lo, hi in zip(robot.q_min, robot.q_max))
    for fact in robot.facts.values():
        assert fact.source.strip() and all(math.isfinite(v) for v in fact.values)
    assert len(robot.q_min) == len(robot.dq_max) == len(robot.holding_n_m) == robot.n_joints
