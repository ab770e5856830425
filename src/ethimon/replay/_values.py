"""A mapped field's value in a deserialised bag message: the field reached with located errors naming it and
a "did you mean" for a misspelt one, whole batches reduced at once; one message's value is made a number by
``ethimon.io``'s :func:`~ethimon.io.reduce_value`, which the live node uses too."""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any

import numpy as np

from ..errors import BagError
from ..io import SignalMap

__all__: list[str] = []


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


_FLOATS = (float, np.float64, np.float32)
#: field values reduced together (bounded memory: a batch, never the bag)
_BATCH = 4096


def _reduce_rows(a: np.ndarray, sm: SignalMap) -> np.ndarray:
    """:meth:`~ethimon.io.SignalMap.reduce_array` of every row of ``a`` (rows: messages), then ``* scale + offset``."""
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
