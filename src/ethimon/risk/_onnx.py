"""ONNX Runtime side of the risk estimator: no torch, no transformers.

Imported only from inside functions (``ethimon.risk`` stays free of onnxruntime).

Where the graph comes from. For an encoder family this module knows (BERT,
which the shipped MiniLM-L6 is, and DistilBERT), the graph is *built* at load
time from the safetensors weights the manifest already pins: numpy reads the
base weights and the LoRA adapter, and a small protobuf writer emits the
encoder, the pooling and the head as standard ONNX operators, each adapted
weight as ``W + scale·B·A`` over initializers (the torch path's ``merge_lora``),
which ONNX Runtime folds into one matrix when the session starts. Nothing is
downloaded or stored: the graph is a pure function of pinned inputs (its
sha256 is reported as :attr:`OnnxModel.graph_sha256`, equal on every machine),
so a retrained adapter needs no extra step, and the repository carries no
90 MB binary. Any other family (MPNet, RoBERTa, ...) runs through a
``model.onnx`` exported beside it (``ethimon export``, which needs torch
once, on the training machine), pinned by sha256 in ``ethimon_onnx.json``.

Trust model, on top of the directory checks in ``_modeldir.py``: a graph is
data. Before ONNX Runtime sees one, :func:`check_graph` refuses operator
domains other than the standard ones and ONNX Runtime's built-in contrib
ops (a custom domain needs a custom-op library: code), model-local
functions, and external-data paths that are absolute, climb out with
``..`` or resolve outside the model directory (a built graph may have no
external data at all). A graph file must match the sha256 its sidecar
pins, and so must every external-data file; the sidecar also pins the
weights the graph was exported from, so a retrained model with a stale
graph is refused. No custom-op library is ever registered.
"""

from __future__ import annotations

import hashlib
import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import DependencyNotInstalled, ModelError

try:
    import numpy as np
    import onnxruntime as ort
    from tokenizers import Tokenizer
except ImportError as exc:  # pragma: no cover - exercised only without the extra
    raise DependencyNotInstalled(
        f"the ONNX risk backend needs onnxruntime and tokenizers ({exc.name} is missing): "
        'pip install "ethimon[risk]"') from exc

from . import _modeldir as M

#: sidecar that pins an exported graph (``ethimon export``)
GRAPH_MANIFEST = "ethimon_onnx.json"
GRAPH_FORMAT = "ethimon-onnx/1"
GRAPH_KEYS = ("format", "graphs", "source_sha256", "max_length", "truncation", "temperature", "unsafe_index",
              "num_labels", "exported_with")
#: operator domains a graph may use: the ONNX standard sets and ONNX Runtime's built-in contrib ops
#: (what its optimiser and quantiser emit). Anything else needs a custom-op library, i.e. code.
ALLOWED_DOMAINS = frozenset({"", "ai.onnx", "ai.onnx.ml", "com.microsoft"})
OPSET = 17
#: families :func:`build_graph` writes from safetensors weights (others need an exported model.onnx)
BUILT_MODEL_TYPES = ("bert", "distilbert")
#: version of the graph builder; part of :attr:`OnnxModel.graph_sha256`'s meaning
BUILDER_VERSION = 1
INPUTS = ("input_ids", "attention_mask")
#: the external-data "location" of a built graph's weights: handed to ONNX Runtime as arrays, never a file
MEMORY = "ethimon-memory"
#: the encoder linears an int8 graph quantises: the attention's (q, k, v, o). The feed-forward pair,
#: the pooler and the head stay fp32. Measured on the 555 natural test rows against fp32 decisions
#: (bench/results/risk/risk_onnx.json): all six linears 538/555, q/k/v/o 546/555 (p50 1.4 vs 2.4 ms,
#: load 2); neither reaches 99.5 %, so int8 stays opt-in (``quantize: int8``), never the default.
INT8_LINEARS = ("q", "k", "v", "o")
#: initializers up to this many elements are written into the graph itself (shapes, axes, constants)
INLINE_MAX = 64
OUTPUT = "logits"


class _NoGraph(Exception):
    """This model has no ONNX graph here (unsupported family, no exported file): ``auto`` uses torch.

    Never raised for a trust failure (a wrong sha256, a refused graph): those are :class:`ModelError`.
    """


# ---------------------------------------------------------------- trust checks on a graph
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


# ---------------------------------------------------------------- weights (numpy)
def _load_st(path: Path, what: str) -> dict:
    from safetensors.numpy import load_file
    try:
        return load_file(str(path))
    except Exception as exc:  # noqa: BLE001 - bf16 (numpy has none), a corrupt file, a pickle
        if "bf16" in str(exc).lower() or "bfloat16" in str(exc).lower():
            raise _NoGraph(f"{path}: bfloat16 weights (numpy has no bfloat16)") from None
        raise ModelError(f"{path}: not a valid safetensors file ({type(exc).__name__}: {str(exc)[:160]}); "
                         f"ethimon loads safetensors {what} only, never pickles") from None


