"""Exception hierarchy of ethimon.

Every error that ethimon raises on purpose derives from :class:`EthimonError`.
Errors about user-written input (spec and scenario files, expressions,
command-line arguments) are :class:`SpecError`; they carry the file, the
1-based line and column where the problem is, and a hint.
"""

from __future__ import annotations

__all__ = ["EthimonError", "SpecError", "ModelError", "DependencyNotInstalled"]


class EthimonError(Exception):
    """Root of every exception ethimon raises on purpose."""


class SpecError(EthimonError, ValueError):
    """Bad user input: a spec, scenario or expression that cannot be used.

    Attributes:
        message: what is wrong, quoting the user's text where that helps.
        path: the file, or ``None`` for input that did not come from a file.
        line: 1-based line, or ``None`` when no position exists.
        column: 1-based column, or ``None``.
        hint: a suggestion for the fix, or ``None``.

    Example:
        >>> e = SpecError("unknown signal 'ee_sped'", path="specs/arm.yaml", line=14,
        ...               column=7, hint="did you mean 'ee_speed'?")
        >>> str(e)
        "specs/arm.yaml:14:7: unknown signal 'ee_sped' (did you mean 'ee_speed'?)"
    """

    def __init__(self, message: str, *, path: str | None = None, line: int | None = None,
                 column: int | None = None, hint: str | None = None) -> None:
        self.message = message
        self.path = path
        self.line = line
        self.column = column
        self.hint = hint
        super().__init__(self.__str__())

    @property
    def location(self) -> str:
        """``path:line:column`` (as much of it as is known)."""
        parts = [self.path or "<input>"]
        if self.line is not None:
            parts.append(str(self.line))
            if self.column is not None:
                parts.append(str(self.column))
        return ":".join(parts)

    def __str__(self) -> str:
        text = f"{self.location}: {self.message}"
        if self.hint:
            text += f" ({self.hint})"
        return text

    def __reduce__(self):  # keep picklable for multiprocessing
        return (_rebuild_spec_error, (self.message, self.path, self.line, self.column, self.hint))


def _rebuild_spec_error(message, path, line, column, hint):
    return SpecError(message, path=path, line=line, column=column, hint=hint)


class ModelError(EthimonError):
    """A model directory or weights file that cannot be used (missing, tampered, pickled)."""


class DependencyNotInstalled(EthimonError, ImportError):
    """An optional dependency is missing; the message names the pip command."""
