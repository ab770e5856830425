"""A mapped field's value made a number, the one way live and replay do it: the reduction (``reduce``,
``scale``, ``offset``, :func:`reduce_value`), the rate between two messages (``derive: rate``,
:func:`rate_between`), and whether a value is a truth value (a ``std_msgs/Bool`` is not a number)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..errors import BagError

#: ``sm`` below: a signal's mapping entry (:class:`~ethimon.io.SignalMap`; not imported: the mapping imports this)

__all__ = ["ByName", "follow", "is_truth", "numbers_of", "rate_between", "reduce_array", "reduce_value"]



class ByName(str):
    """A field-path index by name: ``position[panda_joint4]`` → the entry the message's ``name`` list names."""

    __slots__ = ()

def _fields(obj: Any) -> list[str]:
    f = getattr(obj, "__dataclass_fields__", None)
    return [k for k in f if not k.startswith("_")] if f else []


def is_truth(v: Any) -> bool:
    """A true/false value (a Python or numpy bool, or an array of them)."""
    return isinstance(v, (bool, np.bool_)) or (isinstance(v, np.ndarray) and v.dtype.kind == "b")


def follow(msg: Any, path: tuple) -> Any:
    """Follow a parsed field path into a message (attributes; indices; ``ByName`` through the message's
    ``name`` list). NaN when an index or a name is not in this message (no usable value)."""
    cur, parent = msg, None
    for part in path:
        if isinstance(part, ByName):
            names = getattr(parent, "name", None)
            try:
                part = list(names).index(str(part))
            except (TypeError, ValueError):
                return math.nan
        if isinstance(part, int):
            try:
                cur = cur[part]
            except (IndexError, TypeError, KeyError):
                return math.nan
        else:
            parent, cur = cur, getattr(cur, part)
    return cur


def _numbers(v: Any) -> np.ndarray | None:
    """An array field, a list of numbers or a vector message (x, y, z ...) as floats; None if not numeric."""
    if isinstance(v, np.ndarray):
        if v.dtype.kind in "biuf":
            return v.astype(np.float64, copy=False).ravel()
        return None
    if isinstance(v, (list, tuple)):
        out = []
        for x in v:
            if isinstance(x, (bool, np.bool_, int, float, np.integer, np.floating)):
                out.append(float(x))
            else:
                return None
        return np.asarray(out, dtype=np.float64)
    names = _fields(v)
    if names:
        vals = [getattr(v, k) for k in names]
        if vals and all(isinstance(x, (int, float, np.integer, np.floating)) and not isinstance(x, bool)
                        for x in vals):
            return np.asarray([float(x) for x in vals], dtype=np.float64)
    return None


def numbers_of(v: Any, where: str = "", path: str | None = None) -> np.ndarray | None:
    """The numbers a ``derive: rate`` signal differentiates (a copy); None for an unusable message."""
    if isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, (bool, np.bool_)):
        return np.asarray([float(v)])
    arr = _numbers(v)
    if arr is None:
        if isinstance(v, float):
            return None
        raise BagError(f"{where} is {_kind(v)}: 'derive: rate' needs a number, an array of numbers or a vector "
                       "(x, y, z)", path, hint="point 'field' at e.g. 'pose.position'")
    return np.array(arr, dtype=np.float64)


def reduce_array(arr: np.ndarray, sm: Any) -> float:
    """The mapping's reduction of an array of numbers, then ``* scale + offset`` (NaN: none can be formed)."""
    if arr.size == 0:
        return math.nan
    red = sm.reduce
    if red == "index":
        if sm.index is None or sm.index >= arr.size:
            return math.nan
        x = float(arr[sm.index])
    elif red == "max":
        x = float(arr.max())
    elif red == "min":
        x = float(arr.min())
    elif red == "max_abs":
        x = float(np.abs(arr).max())
    elif red == "norm":
        x = float(math.sqrt(float(np.dot(arr, arr))))
    else:  # mean
        x = float(arr.mean())
    return x * sm.scale + sm.offset


def rate_between(a: np.ndarray | None, b: np.ndarray | None, dt_s: float, sm: Any) -> float:
    """``derive: rate``: the change per second from message ``a`` to message ``b`` (``dt_s`` apart, their
    own times), element by element, then the reduction. NaN when either is unusable or they differ in size."""
    if a is None or b is None or a.size != b.size or not dt_s > 0:
        return math.nan
    d = (b - a) * (1.0 / dt_s)
    if sm.reduce != "value":
        return reduce_array(d, sm)
    return float(d[0]) * sm.scale + sm.offset if d.size == 1 else math.nan


def reduce_value(v: Any, sm: Any, *, where: str = "", path: str | None = None) -> float:
    """One number from a field value: the mapping's reduction, then ``* scale + offset``.

    NaN when the value cannot be formed from this message (an empty array, an index past the end);
    ±inf stays ±inf (the monitor then faults on it as what it is); a value of the wrong kind (text,
    a nested message) raises :class:`~ethimon.errors.BagError`.
    """
    red = sm.reduce
    if red == "value":
        if isinstance(v, (bool, np.bool_)):
            x = 1.0 if v else 0.0
        elif isinstance(v, (int, float, np.integer, np.floating)):
            x = float(v)
        else:
            raise BagError(f"{where} is {_kind(v)}, not one number", path,
                           hint="map a numeric field" if isinstance(v, str) else
                           "pick a reduction: reduce: max | min | max_abs | norm | mean | index")
        return x * sm.scale + sm.offset
    arr = _numbers(v)
    if arr is None:
        if isinstance(v, float) and v != v:
            return math.nan
        raise BagError(f"{where} is {_kind(v)}: reduce {red!r} needs an array of numbers or a vector "
                       f"(x, y, z)", path, hint="point 'field' at a numeric array, e.g. 'velocity' or "
                       "'twist.linear'")
    return reduce_array(arr, sm)


def _kind(v: Any) -> str:
    if isinstance(v, str):
        return "text"
    if isinstance(v, (np.ndarray, list, tuple)):
        return f"an array of {len(v)}"
    t = getattr(v, "__msgtype__", None)
    return f"a message ({t})" if t else type(v).__name__