def _adapter_arrays(adapter: Path) -> dict:
    """The adapter's tensors as float32 arrays; what the torch path refuses (non-float, NaN/inf) is refused."""
    out = {}
    for key, t in _load_st(adapter, "adapters").items():
        if t.dtype.kind != "f":
            raise ModelError(f"{adapter}: tensor {key!r} has dtype {t.dtype}; floating-point weights expected")
        if not np.isfinite(t).all():
            raise ModelError(f"{adapter}: tensor {key!r} holds NaN/inf values")
        out[key] = t.astype(np.float32)
    return out


def lora_pairs(w: dict, tensors: dict, scale: float, adapter: Path) -> dict:
    """``{weight name: (A, B, scale)}`` of an adapter, each checked to fit ``w`` (as ``_backend.merge_lora``)."""
    out = {}
    for key, a in tensors.items():
        if not (key.startswith("lora.") and key.endswith(".A")):
            continue
        name = key[len("lora."):-len(".A")]
        b = tensors.get(f"lora.{name}.B")
        wk = f"{name}.weight"
        if wk not in w:
            raise ModelError(f"{adapter}: adapter names module {name!r}, which the base model lacks")
        if b is None or b.ndim != 2 or a.ndim != 2 or (b.shape[0], a.shape[1]) != w[wk].shape \
                or b.shape[1] != a.shape[0]:
            raise ModelError(f"{adapter}: adapter tensors for {name!r} do not fit the base model")
        out[wk] = (a, b, float(scale))
    return out


def merge_lora_np(w: dict, tensors: dict, scale: float, adapter: Path) -> int:
    """Fold ``scale·B·A`` into ``w[name + '.weight']`` in numpy (float32); return #merged.

    Used for int8 graphs (the quantiser needs the merged matrix). fp32 graphs merge inside the
    graph instead (:meth:`_G.linear`): numpy's BLAS starts a thread per core for these products,
    and on busy shared cores that took 0.8 s instead of 0.02 s.
    """
    pairs = lora_pairs(w, tensors, scale, adapter)
    for wk, (a, b, sc) in pairs.items():
        w[wk] = (w[wk].astype(np.float32) + np.float32(sc) * (b @ a)).astype(np.float32)
    return len(pairs)


# ---------------------------------------------------------------- graph builder
# ONNX's protobuf, written directly. The ``onnx`` package is not imported to build a graph: importing it
# costs ~0.5 s (its ml_dtypes extension), more than the whole one-shot budget; the writer below emits
# the handful of messages a graph needs (field numbers from onnx.proto3), and a test parses its output
# with the onnx package and runs onnx.checker on it.
_FLOAT, _UINT8, _INT8, _INT32, _INT64 = 1, 2, 3, 6, 7
_NP_TYPES = {np.dtype(np.float32): _FLOAT, np.dtype(np.uint8): _UINT8, np.dtype(np.int8): _INT8,
             np.dtype(np.int32): _INT32, np.dtype(np.int64): _INT64}


def _varint(n: int) -> bytes:
    if n < 0:
        n += 1 << 64
    out = bytearray()
    while True:
        b = n & 0x7F
        n >>= 7
        if n:
            out.append(b | 0x80)
        else:
            out.append(b)
            return bytes(out)


def _ld(field_no: int, payload: bytes) -> bytes:
    return _varint(field_no << 3 | 2) + _varint(len(payload)) + payload


def _vi(field_no: int, n: int) -> bytes:
    return _varint(field_no << 3) + _varint(n)


def _str(field_no: int, s: str) -> bytes:
    return _ld(field_no, s.encode())


def _tensor(name: str, arr, external: bool = False) -> bytes:
    """TensorProto: dims (1), data_type (2), name (8), raw_data (9, little-endian) or, ``external``, a
    reference (external_data (13) location "ethimon-memory", data_location (14) EXTERNAL) that
    ONNX Runtime resolves to the array handed over by :func:`session_for` (no file is read)."""
    arr = np.asarray(arr)
    head = b"".join(_vi(1, int(d)) for d in arr.shape) + _vi(2, _NP_TYPES[arr.dtype]) + _str(8, name)
    if external:
        return head + _ld(13, _str(1, "location") + _str(2, MEMORY)) + _vi(14, 1)
    return head + _ld(9, np.ascontiguousarray(arr, arr.dtype.newbyteorder("<")).tobytes())


def _attribute(name: str, v: Any) -> bytes:
    """AttributeProto: name (1), f (2), i (3), s (4), ints (8), type (20)."""
    if isinstance(v, bool) or isinstance(v, int):
        return _str(1, name) + _vi(3, int(v)) + _vi(20, 2)
    if isinstance(v, float):
        import struct
        return _str(1, name) + _varint(2 << 3 | 5) + struct.pack("<f", v) + _vi(20, 1)
    if isinstance(v, str):
        return _str(1, name) + _ld(4, v.encode()) + _vi(20, 3)
    if isinstance(v, (list, tuple)) and all(isinstance(x, int) for x in v):
        return _str(1, name) + b"".join(_vi(8, int(x)) for x in v) + _vi(20, 7)
    raise TypeError(f"attribute {name}={v!r}")


