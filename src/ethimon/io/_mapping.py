"""The mapping file: which topic and field gives which monitor input, live (``ethimon ros2``) and in
replay (``ethimon replay``) alike.

A mapping is YAML (format version 1), read with the project's safe YAML loader
and validated by pydantic models, so errors name ``file:line:column`` with a
hint exactly as spec errors do; :func:`mapping_json_schema` is its JSON Schema.

::

    ethimon: 1
    rate_hz: 100                 # the monitor's cycle rate; inputs are zero-order held
    max_age_s: 0.1               # staleness limit of every signal (null: never stale)
    signals:
      joint_speed_max: {topic: /joint_states, field: velocity, reduce: max_abs}
      human_distance:  {topic: /human/range, field: range, max_age_s: 0.2}
      ee_speed:        {topic: /ee/twist, field: twist.linear, reduce: norm}
      contact_force:   {topic: /ee/wrench, field: wrench.force, reduce: norm, scale: 1.0}
    task: {topic: /task}         # std_msgs/String, scored by the risk estimator

Live (``ethimon ros2``) the same file names each topic's message ``type:``
(``sensor_msgs/msg/JointState``; a bag says it itself) and may hold a
``ros2:`` block of settings only the live node reads.

    # or, for a bag without task text:  risk: none   (the risk rule is then NOT CHECKED)

Per signal also: ``type`` (the message type, checked against the bag), ``offset_s``
(added to every sample time: a clock offset made explicit), ``derive: rate`` (the
rate of change between consecutive messages at their own times, before the
reduction) and joint selection by name, ``field: position[panda_joint4]`` (the
entry whose index the message's ``name`` list gives).
"""

from __future__ import annotations

import difflib
import math
import os
import re
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, PrivateAttr, model_validator

from ..errors import SpecError
from ..language._load import validate_document
from ..language._model import FiniteFloat, Spec
from ..language._yaml import SourceMap, parse_yaml_text, read_yaml
from ._hold import FUTURE_TOLERANCE_S, cycle_grid
from ._values import ByName, numbers_of, rate_between, reduce_array, reduce_value

__all__ = ["FIELD_PATH", "FUTURE_TOLERANCE_S", "MSGTYPE", "REDUCTIONS", "RISK_INPUTS", "ByName", "Mapping", "Ros2Map",
           "SignalMap", "TaskMap", "bool_mismatch", "load_mapping", "load_mapping_text", "mapping_json_schema",
           "check_against_spec", "lint_mapping", "msgtype_key", "parse_field_path"]

_CFG = ConfigDict(extra="forbid", frozen=True, populate_by_name=True, strict=True)
_IDX = r"\[(?:[0-9]{1,9}|[A-Za-z_][A-Za-z0-9_./:-]{0,199})\]"
#: a field path: names separated by dots, each optionally indexed by number or by name, e.g.
#: ``pose.position.x``, ``poses[0].x``, ``position[panda_joint4]`` (the entry the message's ``name`` list names)
FIELD_PATH = r"^[A-Za-z_][A-Za-z0-9_]*(" + _IDX + r")*(\.[A-Za-z_][A-Za-z0-9_]*(" + _IDX + r")*)*$"
_SEGMENT = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)((?:" + _IDX + r")*)")
#: a message type: ``sensor_msgs/msg/JointState`` (ROS 2) or ``sensor_msgs/JointState`` (ROS 1)
MSGTYPE = r"^[A-Za-z][A-Za-z0-9_]*/(msg/)?[A-Za-z][A-Za-z0-9_]*$"
#: the monitor's cycle rate: from a cycle every 10 s to 100 kHz
RATE_HZ = (0.1, 100_000.0)
#: how an array field (or a vector such as geometry_msgs/Vector3) becomes one number
REDUCTIONS = ("value", "max", "min", "max_abs", "norm", "mean", "index")
#: built-in monitor inputs a topic may carry instead of a spec signal
RISK_INPUTS = ("risk", "p_unsafe")
TOPIC = r"^/?[A-Za-z0-9_~{}][A-Za-z0-9_/~{}.-]*$"
#: how far (s) a sample's time may lie ahead of the clock that judges it (clock jitter between two
#: machines) before it is a fault: a stamp in the future cannot be aged (default of ``future_tolerance_s``)


