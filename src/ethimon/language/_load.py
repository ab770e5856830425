"""Reading spec files: YAML → validated :class:`Spec` (shape only)."""

from __future__ import annotations

import os
from typing import Any

from pydantic import ValidationError

from ._errors import FORMAT_VERSION, _shown, validation_to_spec_error
from ._model import Spec
from ._robots import attach_robot
from ._yaml import SourceMap, parse_yaml_text, read_yaml

__all__ = ["parse_spec_file", "parse_spec_text", "validate_document", "check_version"]


def check_version(data: Any, smap: SourceMap, what: str) -> None:
    """Top level must be a mapping with a supported ``ethimon:`` version."""
    if not isinstance(data, dict):
        kind = type(data).__name__ if data is not None else "nothing"
        raise smap.error(f"a {what} must be a mapping of keys, but this file holds {kind}", (),
                         hint="start with 'ethimon: 1' and 'name: ...'")
    if "ethimon" not in data:
        raise smap.error(f"missing format version: this {what} has no 'ethimon:' key", (),
                         hint=f"add 'ethimon: {FORMAT_VERSION}' as the first line")
    v = data["ethimon"]
    if type(v) is not int or v != FORMAT_VERSION:  # not True, not 1.0, not '1'
        raise smap.error(f"unsupported format version {_shown(v)}", ("ethimon",),
                         hint=f"this ethimon reads 'ethimon: {FORMAT_VERSION}' (a whole number)")


def validate_document(model, data: Any, smap: SourceMap, what: str):
    """Validate parsed YAML against a pydantic model; errors point into the file."""
    check_version(data, smap, what)
    try:
        obj = model.model_validate(data)
    except ValidationError as exc:
        raise validation_to_spec_error(exc, smap, model, data) from None
    obj._source = smap
    return obj


def parse_spec_file(path: str | os.PathLike) -> Spec:
    """Read and validate a spec file (expressions are checked by the compiler)."""
    data, smap = read_yaml(path, what="spec")
    return attach_robot(validate_document(Spec, data, smap, "spec"), data, smap)


def parse_spec_text(text: str, path: str = "<string>") -> Spec:
    """Validate spec YAML given as text."""
    data, smap = parse_yaml_text(text, path, what="spec")
    return attach_robot(validate_document(Spec, data, smap, "spec"), data, smap)
