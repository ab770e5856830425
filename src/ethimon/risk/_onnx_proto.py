"""ONNX's protobuf, written directly (no ``onnx`` package to build a graph): the messages a graph needs,
the graph writer :class:`_G` (linears with LoRA merged in the graph, int8 quantisation, layer norm, GELU)
and the :class:`BuiltGraph` it gives."""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

OPSET = 17
#: version of the graph builder; part of :attr:`OnnxModel.graph_sha256`'s meaning
BUILDER_VERSION = 1
#: the external-data "location" of a built graph's weights: handed to ONNX Runtime as arrays, never a file
MEMORY = "ethimon-memory"
#: the encoder linears an int8 graph quantises: the attention's (q, k, v, o). The feed-forward pair,
#: the pooler and the head stay fp32. Measured on the 555 natural test rows against fp32 decisions
#: (bench/results/risk/risk_onnx.json): all six linears 538/555, q/k/v/o 546/555 (p50 1.4 vs 2.4 ms,
#: load 2); neither reaches 99.5 %, so int8 stays opt-in (``quantize: int8``), never the default.
INT8_LINEARS = ("q", "k", "v", "o")
#: initializers up to this many elements are written into the graph itself (shapes, axes, constants)
INLINE_MAX = 64


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
