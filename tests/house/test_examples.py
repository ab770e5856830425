"""The embedding example is a file that runs, and docs/embedding.md (the README's section until issue 24)
shows it verbatim (issue 13)."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "embed_monitor.py"


def _readme_section() -> str:
    text = (ROOT / "docs" / "embedding.md").read_text(encoding="utf-8")
    return text[text.index("## Embedding the monitor in a control loop"):]


def test_readme_shows_the_example_verbatim():
    blocks = re.findall(r"```python\n(.*?)```\n", _readme_section(), re.S)
    assert blocks and blocks[0] == EXAMPLE.read_text(encoding="utf-8")


@pytest.mark.slow
def test_example_runs_and_prints_what_the_readme_says():
    out = subprocess.run([sys.executable, str(EXAMPLE)], capture_output=True, text=True, check=True,
                         cwd=str(ROOT / "examples"), timeout=120).stdout
    shown = re.findall(r"\n```\n(cycle .*?)```\n", _readme_section(), re.S)
    assert shown and out == shown[0]
    lines = out.splitlines()
    assert [ln.split("arm: ")[1].split()[0] for ln in lines] == ["task", "safe_pose", "stop_2"]
    assert "slow_near_human" in lines[1] and "separation" in lines[2]
