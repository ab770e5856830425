"""docs/embedding.md: each section's Python snippet runs as written and prints what the page shows under
"prints" -- "What holds the arm" (``holding()``, ``pending_s``; issue 31 item 3) and "Restarts in a real cell"
(issue 32 item 4)."""

from __future__ import annotations

import contextlib
import io
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _run_section(start: str, end: str) -> str:
    """Run the one ``python`` block of the section from heading ``start`` to ``end``; assert it prints the
    page's one "prints" block, and return that block."""
    text = (ROOT / "docs" / "embedding.md").read_text(encoding="utf-8")
    i = text.index(start)
    sec = text[i:text.index(end, i)]
    code = re.findall(r"```python\n(.*?)```\n", sec, re.S)
    shown = re.findall(r"\nprints\n\n```\n(.*?)```\n", sec, re.S)
    assert len(code) == 1 and len(shown) == 1
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code[0], "docs/embedding.md", "exec"), {"__name__": "docs_snippet"})  # our own docs
    assert out.getvalue() == shown[0]
    return shown[0]


@pytest.mark.slow  # 0.6 s: compiles a spec, starts a loop
def test_the_holding_snippet_prints_what_the_page_shows():
    shown = _run_section("### What holds the arm: `holding()` and the pending hold",
                         "The learned risk runs off the hot path")
    assert "('pending',)" in shown and "estimate" in shown


@pytest.mark.slow  # compiles a spec, builds a loop
def test_the_restart_snippet_prints_what_the_page_shows():
    shown = _run_section("### Restarts in a real cell", "### What holds the arm")
    assert "the stop has not completed" in shown and "waiting for the start" in shown
