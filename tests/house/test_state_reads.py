"""Classes composed by state, not cut by file (issue 33, item 1): a module may read only a few
``self.<name>`` attributes that only *another* module of its package assigns.

The mixin layout this replaces spread one ``self`` over several files: ``runtime/_monitor.py`` read
46 ``self.*`` names, 39 of them set in ``runtime/_construction.py``, so no file could be read alone.
With composition each object owns its state (``Latches``, ``Tiers``, ``RiskInput`` for the monitor)
and a module reads what it assigns itself, or asks an object it holds.

For every package in :data:`BOUNDS` each module is parsed (``ast``, nothing imported): its *reads* are
the names of ``self.<name>`` loads, its *writes* the targets of ``self.<name> = ...`` (plain, augmented,
annotated or unpacked). A *cross read* is a name the module reads, does not assign, and another module
of the package assigns. Names a module defines itself (a method, a property, or a field declared in a
class body, ``name: T``, as pydantic models and dataclasses do) never count. The bound is per package; a
package not listed is not checked yet. ``sim`` is bounded since ``ArmSim`` holds a ``World`` and composes
its parts (issue 33: ``_kinematics.py`` read 14, ``_actuation.py`` 12, ``_sensing.py`` 11 before).
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[2] / "src" / "ethimon"

#: package -> the most cross reads one of its modules may make (small: composition, not shared ``self``)
BOUNDS: dict[str, int] = {
    "runtime": 3,
    "loop": 4,
    "verify": 4,
    "sim": 3,
}


def _self_attrs(tree: ast.AST) -> tuple[set[str], set[str], set[str]]:
    """``(reads, writes, defined)`` of one module: ``self.<name>`` loads, ``self.<name>`` stores, and the
    names of the functions it defines (methods and properties) and of the fields its class bodies declare
    (``name: T``, a pydantic model's or a dataclass's own state)."""
    reads: set[str] = set()
    writes: set[str] = set()
    defined: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ClassDef):
            defined.update(st.target.id for st in node.body
                           if isinstance(st, ast.AnnAssign) and isinstance(st.target, ast.Name))
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            defined.add(node.name)
        elif isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == "self":
            (reads if isinstance(node.ctx, ast.Load) else writes).add(node.attr)
        elif isinstance(node, ast.AugAssign):  # ``self.n += 1`` reads and writes n: its own state
            t = node.target
            if isinstance(t, ast.Attribute) and isinstance(t.value, ast.Name) and t.value.id == "self":
                writes.add(t.attr)
    return reads, writes, defined


def cross_reads(package: Path) -> dict[str, list[str]]:
    """For each module of ``package`` (a directory): the ``self`` names it reads that only another
    module of the package assigns, sorted; modules with none are left out."""
    facts = {p.name: _self_attrs(ast.parse(p.read_text(encoding="utf-8"), str(p)))
             for p in sorted(package.glob("*.py"))}
    out: dict[str, list[str]] = {}
    for name, (reads, writes, defined) in facts.items():
        elsewhere = set().union(*(w for other, (_, w, _) in facts.items() if other != name))
        cross = sorted((reads - writes - defined) & elsewhere)
        if cross:
            out[name] = cross
    return out


@pytest.mark.parametrize("package", sorted(BOUNDS))
def test_modules_read_little_state_that_another_module_assigns(package):
    bound = BOUNDS[package]
    over = {m: names for m, names in cross_reads(SRC / package).items() if len(names) > bound}
    assert not over, (
        f"{package}/: a module reads more than {bound} self.<name> attributes that only another module "
        f"assigns (a class cut by file, not by state; give the state an owner and hold it): "
        + "; ".join(f"{m} reads {len(n)}: {', '.join(n)}" for m, n in over.items()))


def test_the_check_sees_a_mixin_and_passes_composition(tmp_path):
    mixin = tmp_path / "mixin"
    mixin.mkdir()
    (mixin / "_build.py").write_text("class B:\n    def _build(self):\n        self.a = 1\n        self.b = 2\n"
                                     "        self.c: int = 3\n        self.d, self.e = 4, 5\n")
    (mixin / "_use.py").write_text("class U:\n    def go(self):\n        self.n += 1\n"
                                   "        return self.a + self.b + self.c + self.d + self.e + self.n + self.go()\n")
    assert cross_reads(mixin) == {"_use.py": ["a", "b", "c", "d", "e"]}
    composed = tmp_path / "composed"
    composed.mkdir()
    (composed / "_state.py").write_text("class S:\n    def __init__(self):\n        self.a = 1\n"
                                        "    def bump(self):\n        self.a += 1\n        return self.a\n")
    (composed / "_user.py").write_text("class U:\n    def __init__(self, s):\n        self.s = s\n"
                                       "    def go(self):\n        return self.s.bump()\n")
    assert cross_reads(composed) == {}
    # a model reading its own declared fields reads its own state, whoever else names a field alike
    fields = tmp_path / "fields"
    fields.mkdir()
    (fields / "_model.py").write_text("class M:\n    name: str\n    task: list\n"
                                      "    def check(self):\n        return self.name, self.task\n")
    (fields / "_other.py").write_text("class C:\n    def __init__(self):\n        self.name = 'c'\n"
                                      "        self.task = []\n")
    assert cross_reads(fields) == {}