def _value_info(name: str, elem: int, dims: list) -> bytes:
    """ValueInfoProto(name, TypeProto(tensor_type(elem_type, shape(dim: dim_value | dim_param))))."""
    shape = b"".join(_ld(1, _vi(1, d) if isinstance(d, int) else _str(2, d)) for d in dims)
    return _str(1, name) + _ld(2, _ld(1, _vi(1, elem) + _ld(2, shape)))


class _G:
    """A small ONNX graph writer: named initializers and nodes, fresh value names, serialised by hand.

    ``int8``: every ``linear`` becomes a dynamic int8 MatMul (weights quantised here, per output
    column, symmetric; activations quantised per call by DynamicQuantizeLinear), the pattern ONNX
    Runtime fuses into its DynamicQuantizeMatMul kernel. Embeddings, LayerNorms and softmax stay fp32.
    """

    def __init__(self, int8: bool = False) -> None:
        self.nodes: list[bytes] = []
        self.inits: dict[str, Any] = {}
        self.op_types: set[str] = set()
        self.int8 = int8
        self._n = 0

    def init(self, name: str, arr) -> str:
        self.inits[name] = np.ascontiguousarray(arr)
        return name

    def const(self, arr, dtype=np.int64) -> str:
        self._n += 1
        return self.init(f"c{self._n}", np.asarray(arr, dtype=dtype))

    def op(self, op_type: str, *inputs: str, n_out: int = 1, **attrs):
        self._n += 1
        outs = [f"{op_type.lower()}_{self._n}_{j}" for j in range(n_out)]
        self.node(op_type, list(inputs), outs, **attrs)
        return outs[0] if n_out == 1 else outs

    def node(self, op_type: str, inputs: list[str], outputs: list[str], **attrs) -> None:
        """NodeProto: input (1), output (2), name (3), op_type (4), attribute (5); default domain only."""
        self.op_types.add(op_type)
        self.nodes.append(b"".join(_str(1, i) for i in inputs) + b"".join(_str(2, o) for o in outputs)
                          + _str(3, f"n{len(self.nodes)}") + _str(4, op_type)
                          + b"".join(_ld(5, _attribute(k, v)) for k, v in sorted(attrs.items())))

    def linear(self, x: str, w, b, name: str, lora: tuple | None = None) -> str:
        """``x @ w.T + b`` for a 2-D ``x`` (``w`` as stored by torch, out × in: Gemm transB, no copy).

        ``lora = (A, B, scale)``: the weight is ``w + scale·B·A``, written as graph nodes over
        initializers, which ONNX Runtime folds into one constant when the session starts (on its
        own single intra-op thread), exactly the torch path's merge.
        """
        w = np.asarray(w, np.float32)
        bias = self.init(f"{name}.b", np.asarray(b, np.float32))
        if not (self.int8 and name.rpartition(".")[2] in INT8_LINEARS):
            wn = self.init(f"{name}.w", w)
            if lora is not None:
                a, bb, sc = lora
                # one Gemm: scale·B·A + W (alpha = scale, beta = 1), folded in one pass over W
                wn = self.op("Gemm", self.init(f"{name}.lora_B", bb), self.init(f"{name}.lora_A", a), wn,
                             alpha=float(sc), beta=1.0)
            return self.op("Gemm", x, wn, bias, transB=1)
        if lora is not None:
            raise ValueError("int8 layers take weights merged in numpy (merge_lora_np)")
        scale = np.maximum(np.abs(w).max(axis=1), 1e-12) / 127.0  # per output row of w
        q = np.clip(np.rint(w / scale[:, None]), -127, 127).astype(np.int8).T  # in × out
        xq, xs, xz = self.op("DynamicQuantizeLinear", x, n_out=3)
        acc = self.op("MatMulInteger", xq, self.init(f"{name}.wq", q), xz,
                      self.init(f"{name}.wz", np.zeros(q.shape[1], np.int8)))
        y = self.op("Mul", self.op("Cast", acc, to=_FLOAT),
                    self.op("Mul", xs, self.init(f"{name}.ws", scale.astype(np.float32))))
        return self.op("Add", y, bias)

    def layer_norm(self, x: str, g, b, eps: float, name: str) -> str:
        return self.op("LayerNormalization", x, self.init(f"{name}.g", np.asarray(g, np.float32)),
                       self.init(f"{name}.b", np.asarray(b, np.float32)), axis=-1, epsilon=float(eps))

    def gelu(self, x: str) -> str:
        """Exact (erf) GELU, as ``hidden_act: gelu`` in transformers."""
        e = self.op("Erf", self.op("Div", x, self.const(math.sqrt(2.0), np.float32)))
        return self.op("Mul", self.op("Mul", x, self.const(0.5, np.float32)),
                       self.op("Add", e, self.const(1.0, np.float32)))

    def model(self, inputs: list[bytes], outputs: list[bytes]) -> "BuiltGraph":
        """ModelProto: ir_version (1), producer (2, 3), graph (7), opset_import (8); big weights by reference."""
        graph = (b"".join(_ld(1, n) for n in self.nodes) + _str(2, "ethimon_risk")
                 + b"".join(_ld(5, _tensor(k, a, a.size > INLINE_MAX)) for k, a in self.inits.items())
                 + b"".join(_ld(11, v) for v in inputs) + b"".join(_ld(12, v) for v in outputs))
        proto = (_vi(1, 8) + _str(2, "ethimon") + _str(3, str(BUILDER_VERSION)) + _ld(7, graph)
                 + _ld(8, _str(1, "") + _vi(2, OPSET)))
        return BuiltGraph(proto, {k: a for k, a in self.inits.items() if a.size > INLINE_MAX},
                          hashlib.sha256(proto).hexdigest())


