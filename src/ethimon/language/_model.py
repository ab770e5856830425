"""Pydantic models of the spec file format (version 1).

These models validate the *shape* of a spec; names, types and units inside
expressions are checked by the compiler. All models are frozen and reject
unknown keys.

Types are strict: a number field takes a YAML number (an integer is read as
a float), never ``true`` or the text ``'2'``; a whole-number field takes a
YAML integer only (not ``2.0``, ``true`` or ``'2'``); a boolean field takes
``true``/``false`` only.
"""

from __future__ import annotations

import enum
from typing import Annotated, Any, Literal

from pydantic import (BaseModel, ConfigDict, Field, PrivateAttr, ValidationInfo, field_validator,
                      model_validator)

from .._robot import PANDA_HOME_JOINTS_RAD
from ._yaml import SourceMap
from ._errors import FORMAT_VERSION, _LocError  # noqa: F401 - FORMAT_VERSION re-exported

__all__ = [
    "Response", "Signal", "Constant", "Release", "RuleRelease", "OnFault", "RiskConfig", "JudgeConfig",
    "CanaryConfig", "HoldAboveTau",
    "Obligation",
    "SafePose", "Spec", "MANUAL_BY_DEFAULT",
    "FORMAT_VERSION", "RESERVED_INPUTS", "IDENT",
    "RATE_HZ",
]

IDENT = r"^[A-Za-z_][A-Za-z0-9_]*$"
#: step() input keys with a built-in meaning; specs cannot declare them as signals
RESERVED_INPUTS = frozenset({"risk", "p_unsafe", "p", "risk_age_s", "true", "false", "and", "or",
                             "not", "implies", "abs", "min", "max", "sqrt", "prev", "held", "once",
                             "since", "separation_distance", "judge", "task_id"})


class Response(str, enum.Enum):
    """What the arm must do. Ordered by severity: ``none`` < ``safe_pose`` < ``stop_2`` < ``stop_1`` < ``stop_0``.

    * ``safe_pose``: leave the task, drive to the spec's safe pose under its joint-speed limit.
    * ``stop_2``: IEC 60204-1 stop category 2, controlled stop, power kept (held).
    * ``stop_1``: category 1, controlled stop, then power removed.
    * ``stop_0``: category 0, power removed at once (uncontrolled stop).
    """

    NONE = "none"
    SAFE_POSE = "safe_pose"
    STOP_2 = "stop_2"
    STOP_1 = "stop_1"
    STOP_0 = "stop_0"

    @property
    def severity(self) -> int:
        """0 ``none`` .. 4 ``stop_0``: the index in :data:`SEVERITY_ORDER`."""
        return _SEVERITY[self]

    def __str__(self) -> str:
        return self.value


#: The weights of R_e = α·p_unsafe + β·(1 − max p) + γ·Var(p) when a spec sets none (the paper's):
#: ``RiskConfig``'s defaults and the defaults of every function of the formula (``ethimon.risk``).
DEFAULT_ALPHA, DEFAULT_BETA, DEFAULT_GAMMA = 0.6, 0.2, 0.2
#: How Var(p) divides: ``sample`` by K − 1 (torch.var's default), ``population`` by K.
VARIANCE_MODES = ("sample", "population")

#: Every response, least severe first (their declaration order above): the one severity order.
#: ``Response.severity`` is the index here and ``SEVERITY_ORDER[sev]`` the response of a severity;
#: the monitor, the reference interpreter, the offline checker and the simulated arm all read it.
SEVERITY_ORDER: tuple[Response, ...] = tuple(Response)
_SEVERITY = {r: i for i, r in enumerate(SEVERITY_ORDER)}
_RESPONSE_NAMES = tuple(r.value for r in SEVERITY_ORDER[1:])  # the responses of an override
ACTIVE_RESPONSES = Literal[_RESPONSE_NAMES]  # type: ignore[valid-type]

