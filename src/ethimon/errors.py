"""Exception hierarchy of ethimon.

Every error that ethimon raises on purpose derives from :class:`EthimonError`,
and every exception class of ethimon is defined here (packages re-export the
ones that belong to them, e.g. ``ethimon.audit.AuditFormatError``)::

    EthimonError
    ├── SpecError (ValueError)          a spec, scenario or expression file: path:line:column (hint)
    ├── ExprSyntaxError (ValueError)    an expression's syntax, at a character index (spec.parse_expr)
    ├── SimError (ValueError)           a sim: block that validates but cannot be simulated
    ├── ModelError                      a model directory or weights file that cannot be used
    ├── RiskInferenceError              inference failed or gave NaN/inf: treat the text as unsafe
    ├── AuditFormatError (ValueError)   not an audit log at all (unreadable, empty, wrong header)
    ├── AuditTampered (ValueError)      an audit log whose hash chain does not verify (read_log)
    ├── BagError                        a ROS bag that cannot be replayed
    └── DependencyNotInstalled (ImportError)  an optional extra is missing; names the pip command

Errors about user-written input (spec and scenario files, expressions,
command-line arguments) are :class:`SpecError`; they carry the file, the
1-based line and column where the problem is, and a hint. The classes that
also derive from a built-in (``ValueError``, ``ImportError``) do so because
callers catch them by that built-in.
"""

from __future__ import annotations

__all__ = ["AuditFormatError", "AuditTampered", "BagError", "DependencyNotInstalled", "EthimonError",
           "ExprSyntaxError", "ModelError", "RiskInferenceError", "Ros2Error", "SimError", "SpecError"]


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


class ExprSyntaxError(EthimonError, ValueError):
    """A syntax error at character ``index`` of an expression's text (raised by ``ethimon.language.parse_expr``;
    the spec loader turns it into a :class:`SpecError` at the expression's file, line and column)."""

    def __init__(self, message: str, index: int, hint: str | None = None) -> None:
        super().__init__(message)
        self.message = message
        self.index = index
        self.hint = hint

    def __reduce__(self):
        return (type(self), (self.message, self.index, self.hint))


class SimError(EthimonError, ValueError):
    """A ``sim:`` block that validates but cannot be simulated (e.g. an unreachable target)."""


class RiskInferenceError(EthimonError):
    """Inference failed or produced NaN/inf; callers must treat the text as unsafe."""


class AuditFormatError(EthimonError, ValueError):
    """The file is not an ethimon audit log at all (unreadable, empty, wrong header)."""


class AuditTampered(EthimonError, ValueError):
    """An audit log whose hash chain does not verify (edited, removed or reordered records, a wrong key):
    raised by ``ethimon.audit.read_log``; ``verify_log`` reports the same as a value instead."""


class BagError(EthimonError):
    """A bag that cannot be replayed (missing, corrupt, a field the messages lack); names the bag."""

    def __init__(self, message: str, path: str | None = None, hint: str | None = None) -> None:
        self.message, self.path, self.hint = message, path, hint
        text = f"{path}: {message}" if path else message
        super().__init__(text + (f" ({hint})" if hint else ""))

    def __reduce__(self):  # picklable (Ray workers, multiprocessing)
        return (type(self), (self.message, self.path, self.hint))


class Ros2Error(EthimonError):
    """The live ROS 2 node cannot start or go on (a DDS entity that cannot be made, a type it cannot build,
    DDS Security asked for but missing from this Cyclone DDS build)."""