class SignalMap(BaseModel):
    """Where one monitor input comes from, and how it is turned into a number."""

    model_config = _CFG
    topic: str = Field(pattern=TOPIC, max_length=400, description="the bag topic, e.g. /joint_states")
    field: str = Field("data", pattern=FIELD_PATH, max_length=400,
                       description="field path in the message: 'data', 'velocity', 'twist.linear', 'poses[0].x'")
    reduce: Literal["value", "max", "min", "max_abs", "norm", "mean", "index"] = Field(
        "value", description="value (a scalar field) | max | min | max_abs | norm | mean over an array or "
        "vector (x, y, z) | index (element 'index' of an array)")
    index: int | None = Field(None, ge=0, le=1_000_000, description="the element taken by 'reduce: index'")
    scale: FiniteFloat = Field(1.0, description="unit scaling: value * scale + offset")
    offset: FiniteFloat = Field(0.0, description="unit offset: value * scale + offset")
    max_age_s: FiniteFloat | None = Field(
        None, gt=0.0, le=1e6, description="staleness limit of this signal (s, at most 1e6); default: the "
        "mapping's max_age_s")
    stale: bool = Field(True, description="false: this signal is never stale (a latched topic), whatever "
                        "max_age_s says")
    time: Literal["log", "header"] = Field(
        "log", description="sample time: the bag's log (receive) time, or the message's header.stamp")
    offset_s: FiniteFloat = Field(0.0, ge=-1e9, le=1e9, description="added to every sample time (s): a known "
                                  "offset between this topic's clock and the others' (e.g. robot PC vs recorder)")
    derive: Literal["none", "rate"] = Field(
        "none", description="rate: the change per second between consecutive messages of this topic, at their own "
        "times, taken before the reduction (a speed from poses: derive: rate, reduce: norm); the first message "
        "gives no value")
    type: str | None = Field(None, pattern=MSGTYPE, max_length=200,
                             description="the topic's message type (e.g. sensor_msgs/msg/JointState): checked "
                             "against the bag by replay; required live (ethimon ros2)")
    unusual_scale: bool = Field(False, description="true: a zero or negative 'scale' is meant (else refused)")
    samples: Literal["every", "latest"] | None = Field(
        None, description="every: each sample must be judged by a cycle (else the bag is an ERROR saying which "
        "and why); latest: each cycle judges the latest sample, as the monitor does online (the others are "
        "counted, not judged); default: the mapping's 'samples'")

    @model_validator(mode="after")
    def _check(self) -> "SignalMap":
        if self.scale <= 0.0 and not self.unusual_scale:
            what = "0 makes every value the offset" if self.scale == 0.0 else "a negative scale flips the sign"
            raise ValueError(f"scale {self.scale:g}: {what}; set 'unusual_scale: true' if that is meant")
        if self.reduce == "index" and self.index is None:
            raise ValueError("reduce: index needs 'index: <element number>'")
        if self.reduce != "index" and self.index is not None:
            raise ValueError(f"'index' is only used with 'reduce: index' (reduce is {self.reduce!r})")
        return self

    @property
    def field_path(self) -> tuple[str | int | ByName, ...]:
        """``field`` parsed (:func:`parse_field_path`): names, indices and :class:`ByName` entries."""
        return parse_field_path(self.field)

    def number(self, v: Any, *, where: str = "", path: str | None = None) -> float:
        """One message's field value made this signal's number: the reduction, ``* scale + offset``
        (:func:`~ethimon.io.reduce_value`, the one way live and replay do it)."""
        return reduce_value(v, self, where=where, path=path)

    def reduce_array(self, arr: Any) -> float:
        """The reduction of an array of numbers, before ``scale`` and ``offset``."""
        return reduce_array(arr, self)

    def numbers(self, v: Any, *, where: str = "", path: str | None = None) -> Any:
        """A field value as a float array (``derive: rate`` differentiates it), or ``None``."""
        return numbers_of(v, where, path)

    def rate(self, a: Any, b: Any, dt_s: float) -> float:
        """``derive: rate``: the change per second from ``a`` to ``b`` (``dt_s`` apart), reduced and scaled."""
        return rate_between(a, b, dt_s, self)


class TaskMap(BaseModel):
    """The topic that carries the task text (std_msgs/String); each new text is scored by the risk estimator."""

    model_config = _CFG
    topic: str = Field(pattern=TOPIC, max_length=400, description="the task-text topic, e.g. /task")
    field: str = Field("data", pattern=FIELD_PATH, max_length=400, description="the text field (default 'data')")
    type: str | None = Field(None, pattern=MSGTYPE, max_length=200,
                             description="its message type (default std_msgs/msg/String)")

    @property
    def field_path(self) -> tuple[str | int | ByName, ...]:
        """``field`` parsed (:func:`parse_field_path`)."""
        return parse_field_path(self.field)


