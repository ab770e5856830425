"""Counterexamples as scenario files that ``ethimon check`` replays."""

from __future__ import annotations

import math
import os
import re
from typing import Any

import yaml

from ..language import Spec
from ._report import Counterexample

__all__ = ["counterexample_scenario", "write_counterexample"]


def _value(v: Any) -> Any:
    if isinstance(v, float) and (math.isnan(v) or math.isinf(v)):
        return v  # yaml.safe_dump writes .nan / .inf
    return v


def counterexample_scenario(cex: Counterexample, spec: Spec, spec_path: str) -> dict[str, Any]:
    """The scenario document of a counterexample.

    ``inputs`` holds cycle 0; each later cycle is a ``timeline`` entry setting
    what changed (``null`` removes an input). ``expect`` states the refuted
    property, so ``ethimon check`` fails on it (exit 1) while the spec is unchanged
    and passes once the spec is fixed.
    """
    frames = cex.frames
    timeline = []
    prev = frames[0]
    for t, f in enumerate(frames[1:], start=1):
        changed = {k: _value(v) for k, v in f.items() if prev.get(k, _MISSING) != v or
                   (isinstance(v, float) and math.isnan(v))}
        changed.update({k: None for k in prev if k not in f})
        if changed:
            timeline.append({"at": t, "set": changed})
        prev = f
    return {
        "ethimon": 1,
        "name": f"counterexample: {spec.name} {cex.property}",
        "description": (f"Written by 'ethimon verify': refutes {cex.property} at cycle {cex.cycle}. "
                        f"Replaying it fails while the spec is unchanged. {cex.note}"),
        "spec": spec_path,
        "cycles": len(frames),
        "inputs": {k: _value(v) for k, v in frames[0].items()},
        "timeline": timeline,
        "expect": cex.expect,
    }


_MISSING = object()


def write_counterexample(cex: Counterexample, spec: Spec, folder: str | os.PathLike) -> str:
    """Write ``<folder>/<spec name>.<property>.yaml``; returns its path."""
    folder = os.fspath(folder)
    os.makedirs(folder, exist_ok=True)
    safe = re.sub(r"[^A-Za-z0-9_.-]+", "_", f"{spec.name}.{cex.property}")
    path = os.path.join(folder, f"{safe}.yaml")
    spec_path = os.path.relpath(os.path.abspath(spec.path), os.path.abspath(folder)) if spec.path else "SPEC.yaml"
    doc = counterexample_scenario(cex, spec, spec_path.replace(os.sep, "/"))
    with open(path, "w", encoding="utf-8") as fh:
        fh.write("# counterexample written by 'ethimon verify'; replay with: ethimon check " + path + "\n")
        yaml.safe_dump(doc, fh, sort_keys=False, allow_unicode=True, width=100)
    return path
