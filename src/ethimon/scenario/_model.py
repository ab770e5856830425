"""Scenario files: a spec, a task text, a timeline of inputs and expectations."""

from __future__ import annotations

import os
from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, PrivateAttr, model_validator

from ..sim import SimBlock
from ..language._model import ACTIVE_RESPONSES

__all__ = ["Scenario", "TimelineEntry", "Expect", "Value"]

#: strict types: ``cycles: '1000'``, ``at: true`` or ``override: 1`` are errors, not coerced
_CFG = ConfigDict(extra="forbid", frozen=True, strict=True)
#: fields holding a YAML sequence read a list; the items stay strict
_SEQ = {"strict": False}

#: an input value: a number, a boolean, ``null`` (the signal is missing) or a probability vector
Value = float | bool | None | list[float]


class TimelineEntry(BaseModel):
    """From cycle ``at`` on, set these inputs (``null`` removes one: a dropout)."""

    model_config = _CFG
    at: int = Field(ge=0, le=10_000_000, description="cycle at which the values take effect")
    set: dict[str, Value] = Field(default_factory=dict, description="input values from this cycle on")
    for_cycles: int | None = Field(None, ge=1, description="revert to the previous values after this many cycles")


class Expect(BaseModel):
    """What must happen; every key given is checked."""

    model_config = _CFG
    override: bool | None = Field(None, description="an override happens at some cycle (true) or never (false)")
    override_by_cycle: int | None = Field(None, ge=0, description="the first override comes at or before this cycle")
    no_override_before: int | None = Field(None, ge=0, description="no override before this cycle")
    fired: tuple[str, ...] = Field((), description="obligation ids (or 'risk') violated at least once", **_SEQ)
    not_fired: tuple[str, ...] = Field((), description="obligation ids (or 'risk') never violated", **_SEQ)
    response: ACTIVE_RESPONSES | None = Field(None, description="the most severe response that occurs")
    released_by_cycle: int | None = Field(None, ge=0, description="after overriding, execution resumes by this cycle")
    final_override: bool | None = Field(None, description="override state at the last cycle")
    fault: bool | None = Field(None, description="some cycle fails closed on bad input (true) or none does")


class Scenario(BaseModel):
    """A scenario (format version 1) that ``ethimon check`` runs against its spec."""

    model_config = _CFG
    ethimon: Literal[1] = Field(description="format version; this ethimon reads 1")
    name: str = Field(min_length=1)
    description: str = ""
    spec: str = Field(min_length=1, description="path of the spec, relative to this file")
    task: str | None = Field(None, description="task text; scored by the risk model when no risk input is given")
    cycles: int = Field(100, ge=1, le=1_000_000, description="number of control cycles to run")
    inputs: dict[str, Value] = Field(default_factory=dict, description="input values from cycle 0 on")
    timeline: tuple[TimelineEntry, ...] = Field((), **_SEQ)
    expect: Expect = Field(default_factory=Expect)
    sim: SimBlock | None = Field(None, description="PyBullet run (see ethimon.sim); used by check --sim")

    _source: Any = PrivateAttr(default=None)

    @property
    def path(self) -> str | None:
        return self._source.path if self._source is not None else None

    @property
    def spec_path(self) -> str:
        """The spec path resolved against the scenario file's folder."""
        base = os.path.dirname(self.path) if self.path else "."
        return os.path.normpath(os.path.join(base, self.spec))

    @model_validator(mode="after")
    def _check(self) -> "Scenario":
        for i, entry in enumerate(self.timeline):
            if entry.at >= self.cycles:
                from ..language._model import _LocError
                raise _LocError(f"timeline entry at cycle {entry.at} is past the end (cycles: {self.cycles})",
                                ("timeline", i, "at"), hint="raise 'cycles' or move the entry")
        return self
