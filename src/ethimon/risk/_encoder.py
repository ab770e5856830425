"""The risk back-end protocol: an :class:`Encoder` turns views into token windows and windows into
logits; back-ends are registered here, in code, and chosen by name (a spec's
``risk.estimator.backend``, ``load_estimator(backend=...)``, a model directory's ``"encoder"``
manifest key). A spec or a model directory never names code: only a registered name.

Two encoders are registered: ``onnx`` (ONNX Runtime + tokenizers, ``_onnx.OnnxModel``) and
``torch`` (torch + transformers, ``_backend.LoadedModel``). ``auto`` tries the registered
encoders in order (``onnx`` first) and takes the first that has a form of the model.
Torch-free: the loaders import their back-end lazily.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any, Protocol, runtime_checkable

__all__ = ["Encoder", "NoFormHere", "register_encoder", "encoder_names", "load_encoder", "default_labels", "hf_labels"]


@runtime_checkable
class Encoder(Protocol):
    """What the estimator loop (``_estimator.RiskEstimator``) needs of a back-end.

    Attributes:
        model_id: the model's identity for audit logs (name @ adapter digest).
        labels: the K class names, in the order of :meth:`logits`' columns.
        unsafe_index: which class is unsafe (0 ≤ unsafe_index < K).
        temperature: the model's softmax temperature (the estimator may override it).
        max_length, truncation: the token budget and how a text longer than it is read.
        backend: the name this encoder is registered under.
        jit: whether :meth:`trace` has swapped in an optimised copy.
    """

    model_id: str
    labels: tuple[str, ...]
    unsafe_index: int
    temperature: float
    max_length: int
    truncation: str
    backend: str
    jit: bool

    def encode(self, views: list[tuple[str, str]]) -> list[list[list[int]]]:
        """Per ``(context, focus)`` view, the token sequences that read it in full
        (``_reading.pair_windows``; one sequence unless the focus overflows the window)."""
        ...

    def logits(self, seqs: list[list[int]]) -> Any:
        """Raw logits, one row of K numbers per sequence (padding is the encoder's business)."""
        ...

    def trace(self) -> bool:
        """Swap in an optimised copy checked against the model if the back-end has one; return :attr:`jit`."""
        ...


class NoFormHere(Exception):
    """Raised by a loader when this back-end has no form of the model (``auto`` tries the next one).
    Never raised for a trust failure: those are ``ModelError`` and propagate."""


#: loader(model_dir, *, quantize, max_length, num_threads) -> Encoder
Loader = Callable[..., Encoder]
_REGISTRY: dict[str, Loader] = {}


def register_encoder(name: str, loader: Loader) -> None:
    """Register a back-end under ``name`` (code, never a spec: a spec only names it)."""
    if not name.isidentifier() or name == "auto":
        raise ValueError(f"encoder name {name!r}: an identifier other than 'auto' expected")
    _REGISTRY[name] = loader


def encoder_names() -> tuple[str, ...]:
    """The registered back-ends, in the order ``auto`` tries them."""
    return tuple(_REGISTRY)


def default_labels(k: int) -> tuple[str, ...]:
    """Class names of a model that names none: ``("safe", "unsafe")``, else ``class_0 … class_{K-1}``."""
    return ("safe", "unsafe") if k == 2 else tuple(f"class_{i}" for i in range(k))


def hf_labels(config: dict, n: int) -> tuple[str, ...]:
    """A HF config's ``id2label`` names in index order, else :func:`default_labels` of ``n`` classes."""
    id2 = config.get("id2label") if isinstance(config, dict) else None
    if isinstance(id2, dict) and len(id2) == n:
        names = [id2.get(str(i), id2.get(i)) for i in range(n)]
        if all(isinstance(x, str) for x in names):
            return tuple(names)
    return default_labels(n)


def load_encoder(model_dir: str | Path, backend: str = "auto", **kw: Any) -> Encoder:
    """The encoder of ``model_dir`` by name; ``auto``: the directory's ``"encoder"`` manifest key if it
    has one, else the first registered back-end with a form of it.

    Raises:
        ValueError: an unknown name.
        DependencyNotInstalled, ModelError: from the back-end.
    """
    from ..errors import DependencyNotInstalled, ModelError
    if backend != "auto":
        if backend not in _REGISTRY:
            raise ValueError(f"backend={backend!r}; expected one of {('auto',) + encoder_names()}")
        try:
            return _REGISTRY[backend](model_dir, **kw)
        except NoFormHere as exc:
            raise ModelError(f"{model_dir}: no {'ONNX' if backend == 'onnx' else backend} form: {exc}; write one with `ethimon export {model_dir}` "
                             "(needs torch once) or use backend torch") from None
    named = _manifest_encoder(Path(model_dir))
    if named is not None:
        return load_encoder(model_dir, named, **kw)
    names = encoder_names()
    for i, name in enumerate(names):
        try:
            return _REGISTRY[name](model_dir, **kw)
        except NoFormHere:
            continue
        except DependencyNotInstalled as exc:
            if i < len(names) - 1:
                continue
            raise DependencyNotInstalled(
                f"{exc}; or, without torch, ONNX Runtime: pip install \"ethimon[risk]\" (the ONNX backend "
                f"runs the shipped model and BERT/DistilBERT directories, others after `ethimon export`)") from exc
    raise ModelError(f"{model_dir}: no registered back-end ({', '.join(names)}) has a form of this model")


def _manifest_encoder(d: Path) -> str | None:
    """The ``"encoder"`` a model directory's manifest names (data: a registered name, never code)."""
    from . import _modeldir as M
    if not (d / M.MANIFEST).is_file():
        return None
    name = (M.read_manifest(d) or {}).get("encoder")
    if name is None:
        return None
    if name not in _REGISTRY:
        from ..errors import ModelError
        raise ModelError(f"{d / M.MANIFEST}: 'encoder' {name!r} is not a registered back-end "
                         f"(registered: {', '.join(encoder_names())})")
    return name


# ---------------------------------------------------------------- the two back-ends of the package
def _load_onnx(model_dir, *, quantize=None, max_length=None, num_threads=None) -> Encoder:
    from . import _onnx as O
    try:
        return O.load_onnx_model(model_dir, max_length=max_length, quantize=quantize, num_threads=num_threads)
    except O._NoGraph as exc:
        raise NoFormHere(str(exc)) from None


def _load_torch(model_dir, *, quantize=None, max_length=None, num_threads=None) -> Encoder:
    from . import _backend as B
    if num_threads is not None:
        B.torch.set_num_threads(int(num_threads))
    loaded = B.load_model(model_dir, max_length=max_length)
    if quantize == "int8":
        import warnings
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            loaded.module = B.torch.ao.quantization.quantize_dynamic(loaded.module, {B.nn.Linear},
                                                                     dtype=B.torch.qint8)
    return loaded


register_encoder("onnx", _load_onnx)
register_encoder("torch", _load_torch)
