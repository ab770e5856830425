"""Labelled-text CSV loading and splits (standard library only, no torch)."""

from __future__ import annotations

import csv
import random
from dataclasses import dataclass, field
from pathlib import Path

from ..errors import SpecError

__all__ = ["LabelledRows", "load_labelled_csv", "stratified_split"]

#: text columns accepted besides ``input``: the other ETHICS subsets' layouts
#: (justice/virtue ``scenario``; deontology ``scenario`` + ``excuse``, joined by `` [SEP] ``).
TEXT_COLUMNS = (("input",), ("text",), ("scenario", "excuse"), ("scenario",))
PLAIN_TEXT_COLUMNS = TEXT_COLUMNS[:2]  # a labelled CSV: label + input (ETHICS) or label + text (robot sets)


@dataclass
class LabelledRows:
    """Rows of a ``label,input`` CSV (label 1 = wrong/unsafe)."""

    texts: list[str]
    labels: list[int]
    extra: list[dict] = field(default_factory=list)
    dropped: int = 0
    path: str = ""

    def __len__(self) -> int:
        return len(self.texts)

    def subset(self, idx: list[int]) -> "LabelledRows":
        return LabelledRows([self.texts[i] for i in idx], [self.labels[i] for i in idx],
                            [self.extra[i] for i in idx], 0, self.path)

    def sample(self, n: int | None, seed: int) -> "LabelledRows":
        """``n`` rows drawn at random (seeded shuffle of the row order); all rows if ``n`` is falsy."""
        idx = list(range(len(self.texts)))
        random.Random(seed).shuffle(idx)
        return self.subset(idx[:n] if n else idx)


def load_labelled_csv(path: str | Path, *, any_ethics_layout: bool = False) -> LabelledRows:
    """Read a labelled CSV: ``label`` and ``input`` (ETHICS) or ``text``; other columns kept in ``extra``.

    Rows with a missing/non-0/1 label or an empty input are dropped and counted.
    With ``any_ethics_layout`` the text may instead come from ``scenario`` (justice,
    virtue) or ``scenario`` + ``excuse`` (deontology, joined by `` [SEP] ``).

    Raises:
        SpecError: the file is missing, unreadable, or lacks the two columns.
    """
    p = Path(path)
    if not p.is_file():
        raise SpecError("data file does not exist", path=str(p))
    csv.field_size_limit(1 << 24)
    try:
        with p.open(encoding="utf-8", newline="") as f:
            reader = csv.DictReader(f)
            cols = reader.fieldnames or []
            layouts = TEXT_COLUMNS if any_ethics_layout else PLAIN_TEXT_COLUMNS
            text_cols = next((c for c in layouts if all(x in cols for x in c)), None)
            if "label" not in cols or text_cols is None:
                want = " or ".join("+".join(f"'{x}'" for x in c) for c in layouts)
                raise SpecError(f"needs columns 'label' and {want}, found {cols}", path=str(p), line=1)
            texts, labels, extra, dropped = [], [], [], 0
            for row in reader:
                lab = (row.get("label") or "").strip()
                parts = [(row.get(c) or "").strip() for c in text_cols]
                text = " [SEP] ".join(parts) if all(parts) else ""
                if lab not in ("0", "1") or not text:
                    dropped += 1
                    continue
                texts.append(text)
                labels.append(int(lab))
                extra.append({k: v for k, v in row.items() if k != "label" and k not in text_cols})
    except (OSError, UnicodeDecodeError, csv.Error) as exc:
        raise SpecError(f"cannot read CSV: {exc}", path=str(p)) from exc
    if not texts:
        raise SpecError("no usable rows (label must be 0 or 1, input non-empty)", path=str(p))
    return LabelledRows(texts, labels, extra, dropped, str(p))


def stratified_split(labels: list[int], test_frac: float = 0.2, seed: int = 42) -> tuple[list[int], list[int]]:
    """Indices (train, test) of a stratified split; sklearn's when available.

    With scikit-learn installed this is exactly
    ``train_test_split(range(n), test_size=test_frac, random_state=seed, stratify=labels)``.
    """
    idx = list(range(len(labels)))
    try:
        from sklearn.model_selection import train_test_split
    except ImportError:  # pragma: no cover - fallback without sklearn
        rng = random.Random(seed)
        tr, te = [], []
        for c in sorted(set(labels)):
            ci = [i for i in idx if labels[i] == c]
            rng.shuffle(ci)
            k = round(len(ci) * test_frac)
            te += ci[:k]
            tr += ci[k:]
        return sorted(tr), sorted(te)
    tr, te = train_test_split(idx, test_size=test_frac, random_state=seed, stratify=labels)
    return list(tr), list(te)


def concat_rows(parts: list[LabelledRows]) -> LabelledRows:
    """Concatenate several :class:`LabelledRows` (dropped counts add up)."""
    out = LabelledRows([], [], [], 0, "+".join(p.path for p in parts))
    for p in parts:
        out.texts += p.texts
        out.labels += p.labels
        out.extra += p.extra
        out.dropped += p.dropped
    return out