#: the control rates a spec may state (``rate_hz``), the same bounds as a mapping file's
RATE_HZ = (0.1, 100_000.0)
_CFG = ConfigDict(extra="forbid", frozen=True, populate_by_name=True, strict=True)

#: strict: an int is accepted (as a float), a bool or a string is not
FiniteFloat = Annotated[float, Field(allow_inf_nan=False, strict=True)]
#: fields holding a YAML sequence read a list; the items stay strict
_SEQ = {"strict": False}


class Signal(BaseModel):
    """One input the monitor reads every cycle."""

    model_config = _CFG
    type: Literal["number", "bool"] = Field("number", description="'number' (default) or 'bool'")
    unit: str | None = Field(None, description="unit, e.g. m, m/s, N, rad/s, s, 1 (dimensionless)")
    range: tuple[FiniteFloat, FiniteFloat] | None = Field(
        None, description="valid [min, max]; a value outside fails closed (override)", **_SEQ)
    description: str = ""

    @model_validator(mode="after")
    def _check(self) -> "Signal":
        if self.type == "bool":
            if self.range is not None:
                raise ValueError("a bool signal has no range")
            if self.unit not in (None, "", "1"):
                raise ValueError("a bool signal has no unit")
        elif self.range is not None and self.range[0] > self.range[1]:
            raise ValueError(f"range [{self.range[0]}, {self.range[1]}] is empty: min > max")
        return self


class Constant(BaseModel):
    """A named constant usable in expressions."""

    model_config = _CFG
    value: FiniteFloat
    unit: str | None = None
    description: str = ""


class Release(BaseModel):
    """How the risk rule's latch is released (``risk.release``); its ``hold_cycles`` is also
    the default hold of every other rule's release."""

    model_config = _CFG
    mode: Literal["auto", "manual"] = Field(
        "auto", description="auto: hysteresis rule below; manual: only Monitor.acknowledge()/release()/reset()")
    hysteresis: FiniteFloat = Field(0.05, ge=0.0, description="δ: release needs R_e < τ − δ")
    hold_cycles: int = Field(10, ge=1, le=10_000_000,
                             description="N: the release condition must hold N consecutive cycles")
    hold_s: FiniteFloat | None = Field(
        None, gt=0.0, description="hold_cycles written in seconds (needs the spec's rate_hz; a whole number of "
        "cycles at it)")


#: responses whose latch is released manually unless the rule says ``release: auto``
#: (IEC 60204-1 stop categories 0 and 1 cut power: a restart is an operator's decision)
MANUAL_BY_DEFAULT = frozenset({"stop_0", "stop_1"})

_RELEASE_FORMS = "auto, manual or {mode: auto|manual, hold_cycles: N}"


def _release_short_form(v: Any) -> Any:
    """``auto``/``manual`` stand for ``{mode: auto}``/``{mode: manual}``."""
    if isinstance(v, str):
        if v in ("auto", "manual"):
            return {"mode": v}
        raise ValueError(f"expected {_RELEASE_FORMS}")
    return v


class RuleRelease(BaseModel):
    """How one rule's latch (an obligation's, or the fault latch) is released.

    ``auto``: by itself, once the rule's release condition (the obligation holds; for the
    fault latch: a cycle without a fault) has held ``hold_cycles`` consecutive cycles.
    ``manual``: only by the operator, :meth:`Monitor.acknowledge` (refused until that same
    condition has held ``hold_cycles`` consecutive cycles), or by ``release()``/``reset()``.
    """

    model_config = _CFG
    mode: Literal["auto", "manual"] = Field(
        "auto", description="auto: releases by itself; manual: only Monitor.acknowledge()/release()/reset()")
    hold_cycles: int | None = Field(
        None, ge=1, le=10_000_000,
        description="N: the rule's condition must hold N consecutive cycles (default: risk.release.hold_cycles)")
    hold_s: FiniteFloat | None = Field(
        None, gt=0.0, description="hold_cycles written in seconds (needs the spec's rate_hz; a whole number of "
        "cycles at it)")