@dataclass
class BuiltGraph:
    """A built graph: the ModelProto bytes (weights by reference) and the arrays they refer to."""
    proto: bytes
    weights: dict
    #: sha256 of the proto (operators, shapes, small constants); the weights it refers to are the
    #: pinned files' (base_sha256, adapter_sha256), so (this, the pins) identify the model
    sha256: str

    def inline(self) -> bytes:
        """A self-contained ModelProto (weights as raw data): what ``ethimon export`` writes."""
        import onnx
        m = onnx.load_model_from_string(self.proto)
        for t in m.graph.initializer:
            if t.name in self.weights:
                a = np.ascontiguousarray(self.weights[t.name])
                del t.external_data[:]
                t.data_location = 0
                t.raw_data = a.astype(a.dtype.newbyteorder("<"), copy=False).tobytes()
        return m.SerializeToString()


def _activation(g: _G, x: str, act: Any) -> str:
    if act == "gelu":
        return g.gelu(x)
    if act == "relu":
        return g.op("Relu", x)
    raise _NoGraph(f"activation {act!r}")


def _layout(cfg: dict) -> dict:
    """Names and sizes of a BERT or DistilBERT encoder's weights (keys without the model prefix)."""
    mt = cfg.get("model_type")
    if mt == "bert":
        if cfg.get("position_embedding_type", "absolute") != "absolute":
            raise _NoGraph(f"position_embedding_type {cfg.get('position_embedding_type')!r}")
        return {"prefix": "bert.", "layers": cfg.get("num_hidden_layers"), "hidden": cfg.get("hidden_size"),
                "heads": cfg.get("num_attention_heads"), "eps": cfg.get("layer_norm_eps", 1e-12),
                "act": cfg.get("hidden_act", "gelu"), "positions": cfg.get("max_position_embeddings"),
                "emb": "embeddings.word_embeddings.weight", "pos": "embeddings.position_embeddings.weight",
                "type": "embeddings.token_type_embeddings.weight", "emb_ln": "embeddings.LayerNorm",
                "layer": "encoder.layer.{i}.", "q": "attention.self.query", "k": "attention.self.key",
                "v": "attention.self.value", "o": "attention.output.dense", "ln1": "attention.output.LayerNorm",
                "ff1": "intermediate.dense", "ff2": "output.dense", "ln2": "output.LayerNorm"}
    if mt == "distilbert":
        if cfg.get("sinusoidal_pos_embds"):
            pass  # the sinusoidal table is stored in the weights like a learned one
        return {"prefix": "distilbert.", "layers": cfg.get("n_layers"), "hidden": cfg.get("dim"),
                "heads": cfg.get("n_heads"), "eps": 1e-12, "act": cfg.get("activation", "gelu"),
                "positions": cfg.get("max_position_embeddings"),
                "emb": "embeddings.word_embeddings.weight", "pos": "embeddings.position_embeddings.weight",
                "type": None, "emb_ln": "embeddings.LayerNorm",
                "layer": "transformer.layer.{i}.", "q": "attention.q_lin", "k": "attention.k_lin",
                "v": "attention.v_lin", "o": "attention.out_lin", "ln1": "sa_layer_norm",
                "ff1": "ffn.lin1", "ff2": "ffn.lin2", "ln2": "output_layer_norm"}
    raise _NoGraph(f"model_type {mt!r} (built graphs: {', '.join(BUILT_MODEL_TYPES)})")


