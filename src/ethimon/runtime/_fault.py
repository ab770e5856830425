"""Why a cycle failed closed, as a value: ``Fault(kind, message)``.

``kind`` is one of a closed set of short names (:data:`FAULT_KINDS`), for code
that reacts to faults (``f.kind == "stale"``); ``message`` is the one line a
person reads. A fault is never parsed back out of its text.
"""

from __future__ import annotations

__all__ = ["FAULT_KINDS", "Fault"]

#: every kind a :class:`Fault` can have, with what it means
FAULT_KINDS: dict[str, str] = {
    "missing": "a required input is absent (a signal, the risk input, risk_age_s)",
    "invalid": "an input is not a usable value (wrong type, NaN/inf, malformed p, p_unsafe with K != 2)",
    "range": "a number lies outside its declared or reachable range",
    "stale": "the risk estimate (or a live source's signal) is older than its age limit, or its age is not a "
             "valid number",
    "estimator": "the risk estimator raised, hung, died, or has no estimate for the current task text",
    "signals": "the signal source raised, none was given, or it reported a fault of its own (a foreign "
               "publisher on a monitored topic)",
    "deadline": "the control cycle missed its deadline",
    "stall": "the control loop stalled between cycles (or the watchdog fired)",
    "audit": "the audit log is unusable, behind its lag bounds, or refused a record",
    "callback": "a user callback (on_decision) raised",
    "reload": "an override latched before a spec reload is carried over",
    "internal": "an error inside the monitor (fails closed, never raises)",
    "external": "a reason given to Monitor.fault() as plain text",
}


class Fault:
    """One fail-closed reason of a :class:`~ethimon.Decision`.

    Attributes:
        kind: one of :data:`FAULT_KINDS` (``"missing"``, ``"stale"``, ...).
        message: the human-readable reason (``str(fault)`` gives it too).
        subject: the input the fault is about (a signal name, ``"risk"``,
            ``"risk_age_s"``), or ``""``. Code that tracks *which* input failed
            (the audit log's state changes) uses ``(kind, subject)``, never the text.

    Immutable, compared and hashed by ``(kind, message)``. It is deliberately
    not a string: ``"stale" in fault`` raises instead of matching text; test
    ``fault.kind``.

    Example:
        >>> f = Fault("stale", "risk estimate is stale: 0.612 s > 0.5 s")
        >>> f.kind, str(f)
        ('stale', 'risk estimate is stale: 0.612 s > 0.5 s')
    """

    __slots__ = ("kind", "message", "subject")
    kind: str
    message: str
    subject: str

    def __init__(self, kind: str, message: str, subject: str = "") -> None:
        if kind not in FAULT_KINDS:
            raise ValueError(f"fault kind {kind!r} is not one of {sorted(FAULT_KINDS)}")
        object.__setattr__(self, "kind", kind)
        object.__setattr__(self, "message", str(message))
        object.__setattr__(self, "subject", str(subject))

    def __setattr__(self, name: str, value: object) -> None:
        raise AttributeError("Fault is immutable")

    def __delattr__(self, name: str) -> None:
        raise AttributeError("Fault is immutable")

    def __eq__(self, other: object) -> bool:
        if type(other) is not Fault:
            return NotImplemented
        return self.kind == other.kind and self.message == other.message and self.subject == other.subject

    def __hash__(self) -> int:
        return hash((self.kind, self.message, self.subject))

    def __str__(self) -> str:
        return self.message

    def __repr__(self) -> str:
        if self.subject:
            return f"Fault({self.kind!r}, {self.message!r}, subject={self.subject!r})"
        return f"Fault({self.kind!r}, {self.message!r})"

    def __reduce__(self):
        return (Fault, (self.kind, self.message, self.subject))

    def as_dict(self) -> dict:
        """``{"kind": ..., "message": ..., "subject": ...}`` (JSON-ready)."""
        return {"kind": self.kind, "message": self.message, "subject": self.subject}
