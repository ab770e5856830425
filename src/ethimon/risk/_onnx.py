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
from ._encoder import default_labels, hf_labels
from ._onnx_build import (BUILT_MODEL_TYPES, _adapter_arrays, _layout, _load_st, _NoGraph, build_graph, lora_pairs,
                          merge_lora_np)
from ._onnx_check import (ALLOWED_DOMAINS, GRAPH_FORMAT, GRAPH_KEYS, GRAPH_MANIFEST, INPUTS, OUTPUT, _read_pinned,
                          check_graph, check_graph_manifest)
from ._onnx_proto import OPSET, BuiltGraph

# the rooms: the graph's trust checks (_onnx_check), its protobuf writer (_onnx_proto), building one from
# safetensors weights (_onnx_build); here the tokenizer and loading, and the names callers read as ``O.``
__all__ = ["ALLOWED_DOMAINS", "BUILT_MODEL_TYPES", "BuiltGraph", "FastTokenizer", "GRAPH_FORMAT", "GRAPH_KEYS",
           "GRAPH_MANIFEST", "INPUTS", "OPSET", "OUTPUT", "OnnxModel", "build_graph", "check_graph",
           "check_graph_manifest", "load_onnx_model", "lora_pairs", "merge_lora_np", "session_options"]


# ---------------------------------------------------------------- tokenizer
class FastTokenizer:
    """``tokenizer.json`` through the ``tokenizers`` library: ids without padding or truncation."""

    def __init__(self, d: Path) -> None:
        p = d / "tokenizer.json"
        if not p.is_file():
            raise _NoGraph(f"{d}: no tokenizer.json (the ONNX backend reads tokenizers' own format)")
        M.check_model_dir(d)
        try:
            tok = M.tokenizer_call(p, "loading", Tokenizer.from_file, str(p))
        except ModelError:
            raise
        except Exception as exc:  # noqa: BLE001
            raise ModelError(f"{p}: cannot load tokenizer: {type(exc).__name__}: {str(exc)[:160]}") from None
        tok.no_truncation()
        tok.no_padding()
        self._tok, self._path = tok, p
        bare = M.tokenizer_call(p, "encoding", tok.encode, "a", add_special_tokens=False).ids
        full = M.tokenizer_call(p, "encoding", tok.encode, "a", add_special_tokens=True).ids
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
        for e in M.tokenizer_call(self._path, "encoding", self._tok.encode_batch, list(texts), add_special_tokens=False):
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
            enc = self._tok.encode_batch
            ctx = M.tokenizer_call(self._path, "encoding", enc, [views[i][0] for i in paired], add_special_tokens=False)
            foc = M.tokenizer_call(self._path, "encoding", enc, [views[i][1] for i in paired], add_special_tokens=False)
            for i, c, f in zip(paired, ctx, foc):
                out[i] = pair_ids(self.prefix, self.suffix, c.ids, f.ids, max_length, truncation)
        return out

    def _encode_many(self, texts: list[str]) -> list:
        """The encodings of ``texts`` without special tokens: the same ids either way; one text through
        ``encode`` (``encode_batch`` costs ~0.1 ms more to hand one text to its thread pool)."""
        if len(texts) == 1:
            return [self._tok.encode(texts[0], add_special_tokens=False)]
        return self._tok.encode_batch(texts, add_special_tokens=False)

    def encode_view_windows(self, views: list[tuple[str, str]], max_length: int,
                            truncation: str) -> list[list[list[int]]]:
        """As ``_backend.encode_view_windows``: per view, the sequences that read it in full."""
        from ._reading import pair_windows
        if not views:
            return []
        enc = self._encode_many
        foc = enc([f for _c, f in views])
        # only the views that have a context tokenise one (a one-line command has none: one call, not two)
        with_ctx = [c for c, _f in views if c]
        ctx = iter(enc(with_ctx)) if with_ctx else iter(())
        return [pair_windows(self.prefix, self.suffix, next(ctx).ids if cs else [], f.ids, max_length, truncation)
                for (cs, _f), f in zip(views, foc)]


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
    #: the K class names (the manifest's ``labels``, a HF config's ``id2label``, else the defaults)
    labels: tuple = ()
    backend: str = "onnx"
    #: never: a graph is optimised when its session starts
    jit: bool = False

    def encode(self, views: list[tuple[str, str]]) -> list[list[list[int]]]:
        return self.tokenizer.encode_view_windows(views, self.max_length, self.truncation)

    def trace(self) -> bool:
        """Nothing to do: ONNX Runtime optimises the graph when its session starts."""
        return False

    def logits(self, seqs: list[list[int]]):
        """One session run; rows padded to the longest row of this batch (its mask says which tokens count)."""
        n = max(len(s) for s in seqs)
        if all(len(s) == n for s in seqs):      # one text, or rows of one length: no padding to write
            ids = np.array(seqs, dtype=np.int64)
            mask = np.ones(ids.shape, dtype=np.int64)
        else:
            ids = np.full((len(seqs), n), self.tokenizer.pad_id, dtype=np.int64)
            mask = np.zeros((len(seqs), n), dtype=np.int64)
            for i, s in enumerate(seqs):
                ids[i, :len(s)] = s
                mask[i, :len(s)] = 1
        return self.session.run(_OUTPUTS, {"input_ids": ids, "attention_mask": mask})[0]


_OUTPUTS = [OUTPUT]


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
    out.labels = tuple(manifest.get("labels") or default_labels(num_labels))
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
    out = _finish(built, "built", tok, ml, "head", 1.0, n - 1, f"{d.name}@{digest}", {}, quantize, num_threads)
    out.labels = hf_labels(cfg, n)
    return out


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
    out = OnnxModel(session, tok, ml, side["truncation"], float(side["temperature"]), side["unsafe_index"],
                    f"{name}@{source[:12]}", entry["sha256"], entry["file"], manifest or {})
    if manifest is not None:
        n = manifest.get("num_labels", 2)
        out.labels = tuple(manifest.get("labels") or default_labels(n))
    else:
        n = int(side["unsafe_index"]) + 1
        cfg = M.read_json_object(d / "config.json") if (d / "config.json").is_file() else {}
        id2 = cfg.get("id2label")
        out.labels = hf_labels(cfg, len(id2) if isinstance(id2, dict) else cfg.get("num_labels", n))
    return out



def _source_sha(d: Path, manifest: dict | None) -> str:
    """sha256 of what a graph of ``d`` is made from: the (checked) adapter, else the one weights file."""
    if manifest is not None:
        return M.checked_adapter(d, manifest)[1]
    weights = sorted(d.glob("*.safetensors"))
    if len(weights) != 1:
        raise ModelError(f"{d}: {len(weights)} safetensors files; an exported directory has one weights file")
    return M.sha256_file(weights[0])