class Ros2Map(BaseModel):
    """Settings only the live node (``ethimon ros2``) reads; replay ignores them."""

    model_config = _CFG
    allow_unauthenticated_acknowledge: str | None = Field(
        None, min_length=1, max_length=400, description="null (default): an operator acknowledgement on "
        "/ethimon/acknowledge is refused unless DDS Security authenticates the sender; a reason here (e.g. "
        "'bench cell on an isolated network') accepts unauthenticated ones, audited as such")
    publishers: int = Field(1, ge=1, le=64, description="how many publishers each monitored topic may have; "
                            "one more (or a publisher that replaces the first) is a fault naming it")
    deadline_cycles: int = Field(3, ge=1, le=1_000_000, description="DDS only: the deadline QoS offered on "
                                 "/ethimon/override and /ethimon/decision, in cycles of rate_hz (zenoh has no "
                                 "deadline to offer; there a robot times the override itself)")


class Mapping(BaseModel):
    """A replay mapping (format version 1): bag topics → monitor inputs at the monitor's rate."""

    model_config = _CFG
    ethimon: Literal[1] = Field(description="format version; this ethimon reads 1")
    description: str = ""
    rate_hz: FiniteFloat = Field(ge=RATE_HZ[0], le=RATE_HZ[1],
                                 description="the monitor's cycle rate (Hz, 0.1 to 100000); inputs are zero-order "
                                 "held")
    max_age_s: FiniteFloat | None = Field(gt=0.0, le=1e6,
        description="staleness limit (s) of every signal unless it sets its own; null: signals are never "
        "stale (set it: a sensor that dies would otherwise be held forever)")
    samples: Literal["every", "latest"] = Field(
        "every", description="every: each sample must be judged by a cycle, else the bag is an ERROR saying which "
        "and why (a topic faster than rate_hz, a burst, a clock that jumps back); latest: each cycle judges the "
        "latest sample of each input, as the monitor does online, and the samples in between are counted, not "
        "judged (per signal too)")
    start: Literal["first_message", "all_seen"] = Field(
        "first_message", description="first cycle: at the first mapped message (inputs not yet seen are "
        "missing: fail closed), or once every mapped input has been seen")
    signals: dict[str, SignalMap] = Field(
        default_factory=dict, description="spec signal (or 'p_unsafe' / 'risk') → where it comes from; may be "
        "left out only when a task topic is mapped (a text-only bag against a spec with no signals, such as the "
        "shipped governor)")
    task: TaskMap | None = Field(None, description="optional: the task-text topic scored by the risk estimator")
    ros2: Ros2Map = Field(default_factory=Ros2Map, description="live node settings (ethimon ros2)")
    future_tolerance_s: FiniteFloat = Field(
        FUTURE_TOLERANCE_S, ge=0.0, le=1.0, description="a sample time (header stamp + offset_s) further than "
        "this ahead of the clock that judges it is a fault live, and refused by replay: its age cannot be "
        "judged (a robot clock that runs ahead: declare offset_s)")
    risk: Literal["none"] | None = Field(
        None, description="'none': the bag has no task text and no risk topic; the risk rule is reported as NOT "
        "CHECKED and every other rule is checked")

    _source: SourceMap | None = PrivateAttr(default=None)

    @property
    def path(self) -> str | None:
        return self._source.path if self._source else None

    def samples_of(self, name: str) -> str:
        """``"every"`` or ``"latest"`` for signal ``name``."""
        return self.signals[name].samples or self.samples

    def limit_s(self, name: str) -> float | None:
        """The staleness limit of signal ``name`` in seconds (``None``: never stale)."""
        sm = self.signals[name]
        if not sm.stale:
            return None
        return sm.max_age_s if sm.max_age_s is not None else self.max_age_s

    @model_validator(mode="after")
    def _check(self) -> "Mapping":
        if not self.signals and self.task is None:
            raise ValueError("map at least one signal, or a task topic ('task: {topic: /task}') for a bag that "
                             "holds only task texts")
        risky = [n for n in self.signals if n in RISK_INPUTS]
        if len(risky) > 1:
            raise ValueError(f"map one risk input, not {' and '.join(risky)}")
        if risky and self.task is not None:
            raise ValueError(f"both a task topic and a {risky[0]!r} signal give the risk input; keep one")
        if self.risk == "none" and (risky or self.task is not None):
            raise ValueError("'risk: none' says the bag has no risk input, but the mapping maps one "
                             f"({'task' if self.task is not None else risky[0]}); keep one")
        return self

    @property
    def risk_checked(self) -> bool:
        """False when the mapping says ``risk: none`` (the risk rule is not checked)."""
        return self.risk != "none"

    @property
    def risk_signal(self) -> str | None:
        """The mapped signal that gives the risk input (``risk`` or ``p_unsafe``), if one does."""
        return next((k for k in RISK_INPUTS if k in self.signals), None)

    def check(self, spec: Spec, *, risk_given: bool = False) -> None:
        """:func:`check_against_spec`: the mapping fits ``spec`` (located :class:`SpecError` if not)."""
        check_against_spec(self, spec, risk_given=risk_given)

    def lint(self, spec: Spec) -> list[str]:
        """:func:`lint_mapping`: what an engineer would question in this mapping for ``spec``."""
        return lint_mapping(self, spec)

    def grid(self, t0: int, t_end: int) -> Any:
        """The cycle times (ns) at ``rate_hz`` from ``t0`` to ``t_end`` (:func:`~ethimon.io.cycle_grid`)."""
        return cycle_grid(t0, t_end, self.rate_hz)

    @staticmethod
    def same_type(a: str, b: str) -> bool:
        """Whether two message type names name one type (``pkg/Name`` and ``pkg/msg/Name`` do)."""
        return msgtype_key(a) == msgtype_key(b)


