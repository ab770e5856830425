"""One way to hand a risk estimator to the loop, the ROS 2 node, replay, scenarios and the sim:
:func:`as_estimator` turns what a caller has (nothing, a model directory, an estimator, a factory,
a scoring function) into one object with ``probs(text) -> (p_0, ..., p_{K-1})``.

Torch-free: a model is loaded (lazily imported back-end) only when a directory or nothing is given.
"""

from __future__ import annotations

import inspect
import os
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any, Union

from ._estimator import ProbsEstimator

__all__ = ["as_estimator", "ScoreFunction", "EstimatorLike"]

#: what :func:`as_estimator` accepts
EstimatorLike = Union[None, str, "os.PathLike[str]", ProbsEstimator, Callable[[], ProbsEstimator],
                      Callable[[str], Sequence[float]]]


class ScoreFunction:
    """A function ``text -> probabilities`` seen as a :class:`ProbsEstimator`."""

    __slots__ = ("fn",)

    def __init__(self, fn: Callable[[str], Sequence[float]]) -> None:
        self.fn = fn

    def probs(self, text: str) -> Sequence[float]:
        return self.fn(text)

    def __repr__(self) -> str:
        return f"ScoreFunction({getattr(self.fn, '__qualname__', self.fn)!r})"


def _required_args(fn: Callable) -> int | None:
    try:
        sig = inspect.signature(fn)
    except (TypeError, ValueError):
        return None
    return sum(1 for p in sig.parameters.values()
               if p.default is p.empty and p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD))


def as_estimator(x: Any = None, *, spec: Any = None, **load_kw: Any) -> ProbsEstimator:
    """The estimator ``x`` stands for.

    Args:
        x: ``None``: the spec's ``risk.estimator`` (``load_estimator_for``), else the shipped model;
            a model directory (``str`` or path; with ``spec``, the spec's other estimator settings
            apply); an object with ``probs(text)`` (a ``RiskEstimator``, a ``ProcessEstimator``, a
            test's fixed source): itself; a zero-argument callable: a factory, called once; a
            one-argument callable ``text -> probabilities``: wrapped (:class:`ScoreFunction`).
        spec: the spec whose ``risk.estimator`` block applies when a model is loaded.
        load_kw: more ``load_estimator`` keywords when a model is loaded (e.g. ``num_threads``).

    A string is a directory, never code: ``"module:function"`` is refused (name a factory in code, or
    use ``ethimon.loop.ProcessEstimator``, which imports its factory by name on purpose).

    Raises:
        TypeError: ``x`` is none of the above, or a factory returned no estimator.
        ModelError: a directory that does not exist or is refused; DependencyNotInstalled.

    Example:
        >>> from ethimon.risk import as_estimator
        >>> as_estimator(lambda text: (0.9, 0.1)).probs("Put the fork in the drawer.")
        (0.9, 0.1)
    """
    if x is None or isinstance(x, (str, os.PathLike)):
        from .. import risk as R   # the package's names (what a test may monkeypatch), loaded lazily
        load_estimator, load_estimator_for = R.load_estimator, R.load_estimator_for
        if x is not None:
            d = Path(x)
            if not d.is_dir() and (spec is None or (isinstance(x, str) and ":" in x and not d.exists())):
                from ..errors import ModelError
                code = isinstance(x, str) and ":" in x and not d.exists()
                raise ModelError(f"{x}: not a model directory" + (
                    "; an estimator is named by its directory, never by code ('module:function')" if code else ""))
            load_kw = {**load_kw, "model_dir": str(d)}   # with a spec: load_estimator_for says whose model
        return load_estimator_for(spec, **load_kw) if spec is not None else load_estimator(**load_kw)
    if hasattr(x, "probs") and callable(x.probs) and not isinstance(x, type):  # a class is a factory
        return x
    if callable(x):
        n = _required_args(x)
        if n == 0:
            got = x()
            if not (hasattr(got, "probs") and callable(got.probs)):
                raise TypeError(f"the estimator factory {x!r} returned {type(got).__name__}, "
                                "not an object with probs(text)")
            return got
        if n == 1 or n is None:  # None: a signature Python cannot tell (a builtin such as dict.__getitem__)
            return ScoreFunction(x)
        raise TypeError(f"{x!r}: a zero-argument factory or a function text -> probabilities expected "
                        f"({n} required arguments)")
    raise TypeError(f"cannot make a risk estimator of {type(x).__name__}: expected None, a model directory, "
                    "an object with probs(text), a factory or a function text -> probabilities")
