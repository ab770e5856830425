"""The trust model of an ONNX graph (see ``_onnx``): standard operator domains only, no model-local
functions, external data only inside the model directory; a graph file and its external data match the
sha256 its sidecar ``ethimon_onnx.json`` pins, and the sidecar is exactly what ``ethimon export`` writes.
No numpy, no onnxruntime."""

from __future__ import annotations

import hashlib
import os
from pathlib import Path
from typing import Any

from ..errors import ModelError
from . import _modeldir as M

#: sidecar that pins an exported graph (``ethimon export``)
GRAPH_MANIFEST = "ethimon_onnx.json"
GRAPH_FORMAT = "ethimon-onnx/1"
GRAPH_KEYS = ("format", "graphs", "source_sha256", "max_length", "truncation", "temperature", "unsafe_index",
              "num_labels", "exported_with")
#: operator domains a graph may use: the ONNX standard sets and ONNX Runtime's built-in contrib ops
#: (what its optimiser and quantiser emit). Anything else needs a custom-op library, i.e. code.
ALLOWED_DOMAINS = frozenset({"", "ai.onnx", "ai.onnx.ml", "com.microsoft"})
INPUTS = ("input_ids", "attention_mask")
OUTPUT = "logits"


def _tensors_of(graph) -> Any:
    """Every TensorProto of a graph, its nodes' attributes and subgraphs included."""
    yield from graph.initializer
    for sp in graph.sparse_initializer:
        yield sp.values
        yield sp.indices
    for node in graph.node:
        for a in node.attribute:
            if a.HasField("t"):
                yield a.t
            yield from a.tensors
            if a.HasField("sparse_tensor"):
                yield a.sparse_tensor.values
                yield a.sparse_tensor.indices
            for sp in a.sparse_tensors:
                yield sp.values
                yield sp.indices
            if a.HasField("g"):
                yield from _tensors_of(a.g)
            for g in a.graphs:
                yield from _tensors_of(g)


def _nodes_of(graph) -> Any:
    for node in graph.node:
        yield node
        for a in node.attribute:
            if a.HasField("g"):
                yield from _nodes_of(a.g)
            for g in a.graphs:
                yield from _nodes_of(g)


def check_graph(model, where: str, model_dir: Path | None) -> list[Path]:
    """Refuse a graph that could run code or read files outside ``model_dir``; return its external-data files.

    ``model``: an ``onnx.ModelProto`` (parsed without loading external data). ``model_dir=None``
    (a graph built in memory): no external data at all.

    Raises:
        ModelError: naming ``where`` and the domain, function or path.
    """
    for op in model.opset_import:
        if op.domain not in ALLOWED_DOMAINS:
            raise ModelError(f"{where}: custom operator domain {op.domain!r}; ethimon runs only standard ONNX "
                             f"and ONNX Runtime built-in operators ({', '.join(sorted(ALLOWED_DOMAINS - {''}))}) "
                             "and never loads a custom-op library")
    if len(model.functions):
        raise ModelError(f"{where}: {len(model.functions)} model-local function(s) "
                         f"({model.functions[0].domain}:{model.functions[0].name}); inline them when exporting")
    for node in _nodes_of(model.graph):
        if node.domain not in ALLOWED_DOMAINS:
            raise ModelError(f"{where}: node {node.name or node.op_type!r} uses custom operator domain "
                             f"{node.domain!r} (op {node.op_type}); refused")
    files: list[Path] = []
    root = None if model_dir is None else Path(os.path.realpath(model_dir))
    for t in _tensors_of(model.graph):
        if t.data_location != 1:  # TensorProto.EXTERNAL
            continue
        loc = next((e.value for e in t.external_data if e.key == "location"), None)
        if root is None:
            raise ModelError(f"{where}: tensor {t.name!r} has external data ({loc!r}); refused")
        if not loc or os.path.isabs(loc) or "\\" in loc or ".." in Path(loc).parts or ":" in loc:
            raise ModelError(f"{where}: tensor {t.name!r} external-data path {loc!r} must be a relative path "
                             "inside the model directory")
        p = Path(os.path.realpath(root / loc))
        if root not in p.parents:
            raise ModelError(f"{where}: tensor {t.name!r} external-data path {loc!r} resolves to {p}, outside "
                             f"the model directory {root}; refused")
        if not p.is_file():
            raise ModelError(f"{where}: tensor {t.name!r} external-data file {p} is missing")
        if p not in files:
            files.append(p)
    ins = [i.name for i in model.graph.input if i.name not in {x.name for x in model.graph.initializer}]
    outs = [o.name for o in model.graph.output]
    if sorted(ins) != sorted(INPUTS) or OUTPUT not in outs:
        raise ModelError(f"{where}: inputs {ins} and outputs {outs}; a risk graph takes {list(INPUTS)} and "
                         f"gives {OUTPUT!r}")
    return files