def build_graph(w: dict, cfg: dict, head: str, num_labels: int, where: str, *, int8: bool = False,
                lora: dict | None = None) -> BuiltGraph:
    """The classifier as an ONNX graph: ``(input_ids, attention_mask) -> logits``.

    ``w``: encoder weights without the model prefix (``embeddings.…``, ``encoder.layer.…``) plus the
    head's: ``head="mean"|"cls"`` reads ``head.weight``/``head.bias`` (ethimon's PooledClassifier);
    ``head="hf"`` reads the transformers sequence-classification head (BERT: pooler + classifier;
    DistilBERT: pre_classifier + ReLU + classifier). ``int8``: see :class:`_G`. ``lora``: from
    :func:`lora_pairs`, merged inside the graph (every pair must name an encoder linear).
    """
    lora = dict(lora or {})
    L = _layout(cfg)
    nl, hid, nh = L["layers"], L["hidden"], L["heads"]
    if not all(M._is_int(v) and v > 0 for v in (nl, hid, nh)) or hid % nh:
        raise ModelError(f"{where}: layers/hidden size/heads {nl}/{hid}/{nh} do not describe an encoder")
    dh = hid // nh

    def get(key: str):
        if key not in w:
            raise ModelError(f"{where}: weight {key!r} is missing; it would be randomly initialised: refused")
        t = w[key]
        if t.dtype.kind != "f":
            raise ModelError(f"{where}: weight {key!r} has dtype {t.dtype}; floating point expected")
        return t.astype(np.float32, copy=False)

    g = _G(int8)
    ids, mask = INPUTS
    # embeddings: word + position (+ token type 0, folded into the position table)
    pos_tab = get(L["pos"])
    if L["type"]:
        pos_tab = pos_tab + get(L["type"])[0][None, :]
    seq = g.op("Shape", ids, start=1, end=2)  # [L], 1-D
    pos = g.op("Slice", g.init("emb.pos", pos_tab), g.const([0]), seq, g.const([0]))  # rows 0..L-1
    x = g.op("Add", g.op("Gather", g.init("emb.word", get(L["emb"])), ids, axis=0), pos)
    x = g.layer_norm(x, get(L["emb_ln"] + ".weight"), get(L["emb_ln"] + ".bias"), L["eps"], "emb.ln")
    # additive attention mask [B, 1, 1, L]: 0 where attended, float32 min where padded (as transformers)
    maskf = g.op("Cast", mask, to=_FLOAT)
    neg = g.op("Mul", g.op("Sub", g.const(1.0, np.float32), maskf),
               g.const(np.finfo(np.float32).min, np.float32))
    bias = g.op("Unsqueeze", neg, g.const([1, 2]))
    # the hidden state runs as a [B·L, H] matrix (every linear a Gemm); attention reshapes to heads
    bl = g.op("Shape", ids)
    heads_shape = g.op("Concat", bl, g.const([nh, dh]), axis=0)
    flat = g.const([-1, hid])
    x = g.op("Reshape", x, flat)
    inv = g.const(1.0 / math.sqrt(dh), np.float32)
    for i in range(nl):
        p = L["layer"].format(i=i)

        def lin(v: str, key: str, _p=p, _i=i) -> str:
            wk = f"{_p}{L[key]}.weight"
            return g.linear(v, get(wk), get(f"{_p}{L[key]}.bias"), f"l{_i}.{key}", lora.pop(wk, None))

        q = g.op("Transpose", g.op("Reshape", lin(x, "q"), heads_shape), perm=[0, 2, 1, 3])
        k = g.op("Transpose", g.op("Reshape", lin(x, "k"), heads_shape), perm=[0, 2, 3, 1])
        v = g.op("Transpose", g.op("Reshape", lin(x, "v"), heads_shape), perm=[0, 2, 1, 3])
        scores = g.op("Add", g.op("Mul", g.op("MatMul", q, k), inv), bias)
        ctx = g.op("MatMul", g.op("Softmax", scores, axis=-1), v)
        ctx = g.op("Reshape", g.op("Transpose", ctx, perm=[0, 2, 1, 3]), flat)
        x = g.layer_norm(g.op("Add", lin(ctx, "o"), x), get(f"{p}{L['ln1']}.weight"), get(f"{p}{L['ln1']}.bias"),
                         L["eps"], f"l{i}.ln1")
        f = lin(_activation(g, lin(x, "ff1"), L["act"]), "ff2")
        x = g.layer_norm(g.op("Add", f, x), get(f"{p}{L['ln2']}.weight"), get(f"{p}{L['ln2']}.bias"),
                         L["eps"], f"l{i}.ln2")
    if lora:
        raise ModelError(f"{where}: adapter factors for {', '.join(sorted(lora)[:3])} name no linear layer of "
                         "the encoder's blocks")
    x = g.op("Reshape", x, g.op("Concat", bl, g.const([hid]), axis=0))  # [B, L, H]
    cls = g.op("Squeeze", g.op("Gather", x, g.const([0]), axis=1), g.const([1]))
    if head == "mean":
        m3 = g.op("Unsqueeze", maskf, g.const([-1]))
        total = g.op("ReduceSum", g.op("Mul", x, m3), g.const([1]), keepdims=0)
        count = g.op("Max", g.op("ReduceSum", m3, g.const([1]), keepdims=0), g.const([1.0], np.float32))
        pooled = g.op("Div", total, count)
        logits = g.linear(pooled, get("head.weight"), get("head.bias"), "head")
    elif head == "cls":
        logits = g.linear(cls, get("head.weight"), get("head.bias"), "head")
    elif cfg.get("model_type") == "bert":  # BertForSequenceClassification: tanh pooler + classifier
        pooled = g.op("Tanh", g.linear(cls, get("pooler.dense.weight"), get("pooler.dense.bias"), "pooler"))
        logits = g.linear(pooled, get("classifier.weight"), get("classifier.bias"), "classifier")
    else:  # DistilBertForSequenceClassification: pre_classifier + ReLU + classifier
        pre = g.op("Relu", g.linear(cls, get("pre_classifier.weight"), get("pre_classifier.bias"), "pre"))
        logits = g.linear(pre, get("classifier.weight"), get("classifier.bias"), "classifier")
    g.node("Identity", [logits], [OUTPUT])
    return g.model([_value_info(ids, _INT64, ["batch", "seq"]), _value_info(mask, _INT64, ["batch", "seq"])],
                   [_value_info(OUTPUT, _FLOAT, ["batch", num_labels])])


