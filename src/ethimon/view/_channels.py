"""The verdict channels: one set of topic names, JSON Schemas and messages for the ``--mcap`` verdict file
and the live Foxglove server, so that one Foxglove layout serves both.

Every channel is JSON-encoded with a JSON Schema (``jsonschema``). Topics:

* ``/ethimon/decision``: ``cycle``, ``override``, ``response``, ``violations``, ``fault``, ``latched``,
  ``latched_rules`` (the rules whose latch holds the override, by name), ``awaiting_release``
* ``/ethimon/margins``: one number per obligation, by its id (``null`` where not evaluated)
* ``/ethimon/risk``: ``R_e`` (``null``: no usable risk input, or not checked), ``tau``, ``tau_confirm``
  (``null``: no confirm band), ``checked``, ``band`` (``"below"``, ``"confirm"``: in
  [τ_confirm, τ), ``"above"``: R_e ≥ τ, ``null``: no R_e), ``judge`` (the judge's p_unsafe of the task
  text, ``null``: none), ``confirm_hold`` / ``judge_hold`` (the confirm band's or the judge's latch holds)
* ``/ethimon/faults``: ``faults``, each ``kind``, ``message``, ``subject`` (the MCAP file: when they change,
  ``[]`` when they clear; live: every cycle)
* ``/ethimon/inputs/<signal>``: ``value``, the input the monitor read (``null``: missing or stale)

Numbers are strict JSON: NaN is ``null``, ±inf the strings ``"inf"``/``"-inf"``. Standard library only.
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterable, Mapping, Sequence
from typing import Any

__all__ = ["DECISION", "FAULTS", "INPUTS", "MARGINS", "RISK", "TOPICS", "VerdictChannels", "num"]

DECISION = "/ethimon/decision"
MARGINS = "/ethimon/margins"
RISK = "/ethimon/risk"
FAULTS = "/ethimon/faults"
INPUTS = "/ethimon/inputs/"  # + the signal's name
TOPICS = (DECISION, MARGINS, RISK, FAULTS)

_NUM = {"type": ["number", "string", "null"]}
_STRS = {"type": "array", "items": {"type": "string"}}


def num(x: Any) -> float | str | None:
    """A value as a strict-JSON number: NaN, ``None`` or a non-number → ``None``, ±inf → ``"inf"``/``"-inf"``."""
    if x is None:
        return None
    try:
        f = float(x)
    except (TypeError, ValueError, OverflowError):
        return None
    if f != f:
        return None
    if math.isinf(f):
        return "inf" if f > 0 else "-inf"
    return f


def _schema(title: str, props: dict[str, Any]) -> bytes:
    return json.dumps({"$schema": "https://json-schema.org/draft/2020-12/schema", "title": title,
                       "type": "object", "properties": props}).encode()


class VerdictChannels:
    """The channels of one spec (its obligation ids, its mapped inputs, τ and τ_confirm) and the
    messages of one cycle, as plain dicts.

    Args:
        ids: the obligation ids (``Monitor.obligation_ids``), the keys of the margins message.
        inputs: the input signals to publish, one channel each.
        tau: the spec's τ (``risk.threshold``); ``tau_confirm``: ``risk.confirm_threshold`` or ``None``.
        checked: whether R_e is checked (``False``: a replay whose risk rule was not checked).
    """

    def __init__(self, ids: Sequence[str], inputs: Iterable[str], tau: float, tau_confirm: float | None,
                 checked: bool = True) -> None:
        self.ids = tuple(ids)
        self.inputs = tuple(inputs)
        self.tau = float(tau)
        self.tau_confirm = None if tau_confirm is None else float(tau_confirm)
        self.checked = bool(checked)

    @classmethod
    def of_spec(cls, spec: Any, ids: Sequence[str], inputs: Iterable[str] | None = None,
                checked: bool = True) -> VerdictChannels:
        """The channels of ``spec`` (a :class:`~ethimon.language.Spec`); ``inputs``: its signals by default."""
        from ..compiler import plan_of
        plan = plan_of(spec)
        return cls(ids, spec.signals if inputs is None else inputs, plan.risk_plan.threshold,
                   plan.tiers.confirm_threshold, checked)

    def schemas(self) -> list[tuple[str, str, bytes]]:
        """``(topic, schema name, JSON Schema)`` of every channel, the inputs last."""
        out = [
            (DECISION, "ethimon.Decision", _schema("ethimon.Decision", {
                "cycle": {"type": "integer"}, "override": {"type": "boolean"}, "response": {"type": "string"},
                "violations": _STRS, "fault": {"type": "boolean"}, "latched": {"type": "boolean"},
                "latched_rules": _STRS, "awaiting_release": {"type": "boolean"}})),
            (MARGINS, "ethimon.Margins", _schema("ethimon.Margins", {oid: _NUM for oid in self.ids})),
            (RISK, "ethimon.Risk", _schema("ethimon.Risk", {
                "R_e": _NUM, "tau": {"type": "number"}, "tau_confirm": {"type": ["number", "null"]},
                "checked": {"type": "boolean"}, "band": {"type": ["string", "null"]}, "judge": _NUM,
                "confirm_hold": {"type": "boolean"}, "judge_hold": {"type": "boolean"}})),
            (FAULTS, "ethimon.Faults", _schema("ethimon.Faults", {"faults": {"type": "array", "items": {
                "type": "object", "properties": {"kind": {"type": "string"}, "message": {"type": "string"},
                                                 "subject": {"type": ["string", "null"]}}}}})),
        ]
        inp = _schema("ethimon.Input", {"value": _NUM})
        out += [(INPUTS + name, "ethimon.Input", inp) for name in self.inputs]
        return out

    # -- the messages of one cycle -------------------------------------------------------------
    @staticmethod
    def decision(cycle: int, override: bool, response: str, violations: Sequence[str], fault: bool,
                 latched: bool, latched_rules: Sequence[str], awaiting_release: bool = False) -> dict:
        return {"cycle": int(cycle), "override": bool(override), "response": response if override else "none",
                "violations": list(violations), "fault": bool(fault), "latched": bool(latched),
                "latched_rules": list(latched_rules), "awaiting_release": bool(awaiting_release)}

    def margins(self, values: Sequence[float], ids: Sequence[str] | None = None) -> dict:
        """``ids``: the names of ``values`` when not this spec's (a decision's own, after a reload)."""
        ids = ids or self.ids
        if not values:
            return {oid: None for oid in ids}
        return {oid: num(m) for oid, m in zip(ids, values)}

    def risk(self, r: float | None, held: Sequence[str] = (), judge: float | None = None) -> dict:
        """``r``: this cycle's R_e (``None``: none); ``held``: the rules holding the override (``judge``,
        ``confirm`` among them); ``judge``: the judge's p_unsafe of the task text, if any."""
        f = num(r) if self.checked else None
        band = None
        if isinstance(f, float):
            band = "above" if f >= self.tau else (
                "confirm" if self.tau_confirm is not None and f >= self.tau_confirm else "below")
        return {"R_e": f, "tau": self.tau, "tau_confirm": self.tau_confirm, "checked": self.checked,
                "band": band, "judge": num(judge), "confirm_hold": "confirm" in held, "judge_hold": "judge" in held}

    @staticmethod
    def faults(faults: Iterable[Any]) -> dict:
        return {"faults": [{"kind": str(getattr(x, "kind", "fault")), "message": str(getattr(x, "message", x)),
                            "subject": getattr(x, "subject", None)} for x in faults]}

    def input_values(self, values: Mapping[str, Any]) -> list[tuple[str, dict]]:
        """``(topic, message)`` of each input channel (``null`` for a signal absent from ``values``)."""
        get = values.get
        return [(INPUTS + name, {"value": num(get(name))}) for name in self.inputs]

    def messages(self, cycle: int, override: bool, response: str, violations: Sequence[str], fault: bool,
                 latched: bool, held: Sequence[str], margins: Sequence[float], r: float | None,
                 judge: float | None, inputs: Mapping[str, Any], awaiting_release: bool = False,
                 ids: Sequence[str] | None = None) -> list[tuple[str, dict]]:
        """The messages of one cycle but its faults (decision, margins, risk, then the inputs):
        ``held`` the rules whose latch holds the override, ``inputs`` the values the monitor read."""
        return [(DECISION, self.decision(cycle, override, response, violations, fault, latched, held,
                                         awaiting_release)),
                (MARGINS, self.margins(margins, ids)),
                (RISK, self.risk(r, held, judge))] + self.input_values(inputs)

    def of_decision(self, d: Any, inputs: Mapping[str, Any]) -> list[tuple[str, dict]]:
        """Every message of one live cycle: ``d`` a :class:`~ethimon.runtime.Decision`, ``inputs`` the
        values the monitor read (the judge's verdict, if any, under ``"judge"``). Live, the faults
        message is sent every cycle (a viewer that joins late sees them at once)."""
        out = self.messages(d.cycle, d.override, d.response.value, d.violations, bool(d.faults), d.latched,
                            d.latched_rules, d.margins, d.risk, inputs.get("judge"), inputs, d.awaiting_release,
                            d.ids)
        out.insert(3, (FAULTS, self.faults(d.faults)))
        return out