def load_mapping(path: str | os.PathLike) -> Mapping:
    """Read and validate a mapping file.

    Raises:
        SpecError: with ``path:line:column`` and a hint.
    """
    data, smap = read_yaml(path, what="mapping")
    return _validate(data, smap)


def load_mapping_text(text: str, path: str = "<string>") -> Mapping:
    """Like :func:`load_mapping`, from YAML text."""
    data, smap = parse_yaml_text(text, path, what="mapping")
    return _validate(data, smap)


def _validate(data: Any, smap: SourceMap) -> Mapping:
    # unknown keys first, with "did you mean": a misspelt key would otherwise be reported as
    # the required key it was meant to be ("missing required key 'topic'")
    if not isinstance(data, dict):
        kind = type(data).__name__ if data is not None else "nothing"
        raise smap.error(f"a mapping file must be a mapping of keys, but this file holds {kind}", (),
                         hint="start with 'ethimon: 1', 'rate_hz: ...', 'max_age_s: ...' and 'signals:'")
    if isinstance(data, dict):
        _known_keys(data, Mapping, (), smap)
        sigs = data.get("signals")
        if isinstance(sigs, dict):
            for name, sm in sigs.items():
                if isinstance(sm, dict):
                    _known_keys(sm, SignalMap, ("signals", name), smap)
        if isinstance(data.get("task"), dict):
            _known_keys(data["task"], TaskMap, ("task",), smap)
        if isinstance(data.get("ros2"), dict):
            _known_keys(data["ros2"], Ros2Map, ("ros2",), smap)
    return validate_document(Mapping, data, smap, "mapping")


def _known_keys(d: dict, model: type[BaseModel], loc: tuple, smap: SourceMap) -> None:
    known = list(model.model_fields)
    for key in d:
        if key not in known:
            close = difflib.get_close_matches(str(key), known, n=1)
            hint = f"did you mean {close[0]!r}?" if close else f"known keys: {', '.join(known)}"
            where = ".".join(str(p) for p in loc) or "(top level)"
            raise smap.error(f"unknown key {str(key)[:80]!r} in {where}", loc + (key,), hint=hint, key=True)