# ---------------------------------------------------------------- tokenizer
class FastTokenizer:
    """``tokenizer.json`` through the ``tokenizers`` library: ids without padding or truncation."""

    def __init__(self, d: Path) -> None:
        p = d / "tokenizer.json"
        if not p.is_file():
            raise _NoGraph(f"{d}: no tokenizer.json (the ONNX backend reads tokenizers' own format)")
        M.check_model_dir(d)
        try:
            tok = Tokenizer.from_file(str(p))
        except Exception as exc:  # noqa: BLE001
            raise ModelError(f"{p}: cannot load tokenizer: {type(exc).__name__}: {str(exc)[:160]}") from None
        tok.no_truncation()
        tok.no_padding()
        self._tok = tok
        bare = tok.encode("a", add_special_tokens=False).ids
        full = tok.encode("a", add_special_tokens=True).ids
        self.prefix, self.suffix = [], []
        for i in range(len(full) - len(bare) + 1):
            if full[i:i + len(bare)] == bare:
                self.prefix, self.suffix = list(full[:i]), list(full[i + len(bare):])
                break
        pad = None
        cfg = d / "tokenizer_config.json"
        if cfg.is_file():
            pt = M.read_json_object(cfg).get("pad_token")
            pt = pt.get("content") if isinstance(pt, dict) else pt
            pad = tok.token_to_id(pt) if isinstance(pt, str) else None
        self.pad_id = pad if pad is not None else 0

    def encode(self, texts: list[str], max_length: int, truncation: str) -> list[list[int]]:
        """Token ids as ``_backend.encode`` makes them (special tokens, head or head+tail truncation)."""
        budget = max_length - len(self.prefix) - len(self.suffix)
        if budget < 2:
            raise ValueError(f"max_length={max_length} leaves no room for text")
        out = []
        for e in self._tok.encode_batch(list(texts), add_special_tokens=False):
            seq = e.ids
            if len(seq) > budget:
                if truncation == "head_tail":
                    h = budget // 2
                    seq = seq[:h] + seq[len(seq) - (budget - h):]
                else:
                    seq = seq[:budget]
            out.append(self.prefix + list(seq) + self.suffix)
        return out


    def encode_views(self, views: list[tuple[str, str]], max_length: int, truncation: str) -> list[list[int]]:
        """``(context, focus)`` views as ``_backend.encode_views`` makes them (the same ids)."""
        from ._reading import pair_ids
        out: list = [None] * len(views)
        plain = [i for i, (c, _f) in enumerate(views) if not c]
        for i, seq in zip(plain, self.encode([views[i][1] for i in plain], max_length, truncation) if plain else []):
            out[i] = seq
        paired = [i for i, (c, _f) in enumerate(views) if c]
        if paired:
            ctx = self._tok.encode_batch([views[i][0] for i in paired], add_special_tokens=False)
            foc = self._tok.encode_batch([views[i][1] for i in paired], add_special_tokens=False)
            for i, c, f in zip(paired, ctx, foc):
                out[i] = pair_ids(self.prefix, self.suffix, c.ids, f.ids, max_length, truncation)
        return out


# ---------------------------------------------------------------- loading
@dataclass
class OnnxModel:
    session: Any
    tokenizer: FastTokenizer
    max_length: int
    truncation: str
    temperature: float
    unsafe_index: int
    model_id: str
    #: sha256 of the serialised graph ONNX Runtime runs (built graphs: equal on every machine)
    graph_sha256: str
    #: "built" (from the safetensors weights) or the exported file's name
    graph_source: str
    manifest: dict = field(default_factory=dict)
    #: the arrays a built graph's session reads (ONNX Runtime does not copy them: kept alive here)
    weights: dict = field(default_factory=dict, repr=False)

    def logits(self, seqs: list[list[int]]):
        n = max(len(s) for s in seqs)
        ids = np.full((len(seqs), n), self.tokenizer.pad_id, dtype=np.int64)
        mask = np.zeros((len(seqs), n), dtype=np.int64)
        for i, s in enumerate(seqs):
            ids[i, :len(s)] = s
            mask[i, :len(s)] = 1
        return self.session.run([OUTPUT], {"input_ids": ids, "attention_mask": mask})[0]


def session_options(num_threads: int | None) -> "ort.SessionOptions":
    """One intra-op pool of ``num_threads`` (default 1), no spinning (cores are shared), all graph optimisations."""
    so = ort.SessionOptions()
    so.intra_op_num_threads = int(num_threads or 1)
    so.inter_op_num_threads = 1
    so.execution_mode = ort.ExecutionMode.ORT_SEQUENTIAL
    so.graph_optimization_level = ort.GraphOptimizationLevel.ORT_ENABLE_ALL
    so.log_severity_level = 3
    so.add_session_config_entry("session.intra_op.allow_spinning", "0")
    so.add_session_config_entry("session.inter_op.allow_spinning", "0")
    return so


def _session(data: bytes, num_threads: int | None, weights: dict | None = None):
    so = session_options(num_threads)
    if weights:
        names = list(weights)
        so.add_external_initializers(names, [ort.OrtValue.ortvalue_from_numpy(weights[k]) for k in names])
    try:
        return ort.InferenceSession(data, sess_options=so, providers=["CPUExecutionProvider"])
    except Exception as exc:  # noqa: BLE001
        raise ModelError(f"ONNX Runtime refused the graph: {type(exc).__name__}: {str(exc)[:300]}") from None


