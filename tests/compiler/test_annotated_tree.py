"""The checker returns a frozen annotated tree (issue 33 item 2): types, units, windows and the
folded constants on the nodes, set once; no table keyed by ``id(node)`` in the stages that read it."""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path

import pytest

import ethimon
from ethimon.compiler import plan_of
from ethimon.language._expr import Call, walk

ROOT = Path(__file__).resolve().parents[2]
SPEC = """\
ethimon: 1
name: annotated
rate_hz: 100
signals:
  d: {unit: m, range: [0, 10]}
  v: {unit: m/s, range: [0, 5]}
  seen: {type: bool}
constants:
  t_grace: {value: 0.05, unit: s}
  k: 2
obligations:
  - id: near
    when: "d < 0.5 * k"
    require: "held(v < 1, 3) and once(seen, t_grace) and since(seen, d > 1) and prev(v) <= sqrt(v * v) + 1"
"""


def _nodes(plan):
    return [n for ob in plan.obligations for root in (ob.when, ob.require) if root is not None for n in walk(root)]


def test_every_node_of_a_plan_is_annotated_once():
    plan = plan_of(ethimon.load_spec_text(SPEC))
    nodes = _nodes(plan)
    assert nodes and all(n.ann is not None for n in nodes)
    serials = [n.ann.serial for n in nodes]
    assert len(set(serials)) == len(serials)  # one number per node: z3 names its terms by it
    by_func = {n.func: n for n in nodes if isinstance(n, Call)}
    assert by_func["held"].ann.window == 3 and by_func["prev"].ann.window == 1
    assert by_func["since"].ann.window is None  # no bound written: unbounded
    assert by_func["once"].ann.window == 5 and by_func["once"].ann.seconds == 0.05  # 0.05 s at 100 Hz
    assert [n.ann.slot for n in plan.temporal] == list(range(len(plan.temporal)))
    when = plan.obligations[0].when
    assert when.ann.ty.kind == "bool" and when.right.ann.value == 1.0  # 0.5 * k folded
    assert str(by_func["sqrt"].ann.ty.show()) == "a number [m/s]"
    assert plan.type_of(when) is when.ann.ty and plan.window_of(by_func["held"]) == 3


def test_an_annotation_is_frozen_and_set_once():
    plan = plan_of(ethimon.load_spec_text(SPEC))
    node = plan.obligations[0].require
    with pytest.raises(ValueError, match="annotated already"):
        node.annotate(node.ann)
    with pytest.raises(dataclasses.FrozenInstanceError):
        node.ann = None  # type: ignore[misc]
    with pytest.raises(dataclasses.FrozenInstanceError):
        node.ann.window = 7  # type: ignore[misc]


_ID_CALL = re.compile(r"(?<![\w.`])id\(")


def test_no_table_keyed_by_id_of_a_node():
    """The stages that read the tree key nodes by the node (identity: ``eq=False``), never ``id()``."""
    found = []
    for pkg in ("language", "compiler", "verify", "runtime", "offline", "testing"):
        for path in sorted((ROOT / "src" / "ethimon" / pkg).glob("*.py")):
            for i, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                if _ID_CALL.search(line.split("#")[0]):
                    found.append(f"{path.relative_to(ROOT)}:{i}: {line.strip()}")
    assert not found, "\n".join(found)
