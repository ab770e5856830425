"""Times in seconds made whole cycles at the spec's ``rate_hz``: ``within_s``, ``hold_s`` (here, when a
spec is validated) and the windows ``held(e, 0.5 s)`` (by the compiler, with :func:`seconds_to_cycles`).

A time must be a whole number of cycles at the stated rate, up to float noise (a relative
``WHOLE_TOL``: 0.05 s at 100 Hz is 5 cycles); anything else, or a time in a spec that states no rate,
is refused where it is written, with the nearest whole times as the hint. The loaded spec then holds
the counts every consumer reads (``within_cycles``, ``hold_cycles``) beside the seconds written.
"""

from __future__ import annotations

import math
from typing import Any

from ._errors import _LocError

__all__ = ["seconds_to_cycles", "resolve_seconds", "WHOLE_TOL"]

#: relative tolerance for float noise when seconds are made cycles (0.07 s × 100 Hz = 7.000000000000001)
WHOLE_TOL = 1e-9


def _g(x: float) -> str:
    return f"{x:.10g}"


def seconds_to_cycles(seconds: float, rate_hz: float | None, what: str) -> int:
    """``seconds`` at ``rate_hz`` as a whole number of cycles (``round(seconds * rate_hz)``).

    Raises:
        ValueError: no ``rate_hz``, or not a whole number of cycles; its ``msg`` names ``what``
            and its ``hint`` says what to write (the nearest whole times); its ``loc`` is empty,
            the caller knows where the time is written.

    Example:
        >>> seconds_to_cycles(0.05, 100.0, "a window")
        5
    """
    if rate_hz is None:
        raise _LocError(f"{what} is written in seconds ({_g(seconds)} s), but the spec states no rate_hz", (),
                        hint="state rate_hz: the control rate in Hz the spec is written for (top level, e.g. "
                        "'rate_hz: 100'), or count cycles instead")
    exact = seconds * rate_hz
    n = round(exact)
    if abs(exact - n) > WHOLE_TOL * max(1.0, abs(exact)):
        lo = math.floor(exact)
        near = " or ".join(f"{_g(k / rate_hz)} s ({k} cycle{'s' if k != 1 else ''})" for k in (lo, lo + 1) if k >= 1)
        cycle = f"a cycle is {_g(1 / rate_hz)} s at {_g(rate_hz)} Hz"
        raise _LocError(f"{what} is {_g(seconds)} s, {_g(exact)} cycles at rate_hz {_g(rate_hz)}: not a whole "
                        "number of cycles", (), hint=f"{cycle}; write {near}" if near else cycle)
    return int(n)


def _cycles(seconds: float, rate: float | None, what: str, loc: tuple) -> int:
    try:
        return seconds_to_cycles(seconds, rate, what)
    except _LocError as exc:
        raise _LocError(exc.msg, loc, hint=exc.hint) from None


def resolve_seconds(spec: Any) -> dict[str, Any]:  # a language.Spec (its validator calls this: no import back)
    """The fields of ``spec`` whose times in seconds are made counts: ``{field name: new value}``
    (empty when the spec writes no ``within_s``/``hold_s``); the spec's validator sets them.

    Raises:
        ValueError (``_LocError``): at the time that is not whole cycles, or has no rate.
    """
    rate = spec.rate_hz
    out: dict[str, Any] = {}
    obs = list(spec.obligations)
    for i, ob in enumerate(obs):
        update: dict[str, Any] = {}
        if ob.within_s is not None:
            loc = ("obligations", i, "within_s")
            n = _cycles(ob.within_s, rate, f"within_s of obligation {ob.id!r}", loc)
            if n > 1_000_000:
                raise _LocError(f"within_s {_g(ob.within_s)} s is {n} cycles: at most 1000000", loc)
            if ob.within_cycles is not None and ob.within_cycles != n:
                raise _LocError(f"obligation {ob.id!r} gives within_cycles {ob.within_cycles} and within_s "
                                f"{_g(ob.within_s)} s ({n} cycles at {_g(rate)} Hz)", loc,  # type: ignore[arg-type]
                                hint="give one of within_cycles and within_s")
            update["within_cycles"] = n
        rel = _hold(ob.release, rate, ("obligations", i, "release"), f"obligation {ob.id!r}")
        if rel is not ob.release:
            update["release"] = rel
        if update:
            obs[i] = ob.model_copy(update=update)
            out["obligations"] = tuple(obs)
    rel = _hold(spec.risk.release, rate, ("risk", "release"), "risk")
    if rel is not spec.risk.release:
        out["risk"] = spec.risk.model_copy(update={"release": rel})
    rel = _hold(spec.fault_policy.release, rate, ("on_fault", "release"), "on_fault")
    if rel is not spec.fault_policy.release:
        out["fault_policy"] = spec.fault_policy.model_copy(update={"release": rel})
    return out


def _hold(rel: Any, rate: float | None, loc: tuple, who: str) -> Any:
    """``rel`` with its ``hold_s`` made ``hold_cycles`` (``rel`` itself when it has no ``hold_s``)."""
    if rel is None or rel.hold_s is None:
        return rel
    loc = loc + ("hold_s",)
    n = _cycles(rel.hold_s, rate, f"the release hold_s of {who}", loc)
    if not 1 <= n <= 10_000_000:
        raise _LocError(f"the release hold_s of {who}, {_g(rel.hold_s)} s, is {n} cycles: expected 1 to 10000000",
                        loc)
    if "hold_cycles" in rel.model_fields_set and rel.hold_cycles != n:
        raise _LocError(f"the release of {who} gives hold_cycles {rel.hold_cycles} and hold_s {_g(rel.hold_s)} s "
                        f"({n} cycles at {_g(rate)} Hz)", loc, hint="give one of hold_cycles and hold_s")  # type: ignore[arg-type]
    return rel.model_copy(update={"hold_cycles": n})