def _read_pinned(p: Path, want: str, pinned_by: Path, keep: bool = True) -> bytes:
    from .._files import open_regular

    def error(message: str, *, path: str, hint: str | None = None) -> ModelError:
        return ModelError(f"{path}: {message}" + (f" ({hint})" if hint else ""))
    try:
        with open_regular(p, "rb", what="graph file", error=error) as fh:
            h = hashlib.sha256()
            chunks = []
            for chunk in iter(lambda: fh.read(1 << 20), b""):
                h.update(chunk)
                if keep:
                    chunks.append(chunk)
    except OSError as exc:
        raise ModelError(f"{p}: cannot read: {exc.strerror or exc}") from None
    if h.hexdigest() != want:
        raise ModelError(f"{p}: sha256 mismatch ({pinned_by} pins {want[:12]}…, file {h.hexdigest()[:12]}…); "
                         "the graph was modified or corrupted")
    return b"".join(chunks)


def check_graph_manifest(p: Path, m: dict) -> dict:
    """Refuse an ``ethimon_onnx.json`` that is not exactly what ``ethimon export`` writes."""
    def bad(key: str, want: str) -> ModelError:
        return ModelError(f"{p}: {key!r} = {M._short(m.get(key))}: {want}")
    for key in m:
        if key not in GRAPH_KEYS:
            raise ModelError(f"{p}: unknown key {key!r} (known: {', '.join(GRAPH_KEYS)})")
    if m.get("format") != GRAPH_FORMAT:
        raise bad("format", f"{GRAPH_FORMAT!r} expected")
    if not M._is_sha(m.get("source_sha256")):
        raise bad("source_sha256", "64 lowercase hex digits expected")
    graphs = m.get("graphs")
    if not (isinstance(graphs, dict) and graphs and set(graphs) <= {"fp32", "int8"}):
        raise bad("graphs", "an object with 'fp32' and/or 'int8' entries expected")
    for kind, e in graphs.items():
        if not (isinstance(e, dict) and set(e) <= {"file", "sha256", "data_sha256"} and M._is_sha(e.get("sha256"))
                and isinstance(e.get("file"), str) and e["file"] == Path(e["file"]).name
                and e["file"].endswith(".onnx") and "\\" not in e["file"]):
            raise bad("graphs", f"{kind!r}: {{'file': a .onnx file name inside the directory, 'sha256': 64 hex}} "
                                "expected")
        pins = e.get("data_sha256", {})
        if not (isinstance(pins, dict) and all(isinstance(k, str) and M._is_sha(v) for k, v in pins.items())):
            raise bad("graphs", f"{kind!r}: 'data_sha256' must map file names to sha256")
    n = m.get("num_labels", 2)
    if not (M._is_int(n) and 2 <= n <= M.MAX_LABELS):
        raise bad("num_labels", f"an integer in 2..{M.MAX_LABELS} expected")
    if not (M._is_int(m.get("unsafe_index")) and 0 <= m["unsafe_index"] < n):
        raise bad("unsafe_index", f"an integer in 0..{n - 1} expected")
    if not (M._is_int(m.get("max_length")) and 8 <= m["max_length"] <= M.MAX_LENGTH):
        raise bad("max_length", f"an integer in 8..{M.MAX_LENGTH} expected")
    if m.get("truncation") not in ("head", "head_tail"):
        raise bad("truncation", "'head' or 'head_tail' expected")
    if not (M._is_num(m.get("temperature")) and m["temperature"] > 0):
        raise bad("temperature", "a finite number > 0 expected")
    return m
