"""The docstring examples of every ``src/ethimon`` module that imports no heavy extra at import time run
as doctests (issue 13: "doctests are never run").

Heavy: torch, transformers, pybullet, ray, gymnasium, z3, rosbags. A module is left out when it, its
package ``__init__`` or an ethimon module it imports at module level imports one of them at module level
(found from the source, so listing the modules imports nothing). Examples that need a heavy extra or a
model are marked ``# doctest: +SKIP`` where they are written.
"""

from __future__ import annotations

import ast
import doctest
import importlib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "src" / "ethimon"
HEAVY = {"torch", "transformers", "pybullet", "pybullet_data", "ray", "gymnasium", "z3", "rosbags", "onnxruntime", "onnx"}


def _name(path: Path) -> str:
    parts = list(path.relative_to(SRC.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _is_package(name: str) -> bool:
    return (SRC.parent / name.replace(".", "/") / "__init__.py").exists()


def _module_level_imports(name: str) -> set[str]:
    path = SRC.parent / (name.replace(".", "/") + ("/__init__.py" if _is_package(name) else ".py"))
    package = name if _is_package(name) else name.rpartition(".")[0]
    out: set[str] = set()

    def visit(stmts):
        for node in stmts:
            if isinstance(node, ast.Import):
                out.update(a.name for a in node.names)
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    base = package.split(".")[:len(package.split(".")) - (node.level - 1)]
                    mod = ".".join(base + ([node.module] if node.module else []))
                else:
                    mod = node.module or ""
                out.add(mod)
                out.update(f"{mod}.{a.name}" for a in node.names)  # from pkg import submodule
            elif isinstance(node, ast.If):
                if "TYPE_CHECKING" not in ast.unparse(node.test):
                    visit(node.body)
                    visit(node.orelse)
            elif isinstance(node, ast.Try):
                visit(node.body)
    visit(ast.parse(path.read_text(encoding="utf-8")).body)
    return out


def _resolve(imp: str) -> str | None:
    """The ethimon module an imported name lives in (``ethimon.language.Spec`` -> ``ethimon.language``)."""
    target = imp
    while target and not ((SRC.parent / (target.replace(".", "/") + ".py")).exists() or _is_package(target)):
        target = target.rpartition(".")[0]
    return target or None


def _heavy_modules(names: list[str]) -> set[str]:
    """Modules whose import imports a heavy extra: directly, through the packages above them, or through
    an ethimon module they import at module level (a fixed point over the import graph)."""
    deps: dict[str, set[str]] = {}
    heavy: set[str] = set()
    for name in names:
        d = set()
        parent = name.rpartition(".")[0]
        if parent:
            d.add(parent)
        for imp in _module_level_imports(name):
            if imp.split(".")[0] in HEAVY:
                heavy.add(name)
            elif imp.split(".")[0] == "ethimon":
                target = _resolve(imp)
                if target and target != name:
                    d.add(target)
        deps[name] = d
    changed = True
    while changed:
        changed = False
        for name, d in deps.items():
            if name not in heavy and d & heavy:
                heavy.add(name)
                changed = True
    return heavy


_ALL = sorted(_name(p) for p in SRC.rglob("*.py") if p.name != "__main__.py")  # importing __main__ runs it
LIGHT = sorted(set(_ALL) - _heavy_modules(_ALL))


def test_the_heavy_modules_are_left_out_and_most_are_checked():
    assert "ethimon.risk._backend" not in LIGHT and "ethimon.gym" not in LIGHT
    assert {"ethimon.errors", "ethimon.language._expr", "ethimon.runtime._monitor", "ethimon.risk._estimator"} <= set(LIGHT)


@pytest.mark.parametrize("modname", LIGHT)
def test_doctests(modname, monkeypatch):
    monkeypatch.chdir(ROOT)  # examples name repository files such as specs/cobot_cell.yaml
    mod = importlib.import_module(modname)
    tests = [t for t in doctest.DocTestFinder(exclude_empty=True).find(mod, modname) if t.examples]
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    for t in tests:
        runner.run(t)
    assert runner.failures == 0, f"{modname}: {runner.failures} doctest failure(s) (printed above)"
