"""Located messages for a spec that does not validate: a pydantic :class:`ValidationError` (or a
validator's :class:`_LocError`) turned into a :class:`~ethimon.errors.SpecError` at the key's line, with the
field's description, its type and the nearest valid key as hints. Split out of ``_model`` (the spec's
models) so that each reads alone."""

from __future__ import annotations

import difflib
from typing import Any

from pydantic import BaseModel, ValidationError

from ..errors import SpecError
from ._yaml import SourceMap

#: the spec format this ethimon reads (``ethimon: 1``)
FORMAT_VERSION = 1

class _LocError(ValueError):
    def __init__(self, msg: str, loc: tuple, hint: str | None = None) -> None:
        super().__init__(msg)
        self.msg, self.loc, self.hint = msg, loc, hint


def _model_at(model: type[BaseModel], loc: tuple) -> type[BaseModel] | None:
    """The model class that owns the last key of ``loc`` (for "did you mean")."""
    import typing
    cur: Any = model
    skip_key = False
    for part in loc[:-1]:
        if isinstance(part, int):
            continue
        if skip_key:  # a key of a dict-valued field (e.g. a signal name)
            skip_key = False
            continue
        if isinstance(cur, type) and issubclass(cur, BaseModel):
            field = _field(cur, part)
            if field is None:
                return None
            ann = field.annotation
            skip_key = typing.get_origin(ann) is dict
            cur = _unwrap(ann)
        else:
            cur = None
    return cur if isinstance(cur, type) and issubclass(cur, BaseModel) else None


def _field(model: type[BaseModel], key: Any):
    """The field a YAML key names (its name, or its alias: ``on_fault``)."""
    field = model.model_fields.get(key)
    if field is None:
        field = next((f for f in model.model_fields.values() if f.alias == key), None)
    return field


def _unwrap(ann: Any) -> Any:
    import typing
    args = typing.get_args(ann)
    for a in args or ():
        if isinstance(a, type) and issubclass(a, BaseModel):
            return a
        inner = _unwrap(a)
        if inner is not None:
            return inner
    if isinstance(ann, type) and issubclass(ann, BaseModel):
        return ann
    return None


def _fmt_loc(loc: tuple) -> str:
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += ("." if out else "") + str(part)
    return out or "(top level)"


def _shown(value: Any) -> str:
    """A short repr that cannot fail (an int of 4,300+ digits has no repr)."""
    try:
        shown = repr(value)
    except Exception:  # noqa: BLE001 - e.g. ValueError: Exceeds the limit for integer string conversion
        shown = f"<{type(value).__name__}>"
        if isinstance(value, int):
            shown = f"an integer of about {int(value.bit_length() * 0.30103) + 1} digits"
    return shown if len(shown) <= 60 else shown[:57] + "..."


def validation_to_spec_error(exc: ValidationError, smap: SourceMap, model: type[BaseModel],
                             data: Any) -> SpecError:
    """Turn the first pydantic error into a positioned :class:`SpecError`."""
    errs = exc.errors(include_url=False)
    # prefer errors that are not inside union branches' noise
    err = errs[0]
    loc = tuple(p for p in err["loc"] if not (isinstance(p, str) and (p.startswith("function-") or p in (
        "float", "Constant", "constrained-str", "tuple[float, float]"))))
    typ, msg = err["type"], err["msg"]
    ctx_err = (err.get("ctx") or {}).get("error")
    if isinstance(ctx_err, _LocError):
        return smap.error(ctx_err.msg, ctx_err.loc, hint=ctx_err.hint)
    if typ == "extra_forbidden":
        key = loc[-1]
        owner = _model_at(model, loc)
        known = [f.alias or n for n, f in owner.model_fields.items()] if owner else []
        close = difflib.get_close_matches(str(key), known, n=1)
        hint = f"did you mean {close[0]!r}?" if close else (f"known keys: {', '.join(known)}" if known else None)
        return smap.error(f"unknown key {key!r} in {_fmt_loc(loc[:-1])}", loc, hint=hint, key=True)
    if typ == "missing":
        desc = _field_help(model, loc)
        return smap.error(f"missing required key {loc[-1]!r} in {_fmt_loc(loc[:-1])}", loc[:-1],
                          hint=f"add '{loc[-1]}:' ({desc})" if desc else f"add '{loc[-1]}:'")
    if typ == "literal_error" and loc and loc[-1] == "ethimon":
        return smap.error(f"unsupported format version {_shown(err.get('input'))}", loc,
                          hint=f"this ethimon reads 'ethimon: {FORMAT_VERSION}'")
    if loc and loc[-1] == "[key]":  # a dict key that is not one of the allowed names
        expected = (err.get("ctx") or {}).get("expected")
        return smap.error(f"unknown key {_shown(loc[-2])} in {_fmt_loc(loc[:-2])}", loc[:-1], key=True,
                          hint=f"allowed keys: {expected}" if expected else None)
    shown = _shown(err.get("input"))
    msg = msg.replace("Value error, ", "")
    if typ in ("finite_number",):
        msg = "must be a finite number (not NaN or infinity)"
    hint = _TYPE_HINTS.get(typ) or _field_help(model, loc)
    return smap.error(f"{_fmt_loc(loc)}: {msg} (got {shown})", loc, hint=hint)


_TYPE_HINTS = {
    "float_type": "write a number, e.g. 0.5 (true/false and quoted text are not numbers)",
    "float_parsing": "write a number, e.g. 0.5 (true/false and quoted text are not numbers)",
    "int_type": "write a whole number, e.g. 3 (not 3.0, true or quoted text)",
    "int_parsing": "write a whole number, e.g. 3 (not 3.0, true or quoted text)",
    "int_from_float": "write a whole number, e.g. 3 (not 3.0, true or quoted text)",
    "bool_type": "write true or false",
    "bool_parsing": "write true or false",
    "string_type": "write text (quote it if it looks like a number or true/false)",
    "string_too_short": "give a non-empty text",
    "tuple_type": "write a list, e.g. [0, 1]",
    "list_type": "write a list, e.g. [0, 1]",
    "dict_type": "write a mapping of 'key: value' entries",
    "model_type": "write a mapping of 'key: value' entries",
    "finite_number": "write a finite number",
}


def _field_help(model: type[BaseModel], loc: tuple) -> str | None:
    """The description of the field at ``loc`` (its last named key), as a hint."""
    keys = [i for i, p in enumerate(loc) if isinstance(p, str)]
    if not keys:
        return None
    k = keys[-1]
    try:
        owner = _model_at(model, loc[:k + 1])
    except Exception:  # noqa: BLE001 - a hint is best effort
        return None
    field = _field(owner, loc[k]) if owner is not None else None
    return (field.description or None) if field is not None else None
