"""Scoring a bag's task texts: the spec's risk estimator, loaded on the first text and kept
(:class:`TaskScorer`), or a given ``score`` function."""

from __future__ import annotations

import copy
from collections.abc import Callable, Sequence

from ..language import Spec
from typing import Any

__all__ = ["TaskScorer"]

Scorer = Callable[[str], Sequence[float]]


class TaskScorer:
    """Scores task texts with the spec's risk estimator, loaded on the first text and then kept:
    share one across the bags of a run so the model loads once.

    Args:
        spec: whose ``risk.estimator`` block picks the model.
        model_dir: overrides the spec's model directory.

    A load failure (``ModelError``, ``DependencyNotInstalled``) is raised on every use, as a fresh
    exception (the bag being replayed is an error, not a run of fault cycles).
    """

    def __init__(self, spec: Spec, *, model_dir: str | None = None) -> None:
        self.spec, self.model_dir = spec, model_dir
        self._probs: Scorer | None = None
        self._failed: BaseException | None = None

    def load(self) -> None:
        if self._probs is not None:
            return
        if self._failed is not None:
            exc = copy.copy(self._failed)  # a fresh copy: no traceback chained across bags
            exc.__traceback__ = exc.__context__ = exc.__cause__ = None
            raise exc
        try:
            from ..risk import as_estimator, default_threads  # lazy: torch only when a text must be scored
            # texts are scored one at a time: one thread (torch's default of 2 spins on busy cores)
            self._probs = as_estimator(self.model_dir, spec=self.spec, num_threads=default_threads(1)).probs
        except Exception as exc:
            self._failed = exc
            raise

    def __call__(self, text: str) -> Sequence[float]:
        self.load()
        assert self._probs is not None
        return self._probs(text)


class _Lazy:
    """Scores task texts: ``score`` if given, else the spec's estimator (loaded on the first text)."""

    def __init__(self, spec: Spec, score: Scorer | None) -> None:
        if score is None:
            self.fn: Any = TaskScorer(spec)
        else:  # the one hand-over: an estimator, a function text -> probabilities, a factory
            from ..risk import as_estimator
            self.fn = as_estimator(score).probs

    def score(self, text: str, k: int) -> tuple[tuple[float, ...] | None, str | None]:
        load = getattr(self.fn, "load", None)
        if load is not None:
            load()  # a model that cannot be loaded is an error of the replay, not an estimator fault
        try:
            got = tuple(float(x) for x in self.fn(text))
        except Exception as exc:  # noqa: BLE001 - an estimator failure is a fault on those cycles
            return None, f"the risk estimator failed on this text: {type(exc).__name__}: {exc}"[:300]
        if len(got) != k:
            return None, f"the risk estimator gave {len(got)} probabilities; the spec has risk.classes {k}"
        return got, None
