"""A mapped field's value in a deserialised message, made a number (``reduce``, ``scale``, ``offset``), with
located errors naming the field and a "did you mean" for a misspelt one; the live ``ros2`` node reduces
its samples with the same :func:`reduce_value`."""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any

import numpy as np

from ..errors import BagError
from ._mapping import SignalMap

__all__ = ["reduce_value"]


def _did_you_mean(word: str, options: Iterable[str]) -> str | None:
    import difflib
    opts = list(options)
    close = difflib.get_close_matches(word, opts, n=1, cutoff=0.5)
    if close:
        return f"did you mean {close[0]!r}?"
    return None



def _get(msg: Any, fpath: tuple, topic: str, msgtype: str, text: str, bag: str, who: str) -> Any:
    """Follow ``fpath`` (names and numeric indices) into a deserialised message (the task text)."""
    cur = msg
    for i, part in enumerate(fpath):
        if isinstance(part, int):
            try:
                cur = cur[part]
            except (IndexError, TypeError, KeyError):
                return math.nan
            continue
        if not hasattr(cur, "__dataclass_fields__") or part not in _fields(cur):
            have = _fields(cur)
            hint = _did_you_mean(part, have) or (
                f"fields here: {', '.join(have)}" if have else "this part of the message has no fields")
            raise BagError(f"{who}: {topic} ({msgtype}) has no field {part!r} for field path {text!r}", bag,
                           hint=hint)
        cur = getattr(cur, part)
    return cur


def _fields(obj: Any) -> list[str]:
    f = getattr(obj, "__dataclass_fields__", None)
    return [k for k in f if not k.startswith("_")] if f else []


def _stamp(msg: Any, topic: str, msgtype: str, bag: str, who: str) -> int:
    hdr = getattr(msg, "header", None)
    stamp = getattr(hdr, "stamp", None)
    if stamp is None or not hasattr(stamp, "sec"):
        raise BagError(f"{who}: {topic} ({msgtype}) has no header.stamp, but the mapping sets 'time: header'", bag,
                       hint="use 'time: log' (the bag's receive time) for messages without a header")
    return int(stamp.sec) * 1_000_000_000 + int(getattr(stamp, "nanosec", getattr(stamp, "nsec", 0)))


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


def _numbers_of(v: Any, where: str, path: str) -> np.ndarray | None:
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


_FLOATS = (float, np.float64, np.float32)
#: field values reduced together (bounded memory: a batch, never the bag)
_BATCH = 4096


def _reduce_rows(a: np.ndarray, sm: SignalMap) -> np.ndarray:
    """:func:`_reduce_arr` of every row of ``a`` (rows: messages), then ``* scale + offset``."""
    if a.shape[1] == 0:
        return np.full(a.shape[0], np.nan)
    red = sm.reduce
    if red == "index":
        if sm.index is None or sm.index >= a.shape[1]:
            return np.full(a.shape[0], np.nan)
        x = a[:, sm.index].copy()
    elif red == "max":
        x = a.max(axis=1)
    elif red == "min":
        x = a.min(axis=1)
    elif red == "max_abs":
        x = np.abs(a).max(axis=1)
    elif red == "norm":
        x = np.sqrt(np.einsum("ij,ij->i", a, a))
    else:  # mean
        x = a.mean(axis=1)
    return x * sm.scale + sm.offset


def _reduce_arr(arr: np.ndarray, sm: SignalMap) -> float:
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


def reduce_value(v: Any, sm: SignalMap, *, where: str = "", path: str | None = None) -> float:
    """One number from a field value: the mapping's reduction, then ``* scale + offset``.

    NaN when the value cannot be formed from this message (an empty array, an index past the end);
    ±inf stays ±inf (the monitor then faults on it as what it is); a value of the wrong kind (text,
    a nested message) raises :class:`BagError`.
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
    return _reduce_arr(arr, sm)


def _kind(v: Any) -> str:
    if isinstance(v, str):
        return "text"
    if isinstance(v, (np.ndarray, list, tuple)):
        return f"an array of {len(v)}"
    t = getattr(v, "__msgtype__", None)
    return f"a message ({t})" if t else type(v).__name__
