"""The judge's canaries: texts with known answers a judge must get right before its verdicts count.

The shipped set (``canaries/canaries.csv``, package data) holds 48 texts written for this purpose, half
unsafe, in six forms (one-liners, plans, JSON task programs, code calls, chat turns, speech
transcripts) with ten minimal pairs; a spec adds its own with ``risk.judge.canaries.path``. stdlib only.
"""

from __future__ import annotations

import csv
import os
from pathlib import Path
from typing import NamedTuple

__all__ = ["CanaryCheck", "load_canaries"]

_CANARY_DIR = Path(__file__).resolve().parent / "canaries"


class CanaryCheck(NamedTuple):
    """One canary run: ``passed``, how many were asked, the ids missed and the separation."""

    passed: bool
    asked: int
    total: int
    missed: tuple[str, ...]
    min_unsafe: float | None
    max_safe: float | None
    detail: str
    at: float

    def line(self) -> str:
        """One line for results, summaries and audit records."""
        if self.passed:
            return (f"passed {self.asked}/{self.total} (unsafe >= {self.min_unsafe:.2f} > safe <= "
                    f"{self.max_safe:.2f})")
        return f"failed: {self.detail}"


def load_canaries(extra: str | os.PathLike | None = None) -> tuple[tuple[str, str, int, str], ...]:
    """The canary texts: ``(id, form, label, text)`` rows, the shipped set then ``extra``'s.

    A CSV with columns ``id, form, label, text`` (label ``1`` unsafe, ``0`` safe; others ignored).
    The shipped set (``ethimon/risk/canaries/canaries.csv``) holds 48 texts, half unsafe, in six
    forms (one-liners, plans, JSON, code calls, chat, speech) with ten minimal pairs. Rows are asked
    alternating safe and unsafe, so a constant judge fails on its first or second answer.

    Raises:
        ValueError: a located problem in a canary file (missing column, bad label, empty text).

    Example:
        >>> rows = load_canaries()
        >>> len(rows) >= 40, sum(r[2] for r in rows) * 2 == len(rows)
        (True, True)
    """
    rows: list[tuple[str, str, int, str]] = []
    for path in [_CANARY_DIR / "canaries.csv"] + ([Path(extra)] if extra is not None else []):
        try:
            with open(path, newline="", encoding="utf-8") as f:
                reader = csv.DictReader(f)
                if not reader.fieldnames or not {"id", "label", "text"} <= set(reader.fieldnames):
                    raise ValueError(f"{path}: a canary file needs the columns id, label, text "
                                     f"(form optional); found {reader.fieldnames}")
                for n, r in enumerate(reader, start=2):
                    lab = (r.get("label") or "").strip()
                    text = r.get("text") or ""
                    if lab not in ("0", "1") or not text.strip():
                        raise ValueError(f"{path}:{n}: label must be 0 (safe) or 1 (unsafe) and text non-empty, "
                                         f"got label {lab!r}")
                    rows.append(((r.get("id") or f"row{n}").strip(), (r.get("form") or "").strip(), int(lab), text))
        except OSError as exc:
            raise ValueError(f"canary file {path}: {exc.strerror or exc}; hint: risk.judge.canaries.path is a "
                             "CSV with columns id, form, label, text") from None
    if not any(r[2] == 1 for r in rows) or not any(r[2] == 0 for r in rows):
        raise ValueError("the canary set needs safe (0) and unsafe (1) texts")
    safe, unsafe = [r for r in rows if r[2] == 0], [r for r in rows if r[2] == 1]
    mixed: list[tuple[str, str, int, str]] = []
    for k in range(max(len(safe), len(unsafe))):  # alternate: a constant judge misses at once
        mixed += ([safe[k]] if k < len(safe) else []) + ([unsafe[k]] if k < len(unsafe) else [])
    return tuple(mixed)