def _config(d: Path) -> dict:
    p = d / "config.json"
    if not p.is_file():
        raise ModelError(f"{d}: config.json is missing")
    return M.read_json_object(p)


def _strip(w: dict, prefix: str) -> dict:
    return {k[len(prefix):] if k.startswith(prefix) else k: v for k, v in w.items()}


def load_onnx_model(model_dir: str | os.PathLike, *, max_length: int | None = None, quantize: str | None = None,
                    num_threads: int | None = None) -> OnnxModel:
    """The ONNX form of a model directory (see the module docstring for where the graph comes from).

    Raises:
        _NoGraph: this directory has no ONNX form here (``auto`` then uses torch).
        ModelError: the directory, a pinned file or the graph is refused.
    """
    d = Path(model_dir)
    if not d.is_dir():
        raise ModelError(f"model directory {d} does not exist")
    manifest = M.read_manifest(d)
    M.check_model_dir(d)
    exported = d / GRAPH_MANIFEST
    if exported.exists() or exported.is_symlink():
        return _load_exported(d, manifest, max_length, quantize, num_threads)
    if manifest is None:
        return _build_hf_dir(d, max_length, quantize, num_threads)
    adapter, got = M.checked_adapter(d, manifest)
    base_dir = M.resolve_base(d, manifest)
    base_w = base_dir / "model.safetensors"
    if not base_w.is_file():
        M.check_no_pickle_only(base_dir)
        raise ModelError(f"{base_w} is missing (the base weights must be model.safetensors)")
    want_b = manifest.get("base_sha256")
    # the pinned base (90 MB) is hashed on a second thread while the graph is built (hashlib lets go of
    # the GIL); nothing is returned, and no session serves a text, before the digest has matched
    base_sha = _Digest(base_w) if want_b else None
    M.check_model_dir(base_dir)
    cfg = _config(base_dir)
    layout = _layout(cfg)  # _NoGraph before the weights are read
    tok = FastTokenizer(d if any((d / n).is_file() for n in M.TOKENIZER_FILES) else base_dir)
    w = _strip(_load_st(base_w, "weights"), layout["prefix"])
    tensors = _adapter_arrays(adapter)
    lora, pairs = manifest.get("lora"), None
    if lora:
        scale = float(lora["alpha"]) / float(lora["r"])
        if quantize == "int8":
            merge_lora_np(w, tensors, scale, adapter)
        else:
            pairs = lora_pairs(w, tensors, scale, adapter)
    num_labels = manifest.get("num_labels", 2)
    for k in ("head.weight", "head.bias"):
        if k not in tensors:
            raise ModelError(f"{adapter}: head weights missing ({k})")
        w[k] = tensors[k]
    if w["head.weight"].shape != (num_labels, layout["hidden"]) or w["head.bias"].shape != (num_labels,):
        raise ModelError(f"{adapter}: head weights of the wrong shape {w['head.weight'].shape}")
    ml = int(max_length or manifest.get("max_length", 128))
    pos = M.usable_positions(_Cfg(cfg))
    if pos is not None and ml > pos:
        mp = d / M.MANIFEST
        src = f"max_length={ml}" if max_length else f"{mp}: 'max_length' = {ml}"
        raise ModelError(f"{src}: more tokens than the base model's {pos} positions ({base_dir / 'config.json'})")
    built = build_graph(w, cfg, manifest.get("pooling", "mean"), num_labels, str(d), int8=quantize == "int8",
                        lora=pairs)
    name = manifest.get("name", d.name)
    out = _finish(built, "built", tok, ml, manifest.get("truncation", "head_tail"),
                  float(manifest.get("temperature", 1.0)), manifest.get("unsafe_index", num_labels - 1),
                  f"{name}@{got[:12]}", manifest, quantize, num_threads)
    if base_sha is not None and base_sha.result() != want_b:  # before the session is handed out
        raise ModelError(f"{base_w}: sha256 mismatch with the pinned base "
                         f"({want_b[:12]}…); reinstall the exact base ({M.BASE_PIP})")
    return out


class _Digest:
    """``M.sha256_file(path)`` computed on a thread; :meth:`result` waits for it (and re-raises its error)."""

    def __init__(self, path: Path) -> None:
        import threading
        self._out: list = []
        self._t = threading.Thread(target=self._run, args=(path,), name="ethimon-sha256", daemon=True)
        self._t.start()

    def _run(self, path: Path) -> None:
        try:
            self._out.append(M.sha256_file(path))
        except BaseException as exc:  # noqa: BLE001 - handed to result()
            self._out.append(exc)

    def result(self) -> str:
        self._t.join()
        r = self._out[0]
        if isinstance(r, BaseException):
            raise ModelError(f"cannot hash the base weights: {r}") from r
        return r


class _Cfg:
    """A config.json dict seen through attributes (for ``usable_positions``)."""

    def __init__(self, d: dict) -> None:
        self.__dict__.update(d)


