"""The seams between the live and recorded-data packages (issue 33: "`ros2/` and `replay/` import only public
names of each other and of `io/`"; "a new transport touches the files named and nothing silent").

A module in ``ros2/``, ``replay/`` or ``zenoh/`` that imports from ``io``, or from another of these packages,
imports the package itself (never one of its private modules) and only names in that package's ``__all__``:
what a transport or replay needs of the seam is public, reviewed in ``tests/house/test_exports.py``.
"""

from __future__ import annotations

import ast
from pathlib import Path

SRC = Path(__file__).resolve().parents[2] / "src" / "ethimon"

#: the packages on the seam: what they import of each other must be public
SEAM = ("io", "ros2", "replay", "zenoh")
#: the packages whose imports are checked
CHECKED = ("ros2", "replay", "zenoh")


def public_names(pkg: str, src: Path = SRC) -> set[str]:
    """A package's ``__all__``, read from its ``__init__.py`` without importing it."""
    tree = ast.parse((src / pkg / "__init__.py").read_text(encoding="utf-8"))
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(isinstance(t, ast.Name) and t.id == "__all__" for t in node.targets):
            return set(ast.literal_eval(node.value))
    return set()


def seam_violations(src: Path = SRC) -> list[str]:
    bad = []
    public = {p: public_names(p, src) for p in SEAM}
    for here in CHECKED:
        for path in sorted((src / here).rglob("*.py")):
            rel = path.relative_to(src.parent)
            package = list(path.relative_to(src.parent).with_suffix("").parts[:-1])
            for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
                if isinstance(node, ast.Import):
                    for a in node.names:
                        parts = a.name.split(".")
                        if parts[0] == "ethimon" and len(parts) > 2 and parts[1] in SEAM and parts[1] != here:
                            bad.append(f"{rel}:{node.lineno}: import {a.name} (a module inside {parts[1]})")
                    continue
                if not isinstance(node, ast.ImportFrom):
                    continue
                if node.level:
                    base = package[:len(package) - (node.level - 1)]
                    target = base + (node.module.split(".") if node.module else [])
                else:
                    target = (node.module or "").split(".")
                if target[0] != "ethimon" or len(target) < 2 or target[1] not in SEAM or target[1] == here:
                    continue
                there = target[1]
                if len(target) > 2:
                    bad.append(f"{rel}:{node.lineno}: from {'.'.join(target)} import ... (a module inside "
                               f"{there}: import from ethimon.{there})")
                    continue
                for a in node.names:
                    if a.name not in public[there]:
                        bad.append(f"{rel}:{node.lineno}: {a.name} is not in ethimon.{there}.__all__")
    return bad


def test_the_seam_packages_import_only_each_others_public_names():
    bad = seam_violations()
    assert bad == [], ("ros2/, replay/ and zenoh/ import only public names of io and of each other (export the "
                       "name, reviewed in tests/house/test_exports.py, or move the code into io):\n" + "\n".join(bad))


def test_the_seam_check_sees_private_modules_private_names_and_lazy_imports(tmp_path):
    pkg = tmp_path / "ethimon"
    for p in ("io", "ros2", "replay", "zenoh"):
        (pkg / p).mkdir(parents=True)
        (pkg / p / "__init__.py").write_text('__all__ = ["Public"]\nPublic = 1\n')
    (pkg / "ros2" / "_a.py").write_text("from ..io import Public\nfrom ..io._live import x\n"
                                        "def f():\n    from ethimon.replay import hidden\n")
    (pkg / "zenoh" / "_b.py").write_text("import ethimon.ros2._node\nfrom ..ros2 import Public\nfrom ._c import y\n")
    bad = seam_violations(pkg)
    assert len(bad) == 3, bad
    assert "ros2/_a.py:2" in bad[0] and "ethimon.io._live" in bad[0]
    assert "ros2/_a.py:4" in bad[1] and "hidden" in bad[1]
    assert "zenoh/_b.py:1" in bad[2]
