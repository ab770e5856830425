"""bench/ (issue 13): split by concern, one way to run a script, machine facts in every result.

Nothing is timed here (timings live in bench/ scripts, never in tests); these check the layout,
that every script still parses its arguments when run the documented way, that every script
writes the machine facts, and that no document points at a flat bench path that no longer exists.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
BENCH = ROOT / "bench"
CONCERNS = ("monitor", "risk", "sim", "verify")
#: imported by the scripts, not run: no JSON of their own
LIBRARIES = {"risk_data.py", "_recorded_judge.py", "__init__.py"}
DOCS = ["README.md", "bench/README.md", "verification/README.md", "src/ethimon/sim/README.md",
        "src/ethimon/risk/default_model/MODEL_CARD.md", "CHANGELOG.md",
        *sorted(str(p.relative_to(ROOT)) for p in (ROOT / "docs").glob("*.md"))]


def scripts() -> list[Path]:
    return sorted(p for c in CONCERNS for p in (BENCH / c).glob("*.py") if p.name not in LIBRARIES)


def module(p: Path) -> str:
    return ".".join(p.relative_to(ROOT).with_suffix("").parts)


def test_scripts_live_in_concern_folders_only() -> None:
    assert sorted(p.name for p in BENCH.glob("*.py")) == ["__init__.py", "_machine.py"]
    assert len(scripts()) >= 15
    for c in CONCERNS:
        assert (BENCH / c / "__init__.py").is_file()


def test_no_script_patches_sys_path() -> None:
    offenders = [str(p.relative_to(ROOT)) for p in BENCH.rglob("*.py") if "sys.path" in p.read_text(encoding="utf-8")]
    assert offenders == []


def test_every_script_records_machine_facts() -> None:
    # machine_facts() directly, or sim_realtime.machine() (which wraps it)
    missing = [p.name for p in scripts() if not re.search(r"\bmachine_facts\(|\bmachine\(\)", p.read_text(encoding="utf-8"))]
    assert missing == []


@pytest.mark.slow
def test_every_script_runs_as_a_module_and_the_facts_carry_the_load() -> None:
    """``python -m bench.<concern>.<script> --help`` for all of them, in one interpreter."""
    code = (
        "import contextlib, io, json, runpy, sys\n"
        "from bench._machine import machine_facts\n"
        "out = {'facts': machine_facts(extra=1)}\n"
        "for mod in sys.argv[1:]:\n"
        "    sys.argv = [mod, '--help']\n"
        "    buf = io.StringIO()\n"
        "    try:\n"
        "        with contextlib.redirect_stdout(buf):\n"
        "            runpy.run_module(mod, run_name='__main__', alter_sys=True)\n"
        "        out[mod] = 'returned without exiting'\n"
        "    except SystemExit as e:\n"
        "        out[mod] = (e.code, buf.getvalue().startswith('usage:'))\n"
        "print(json.dumps(out))\n")
    mods = [module(p) for p in scripts()]
    proc = subprocess.run([sys.executable, "-c", code, *mods], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout.splitlines()[-1])
    facts = out.pop("facts")
    assert facts["extra"] == 1 and "cpu" in facts and "python" in facts and "date_utc" in facts
    assert facts["loadavg"] is None or len(facts["loadavg"]) == 3
    assert out == {m: [0, True] for m in mods}


def test_documents_show_the_new_paths_and_commands() -> None:
    flat = re.compile(r"bench/(?!_machine\.py|__init__\.py)[a-z_0-9]+\.py|python bench/|bench/data/|"
                      r"bench/results/(?!(monitor|risk|sim|verify)/|<concern>)[a-z_0-9*]")
    hits = [f"{d}:{i}: {line.strip()}" for d in DOCS
            for i, line in enumerate((ROOT / d).read_text(encoding="utf-8").splitlines(), 1) if flat.search(line)]
    assert hits == []


def test_bench_readme_lists_every_script() -> None:
    text = (BENCH / "README.md").read_text(encoding="utf-8")
    assert [p.name for p in scripts() if f"`{p.name}`" not in text] == []
    for p in scripts():
        assert f"python -m {module(p)}" in text, p.name