#: what a ``release:`` key accepts (for the JSON Schema; the short forms become mappings)
_RELEASE_INPUT = Literal["auto", "manual"] | RuleRelease | None


class OnFault(BaseModel):
    """The response to a fault and how the fault latch is released (``on_fault``)."""

    model_config = _CFG
    response: ACTIVE_RESPONSES = Field("safe_pose", description="response to missing/NaN/out-of-range/stale input")
    release: RuleRelease | None = Field(
        None, description=f"{_RELEASE_FORMS}; default manual (a fault stop is acknowledged by the operator)")

    @field_validator("release", mode="before", json_schema_input_type=_RELEASE_INPUT)
    @classmethod
    def _short(cls, v: Any) -> Any:
        return _release_short_form(v)


class EstimatorConfig(BaseModel):
    """Which learned model scores task texts for this spec, and how (used by the CLI and
    :func:`ethimon.risk.load_estimator_for`; a :class:`Monitor` itself only reads inputs)."""

    model_config = _CFG
    model: str | None = Field(
        None, min_length=1, description="model directory, relative to the spec file; null: the shipped default")
    quantize: Literal["int8"] | None = Field(None, description="null: fp32; int8: dynamic int8 Linear layers")
    temperature: FiniteFloat | None = Field(
        None, gt=0.0, le=100.0, description="softmax temperature replacing the model's own, e.g. fitted on "
        "your domain's validation rows with `ethimon evaluate --calibrate-on`")
    max_length: int | None = Field(None, ge=8, le=4096, description="token budget (default: the model's)")
    backend: Literal["auto", "onnx", "torch"] = Field(
        "auto", description="auto: ONNX Runtime when installed and the model has an ONNX form, else torch; "
        "onnx: ONNX Runtime only (no torch in the process); torch: torch + transformers")


class CanaryConfig(BaseModel):
    """When a judge answers its canaries (``risk.judge.canaries``); the shipped set is always asked."""

    model_config = _CFG
    path: str | None = Field(None, min_length=1, description="a CSV (id, form, label, text) of the spec's own "
                             "canaries, added to the shipped set; relative to the spec file")
    every_s: FiniteFloat = Field(600.0, gt=0.0, le=86400.0, description="ask the canaries again after this many "
                                 "seconds")
    every_texts: int = Field(500, ge=1, le=1_000_000, description="ask the canaries again after this many texts")


class HoldAboveTau(BaseModel):
    """``risk.judge_may_hold_above_tau``: a safe verdict turns an R_e ≥ τ stop into a confirm hold."""

    model_config = _CFG
    ceiling: FiniteFloat = Field(description="only for τ <= R_e < ceiling; above it R_e stops whatever the "
                                 "judge says (ceiling <= 1)")


