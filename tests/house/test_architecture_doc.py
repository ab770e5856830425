"""ARCHITECTURE.md says what the code is: its table of floors is ``test_import_direction.ALLOWED``'s, every
module it names as ``package/_module.py`` exists, and every package's private modules (its rooms) are
named in it at least once (issue 24, item 4); the room list is generated from the rooms' docstrings
(``tests/house/rooms.py``, issue 33 item 5)."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "src" / "ethimon"
DOC = ROOT / "ARCHITECTURE.md"

from tests.house.test_import_direction import ALLOWED

#: ``runtime/_monitor.py``, ``cli/__init__.py``: a path inside a package, as the file writes it
_MODULE = re.compile(r"(?<![\w/.])([a-z0-9_]+/_[a-z0-9_]+\.py)\b")


def floors_of(text: str) -> set[str]:
    """The floors in the first column of the table under '## Floors' (each written as `name`)."""
    section = text.split("## Floors", 1)[1].split("\n## ", 1)[0]
    out: set[str] = set()
    for line in section.splitlines():
        if line.startswith("| `"):
            out |= set(re.findall(r"`([^`]+)`", line.split("|")[1]))
    return out


def modules_named(text: str) -> set[str]:
    return set(_MODULE.findall(text))


def rooms(src: Path = SRC) -> set[str]:
    """Every private module of every package: ``package/_module.py`` (``__init__``/``__main__`` aside)."""
    return {p.relative_to(src).as_posix() for p in src.glob("*/_*.py") if not p.name.startswith("__")}


def test_the_floors_table_is_the_import_rule():
    assert floors_of(DOC.read_text(encoding="utf-8")) == set(ALLOWED)


def test_every_module_the_architecture_names_exists():
    missing = sorted(m for m in modules_named(DOC.read_text(encoding="utf-8")) if not (SRC / m).is_file())
    assert not missing, f"ARCHITECTURE.md names modules that do not exist: {missing}"


def test_the_room_list_is_generated_from_the_docstrings():
    from tests.house import rooms
    got = rooms.current(DOC.read_text(encoding="utf-8"))
    assert got is not None, "ARCHITECTURE.md lost the markers of its generated room list"
    assert got == rooms.block(), "the room list differs from the modules' docstrings: python -m tests.house.rooms --write"


def test_the_room_summary_is_the_first_sentence_in_markdown():
    from tests.house.rooms import summary
    assert summary("``ethimon check``: run :class:`~ethimon.scenario.Scenario` files.\n\nMore.") == \
        "`ethimon check`: run `Scenario` files"
    assert summary("One job, across\n  two lines. And more") == "One job, across two lines"


def test_every_room_is_named_in_the_architecture():
    unnamed = sorted(rooms() - modules_named(DOC.read_text(encoding="utf-8")))
    assert not unnamed, f"list these rooms in ARCHITECTURE.md ('## Rooms', one line each): {unnamed}"


def test_the_checks_see_what_they_claim(tmp_path):
    text = "| `errors`, `_files` | x | y |\n"
    assert floors_of("## Floors\n\n" + text + "\n## Next\n| `cli` | z |") == {"errors", "_files"}
    assert modules_named("see `runtime/_monitor.py`, src/ethimon/sim/_arm.py and a.b/_c.py") == {"runtime/_monitor.py"}
    (tmp_path / "pkg").mkdir()
    for name in ("__init__.py", "_room.py", "public.py"):
        (tmp_path / "pkg" / name).write_text("")
    assert rooms(tmp_path) == {"pkg/_room.py"}
