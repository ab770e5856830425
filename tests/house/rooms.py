"""ARCHITECTURE.md's room list, made from the rooms' own docstrings (issue 33 item 5: not a hand copy).

Each private module's docstring opens with the sentence that says its one job; the list under
'## Rooms' is that sentence for every room, between the two markers, in path order::

    python -m tests.house.rooms          # print the list
    python -m tests.house.rooms --write  # put it into ARCHITECTURE.md

``tests/house/test_architecture_doc.py`` fails when the file's list is not the generated one.
"""

from __future__ import annotations

import ast
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "src" / "ethimon"
DOC = ROOT / "ARCHITECTURE.md"
BEGIN = "<!-- rooms: generated from the modules' docstrings by `python -m tests.house.rooms --write` -->"
END = "<!-- /rooms -->"

_ROLE = re.compile(r":(?:class|func|meth|data|attr|mod|exc):`~?([^`]+)`")


def summary(docstring: str) -> str:
    """The first sentence of a docstring's first paragraph, in Markdown (``x`` → `x`, roles → their
    last name), without its full stop."""
    para = " ".join(docstring.strip().split("\n\n", 1)[0].split())
    para = _ROLE.sub(lambda m: f"`{m.group(1).rsplit('.', 1)[-1]}`", para).replace("``", "`")
    m = re.search(r"\.(\s|$)", para)
    first = para[:m.start()] if m else para
    return first.rstrip(".: ")


def room_lines(src: Path = SRC) -> list[str]:
    """``- `package/_module.py`: summary`` for every private module of every package, sorted."""
    out = []
    for p in sorted(src.glob("*/_*.py")):
        if p.name.startswith("__"):
            continue
        doc = ast.get_docstring(ast.parse(p.read_text(encoding="utf-8"))) or ""
        out.append(f"- `{p.relative_to(src).as_posix()}`: {summary(doc) or '(no docstring)'}")
    return out


def block(src: Path = SRC) -> str:
    return "\n".join([BEGIN, *room_lines(src), END])


def current(text: str) -> str | None:
    """The generated block as it stands in ``text`` (``None``: no markers)."""
    if BEGIN not in text or END not in text:
        return None
    a = text.index(BEGIN)
    return text[a:text.index(END, a) + len(END)]


def write(doc: Path = DOC) -> bool:
    """Put the generated block into ``doc``; True when it changed."""
    text = doc.read_text(encoding="utf-8")
    old = current(text)
    if old is None:
        raise SystemExit(f"{doc}: no markers {BEGIN!r} ... {END!r}")
    new = text.replace(old, block())
    if new != text:
        doc.write_text(new, encoding="utf-8")
    return new != text


if __name__ == "__main__":  # pragma: no cover - a tool
    if "--write" in sys.argv[1:]:
        print("ARCHITECTURE.md updated" if write() else "ARCHITECTURE.md was up to date")
    else:
        print(block())
