"""The README is one page and the reference lives in docs/ (issue 24 item 5)."""

from __future__ import annotations

import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"

#: every heading of README.md before issue 24 (a52effd, 1,681 lines): each must still exist somewhere
HEADINGS_BEFORE_ISSUE_24 = [
    "# ethimon", "## Quickstart", "## Embedding the monitor in a control loop", "## Trust model",
    "## Spec reference", "### Expressions", "### Scenario reference", "## Simulation (PyBullet)",
    "## Replaying ROS bags", "### Your own bag, step by step", "### How a bag becomes cycles",
    "## Live on ROS 2 (`ethimon ros2`)", "## Fleet scale (Ray)", "## Shielding an RL policy (Gymnasium)",
    "## Offline checking", "## Verification", "## Training and evaluation",
    "## The judge tier and the confirm band", "## Deploying on a robot computer (ONNX Runtime, no torch)",
    "## Results", "## Layout",
]


def headings(path: Path) -> list[str]:
    out, fence = [], False
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("```"):
            fence = not fence
        elif not fence and line.startswith("#"):
            out.append(line.rstrip())
    return out


def test_readme_is_one_page() -> None:
    assert len((ROOT / "README.md").read_text(encoding="utf-8").splitlines()) <= 450


def test_every_old_heading_lives_in_the_readme_or_docs() -> None:
    found = set(headings(ROOT / "README.md"))
    for p in DOCS.glob("*.md"):
        found |= set(headings(p))
    assert [h for h in HEADINGS_BEFORE_ISSUE_24 if h not in found] == []


def test_every_doc_is_linked_from_the_readme_and_the_index() -> None:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    index = (DOCS / "README.md").read_text(encoding="utf-8")
    for p in DOCS.glob("*.md"):
        if p.name != "README.md":
            assert f"](docs/{p.name}" in readme, p.name
            assert f"]({p.name})" in index, p.name


def test_relative_links_resolve() -> None:
    files = [ROOT / "README.md", ROOT / "CHANGELOG.md", *DOCS.glob("*.md")]
    bad = []
    for f in files:
        text = re.sub(r"```.*?```|`[^`]*`", "", f.read_text(encoding="utf-8"), flags=re.S)  # code is no link
        for target in re.findall(r"\]\(([^)\s]+)\)", text):
            if "://" in target or target.startswith("#"):
                continue
            if not (f.parent / target.split("#")[0]).exists():
                bad.append(f"{f.relative_to(ROOT)}: {target}")
    assert bad == []


def test_layout_names_every_package() -> None:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    pkgs = sorted(p.name for p in (ROOT / "src" / "ethimon").iterdir() if (p / "__init__.py").is_file())
    assert [p for p in pkgs if f"src/ethimon/{p}/" not in readme and f"{p}/ " not in readme] == []


def test_cli_docstring_names_every_exit_code_main_returns() -> None:
    src = (ROOT / "src" / "ethimon" / "cli" / "__init__.py").read_text(encoding="utf-8")
    tree = ast.parse(src)
    doc = ast.get_docstring(tree) or ""
    main = next(n for n in tree.body if isinstance(n, ast.FunctionDef) and n.name == "main")
    codes = {n.value.value for n in ast.walk(main)
             if isinstance(n, ast.Return) and isinstance(n.value, ast.Constant) and isinstance(n.value.value, int)}
    assert {0, 2, 3, 130} <= codes
    stated = {int(c) for c in re.findall(r"\b(\d+) [a-z]", doc.split("Exit codes:")[1])}
    assert codes - stated == set(), doc


def test_bench_readme_says_not_cited_only_of_uncited_scripts() -> None:
    bench = (ROOT / "bench" / "README.md").read_text(encoding="utf-8")
    cited = "".join(p.read_text(encoding="utf-8") for p in [ROOT / "README.md", *DOCS.glob("*.md"),
                                                           ROOT / "src/ethimon/risk/default_model/MODEL_CARD.md"])
    wrong = [m for m in re.findall(r"^\| `(\w+\.py)` \|[^\n]*not cited yet", bench, re.M) if m in cited]
    assert wrong == []
