"""The input boundary of an offline trace: columns in, converted values and validity masks out.

A trace is a mapping of column name to one value per monitor cycle. Cycle ``t``
is checked exactly as :meth:`ethimon.Monitor.step` checks the mapping that
:func:`row` builds for it:

* a 1-d numpy array of booleans, integers or floats gives ``column[t].item()``
  (a built-in ``bool``, ``int`` or ``float``);
* a 1-d array of objects (or a list holding ``None``, strings, ...) gives the
  element itself;
* ``None`` in an object column, or a masked entry of a :class:`numpy.ma.MaskedArray`,
  means the input is missing that cycle (the key is left out);
* ``p`` may also be a 2-d numeric array, one row of class probabilities per
  cycle (``column[t].tolist()``; a row with any masked entry is missing).

Numeric columns are converted with numpy in one pass per column; object
columns element by element with the monitor's own rules
(:mod:`ethimon.runtime._inputs`), so NaN, infinities, out-of-range values,
wrong types and missing values fail closed on exactly the cycles the monitor
would.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from ..compiler._risk_formula import risk_from_probs, two_class_risk
from ..runtime._inputs import as_bool, as_number, as_probs

__all__ = ["Inputs", "read_inputs", "row", "RISK_KEYS"]

RISK_KEYS = ("risk", "p_unsafe", "p")
_NUMERIC = "biuf"


class Inputs:
    """Converted columns of one trace (see the module docstring)."""

    __slots__ = ("n", "values", "ok", "risk", "risk_ok", "age_ok", "input_fault", "cols")

    def __init__(self, n: int) -> None:
        self.n = n
        self.values: dict[str, np.ndarray] = {}  # signal name -> float64 or bool array (garbage where not ok)
        self.ok: dict[str, np.ndarray] = {}  # signal name -> usable this cycle
        self.risk = np.full(n, np.nan)  # R_e, NaN where no usable risk input arrived
        self.risk_ok = np.zeros(n, bool)  # R_e formed (Decision.risk is not None)
        self.age_ok = np.ones(n, bool)  # the estimate is fresh enough (always, without risk.max_age_s)
        self.input_fault = np.zeros(n, bool)
        self.cols: dict[str, tuple[np.ndarray, np.ndarray]] = {}  # name -> (data, present), for row()


def _column(name: str, col: Any, n: int | None, *, two_d: bool = False) -> tuple[np.ndarray, np.ndarray, int]:
    """``(data, present, n)`` of one column; raises ValueError naming the column if it has the wrong shape."""
    if isinstance(col, np.ma.MaskedArray):
        data = np.ma.getdata(col)
        mask = np.ma.getmaskarray(col)
    else:
        data = col if isinstance(col, np.ndarray) else _as_array(col)
        mask = None
    if data.ndim == 2 and two_d and data.dtype.kind in _NUMERIC:
        present = ~mask.any(axis=1) if mask is not None else np.ones(len(data), bool)
    elif data.ndim != 1:
        want = "a 1-d array (one value per cycle)" + (", or a 2-d numeric array (cycles × classes)" if two_d else "")
        raise ValueError(f"column {name!r} has shape {data.shape}: expected {want}")
    else:
        present = ~mask if mask is not None else np.ones(len(data), bool)
        if data.dtype.kind == "O":
            present = present & np.fromiter((v is not None for v in data), bool, len(data))
    if n is not None and len(data) != n:
        raise ValueError(f"column {name!r} has {len(data)} values, but the trace has {n} cycles "
                         "(every column holds one value per monitor cycle)")
    return data, present, len(data)


def _as_array(col: Any) -> np.ndarray:
    """A sequence as a 1-d array, keeping the elements (``None``, strings, sequences) as objects if needed."""
    try:
        arr = np.asarray(col)
    except Exception:  # noqa: BLE001 - an element numpy cannot read (its __len__ raises, ...): kept as an object
        arr = None
    if arr is None or arr.dtype.kind not in _NUMERIC or arr.ndim != 1:
        items = list(col)
        arr = np.empty(len(items), dtype=object)
        for i, v in enumerate(items):
            arr[i] = v
    return arr


def _objects(data: np.ndarray) -> np.ndarray:
    """A non-numeric 1-d array as the objects ``row()`` passes (``.item()`` of each element)."""
    if data.dtype.kind == "O":
        return data
    out = np.empty(len(data), dtype=object)
    for i, v in enumerate(data.tolist()):
        out[i] = v
    return out


def _numbers(data: np.ndarray, present: np.ndarray, lo: float, hi: float) -> tuple[np.ndarray, np.ndarray]:
    """As ``as_number`` and the range test: ``(values, usable)``."""
    k = data.dtype.kind
    if k == "b":
        return np.zeros(len(data)), np.zeros(len(data), bool)
    if k in "iuf":
        x = data.astype(np.float64, copy=False)
        with np.errstate(invalid="ignore"):
            ok = present & (x >= lo) & (x <= hi)
        if k == "f":
            ok &= np.isfinite(x)
        return x, ok
    objs = _objects(data)
    x = np.zeros(len(data))
    ok = np.zeros(len(data), bool)
    for i in np.flatnonzero(present):
        f = as_number(objs[i])
        if f is not None and lo <= f <= hi:
            x[i] = f
            ok[i] = True
    return x, ok


def _bools(data: np.ndarray, present: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """As ``as_bool``: ``(values, usable)``."""
    k = data.dtype.kind
    if k == "b":
        return data.astype(bool, copy=False), present.copy()
    if k in "iuf":
        x = data.astype(np.float64, copy=False)
        with np.errstate(invalid="ignore"):
            one = x == 1.0
            ok = present & (one | (x == 0.0))
        return one, ok
    objs = _objects(data)
    v = np.zeros(len(data), bool)
    ok = np.zeros(len(data), bool)
    for i in np.flatnonzero(present):
        b = as_bool(objs[i])
        if b is not None:
            v[i] = b
            ok[i] = True
    return v, ok


def read_inputs(plan, columns: Mapping[str, Any], length: int | None = None, *,
                max_age_s: float | None = None) -> Inputs:
    """Convert the columns a plan reads; missing columns are missing inputs on every cycle.

    ``max_age_s`` is the age limit when the spec sets none (as ``Monitor(max_age_s=...)``).
    """
    if not isinstance(columns, Mapping):
        raise TypeError(f"columns must be a mapping of column name to values, got {type(columns).__name__}")
    r = plan.risk_plan  # the whole risk rule, resolved once by the plan
    max_age = r.max_age_s if r.max_age_s is not None else max_age_s
    wanted = [s.name for s in plan.signals] + list(RISK_KEYS)
    if max_age is not None:
        wanted.append("risk_age_s")
    n = length
    if n is not None and (not isinstance(n, int) or isinstance(n, bool) or n < 0):
        raise ValueError(f"length must be a whole number >= 0, got {n!r}")
    cols: dict[str, tuple[np.ndarray, np.ndarray]] = {}
    for name in wanted:
        if name in columns and columns[name] is not None:
            data, present, n = _column(name, columns[name], n, two_d=(name == "p"))
            cols[name] = (data, present)
    if n is None:
        raise ValueError("the trace has none of the columns the spec reads, so its length is unknown "
                         f"(columns read: {', '.join(wanted)}); pass length=")
    inp = Inputs(n)
    inp.cols = cols
    absent = (np.zeros(0), np.zeros(n, bool))
    bad = np.zeros(n, bool)
    for s in plan.signals:
        data, present = cols.get(s.name, absent)
        if s.kind == "bool":
            v, ok = _bools(data, present) if s.name in cols else (np.zeros(n, bool), present)
        else:
            v, ok = _numbers(data, present, s.lo, s.hi) if s.name in cols else (np.zeros(n), present)
        inp.values[s.name] = v
        inp.ok[s.name] = ok
        bad |= ~ok
    _risk(inp, cols, r)
    if max_age is not None:
        data, present = cols.get("risk_age_s", absent)
        if "risk_age_s" in cols:
            _, inp.age_ok = _numbers(data, present, 0.0, float(max_age))
        else:
            inp.age_ok = np.zeros(n, bool)
    inp.input_fault = bad | ~inp.risk_ok | ~inp.age_ok
    return inp


def _risk(inp: Inputs, cols, r) -> None:
    """R_e per cycle, from the first of ``risk``, ``p_unsafe``, ``p`` present that cycle (as ``Monitor._risk``)."""
    n = inp.n
    lo, hi = r.accepted  # the plan's RiskPlan: the range the monitor accepts, written once
    alpha, beta, gamma = float(r.alpha), float(r.beta), float(r.gamma)
    sample = r.variance == "sample"
    k = int(r.classes)
    taken = np.zeros(n, bool)  # a risk input was present (earlier keys win, even when unusable)
    value = np.full(n, np.nan)
    ok = np.zeros(n, bool)
    if "risk" in cols:
        data, present = cols["risk"]
        x, good = _numbers(data, present, lo, hi)
        value = np.where(good, x, value)
        ok |= good
        taken |= present
    if "p_unsafe" in cols:
        data, present = cols["p_unsafe"]
        use = present & ~taken
        if k == 2 and use.any():
            q, good = _numbers(data, use, 0.0, 1.0)
            with np.errstate(all="ignore"):
                re = two_class_risk(q, alpha, beta, gamma, "sample" if sample else "population", where=np.where)
            value = np.where(good, re, value)
            ok |= good
        taken |= use
    if "p" in cols:
        data, present = cols["p"]
        use = present & ~taken
        if use.any():
            re, good = _probs(data, use, k, alpha, beta, gamma, sample, int(r.unsafe_index))
            value = np.where(good, re, value)
            ok |= good
    with np.errstate(invalid="ignore"):
        ok &= np.isfinite(value)  # the monitor never trusts a non-finite R_e
    inp.risk = np.where(ok, value, np.nan)
    inp.risk_ok = ok


def _probs(data: np.ndarray, use: np.ndarray, k: int, alpha: float, beta: float, gamma: float,
           sample: bool, uidx: int) -> tuple[np.ndarray, np.ndarray]:
    """R_e from ``p`` on the cycles in ``use``: vectorised for a 2-d float array, else row by row."""
    n = len(use)
    if data.ndim == 2 and data.dtype.kind in "iuf":
        if data.shape[1] != k:
            return np.full(n, np.nan), np.zeros(n, bool)
        p = data.astype(np.float64, copy=False)
        with np.errstate(all="ignore"):
            good = use & np.isfinite(p).all(axis=1) & ((p >= 0.0) & (p <= 1.0)).all(axis=1)
            total = np.zeros(n)
            top = np.full(n, -np.inf)
            for j in range(k):  # the same order of operations as risk_from_probs
                v = p[:, j]
                total = total + v
                top = np.where(v > top, v, top)
            good &= np.abs(total - 1.0) <= 1e-3
            mean = total / k
            ss = np.zeros(n)
            for j in range(k):
                dv = p[:, j] - mean
                ss = ss + dv * dv
            var = ss / (k - 1) if sample else ss / k
            re = alpha * p[:, uidx] + beta * (1.0 - top) + gamma * var
        return re, good
    if data.ndim == 2:  # a boolean matrix: each row is a list of bools (not numbers)
        return np.full(n, np.nan), np.zeros(n, bool)
    objs = _objects(data)
    re = np.full(n, np.nan)
    good = np.zeros(n, bool)
    variance = "sample" if sample else "population"
    for i in np.flatnonzero(use):
        probs, why = as_probs(objs[i], k)
        if why is None:
            re[i] = risk_from_probs(probs, alpha, beta, gamma, variance, uidx)
            good[i] = True
    return re, good


def row(inp: Inputs, t: int) -> dict[str, Any]:
    """The inputs of cycle ``t`` exactly as ``Monitor.step`` is given them (missing keys left out)."""
    out: dict[str, Any] = {}
    for name, (data, present) in inp.cols.items():
        if not present[t]:
            continue
        v = data[t]
        if data.dtype.kind == "O":
            out[name] = v
        elif data.ndim == 2:
            out[name] = v.tolist()
        else:
            out[name] = v.item()
    return out
