"""A small unit algebra for compile-time dimensional checks.

Units are products of named base symbols with integer exponents, e.g.
``m/s^2`` is ``{m: 1, s: -2}``. Symbols are opaque (``N`` is not expanded to
``kg*m/s^2``); there is no scaling between units, so ``mm`` and ``m`` are
different units and mixing them is an error, which is the point.
``None`` means "unknown" (a bare literal or an undeclared unit) and is
compatible with anything.
"""

from __future__ import annotations

import re

__all__ = ["Unit", "parse_unit", "format_unit", "mul", "div", "sqrt_unit", "DIMENSIONLESS"]

Unit = tuple[tuple[str, int], ...]  # sorted (symbol, exponent) pairs; () is dimensionless
DIMENSIONLESS: Unit = ()

_FACTOR = re.compile(r"^\s*([A-Za-z_%°][A-Za-z0-9_%°]*)\s*(?:\^\s*(-?\d+))?\s*$")


def parse_unit(text: str | None) -> Unit | None:
    """Parse ``"m/s^2"``, ``"N*m"``, ``"rad/s"``, ``"1"`` or ``""``.

    Raises:
        ValueError: unreadable unit text.

    Example:
        >>> parse_unit("kg*m/s^2")
        (('kg', 1), ('m', 1), ('s', -2))
    """
    if text is None:
        return None
    t = text.strip()
    if t in ("", "1", "-"):
        return DIMENSIONLESS
    exps: dict[str, int] = {}
    num_den = t.split("/")
    if len(num_den) > 2:
        raise ValueError(f"unit {text!r} has more than one '/'; write e.g. 'm/s^2' or 'm/(s*s)' as 'm/s^2'")
    for sign, part in zip((1, -1), num_den):
        part = part.strip()
        if part.startswith("(") and part.endswith(")"):
            part = part[1:-1]
        if part in ("", "1") and sign == 1:
            continue
        for factor in part.split("*"):
            m = _FACTOR.match(factor)
            if not m:
                raise ValueError(f"cannot read unit {text!r} (at {factor.strip()!r})")
            sym, exp = m.group(1), int(m.group(2) or 1)
            exps[sym] = exps.get(sym, 0) + sign * exp
    return tuple(sorted((k, v) for k, v in exps.items() if v != 0))


def format_unit(u: Unit | None) -> str:
    """Render a unit back to text (``"1"`` for dimensionless)."""
    if u is None:
        return "?"
    if not u:
        return "1"
    num = [s if e == 1 else f"{s}^{e}" for s, e in u if e > 0]
    den = [s if e == -1 else f"{s}^{-e}" for s, e in u if e < 0]
    out = "*".join(num) or "1"
    if den:
        out += "/" + "*".join(den)
    return out


def _combine(a: Unit, b: Unit, sign: int) -> Unit:
    exps = dict(a)
    for s, e in b:
        exps[s] = exps.get(s, 0) + sign * e
    return tuple(sorted((k, v) for k, v in exps.items() if v != 0))


def mul(a: Unit | None, b: Unit | None) -> Unit | None:
    """Unit of a product (unknown if either is unknown)."""
    return None if a is None or b is None else _combine(a, b, 1)


def div(a: Unit | None, b: Unit | None) -> Unit | None:
    """Unit of a quotient (unknown if either is unknown)."""
    return None if a is None or b is None else _combine(a, b, -1)


def sqrt_unit(a: Unit | None) -> Unit | None:
    """Unit of a square root, or raises ValueError for odd exponents."""
    if a is None:
        return None
    if any(e % 2 for _, e in a):
        raise ValueError(f"square root of '{format_unit(a)}' has no whole-number unit")
    return tuple((s, e // 2) for s, e in a)
