"""The input boundary of a monitor cycle: what counts as a usable value.

One rule, shared by :class:`~ethimon.Monitor` and the reference interpreter:
a value is usable only if it converts to a finite built-in ``float`` (or a
``bool`` for a bool signal) **once**, here, and everything downstream uses that
converted copy. So a float subclass holding NaN, an object whose comparisons
always pass, a ``numpy.bool_`` passed as a number, a dict passed as ``p`` or a
sequence that yields other values when read twice can never reach a
comparison of the monitor.

* A number is a built-in ``int`` or ``float``, or any other
  :class:`numbers.Real` that is not a bool (``numpy.float32``, ``numpy.int64``,
  ``fractions.Fraction``...), judged by its real type (``type(v)``, never a
  ``__class__`` the object claims); it is converted with ``float()`` (which
  always returns a built-in float) and must be finite. ``bool``, ``numpy.bool_``,
  strings, ``Decimal``, tensors and anything else are not numbers.
* A bool is ``True``/``False``, a ``numpy.bool_``, or a number equal to 0 or 1.
* A value whose conversion raises (any ``Exception`` from its ``__float__`` or,
  for ``p``, its iterator) is not usable: an ``invalid`` fault of that input, the
  same for the monitor and the offline checker, which share these functions.
* ``p`` is an ordered, finite sequence of numbers (a list, tuple or 1-d array),
  read exactly once; a mapping, a set, a string or bytes is not.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Set
from itertools import islice
from numbers import Real
from typing import Any

__all__ = ["as_number", "as_bool", "as_probs"]

_isfinite = math.isfinite


def _is_numpy_bool(v: Any) -> bool:
    c = type(v)  # type(), never v.__class__: an object can claim any __class__
    return c.__name__ in ("bool_", "bool") and c.__module__ == "numpy"


def as_number(v: Any) -> float | None:
    """``v`` as a finite built-in float, or ``None`` if it is not a usable number.

    Example:
        >>> as_number(2), as_number(0.5), as_number(True), as_number("1"), as_number(float("nan"))
        (2.0, 0.5, None, None, None)
    """
    c = type(v)  # type(), never v.__class__: an object can claim any __class__
    if c is float:
        return v if _isfinite(v) else None
    if not issubclass(c, Real) or issubclass(c, bool):  # the real type, not a claimed __class__
        return None
    try:
        f = float(v)  # exactly once; float() always returns a built-in float
    except Exception:  # noqa: BLE001 - 10**400, a __float__ that raises anything: not a usable number
        return None
    return f if _isfinite(f) else None


def as_bool(v: Any) -> bool | None:
    """``v`` as a built-in bool, or ``None`` if it is not a usable truth value.

    Example:
        >>> as_bool(True), as_bool(1), as_bool(0.0), as_bool(2), as_bool("yes")
        (True, True, False, None, None)
    """
    if v is True or v is False:
        return v
    if _is_numpy_bool(v):
        return bool(v)
    c = type(v)
    if c is str or c is bytes:
        return None
    if issubclass(c, Real) and not issubclass(c, bool):
        try:
            f = float(v)
        except Exception:  # noqa: BLE001 - a __float__ that raises: not a usable truth value
            return None
        if f == 0.0:
            return False
        if f == 1.0:
            return True
    return None


def as_probs(p: Any, k: int) -> tuple[tuple[float, ...] | None, str | None]:
    """``p`` read once as ``k`` probabilities: ``(values, None)`` or ``(None, why)``.

    Checks: an ordered sequence (not a mapping, set, string or bytes), exactly
    ``k`` entries, each a finite number in [0, 1], summing to 1 within 1e-3.

    Example:
        >>> as_probs([0.25, 0.75], 2)
        ((0.25, 0.75), None)
        >>> as_probs({0: 0.5, 1: 0.5}, 2)[1]
        'p must be an ordered sequence of probabilities, got dict'
    """
    tp = type(p)
    if (tp is tuple or tp is list) and len(p) == k:  # the common case: k built-in floats
        t = p if tp is tuple else tuple(p)  # a list is copied once: the copy is what is read
        s = 0.0
        for v in t:
            if type(v) is not float or not 0.0 <= v <= 1.0:
                break
            s += v
        else:
            if abs(s - 1.0) <= 1e-3:
                return t, None
    if issubclass(tp, (Mapping, Set, str, bytes, bytearray)) or not hasattr(tp, "__iter__"):
        return None, f"p must be an ordered sequence of probabilities, got {type(p).__name__}"
    try:
        items = list(islice(p, k + 1))  # read once; never more than k + 1 items
    except Exception:  # noqa: BLE001 - an iterator that raises: not a sequence of probabilities
        return None, f"p must be an ordered sequence of probabilities, got {type(p).__name__}"
    if len(items) != k:
        n = f"more than {k}" if len(items) > k else str(len(items))
        return None, f"p has {n} classes, the spec expects {k}"
    out = []
    s = 0.0
    for v in items:
        f = as_number(v)
        if f is None or not 0.0 <= f <= 1.0:
            return None, f"p contains {v!r} (NaN, not a number or outside [0, 1])"
        out.append(f)
        s += f
    if abs(s - 1.0) > 1e-3:
        return None, f"p sums to {s:.6g}, not 1"
    return tuple(out), None