class JudgeConfig(BaseModel):
    """A second opinion on task texts (``risk.judge``): an OpenAI-compatible chat-completions server
    asked for a one-token verdict (see :mod:`ethimon.risk` ``Judge``). Its p_unsafe reaches the monitor
    as the ``judge`` input: < ``safe_below`` is a safe verdict, ≥ ``unsafe_from`` an unsafe one, between
    them the judge is unsure; none (timeout, error, malformed answer) leaves the confirm band to a person."""

    model_config = _CFG
    url: str = Field(min_length=1, description="base URL of the server, e.g. http://127.0.0.1:8000/v1 "
                     "(POSTs to <url>/chat/completions)")
    model: str = Field(min_length=1, description="model name the server serves")
    timeout_s: FiniteFloat = Field(5.0, gt=0.0, le=120.0, description="a slower answer is no judgement")
    api_key_env: str | None = Field(None, pattern=IDENT, description="environment variable holding the API "
                                    "key (never written to logs or the audit trail); null: no key")
    prompt: str | None = Field(None, min_length=1, description="system prompt (the rubric) replacing the "
                               "built-in one; the task text is always sent as quoted data")
    safe_below: FiniteFloat = Field(0.2, ge=0.0, le=1.0, description="judge p_unsafe below this: safe")
    unsafe_from: FiniteFloat = Field(0.8, ge=0.0, le=1.0, description="judge p_unsafe from this on: unsafe")
    canaries: CanaryConfig = Field(default_factory=CanaryConfig, description="{path, every_s, every_texts}: the "
                                   "canary texts the judge must answer right before its verdicts count")

    @model_validator(mode="after")
    def _check(self) -> "JudgeConfig":
        import urllib.parse
        u = urllib.parse.urlsplit(self.url)
        try:
            port = u.port  # raises for a port outside 0-65535 or not a number
        except ValueError:
            port = -1
        if port == 0 or port == -1:
            raise _LocError(f"risk.judge.url {self.url!r} has no usable port (1-65535)", ("risk", "judge", "url"),
                            hint="e.g. http://127.0.0.1:8080/v1; leave the port out for the scheme's default")
        if u.scheme not in ("http", "https") or not u.hostname:
            raise _LocError(f"risk.judge.url {self.url!r} is not an http(s) URL", ("risk", "judge", "url"),
                            hint="e.g. http://127.0.0.1:8080/v1 (llama-server), http://127.0.0.1:8000/v1 (vLLM), "
                            "http://127.0.0.1:11434/v1 (Ollama)")
        if self.safe_below > self.unsafe_from:
            raise _LocError(f"risk.judge.safe_below {self.safe_below} is above unsafe_from {self.unsafe_from}: "
                            "a verdict would be both safe and unsafe", ("risk", "judge", "safe_below"),
                            hint="set safe_below <= unsafe_from, e.g. 0.2 and 0.8")
        return self


