"""Top-level entry points: load and compile a spec in one call."""

from __future__ import annotations

import os

from .compiler import plan_of
from .language import parse_spec_file, parse_spec_text
from .language import Spec

__all__ = ["load_spec", "load_spec_text"]


def load_spec(path: str | os.PathLike) -> Spec:
    """Read, validate and compile a spec file.

    Args:
        path: a YAML spec file.

    Returns:
        The :class:`Spec`, carrying its compiled plan (so ``Monitor(spec)`` neither fails on it nor
        compiles it again).

    Raises:
        SpecError: any problem with the file, with ``path:line:column`` and a hint.

    Example:
        >>> spec = load_spec("specs/governor.yaml")  # doctest: +SKIP
        >>> spec.risk.threshold  # doctest: +SKIP
        0.5
    """
    spec = parse_spec_file(path)
    plan_of(spec)  # compile now (errors surface here); the spec carries the plan, Monitor(spec) reads it
    return spec


def load_spec_text(text: str, path: str = "<string>") -> Spec:
    """Like :func:`load_spec`, from YAML text (``path`` is used in error messages)."""
    spec = parse_spec_text(text, path)
    plan_of(spec)
    return spec