def _finish(built: BuiltGraph, source: str, tok, ml, trunc, temp, ui, model_id, manifest, quantize,
            num_threads) -> OnnxModel:
    session = _session(built.proto, num_threads, built.weights)
    return OnnxModel(session, tok, ml, trunc, temp, ui, model_id, built.sha256, source, manifest or {},
                     built.weights)


def _build_hf_dir(d: Path, max_length: int | None, quantize, num_threads) -> OnnxModel:
    if not (d / "config.json").is_file():
        raise ModelError(f"{d}: neither {M.MANIFEST} nor config.json found; not a model directory")
    cfg = M.check_model_dir(d) or {}
    M._check_classifier_config(d / "config.json", cfg)
    layout = _layout(cfg)
    M.check_no_pickle_only(d)
    weights = sorted(d.glob("*.safetensors"))
    if len(weights) != 1:
        raise _NoGraph(f"{d}: {len(weights)} safetensors files (sharded weights)")
    tok = FastTokenizer(d)
    id2label = cfg.get("id2label")
    n = len(id2label) if isinstance(id2label, dict) else cfg.get("num_labels", 2)
    w = _strip(_load_st(weights[0], "weights"), layout["prefix"])
    pos = M.usable_positions(_Cfg(cfg))
    tcfg = M.read_json_object(d / "tokenizer_config.json") if (d / "tokenizer_config.json").is_file() else {}
    limit = tcfg.get("model_max_length", 512)
    ml = int(max_length or min(512, limit if M._is_int(limit) and limit < 100000 else 512, pos or 512))
    if pos is not None and ml > pos:
        raise ModelError(f"max_length={ml}: more tokens than the {pos} positions of {d / 'config.json'}")
    built = build_graph(w, cfg, "hf", n, str(d), int8=quantize == "int8")
    digest = M.sha256_file(weights[0])[:12]
    return _finish(built, "built", tok, ml, "head", 1.0, n - 1, f"{d.name}@{digest}", {}, quantize,
                   num_threads)


def _load_exported(d: Path, manifest: dict | None, max_length, quantize, num_threads) -> OnnxModel:
    """A graph file written by ``ethimon export``, pinned by ``ethimon_onnx.json``."""
    sp = d / GRAPH_MANIFEST
    side = check_graph_manifest(sp, M.read_json_object(sp, "the graph manifest"))
    kind = "int8" if quantize == "int8" else "fp32"
    entry = side["graphs"].get(kind)
    if entry is None:
        raise ModelError(f"{sp}: no {kind} graph (exported: {', '.join(side['graphs'])}); "
                         f"run `ethimon export {d}{' --int8' if kind == 'int8' else ''}`")
    source = _source_sha(d, manifest)
    if source != side["source_sha256"]:
        raise ModelError(f"{sp}: the graph was exported from weights {side['source_sha256'][:12]}…, the "
                         f"directory now holds {source[:12]}…; the graph is stale: run `ethimon export {d}`")
    gp = d / entry["file"]
    data = _read_pinned(gp, entry["sha256"], sp)
    try:
        import onnx  # parsing a graph file for its checks (building one needs no onnx)
    except ImportError as exc:
        raise DependencyNotInstalled(f"checking an exported graph needs the onnx package: pip install "
                                     f'"ethimon[risk]" ({exc})') from exc
    try:
        model = onnx.load_model_from_string(data)
    except Exception as exc:  # noqa: BLE001
        raise ModelError(f"{gp}: not an ONNX model ({type(exc).__name__}: {str(exc)[:160]})") from None
    files = check_graph(model, str(gp), d)
    pins = entry.get("data_sha256", {})
    for f in files:
        rel = f.relative_to(Path(os.path.realpath(d))).as_posix()
        if rel not in pins:
            raise ModelError(f"{gp}: external-data file {rel} is not pinned in {sp}")
        _read_pinned(f, pins[rel], sp, keep=False)
    tok = FastTokenizer(d if manifest is None or any((d / n).is_file() for n in M.TOKENIZER_FILES)
                        else M.resolve_base(d, manifest))  # the tokenizer torch would read
    ml = int(max_length or side["max_length"])
    if files:  # ONNX Runtime reads external data next to the graph file: give it the checked path
        try:
            session = ort.InferenceSession(str(gp), sess_options=session_options(num_threads),
                                           providers=["CPUExecutionProvider"])
        except Exception as exc:  # noqa: BLE001
            raise ModelError(f"{gp}: ONNX Runtime refused the graph: {type(exc).__name__}: {str(exc)[:300]}") \
                from None
    else:
        session = _session(data, num_threads)
    name = (manifest or {}).get("name", d.name)
    return OnnxModel(session, tok, ml, side["truncation"], float(side["temperature"]), side["unsafe_index"],
                     f"{name}@{source[:12]}", entry["sha256"], entry["file"], manifest or {})


def _source_sha(d: Path, manifest: dict | None) -> str:
    """sha256 of what a graph of ``d`` is made from: the (checked) adapter, else the one weights file."""
    if manifest is not None:
        return M.checked_adapter(d, manifest)[1]
    weights = sorted(d.glob("*.safetensors"))
    if len(weights) != 1:
        raise ModelError(f"{d}: {len(weights)} safetensors files; an exported directory has one weights file")
    return M.sha256_file(weights[0])


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