class RiskConfig(BaseModel):
    """How R_e is formed and judged. The rule R_e ≥ τ ⇒ override is always present."""

    model_config = _CFG
    alpha: FiniteFloat = Field(DEFAULT_ALPHA, description="weight α of p_unsafe")
    beta: FiniteFloat = Field(DEFAULT_BETA, description="weight β of (1 − max p)")
    gamma: FiniteFloat = Field(DEFAULT_GAMMA, description="weight γ of Var(p)")
    variance: Literal[VARIANCE_MODES] = Field(  # type: ignore[valid-type]
        "sample", description="sample (÷(K−1), torch.var default) or population (÷K)")
    threshold: FiniteFloat = Field(0.5, description="τ: R_e ≥ τ ⇒ override; 0 < τ ≤ 1")
    classes: int = Field(2, ge=2, le=1000, description="number of classifier classes K")
    unsafe_index: int = Field(-1, description="index of the unsafe class in p")
    response: ACTIVE_RESPONSES = "safe_pose"
    release: Release = Field(default_factory=Release)
    max_age_s: FiniteFloat | None = Field(
        None, gt=0.0, description="estimates older than this (input risk_age_s) fail closed")
    estimator: EstimatorConfig = Field(default_factory=EstimatorConfig)
    confirm_threshold: FiniteFloat | None = Field(
        None, description="τ_confirm: R_e in [τ_confirm, τ) holds the arm (stop_2) until an operator confirms "
        "(Monitor.acknowledge) or the judge decides; null (default): no confirm band")
    judge: JudgeConfig | None = Field(None, description="{url, model, timeout_s, api_key_env, prompt}: the "
                                      "judge tier (null: none; the confirm band is then a person's)")
    judges: list[JudgeConfig] | None = Field(None, min_length=1, max_length=8, description="several judges in "
                                             "consensus (instead of judge): in the band a text executes only if "
                                             "every judge says safe; any unsafe verdict stops")
    judge_may_hold_above_tau: HoldAboveTau | None = Field(
        None, description="{ceiling}: a canary-passed judge's safe verdict turns an R_e >= τ stop into a confirm "
        "hold (stop_2, released by a person), never into execute, and only for R_e < ceiling; null (default): off")
    allow: dict[Literal["threshold", "weights"], Annotated[str, Field(min_length=1)]] = Field(
        default_factory=dict, description="opt-outs, each with the reason: 'threshold' lets τ lie outside "
        "(0, 1], 'weights' lets α, β, γ be negative or all 0 (either can switch the risk rule off or on for good)")

    @property
    def judge_list(self) -> list[JudgeConfig]:
        """The spec's judges: ``judges``, or ``[judge]``, or ``[]``."""
        return list(self.judges) if self.judges else ([self.judge] if self.judge is not None else [])

    def judge_cuts(self) -> tuple[float, float] | None:
        """``(safe_below, unsafe_from)`` the monitor applies to its ``judge`` input (``None``: no judge).

        One judge: its own. Several (``judges``): the input is their consensus (0.0 every judge safe, 1.0
        any unsafe, null otherwise), read with the strictest cuts: the least ``safe_below`` and the
        greatest ``unsafe_from``."""
        js = self.judge_list
        if not js:
            return None
        return min(j.safe_below for j in js), max(j.unsafe_from for j in js)

    @model_validator(mode="after")
    def _check(self) -> "RiskConfig":
        if not -self.classes <= self.unsafe_index < self.classes:
            raise ValueError(f"unsafe_index {self.unsafe_index} is outside 0..{self.classes - 1}")
        tau = self.threshold
        if not 0.0 < tau <= 1.0 and "threshold" not in self.allow:
            what = ("R_e ≥ τ would hold on every cycle, so the arm would always be overridden" if tau <= 0 else
                    "R_e is a score in [0, 1] for the usual weights, so the risk rule would never fire")
            raise _LocError(f"risk.threshold τ = {tau} is outside (0, 1]: {what}", ("risk", "threshold"),
                            hint="set 0 < τ ≤ 1, or opt out with 'allow: {threshold: <reason>}' under risk:")
        if self.judge is not None and self.judges:
            raise _LocError("risk sets both judge and judges", ("risk", "judges"),
                            hint="one judge: risk.judge; several in consensus: risk.judges (a list); not both")
        hold = self.judge_may_hold_above_tau
        if hold is not None:
            if self.judge is None and not self.judges:
                raise _LocError("risk.judge_may_hold_above_tau needs a judge (risk.judge or risk.judges)",
                                ("risk", "judge_may_hold_above_tau"), hint="add risk.judge, or remove the option")
            if not tau < hold.ceiling <= 1.0:
                raise _LocError(f"risk.judge_may_hold_above_tau.ceiling {hold.ceiling} is not in (τ = {tau}, 1]: "
                                "no R_e could be held", ("risk", "judge_may_hold_above_tau", "ceiling"),
                                hint="e.g. ceiling: 0.8 with threshold 0.47")
        tc = self.confirm_threshold
        if tc is not None and not 0.0 <= tc < tau:
            raise _LocError(f"risk.confirm_threshold τ_confirm = {tc} is not in [0, τ = {tau}): the confirm band "
                            "[τ_confirm, τ) would be empty or negative", ("risk", "confirm_threshold"),
                            hint="set 0 <= confirm_threshold < threshold, or remove the key (no band)")
        weights = {"alpha": self.alpha, "beta": self.beta, "gamma": self.gamma}
        if "weights" not in self.allow:
            for name, w in weights.items():
                if w < 0:
                    raise _LocError(f"risk.{name} = {w} is negative: R_e would fall as that term grows",
                                    ("risk", name), hint="weights are ≥ 0; or opt out with "
                                    "'allow: {weights: <reason>}' under risk:")
            if sum(weights.values()) <= 0:
                raise _LocError("risk weights alpha, beta and gamma are all 0: R_e would be 0 on every cycle "
                                "and the risk rule could never fire", ("risk",),
                                hint="the paper's weights are alpha 0.6, beta 0.2, gamma 0.2; or opt out with "
                                "'allow: {weights: <reason>}' under risk:")
        return self


