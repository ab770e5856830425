"""docs/embedding.md "What holds the arm": its snippet (Monitor.holding(), GovernedLoop.holding(), the step
input pending_s) runs as written and prints what the page shows (issue 31 item 3)."""

from __future__ import annotations

import contextlib
import io
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _section() -> str:
    text = (ROOT / "docs" / "embedding.md").read_text(encoding="utf-8")
    start = text.index("### What holds the arm: `holding()` and the pending hold")
    return text[start:text.index("The learned risk runs off the hot path", start)]


@pytest.mark.slow  # 0.6 s: compiles a spec, starts a loop
def test_the_holding_snippet_prints_what_the_page_shows():
    sec = _section()
    code = re.findall(r"```python\n(.*?)```\n", sec, re.S)
    shown = re.findall(r"\nprints\n\n```\n(.*?)```\n", sec, re.S)
    assert len(code) == 1 and len(shown) == 1
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code[0], "docs/embedding.md", "exec"), {"__name__": "docs_snippet"})  # our own docs
    assert out.getvalue() == shown[0]
    assert "('pending',)" in shown[0] and "estimate" in shown[0]
