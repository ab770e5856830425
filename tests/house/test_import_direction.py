"""Imports flow one way: every ``ethimon`` import, lazy ones inside functions included, goes down a floor.

The floors, lowest first (a package may import only what its row lists; its
own modules are always allowed):

    errors, _files, _robot  shared error types, safe file opening, robot facts (the Panda's home pose)
    _batch                  the one batch runner: run(units, executor), Serial, Outcome, Report, plain data
    language                YAML → validated Spec, the expression parser (stage 1)
    compiler                names, types, units → Plan → closures; the R_e formula
    _api                    load_spec = language + compiler in one call
    runtime                 Monitor.step → Decision (never loads files)
    audit, risk, sim,       beside each other above runtime: none imports another
      verify, testing       (testing: ReferenceMonitor, the test oracle)
    scenario                scenario files (may carry a sim block, may score text with risk)
    io                      the mapping, the hold, the value reduction, Channel, LiveMonitor, LiveNode (the seam;
                            LiveNode builds a loop and hands over an estimator: loop, risk)
    offline, replay         recorded data checked offline (replay may use offline and io)
    fleet                   many scenario files / bags on Ray (ray imported lazily)
    gym                     Gymnasium: the monitor as a shield, the sim cell as an env
    view                    the verdict channels (MCAP and the live Foxglove server): reads decisions as values
    loop                    GovernedLoop: runtime + audit + risk + verify (SMT gate on reload) + view
    _lint                   ethimon lint as a library: load, compile, release policies, a mapping
    ethimon (root)          the public names
    cli                     the command line, on top

A package not in the table fails the test: give it a row.
"""

from __future__ import annotations

import ast
from pathlib import Path

SRC = Path(__file__).resolve().parents[2] / "src" / "ethimon"

_LOW = {"errors", "_files", "_robot", "_batch"}
_LANGUAGE = _LOW | {"language"}
_COMPILED = _LANGUAGE | {"compiler"}
_BESIDE = _COMPILED | {"_api", "runtime"}

#: floor -> the floors it may import (besides itself)
ALLOWED: dict[str, set[str]] = {
    "errors": set(),
    "_files": {"errors"},
    "_robot": {"errors"},
    "_batch": {"errors"},
    "language": _LOW,
    "compiler": _LANGUAGE,
    "_api": _COMPILED,
    "runtime": _COMPILED,
    "audit": _BESIDE,
    "view": _BESIDE,
    "risk": _BESIDE,
    "sim": _BESIDE,
    "verify": _BESIDE,
    "testing": _BESIDE,
    "scenario": _BESIDE | {"sim", "risk"},
    "offline": _BESIDE | {"audit", "risk"},
    "io": _BESIDE | {"audit", "loop", "risk"},
    "replay": _BESIDE | {"audit", "risk", "offline", "io", "view"},
    "fleet": _BESIDE | {"audit", "risk", "sim", "scenario", "replay", "offline", "io"},
    "gym": _BESIDE | {"sim", "risk", "audit"},
    "loop": _BESIDE | {"audit", "risk", "verify", "view"},
    "_lint": _BESIDE | {"verify", "scenario", "replay", "io", "risk"},
    "ros2": _BESIDE | {"audit", "risk", "offline", "replay", "loop", "io", "view"},
    "zenoh": _BESIDE | {"risk", "loop", "io", "ros2"},
    "ethimon": _BESIDE | {"audit", "risk", "sim", "verify", "testing", "scenario", "offline", "replay", "loop", "io",
                          "fleet"},
    "cli": _BESIDE | {"audit", "risk", "sim", "verify", "testing", "scenario", "offline", "replay", "loop", "io",
                      "fleet", "ros2", "ethimon", "_lint", "view", "zenoh"},
}


def floor_of(dotted: str) -> str:
    """``ethimon.runtime._monitor`` → ``runtime``; ``ethimon`` → ``ethimon`` (the root package)."""
    parts = dotted.split(".")
    assert parts[0] == "ethimon", dotted
    return parts[1] if len(parts) > 1 else "ethimon"


def _module_name(path: Path, src: Path) -> tuple[str, list[str]]:
    rel = path.relative_to(src.parent).with_suffix("")
    parts = list(rel.parts)
    package = parts[:-1]
    if parts[-1] == "__init__":
        parts = parts[:-1]
        package = parts
    return ".".join(parts), package


def imports_of(path: Path, src: Path = SRC) -> list[tuple[int, str]]:
    """Every ``ethimon`` module or name this file imports, with its line (anywhere in the file)."""
    module, package = _module_name(path, src)
    out = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
        if isinstance(node, ast.Import):
            out += [(node.lineno, a.name) for a in node.names if a.name.split(".")[0] == "ethimon"]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[:len(package) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.split(".")[0] != "ethimon":
                continue
            if target == "ethimon":  # from ethimon import runtime / from . import _api: the names are modules
                out += [(node.lineno, f"ethimon.{a.name}") for a in node.names]
            else:
                out.append((node.lineno, target))
    return out


def violations(src: Path = SRC) -> list[str]:
    bad = []
    for path in sorted(src.rglob("*.py")):
        module, _ = _module_name(path, src)
        here = floor_of(module)
        allowed = ALLOWED.get(here)
        if allowed is None:
            bad.append(f"{path.relative_to(src.parent)}: package {here!r} has no row in ALLOWED")
            continue
        for line, target in imports_of(path, src):
            there = floor_of(target)
            if there not in ALLOWED and target.count(".") == 1 and not (src / f"{there}.py").exists() \
                    and not (src / there).is_dir():
                there = "ethimon"  # from ethimon import Monitor: a name of the root package
            if there != here and there not in allowed:
                bad.append(f"{path.relative_to(src.parent)}:{line}: {here} imports {target} ({there})")
    return bad


def test_every_package_has_a_floor():
    packages = {p.name for p in SRC.iterdir() if p.is_dir() and (p / "__init__.py").exists()}
    modules = {p.stem for p in SRC.glob("*.py") if p.stem != "__init__"}
    assert packages | modules <= set(ALLOWED), sorted((packages | modules) - set(ALLOWED))


def test_imports_only_go_down():
    bad = violations()
    assert not bad, "imports against the floors (see this file's docstring):\n" + "\n".join(bad)


def test_the_checker_sees_lazy_and_relative_imports(tmp_path):
    pkg = tmp_path / "ethimon"
    (pkg / "runtime").mkdir(parents=True)
    (pkg / "verify").mkdir()
    for p in (pkg / "__init__.py", pkg / "runtime" / "__init__.py", pkg / "verify" / "__init__.py"):
        p.write_text("")
    (pkg / "runtime" / "_m.py").write_text("def f():\n    from ..verify import verify_spec\n")
    (pkg / "verify" / "_c.py").write_text("from ..runtime import Monitor\nimport ethimon.compiler\n")
    bad = violations(pkg)
    assert len(bad) == 1 and "runtime imports ethimon.verify" in bad[0] and "_m.py:2" in bad[0], bad