class Obligation(BaseModel):
    """One checked rule: ``when`` ⇒ ``require`` (within ``within_cycles``)."""

    model_config = _CFG
    id: str = Field(pattern=IDENT, description="identifier, unique within the spec")
    description: str = ""
    when: str | None = Field(None, description="trigger condition (default: always)")
    require: str = Field(description="condition that must hold (when triggered)")
    within_cycles: int | None = Field(
        None, ge=0, le=1_000_000,
        description="bounded response: after the trigger, require must hold within this many cycles")
    within_s: FiniteFloat | None = Field(
        None, ge=0.0, description="within_cycles written in seconds (needs the spec's rate_hz; must be a whole "
        "number of cycles at it); the spec's within_cycles then holds the count")
    response: ACTIVE_RESPONSES = "safe_pose"
    release: RuleRelease | None = Field(
        None, description=f"{_RELEASE_FORMS}; default manual for stop_0/stop_1, else auto")

    @field_validator("release", mode="before", json_schema_input_type=_RELEASE_INPUT)
    @classmethod
    def _short(cls, v: Any) -> Any:
        return _release_short_form(v)

    @field_validator("when", "require", mode="before")
    @classmethod
    def _expr_text(cls, v: Any) -> Any:
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, (int, float)):
            raise ValueError("expected a condition (text), got a number")
        return v


class SafePose(BaseModel):
    """Where the arm goes on override, and how fast it may move there."""

    model_config = _CFG
    joints_rad: tuple[FiniteFloat, ...] = Field(
        PANDA_HOME_JOINTS_RAD, description="joint configuration (rad), one per joint of the spec's robot; default: the robot's home pose (the Panda's ready pose)", **_SEQ)
    max_joint_speed_rad_s: FiniteFloat = Field(1.0, gt=0.0, le=10.0,
                                               description="joint-speed limit on the way (rad/s)")
    tolerance_rad: FiniteFloat = Field(0.02, gt=0.0, le=1.0, description="reached when every joint is this close")

    @field_validator("joints_rad")
    @classmethod
    def _len(cls, v: tuple[float, ...]) -> tuple[float, ...]:
        if not 1 <= len(v) <= 16:
            raise ValueError(f"expected 1 to 16 joint values, got {len(v)}")
        return v


class Restart(BaseModel):
    """What resumes motion after an operator's acknowledgement (``restart``).

    An accepted acknowledgement is a reset: it releases the manual latches and never starts
    motion by itself (ISO 13849-1:2015 5.2.2, IEC 60204-1:2016 9.2.2 as we read them). ``start``
    names the separate start condition: ``command`` (default), a deliberate start command
    after the acknowledgement (``GovernedArm.start()``, ``GovernedLoop.start_motion()``, a scenario's
    ``sim.start_at_s``); or the name of a ``bool`` input (a start button wired to the monitor): its
    rising edge, false to true, after the acknowledgement. ``standstill`` optionally names a ``bool``
    input by which the robot reports that the stop has completed (standstill, brakes engaged, power
    state settled): ``GovernedLoop.acknowledge`` is refused while it is false or missing. Automatic
    releases (``release: auto``) restart by themselves, as before: speed and separation monitoring
    may resume once the separation is restored.
    """

    model_config = _CFG
    start: Annotated[str, Field(pattern=IDENT)] = Field(
        "command", description="command (default): a separate start command after the acknowledgement; "
        "or the name of a bool input whose rising edge after the acknowledgement starts motion")
    standstill: Annotated[str, Field(pattern=IDENT)] | None = Field(
        None, description="the name of a bool input by which the robot reports that its stop has completed "
        "(standstill, brakes engaged, power state settled): an acknowledgement is refused while it is false "
        "or missing; null (default): the integrator's controller must gate acknowledgements on it")