def mapping_json_schema() -> dict[str, Any]:
    """The JSON Schema of mapping files (for editors)."""
    schema = Mapping.model_json_schema()
    schema["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    schema["title"] = "ethimon replay mapping (format 1)"
    return schema


def _err(mapping: Mapping, message: str, loc: tuple, *, hint: str | None = None, key: bool = False) -> SpecError:
    if mapping._source is not None:
        return mapping._source.error(message, loc, hint=hint, key=key)
    return SpecError(message, hint=hint)


def check_against_spec(mapping: Mapping, spec: Spec, *, risk_given: bool = False) -> None:
    """The mapping runs at the spec's ``rate_hz`` (when the spec states one), every mapped name is a
    signal of ``spec`` (or a risk input), every spec signal is mapped, and there is a risk input (a task topic, a ``p_unsafe``/``risk`` signal, or ``risk_given``).

    Raises:
        SpecError: pointing into the mapping file.
    """
    rate = spec.rate_hz
    if rate is not None and not math.isclose(mapping.rate_hz, rate, rel_tol=1e-9):
        raise _err(mapping, f"the mapping runs the monitor at rate_hz {mapping.rate_hz:g}, but spec {spec.name!r} is "
                   f"written for rate_hz {rate:g}: its windows in cycles would mean other times", ("rate_hz",),
                   hint=f"set 'rate_hz: {rate:g}' in the mapping (or use a spec written for {mapping.rate_hz:g} Hz)")
    known = list(spec.signals) + list(RISK_INPUTS)
    for name, sm in mapping.signals.items():
        if name in known:
            if name in spec.signals and spec.signals[name].type == "bool" and (
                    sm.scale != 1.0 or sm.offset != 0.0 or sm.reduce not in ("value", "index")):
                raise _err(mapping, f"signal {name!r} is a bool in spec {spec.name!r}: no scale, offset or "
                           f"numeric reduction", ("signals", name), hint="use 'reduce: value' (or index) on a "
                           "bool field")
            continue
        close = difflib.get_close_matches(name, known, n=1, cutoff=0.6)
        hint = f"did you mean {close[0]!r}?" if close else "known inputs: " + ", ".join(known)
        shown = name if len(name) <= 80 else name[:77] + "..."
        raise _err(mapping, f"unknown input {shown!r}: spec {spec.name!r} has no signal of that name",
                   ("signals", name), hint=hint, key=True)
    missing = [n for n in spec.signals if n not in mapping.signals]
    if missing:
        raise _err(mapping, f"spec {spec.name!r} reads {', '.join(map(repr, missing))}, which the mapping does "
                   f"not map", ("signals",), key=True,
                   hint="add each under 'signals:' with its topic and field (an unmapped signal would fail "
                   "closed on every cycle)")
    if (not risk_given and mapping.risk_checked and mapping.task is None
            and not any(n in mapping.signals for n in RISK_INPUTS)):
        raise _err(mapping, "the mapping gives no risk input: the monitor's risk rule would fail closed on "
                   "every cycle", (), hint="add 'task: {topic: /your/task_text}' (scored by the risk model), "
                   "map a 'p_unsafe' or 'risk' signal from a topic, or write 'risk: none' if the bag has no task "
                   "text (the risk rule is then reported as NOT CHECKED)")


def bool_mismatch(name: str, spec: Spec, topic: str, msgtype: str) -> str | None:
    """Why a true/false field cannot feed input ``name`` of ``spec`` (``None``: it can, a bool signal).
    The one message live and replay give for it."""
    sig = spec.signals.get(name)
    if sig is not None and sig.type == "bool":
        return None
    what = f"a {sig.type} signal" if sig is not None else "a probability"
    return (f"signal {name!r} is {what} in spec {spec.name!r}, but {topic} ({msgtype}) gives true/false: a bool "
            "is not a number")


def parse_field_path(path: str) -> tuple[str | int | ByName, ...]:
    """``'poses[0].position.x'`` → ``('poses', 0, 'position', 'x')``; ``'position[j4]'`` → ``('position', ByName('j4'))``."""
    out: list[str | int | ByName] = []
    for part in path.split("."):
        m = _SEGMENT.fullmatch(part)
        if m is None:  # pragma: no cover - the model's pattern already refused it
            raise ValueError(f"bad field path {path!r}")
        out.append(m.group(1))
        for i in re.findall(r"\[([^\]]+)\]", m.group(2)):
            out.append(int(i) if i.isdigit() else ByName(i))
    return tuple(out)


def msgtype_key(t: str) -> str:
    """``sensor_msgs/JointState`` and ``sensor_msgs/msg/JointState`` compare equal."""
    parts = t.split("/")
    return f"{parts[0]}/{parts[-1]}"


_PREV = re.compile(r"\bprev\s*\(\s*([A-Za-z_][A-Za-z0-9_]*)\s*[,)]")


def lint_mapping(mapping: Mapping, spec: Spec) -> list[str]:
    """Warnings about a mapping for replay: ``prev()`` of a zero-order-held input (a topic slower than
    the cycle rate repeats its value between messages, so ``x - prev(x)`` is 0, 0, 0, then a jump)."""
    out: list[str] = []
    seen: set[tuple[str, str]] = set()
    for ob in spec.obligations:
        for text in (ob.when, ob.require):
            for sig in _PREV.findall(text or ""):
                sm = mapping.signals.get(sig)
                if sm is None or sm.derive == "rate" or (ob.id, sig) in seen:
                    continue
                seen.add((ob.id, sig))
                out.append(f"obligation {ob.id!r}: prev({sig}) of an input held at {mapping.rate_hz:g} Hz: if "
                           f"{sm.topic} is slower than the cycle rate, prev() sees repeated values (0, 0, 0, then "
                           f"a jump); map the rate itself with 'derive: rate' on {sm.topic}")
    return out

