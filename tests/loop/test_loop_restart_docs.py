"""docs/embedding.md "Restarts in a real cell": its snippet runs as written and prints what the page shows
(issue 32 item 4)."""

from __future__ import annotations

import contextlib
import io
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.slow  # compiles a spec, builds a loop
def test_the_restart_snippet_prints_what_the_page_shows():
    text = (ROOT / "docs" / "embedding.md").read_text(encoding="utf-8")
    start = text.index("### Restarts in a real cell")
    sec = text[start:text.index("### What holds the arm", start)]
    code = re.findall(r"```python\n(.*?)```\n", sec, re.S)
    shown = re.findall(r"\nprints\n\n```\n(.*?)```\n", sec, re.S)
    assert len(code) == 1 and len(shown) == 1
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code[0], "docs/embedding.md", "exec"), {"__name__": "docs_snippet"})  # our own docs
    assert out.getvalue() == shown[0]
    assert "the stop has not completed" in shown[0] and "waiting for the start" in shown[0]
