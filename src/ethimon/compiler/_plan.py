"""The Plan: the checked, resolved form of a spec that every later consumer reads.

The runtime monitor builds its closures from it, the reference interpreter walks it, the offline
checker vectorises it and ``ethimon verify`` translates it to SMT. Every rule's release (mode, hold),
severity and the risk rule's τ and exact release cut are resolved here once, by
:func:`~ethimon.compiler.compile_plan` (``compiler/_typecheck.py``), so no consumer re-reads them
from the :class:`~ethimon.Spec`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from functools import cached_property

from ..language._expr import Call, Node
from ..language import Response, Spec
from ._risk_formula import risk_range
from ._units import Unit, format_unit

__all__ = ["Plan", "ObligationPlan", "SignalSlot", "LatchRule", "RiskPlan", "Tiers", "JudgePlan", "EstimatorPlan",
           "RestartPlan", "Ty", "BOOL", "Annotation", "RISK_NAME", "MAX_WINDOW"]

RISK_NAME = "risk"
MAX_WINDOW = 1_000_000


@dataclass(frozen=True)
class Ty:
    """Type of an expression: ``bool`` or ``num`` with a unit (``None`` = unknown)."""

    kind: str  # "bool" | "num"
    unit: Unit | None = None

    def show(self) -> str:
        return "a boolean" if self.kind == "bool" else f"a number [{format_unit(self.unit)}]"


BOOL = Ty("bool")


@dataclass(frozen=True)
class Annotation:
    """What the checker found out about one expression node, set on it once (``node.ann``).

    The checked tree of a :class:`Plan` carries these; every consumer (closures, reference,
    offline, z3, the float bounds) reads them from the node, never from a table keyed by ``id()``.

    Attributes:
        ty: the node's type, with its unit where known (:class:`Ty`).
        value: the value of a constant numeric subexpression (folded by the checker), else ``None``.
        window: a temporal node's bound in cycles (``prev``: 1; an unbounded ``since``: ``None``),
            a window written in seconds already its whole cycles at ``rate_hz``; ``None`` elsewhere.
        seconds: the seconds the author wrote for a window in time (``held(e, 0.5 s)``, or a
            constant in s), for printers; else ``None``.
        slot: a temporal node's index in :attr:`Plan.temporal` (its state's slot), else ``None``.
        serial: the node's number in its plan (the order the checker met it), unique within the
            plan: what names a node's z3 terms (``sqrt#7@3``), the same in every encoding of the plan.
    """

    ty: Ty
    value: float | None = None
    window: int | None = None
    seconds: float | None = None
    slot: int | None = None
    serial: int = -1


@dataclass(frozen=True)
class SignalSlot:
    """A declared signal resolved to an input slot."""

    name: str
    slot: int
    kind: str  # "number" | "bool"
    lo: float
    hi: float
    unit: Unit | None


@dataclass(frozen=True)
class LatchRule:
    """One rule's latch, resolved once (defaults filled in): what it does and how it releases.

    (Not the spec's ``release:`` block of a rule, :class:`ethimon.language.RuleRelease`, from which
    it is resolved: this is its compiled form, one per latch of the monitor.)

    Attributes:
        name: the rule: an obligation id, ``"risk"``, ``"fault"``, ``"judge"`` or ``"confirm"``.
        response: its response while latched.
        manual: released only by ``Monitor.acknowledge()`` (else after ``hold`` good cycles).
        hold: N, the consecutive cycles its release condition must hold.
    """

    name: str
    response: Response
    manual: bool
    hold: int

    @property
    def severity(self) -> int:
        return self.response.severity

    @property
    def mode(self) -> str:
        """``"manual"`` or ``"auto"``, as the spec writes it."""
        return "manual" if self.manual else "auto"


@dataclass(frozen=True)
class RiskPlan:
    """The whole risk rule, resolved once: what the monitor reads of R_e and how it judges it.

    Attributes:
        threshold: τ, the rule fires at ``R_e >= threshold``.
        release_exact: the exact release bound τ − δ (the spec's decimals, as a fraction).
        release_cut: its float test: a float R_e is below τ − δ exactly when ``R_e < release_cut``.
        alpha, beta, gamma: the formula's weights (R_e = α·p_unsafe + β·(1 − max p) + γ·Var(p)).
        classes: K, the classifier's number of classes.
        unsafe_index: the index of the unsafe class in ``p``.
        variance: ``"sample"`` or ``"population"``.
        max_age_s: the spec's ``risk.max_age_s`` (``None``: the caller's limit, or none).
        latch: the rule's latch (:class:`LatchRule`: response, manual, hold).
        hysteresis: δ as written (``risk.release.hysteresis``; :attr:`release_exact` is τ − δ exactly).
    """

    threshold: float
    release_exact: Fraction
    release_cut: float
    alpha: float
    beta: float
    gamma: float
    classes: int
    unsafe_index: int
    variance: str
    max_age_s: float | None
    latch: "LatchRule"
    hysteresis: float

    @cached_property
    def reachable(self) -> tuple[float, float]:
        """The exact ``(lo, hi)`` of R_e over every probability vector (``risk_range``; computed on
        first use and kept: it takes seconds for hundreds of classes)."""
        return risk_range(self.alpha, self.beta, self.gamma, self.variance, self.classes)

    @cached_property
    def accepted(self) -> tuple[float, float]:
        """The ``risk`` inputs the monitor accepts: ``(min(0, lo), max(1, hi))`` of :attr:`reachable`,
        the one place this range is written."""
        lo, hi = self.reachable
        return min(0.0, lo), max(1.0, hi)


@dataclass(frozen=True)
class JudgePlan:
    """One judge's client settings, resolved once (``risk.judge``, or one of ``risk.judges``).

    Attributes:
        where: where the spec writes it: ``"risk.judge"`` or ``"risk.judges[k]"`` (for messages).
        url, model, timeout_s, api_key_env, prompt: the server, the model it serves, the time limit,
            the key variable the spec names (the operator's must match) and the rubric (``None``: built in).
        safe_below, unsafe_from: this judge's own cuts on its p_unsafe.
        canaries_path: the spec's own canary CSV as written (relative to the spec file), or ``None``.
        canaries_every_s, canaries_every_texts: when the canaries are asked again.
    """

    where: str
    url: str
    model: str
    timeout_s: float
    api_key_env: str | None
    prompt: str | None
    safe_below: float
    unsafe_from: float
    canaries_path: str | None
    canaries_every_s: float
    canaries_every_texts: int


@dataclass(frozen=True)
class EstimatorPlan:
    """Which learned model scores task texts for the spec, and how (``risk.estimator``, defaults filled in).

    Not part of the risk rule (the monitor only reads its inputs): the loaders read it
    (``ethimon.risk.load_estimator_for``), and a reload compares it.

    Attributes:
        model: the model directory as written (relative to the spec file), ``None``: the shipped default.
        quantize, temperature, max_length, backend: as :class:`ethimon.language.EstimatorConfig` says.
    """

    model: str | None
    quantize: str | None
    temperature: float | None
    max_length: int | None
    backend: str


@dataclass(frozen=True)
class RestartPlan:
    """The spec's ``restart:`` block (GovernedLoop gates restarts only with one).

    Attributes:
        start: ``"command"`` or the bool input whose rising edge starts motion.
        standstill: the bool input reporting a completed stop, or ``None``.
    """

    start: str
    standstill: str | None


@dataclass(frozen=True)
class Tiers:
    """The tiers of the risk rule, resolved once (all ``None``: none; the monitor then runs without them).

    Attributes:
        confirm_threshold: the confirm band's lower edge (``risk.confirm_threshold``): a person
            confirms a text with ``confirm_threshold <= R_e < τ``.
        judge_cuts: ``(safe_below, unsafe_from)`` applied to the ``judge`` input (one judge's, or the
            strictest of several in consensus).
        hold_ceiling: ``risk.judge_may_hold_above_tau``'s ceiling, only with a judge: a safe verdict
            turns ``τ <= R_e < ceiling`` into a confirm hold.
        judges: every judge's client settings (:class:`JudgePlan`), in the spec's order (empty: none).
        consensus: the spec writes ``risk.judges`` (a panel, even of one) rather than ``risk.judge``.
    """

    confirm_threshold: float | None = None
    judge_cuts: tuple[float, float] | None = None
    hold_ceiling: float | None = None
    judges: tuple[JudgePlan, ...] = ()
    consensus: bool = False

    @property
    def on(self) -> bool:
        """Whether the spec has a tier (a confirm band or a judge)."""
        return self.confirm_threshold is not None or self.judge_cuts is not None


@dataclass(frozen=True)
class ObligationPlan:
    """A checked obligation: ``when ⇒ require`` with optional bounded response."""

    index: int
    id: str
    description: str
    when: Node | None
    require: Node
    within_cycles: int | None
    response: Response
    when_text: str | None
    require_text: str
    #: ``"auto"`` or ``"manual"``: how this rule's latch is released (defaults filled in)
    release_mode: str = "auto"
    #: N: the obligation must hold N consecutive valid cycles before its latch releases
    release_hold: int = 10

    @property
    def manual(self) -> bool:
        return self.release_mode == "manual"

    @property
    def rule(self) -> LatchRule:
        """This obligation's latch as a :class:`LatchRule`."""
        return LatchRule(self.id, self.response, self.manual, self.release_hold)


@dataclass(frozen=True)
class Plan:
    """The compiled, checked form of a spec.

    Attributes:
        spec: the spec it came from.
        signals: declared signals in slot order; slot ``len(signals)`` holds R_e.
        risk_slot: the slot index of R_e (``risk`` in expressions).
        constants: constant values by name.
        obligations: checked obligations in spec order.
        temporal: every temporal call node, children before parents (``node.ann.slot`` is its index).
        rate_hz: the spec's stated control rate (``None``: it counts cycles only).
        slots: input slot of every name an expression can read (signals and ``risk``),
            built once here for every consumer (code generation, fault-path evaluation).
        on_fault: the response to a fault.
        threshold: τ, the risk rule fires at ``R_e >= threshold``.
        release_exact: the exact release bound τ − δ (the spec's decimals, as a fraction).
        release_cut: the float test of it: a float R_e is below τ − δ exactly when ``R_e < release_cut``.
        risk_rule, fault_rule: the risk rule's and the fault latch's :class:`LatchRule`.
        risk_plan: the whole risk rule (:class:`RiskPlan`: τ, the exact cut, the weights, K, the
            variance, the accepted range, the max age, its latch), read instead of ``spec.risk``.
        tiers: the confirm band and the judge (:class:`Tiers`, with every judge's settings).
        estimator: the spec's estimator settings (:class:`EstimatorPlan`).
        restart: the spec's ``restart:`` block (:class:`RestartPlan`), ``None`` when it writes none.

    Every node of ``obligations``' trees is annotated (``node.ann``, an :class:`Annotation`: its
    type and unit, a temporal node's window in cycles and the seconds the author wrote, a constant's
    folded value), set once by the checker: the checked tree is frozen too; :meth:`type_of` and
    :meth:`window_of` read it.

    The plan is frozen: built once by :func:`~ethimon.compiler.compile_plan`, never changed.

    Every consumer (monitor, reference, offline, z3, lints) reads releases, holds, severities,
    τ and the cut from here (:meth:`rules`), never again from the spec.

    The plan points at its spec (``spec``, where it came from); the spec carries its plan in a
    private holder that is no part of its value, set once by :func:`~ethimon.compiler.plan_of`.
    Only two things go back from a plan to its spec: :func:`~ethimon.compiler.plan_of` (whether a
    spec's carried plan is its own) and ``Monitor.spec`` (the source a monitor built from a plan
    shows); ``tests/house/test_plan_reads.py`` keeps every other consumer on the plan.
    """

    spec: Spec
    signals: tuple[SignalSlot, ...]
    risk_slot: int
    constants: dict[str, float]
    obligations: tuple[ObligationPlan, ...]
    temporal: tuple[Call, ...]
    rate_hz: float | None = None
    slots: dict[str, int] = field(default_factory=dict)
    on_fault: Response = Response.SAFE_POSE
    # resolved by compile_plan (no second set of defaults here: a plan built without them is refused)
    threshold: float = None  # type: ignore[assignment]
    release_exact: Fraction = None  # type: ignore[assignment]
    release_cut: float = None  # type: ignore[assignment]
    risk_rule: LatchRule = None  # type: ignore[assignment]
    fault_rule: LatchRule = None  # type: ignore[assignment]
    risk_plan: RiskPlan = None  # type: ignore[assignment]
    tiers: Tiers = None  # type: ignore[assignment]
    estimator: EstimatorPlan = None  # type: ignore[assignment]
    restart: RestartPlan | None = None

    def __post_init__(self) -> None:
        missing = [k for k in ("threshold", "release_exact", "release_cut", "risk_rule", "fault_rule", "risk_plan",
                               "tiers", "estimator")
                   if getattr(self, k) is None]
        if missing:
            raise TypeError(f"a Plan is built by compile_plan(spec); missing: {', '.join(missing)}")

    def rules(self) -> tuple[LatchRule, ...]:
        """Every latch in the monitor's order: the obligations, ``risk``, ``fault``, ``judge``
        (the judge's unsafe verdict: the risk rule's response and release) and ``confirm`` (the
        confirm band: stop 2, released automatically, the risk rule's hold). The names are unique
        (the spec reserves the last four as obligation ids)."""
        r = self.risk_rule
        return tuple(ob.rule for ob in self.obligations) + (
            r, self.fault_rule, LatchRule("judge", r.response, r.manual, r.hold),
            LatchRule("confirm", Response.STOP_2, False, r.hold))

    @property
    def manual_rules(self) -> tuple[str, ...]:
        """The rules whose latch waits for ``Monitor.acknowledge()`` (obligation ids, ``risk``, ``fault``)."""
        return tuple([ob.id for ob in self.obligations if ob.manual]
                     + [r.name for r in (self.risk_rule, self.fault_rule) if r.manual])

    def cycles(self, n: int) -> str:
        """``n`` cycles for a person: ``"3 cycles"``, with the time when the spec states its rate:
        ``"3 cycles (0.03 s at 100 Hz)"`` (what a spec written in seconds said)."""
        text = f"{n} cycle{'s' if n != 1 else ''}"
        if self.rate_hz:
            text += f" ({n / self.rate_hz:.10g} s at {self.rate_hz:g} Hz)"
        return text

    @property
    def n_slots(self) -> int:
        return len(self.signals) + 1

    @staticmethod
    def type_of(node: Node) -> Ty:
        """The checked type of ``node`` (its annotation's)."""
        return node.ann.ty

    @staticmethod
    def window_of(node: Node) -> int | None:
        """The window of temporal node ``node`` in cycles (its annotation's; ``None``: unbounded)."""
        return node.ann.window