class _Carried:
    """What the compiler made of a spec (its plan), carried by the spec object itself.

    No part of the spec's value: equal to any other ``_Carried`` (so ``==`` on specs compares only
    what the file says), not copied by ``copy``/``deepcopy`` and not pickled (a copy is another
    spec: it gets its own plan). Set once by the compiler (``compiler.plan_of``), which also
    checks ``plan.spec is spec`` (a ``model_copy`` shares the holder of its original).
    """

    __slots__ = ("plan",)

    def __init__(self, plan: Any = None) -> None:
        self.plan = plan

    def __eq__(self, other: object) -> bool:
        return isinstance(other, _Carried)

    __hash__ = None  # type: ignore[assignment]

    def __copy__(self) -> "_Carried":
        return _Carried()

    def __deepcopy__(self, memo: dict) -> "_Carried":
        return _Carried()

    def __reduce__(self):
        return (_Carried, ())


class Spec(BaseModel):
    """A validated spec (format version 1). Build it with :func:`ethimon.load_spec`."""

    model_config = _CFG
    ethimon: Literal[1] = Field(description="format version; this ethimon reads 1")
    name: str = Field(min_length=1)
    description: str = ""
    rate_hz: FiniteFloat | None = Field(
        None, ge=RATE_HZ[0], le=RATE_HZ[1], description="the control rate (Hz) the spec is written for: needed by "
        "times in seconds (held(e, 0.5 s), within_s, hold_s), each a whole number of cycles at it; a replay or "
        "live mapping must run at this rate; null: the spec counts cycles only")
    signals: dict[Annotated[str, Field(pattern=IDENT)], Signal] = Field(default_factory=dict)
    constants: dict[Annotated[str, Field(pattern=IDENT)], FiniteFloat | Constant] = Field(default_factory=dict)
    risk: RiskConfig = Field(default_factory=RiskConfig)
    obligations: tuple[Obligation, ...] = Field((), **_SEQ)
    fault_policy: OnFault = Field(
        default_factory=OnFault, alias="on_fault",
        description="response to missing/NaN/out-of-range/stale input: safe_pose | stop_2 | stop_1 | stop_0, "
        "or {response: ..., release: auto | manual | {mode, hold_cycles}}")
    safe_pose: SafePose = Field(default_factory=SafePose)
    restart: Restart = Field(
        default_factory=Restart, description="what resumes motion after an accepted acknowledgement "
        "(a reset never starts motion): {start: command} (default) or {start: <bool input>}; "
        "standstill: <bool input>, the robot's word that the stop has completed")
    robot: str = Field("panda", min_length=1, description="the arm: a shipped robot description (panda, ur5e) "
                       "or the path of a robot YAML file (data, never code), relative to the spec; its joint "
                       "count and rated limits are what lint and verify check the safe pose against")

    _source: SourceMap | None = PrivateAttr(default=None)
    #: the robot description (``language._robots``), attached when the spec is read
    _robot: Any = PrivateAttr(default=None)
    #: the compiled plan, set by the compiler (see :class:`_Carried`); not part of the spec's value
    _compiled: _Carried = PrivateAttr(default_factory=_Carried)

    @field_validator("fault_policy", mode="before", json_schema_input_type=ACTIVE_RESPONSES | OnFault)
    @classmethod
    def _fault_short(cls, v: Any) -> Any:
        if isinstance(v, str):
            if v in _RESPONSE_NAMES:
                return {"response": v}
            raise ValueError("expected safe_pose, stop_2, stop_1 or stop_0, or a mapping "
                             "{response: ..., release: auto|manual}")
        return v

    @field_validator("restart")
    @classmethod
    def _restart_signal(cls, v: Restart, info: ValidationInfo) -> Restart:
        if "signals" not in info.data:  # (signals validated before restart)
            return v
        for key, name, what, role in (
                ("start", v.start if v.start != "command" else None, "(command, or the name of a bool input: "
                 "a start button)", "a start condition needs a bool input (its rising edge starts motion)"),
                ("standstill", v.standstill, "(the name of a bool input: the robot's word that its stop has "
                 "completed)", "a standstill report needs a bool input (true: the stop has completed)")):
            if name is None:
                continue
            sig = info.data["signals"].get(name)
            if sig is None:
                raise ValueError(f"{key}: {name!r} is not a declared signal {what}")
            if sig.type != "bool":
                raise ValueError(f"{key}: signal {name!r} is {sig.type}, {role}")
        return v

    @property
    def on_fault(self) -> str:
        """The response to a fault (``on_fault`` or ``on_fault.response``), e.g. ``'stop_1'``."""
        return self.fault_policy.response

    def fault_release(self) -> tuple[str, int]:
        """``(mode, hold_cycles)`` of the fault latch, defaults filled in (manual)."""
        return _resolved(self.fault_policy.release, "manual", self.risk.release.hold_cycles)

    def obligation_release(self, ob: "Obligation") -> tuple[str, int]:
        """``(mode, hold_cycles)`` of an obligation's latch, defaults filled in (manual for
        stop_0/stop_1, else auto; hold: ``risk.release.hold_cycles``)."""
        default = "manual" if ob.response in MANUAL_BY_DEFAULT else "auto"
        return _resolved(ob.release, default, self.risk.release.hold_cycles)

    @property
    def path(self) -> str | None:
        """The file this spec came from (``None`` if built in code)."""
        return self._source.path if self._source else None

    @property
    def source(self) -> SourceMap:
        """Positions of every value in the spec file."""
        return self._source or SourceMap("<spec>")

    @model_validator(mode="after")
    def _check(self) -> "Spec":
        seen: dict[str, int] = {}
        for i, ob in enumerate(self.obligations):
            if ob.id == "risk":
                raise _LocError("obligation id 'risk' is reserved: it names the built-in rule R_e ≥ τ in "
                                "decisions, scenarios and the audit log", ("obligations", i, "id"),
                                hint="pick another id, e.g. 'risk_limit'")
            if ob.id in ("confirm", "judge"):
                raise _LocError(f"obligation id {ob.id!r} is reserved: it names the tier rule of the "
                                "risk.confirm_threshold band / the judge in decisions and acknowledge()",
                                ("obligations", i, "id"), hint=f"pick another id, e.g. '{ob.id}_check'")
            if ob.id == "fault":
                raise _LocError("obligation id 'fault' is reserved: it names the fault latch in "
                                "Monitor.latched_rules and acknowledge()", ("obligations", i, "id"),
                                hint="pick another id, e.g. 'fault_check'")
            if ob.id in seen:
                raise _LocError(f"duplicate obligation id {ob.id!r} (first is obligations[{seen[ob.id]}])",
                                ("obligations", i, "id"))
            seen[ob.id] = i
        from ._time import resolve_seconds  # the one place times in seconds become cycles
        for key, value in resolve_seconds(self).items():
            object.__setattr__(self, key, value)
        for name in self.signals:
            if name in RESERVED_INPUTS:
                raise _LocError(f"{name!r} is a built-in name and cannot be declared as a signal",
                                ("signals", name), hint="'risk', 'p_unsafe', 'p' and 'risk_age_s' are "
                                "read by the risk rule; pick another name")
        for name in self.constants:
            if name in RESERVED_INPUTS:
                raise _LocError(f"{name!r} is a built-in name and cannot be a constant", ("constants", name))
            if name in self.signals:
                raise _LocError(f"{name!r} is declared both as a signal and as a constant", ("constants", name))
        return self


def _resolved(rel: RuleRelease | None, default_mode: str, default_hold: int) -> tuple[str, int]:
    if rel is None:
        return default_mode, int(default_hold)
    return rel.mode, int(rel.hold_cycles if rel.hold_cycles is not None else default_hold)
