"""The spec's own near-human speed rule, as the safe-pose planner needs it (no PyBullet).

A rule of the form ``when: human_distance < D`` / ``require: ee_speed <= V`` (``D`` and
``V`` numbers or the spec's constants; ``<``/``<=`` either way) says how fast the arm may
move near a person. The safe-pose retreat obeys the strictest such rule of the spec.

Example:
    >>> import ethimon
    >>> near_human_speed_rule(ethimon.load_spec("specs/cobot_cell.yaml"))   # doctest: +SKIP
    (1.5, 0.25)
"""

from __future__ import annotations

import re
from typing import Any

__all__ = ["near_human_speed_rule", "near_human_grace_cycles", "retreat_speed_rule",
           "RETREAT_NEAR_HUMAN_DEFAULT"]

#: the safe-pose retreat's own speed limit near people when the spec states none:
#: ``(distance_m, speed_m_s)`` = 0.25 m/s within 1.5 m (ISO 10218-1's reduced speed, 250 mm/s;
#: cobot_cell's slow zone). Issue 32 item 5: a governor-only spec left retreats uncapped.
RETREAT_NEAR_HUMAN_DEFAULT: tuple[float, float] = (1.5, 0.25)

_NUM_OR_NAME = r"([A-Za-z_][A-Za-z0-9_]*|[0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)"
_WHEN = re.compile(rf"^\s*human_distance\s*<=?\s*{_NUM_OR_NAME}\s*$")
_WHEN_REV = re.compile(rf"^\s*{_NUM_OR_NAME}\s*>=?\s*human_distance\s*$")
_REQ = re.compile(rf"^\s*ee_speed\s*<=?\s*{_NUM_OR_NAME}\s*$")


def _value(tok: str, spec: Any) -> float | None:
    try:
        return float(tok)
    except ValueError:
        c = getattr(spec, "constants", {}).get(tok)
        return float(c.value) if c is not None else None


def near_human_speed_rule(spec: Any) -> tuple[float, float] | None:
    """``(distance_m, speed_m_s)`` of the spec's strictest near-human speed rule, or ``None``."""
    best: tuple[float, float] | None = None
    for ob in getattr(spec, "obligations", ()) or ():
        when = getattr(ob, "when", None) or ""
        m = _WHEN.match(when) or _WHEN_REV.match(when)
        r = _REQ.match(getattr(ob, "require", "") or "")
        if not (m and r):
            continue
        d, v = _value(m.group(1), spec), _value(r.group(1), spec)
        if d is None or v is None or d <= 0 or v <= 0:
            continue
        if best is None or v < best[1] or (v == best[1] and d > best[0]):
            best = (max(d, best[0]) if best and v == best[1] else d, v)
    return best


def near_human_grace_cycles(spec: Any) -> int:
    """The longest grace (``within_cycles``) among the spec's near-human speed rules: the cycles
    the monitor lets a breach last before it fires (0 without such a rule)."""
    out = 0
    for ob in getattr(spec, "obligations", ()) or ():
        when = getattr(ob, "when", None) or ""
        if (_WHEN.match(when) or _WHEN_REV.match(when)) and _REQ.match(getattr(ob, "require", "") or ""):
            out = max(out, int(getattr(ob, "within_cycles", 0) or 0))
    return out


def retreat_speed_rule(spec: Any) -> tuple[float, float]:
    """The ``(distance_m, speed_m_s)`` a safe-pose retreat keeps near people: the spec's
    strictest near-human speed rule, else :data:`RETREAT_NEAR_HUMAN_DEFAULT` (a retreat is
    never uncapped near a person; ``ethimon lint`` says so as ``lint.retreat_uncapped``)."""
    return near_human_speed_rule(spec) or RETREAT_NEAR_HUMAN_DEFAULT
