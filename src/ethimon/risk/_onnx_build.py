"""A BERT or DistilBERT risk graph built from its safetensors weights (numpy): the base weights and the
LoRA adapter read and checked, the encoder, pooling and head written as standard ONNX operators."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ModelError
from . import _modeldir as M
from ._onnx_check import INPUTS, OUTPUT
from ._onnx_proto import _FLOAT, _INT64, BuiltGraph, _G, _value_info

#: families :func:`build_graph` writes from safetensors weights (others need an exported model.onnx)
BUILT_MODEL_TYPES = ("bert", "distilbert")


class _NoGraph(Exception):
    """This model has no ONNX graph here (unsupported family, no exported file): ``auto`` uses torch.

    Never raised for a trust failure (a wrong sha256, a refused graph): those are :class:`ModelError`.
    """



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
