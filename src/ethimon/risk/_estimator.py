"""The learned risk estimator: text -> class probabilities -> R_e.

No torch at import time; :func:`load_estimator` imports the backend lazily.

Fail-closed contract: a failed inference or one that yields a NaN/inf
probability raises :class:`RiskInferenceError` (an :class:`EthimonError`);
nothing is cached for it and no low risk is ever returned in its place.
"""

from __future__ import annotations

import math
import sys
import threading
import time
import unicodedata
from collections import OrderedDict
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Protocol, runtime_checkable

from ..errors import RiskInferenceError
from ._formula import DEFAULT_ALPHA, DEFAULT_BETA, DEFAULT_GAMMA, VARIANCE_MODES, risk_from_probs
from ._reading import READINGS, View, views

__all__ = ["DEFAULT_TAU", "ProbsEstimator", "RiskEstimate", "RiskEstimator", "RiskInferenceError", "load_estimator",
           "default_model_dir", "default_threads", "normalize_text"]


@runtime_checkable
class ProbsEstimator(Protocol):
    """Anything with ``probs(text) -> (p_0, ..., p_{K-1})``: a :class:`RiskEstimator`
    (:func:`load_estimator`), a ``ProcessEstimator``, or a test's fixed source. What scenarios,
    replay and :class:`~ethimon.loop.AsyncRiskSource` score task texts with."""

    def probs(self, text: str) -> Sequence[float]: ...

QUANTIZE_MODES = (None, "fp32", "int8")
#: inference backends (the encoders registered in ``_encoder``): ``onnx`` (ONNX Runtime + tokenizers,
#: no torch in the process), ``torch`` (torch + transformers, what training uses), ``auto`` (the model
#: directory's ``"encoder"``, else ONNX when onnxruntime is installed and the model has an ONNX form,
#: else torch)
BACKENDS = ("auto", "onnx", "torch")

#: rows an estimator scores eagerly at most before it traces itself (``jit=None``). Tracing
#: (TorchScript trace + freeze + a check against the eager model) costs about 0.5 s
#: on one quiet core and saves about 1.5–5 ms per sentence, so it pays after a few
#: hundred sentences: in an evaluation or a long-running service, never in a
#: one-shot command that scores one text.
JIT_AFTER_ROWS = 256


def default_threads(rows: int) -> int:
    """Torch threads for a command that scores ``rows`` texts: 1 for one text, else at most 2.

    One sentence is too small to split (a second thread only adds start-up and
    synchronisation); a batch uses up to two threads, fewer when the cores are
    busy (a thread per core that another process already keeps busy makes
    OpenMP spin: measured 7x slower on 2 shared cores). The rule reads the
    cores this process may use and the 1-minute load average.

    >>> default_threads(1)
    1
    >>> 1 <= default_threads(64) <= 2
    True
    """
    if rows <= 1:
        return 1
    import os
    try:
        cores = len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        cores = os.cpu_count() or 1
    try:
        load = os.getloadavg()[0]
    except (AttributeError, OSError):  # pragma: no cover - not Unix
        load = 0.0
    return max(1, min(2, cores, int(cores - load + 0.5)))


@dataclass(frozen=True)
class RiskEstimate:
    """One risk estimate of a task text.

    Attributes:
        p: the K class probabilities (two classes: ``(p_safe, p_unsafe)``).
        p_unsafe: probability of the unsafe class.
        risk: R_e by the spec's formula.
        latency_s: wall time of this call (cache hits included).
        cached: whether the probabilities came from the LRU cache.
        model_id: the estimator's ``model_id`` (for audit logs).
        t_monotonic: ``time.monotonic()`` when the estimate was made; the
            monitor's ``risk_age_s`` is ``time.monotonic() - t_monotonic``.
    """

    p: tuple[float, ...]
    p_unsafe: float
    risk: float
    latency_s: float
    cached: bool = False
    model_id: str = ""
    t_monotonic: float = 0.0


def default_model_dir() -> Path:
    """The shipped default model directory (inside the installed package)."""
    return Path(__file__).resolve().parent / "default_model"


#: sha256 of the shipped ``default_model/ethimon_model.json``. The manifest pins the
#: adapter and base weights by sha256, and carries the temperature; pinning the
#: manifest itself here means an edited shipped model (weights, T, labels) is refused.
DEFAULT_MANIFEST_SHA256 = "2fb9a23c13c368ea220cc2e06c42e02a848c78193857a46d070876ccd76efbfe"

#: τ of the shipped default model: R_e ≥ τ flags a text. Chosen on validation rows of writers the
#: model never trained on (val_other + w13–w21 train.csv) for a 10 % false-alarm budget
#: (MODEL_CARD.md, bench/results/risk/writers/DECISIONS.md); ``ethimon risk``/``evaluate``
#: use it without ``--spec``, and the shipped specs write it as their ``risk.threshold``.
#: (A spec that writes no threshold gets the spec language's default, 0.5.)
DEFAULT_TAU = 0.606
#: τ_confirm of the shipped default model (MODEL_CARD.md; specs/governor.yaml's risk.confirm_threshold):
#: ``ethimon risk`` without ``--spec`` uses this pair; ``ethimon lint`` warns on a spec that loads the
#: shipped model with another.
DEFAULT_TAU_CONFIRM = 0.328


def model_tau_warnings(spec: Any) -> list[str]:
    """``ethimon lint``: a spec with a ``risk:`` block that loads the shipped model at another τ (or
    a confirm band at another τ_confirm) than the model card's pair; no band at all is a choice.

    Whether the spec writes a ``risk:`` block is read from the spec; τ, τ_confirm and the model from its plan."""
    if "risk" not in getattr(spec, "model_fields_set", ()):
        return []
    from ..compiler import plan_of
    plan = plan_of(spec)
    if plan.estimator.model is not None:
        return []
    tau, tc = plan.risk_plan.threshold, plan.tiers.confirm_threshold
    if tau == DEFAULT_TAU and (tc is None or tc == DEFAULT_TAU_CONFIRM):
        return []
    have = f"tau {tau:g}" + (f", tau_confirm {tc:g}" if tc is not None else "")
    return [f"risk: {have} differs from the shipped model's pair (tau {DEFAULT_TAU:g}, tau_confirm "
            f"{DEFAULT_TAU_CONFIRM:g}; MODEL_CARD.md), which this spec loads (no risk.estimator.model): "
            "the outcome figures of the model card do not hold at another pair"]


def check_default_manifest(d: Path) -> None:
    """Refuse a shipped default model whose manifest is not the one this code pins."""
    import hashlib

    from ..errors import ModelError
    p = d / "ethimon_model.json"
    try:
        digest = hashlib.sha256(p.read_bytes()).hexdigest()
    except OSError as exc:
        raise ModelError(f"{p}: cannot read the default model's manifest: {exc.strerror or exc}") from None
    if digest != DEFAULT_MANIFEST_SHA256:
        raise ModelError(f"{p}: sha256 {digest[:12]}… does not match the pinned default model "
                         f"({DEFAULT_MANIFEST_SHA256[:12]}…); the shipped model was modified — reinstall ethimon")


def normalize_text(text: str) -> str:
    r"""Cache key of a task text: NFKC, surrounding/duplicate whitespace removed; line breaks
    (one per non-empty line) kept, since a plan's or a code block's lines are its steps.

    >>> normalize_text("  1.  pick(x)\n\n  2. place(y) ")
    '1. pick(x)\n2. place(y)'
    """
    if not text.isascii():
        text = unicodedata.normalize("NFKC", text)
    if "\n" not in text and "\r" not in text:
        return " ".join(text.split())
    return "\n".join(" ".join(ln.split()) for ln in text.splitlines() if ln.strip())


class RiskEstimator:
    """Wraps a loaded classifier with batching, an LRU cache and the R_e formula.

    Build one with :func:`load_estimator`. Thread-safe: one lock serialises
    inference and cache updates.
    """

    def __init__(self, loaded: Any, *, cache_size: int = 4096, batch_size: int = 32,
                 quantized: str | None = None, trace_after: int | None = None,
                 reading: str = "steps") -> None:
        if reading not in READINGS:
            raise ValueError(f"reading={reading!r}; expected one of {READINGS}")
        #: how a text is read (``ethimon.risk._reading``): ``"steps"`` scores every step of a plan
        #: in context and the instruction after a scene, and takes the riskiest; ``"flat"`` the text only
        self.reading = reading
        self._m = loaded
        self._cache: OrderedDict[str, tuple[float, ...]] = OrderedDict()
        self._cache_size = int(cache_size)
        self._batch_size = int(batch_size)
        self._lock = threading.RLock()
        self._hits = 0
        self._misses = 0
        self.quantized = quantized
        self.model_id = loaded.model_id + ("+int8" if quantized == "int8" else "")
        self.max_length = loaded.max_length
        self.truncation = loaded.truncation
        self.temperature = loaded.temperature
        #: the registered name of the encoder that runs (``"onnx"``: ONNX Runtime, no torch; ``"torch"``)
        self.backend = loaded.backend
        #: the K class names; :meth:`probs` returns K probabilities in this order
        self.labels = tuple(loaded.labels)
        #: sha256 of the ONNX graph that runs (``None`` on torch), for audit logs
        self.graph_sha256 = getattr(loaded, "graph_sha256", None)
        #: whether the model runs as a TorchScript-frozen copy (see :meth:`trace`; never on ONNX)
        self.jit = bool(loaded.jit)
        self._trace_after = trace_after
        self._rows = 0
        #: raw logits of every view scored, keyed by its content (context and focus): a plan read again
        #: with one more step, or a step shared by texts, is scored once (bounded like the text cache)
        self._views: OrderedDict[str, tuple[float, ...]] = OrderedDict()
        self._views_size = 8 * self._cache_size
        #: where p_unsafe is in what :meth:`probs` returns (1 for two classes: ``(p_safe, p_unsafe)``)
        self.unsafe_at = _at(loaded.unsafe_index, len(self.labels))

    # -------------------------------------------------------------- public
    def probs(self, text: str) -> tuple[float, ...]:
        """``(p_safe, p_unsafe)`` of one text (cached).

        Raises:
            TypeError: ``text`` is not a string.
            RiskInferenceError: the forward pass failed or gave NaN/inf.
        """
        if not isinstance(text, str):
            raise TypeError(f"text must be a str, got {type(text).__name__}")
        key = normalize_text(text)
        cache = self._cache
        with self._lock:
            hit = cache.get(key)
            if hit is not None:
                cache.move_to_end(key)
                self._hits += 1
                return hit
        return self._infer([key])[0]

    def probs_batch(self, texts: list[str]) -> list[tuple[float, ...]]:
        """Probabilities of many texts; uncached ones run in length-sorted batches."""
        keys = []
        for t in texts:
            if not isinstance(t, str):
                raise TypeError(f"texts must be strings, got {type(t).__name__}")
            keys.append(normalize_text(t))
        out: dict[str, tuple[float, ...]] = {}
        with self._lock:
            for k in keys:
                hit = self._cache.get(k)
                if hit is not None:
                    self._cache.move_to_end(k)
                    self._hits += 1
                    out[k] = hit
        todo = list(dict.fromkeys(k for k in keys if k not in out))
        if todo:
            out.update(zip(todo, self._infer(todo)))
        return [out[k] for k in keys]

    def estimate(self, text: str, alpha: float = DEFAULT_ALPHA, beta: float = DEFAULT_BETA,
                 gamma: float = DEFAULT_GAMMA, variance: str = "sample") -> RiskEstimate:
        """Probabilities and R_e of one text.

        Example:
            >>> est = load_estimator()                       # doctest: +SKIP
            >>> est.estimate("Hand the knife to the child blade first.").risk > 0.4  # doctest: +SKIP
            True
        """
        if variance not in VARIANCE_MODES:
            raise ValueError(f"variance={variance!r}; expected one of {VARIANCE_MODES}")
        t0 = time.perf_counter()
        h0 = self._hits
        p = self.probs(text)
        risk = risk_from_probs(p, alpha, beta, gamma, variance, self.unsafe_at)
        return RiskEstimate(p, p[self.unsafe_at], risk, time.perf_counter() - t0, self._hits != h0,
                            self.model_id, time.monotonic())

    def cache_info(self) -> dict[str, int]:
        """``{"hits", "misses", "size", "maxsize"}`` of the LRU cache."""
        return {"hits": self._hits, "misses": self._misses, "size": len(self._cache),
                "maxsize": self._cache_size}

    def cache_clear(self) -> None:
        with self._lock:
            self._cache.clear()
            self._views.clear()
            self._hits = self._misses = 0

    def trace(self) -> bool:
        """Run a TorchScript-frozen copy of the model from now on (at most once); return :attr:`jit`.

        The copy is checked against the eager model first (see
        ``_backend.trace_for_inference``); if tracing fails or disagrees, a
        :class:`RuntimeWarning` says so and the eager model stays (same
        results, slower). Call it before a control loop starts, not inside it:
        it takes about 0.5 s on one quiet core.
        """
        with self._lock:
            self._trace_after = None
            if self.jit:
                return self.jit
            try:
                self.jit = bool(self._m.trace())
            except Exception as exc:  # noqa: BLE001 - any tracing failure: keep the eager model
                import warnings
                warnings.warn(f"TorchScript tracing of the risk model failed ({type(exc).__name__}: {exc}); "
                              "using the eager model (same results, slower)", RuntimeWarning, stacklevel=2)
            if self.jit:
                self._views.clear()   # the traced copy agrees within 1e-4, not bit for bit
            return self.jit

    def logits_batch(self, texts: list[str], *, progress: bool = False,
                     desc: str = "scoring") -> list[list[float]]:
        """Raw (untempered) logits, for evaluation and calibration (a text asked twice is run once).

        ``progress``: a tqdm bar on stderr (rows done), if tqdm is installed.
        """
        keys = [normalize_text(t) for t in texts]
        bar = None
        if progress:
            try:
                from tqdm import tqdm
                bar = tqdm(total=len(keys), desc=desc, unit="row", file=sys.stderr, leave=False,
                           dynamic_ncols=True)
            except ImportError:  # pragma: no cover - tqdm ships with the risk extra
                bar = None
        try:
            return [r for r, _v, _p in self._score(keys, raw=True,
                                                 on_batch=None if bar is None else bar.update)]
        finally:
            if bar is not None:
                bar.close()

    def read(self, text: str) -> list[tuple[View, tuple[float, ...]]]:
        """Every view of ``text`` this estimator scores (see ``ethimon.risk._reading``) with its
        ``(p_safe, p_unsafe)``, uncached; the riskiest one gives :meth:`probs`."""
        vs = views(normalize_text(text), self.reading)
        return list(zip(vs, self._forward_views(vs, raw=False)))

    def explain(self, text: str, top_words: int = 5) -> dict[str, Any]:
        """Which view (step, instruction) drove the score of ``text``, and which of its words.

        The words: leave-one-word-out occlusion on the driving view's focus (its
        context kept): the drop in p_unsafe when the word is removed, one
        batched forward pass for all words. Returns ``{"p", "p_unsafe",
        "driver": {kind, index, focus, context, p_unsafe}, "views": [...],
        "words": [(word, drop), ...]}``, words sorted by drop, largest first.
        """
        scored = self.read(text)
        at = self.unsafe_at
        best = max(range(len(scored)), key=lambda i: scored[i][1][at])
        v, p = scored[best]
        words = v.focus.split()
        occl = [View(" ".join(words[:j] + words[j + 1:]), v.context, v.kind, v.index)
                for j in range(len(words))] if len(words) > 1 else []
        drops = []
        if occl:
            for j, q in enumerate(self._forward_views(occl, raw=False)):
                drops.append((words[j], p[at] - q[at]))
            drops.sort(key=lambda wd: -wd[1])

        def row(vv: View, pp: tuple[float, ...]) -> dict[str, Any]:
            return {"kind": vv.kind, "index": vv.index, "focus": vv.focus, "context": vv.context,
                    "p_unsafe": pp[at]}
        return {"p": p, "p_unsafe": p[at], "driver": row(v, p), "views": [row(a, b) for a, b in scored],
                "words": drops[:max(0, int(top_words))], "reading": self.reading}

    # -------------------------------------------------------------- internals
    def _infer(self, keys: list[str]) -> list[tuple[float, ...]]:
        probs = [p for p, _v, _q in self._score(keys, raw=False)]
        with self._lock:
            self._misses += len(keys)
            if self._cache_size > 0:
                for k, p in zip(keys, probs):
                    self._cache[k] = p
                    self._cache.move_to_end(k)
                while len(self._cache) > self._cache_size:
                    self._cache.popitem(last=False)
        return probs

    def _score(self, keys: list[str], raw: bool, on_batch: Any = None) -> list[tuple[Any, View, tuple]]:
        """Per text: (its result, the view that gave it, that view's probabilities).

        Every view of every text runs in one set of length-sorted batches; a
        text's result is that of its riskiest view (highest p_unsafe at the
        model's temperature). ``raw``: the result is that view's raw logits.
        """
        flat: list[View] = []
        owner: list[list[int]] = []
        for k in keys:  # views() has no duplicates within a text; texts are not merged (rows = what was asked)
            vs = views(k, self.reading)
            owner.append(list(range(len(flat), len(flat) + len(vs))))
            flat += vs
        share = len(keys) / max(1, len(flat))   # a progress bar counts texts, not views

        def progress(n: int) -> None:
            on_batch(n * share)
        logits = self._forward_views(flat, raw=True, on_batch=progress if on_batch is not None else None)
        T = self._m.temperature
        ui = self._m.unsafe_index
        at = self.unsafe_at
        out = []
        for ids in owner:
            best, best_p = ids[0], None
            for j in ids:
                p = _tempered(logits[j], T, ui)
                if best_p is None or p[at] > best_p[at]:
                    best, best_p = j, p
            out.append((logits[best] if raw else best_p, flat[best], best_p))
        return out

    def _forward(self, keys: list[str], raw: bool, on_batch: Any = None) -> list:
        """The whole texts ``keys`` through the model (no reading into views)."""
        return self._forward_views([View(k) for k in keys], raw, on_batch)

    def _forward_views(self, vs: list[View], raw: bool, on_batch: Any = None) -> list:
        """The one estimator loop, for every back-end: per view, the raw logits (``raw``) or the K
        probabilities at the temperature of its riskiest window.

        A view already scored (the same context and focus: a step of a plan read again with one more
        step, a step two texts share) is taken from the view cache; the others are encoded once, run in
        length-sorted batches, checked finite and cached. Any failure raises
        :class:`RiskInferenceError` (fail closed) and caches nothing.
        """
        if not vs:
            return []
        enc = self._m
        keys = [v.key() for v in vs]
        got: dict[str, tuple[float, ...]] = {}
        with self._lock:
            if self._views_size > 0:
                for k in keys:
                    hit = self._views.get(k)
                    if hit is not None:
                        self._views.move_to_end(k)
                        got[k] = hit
        todo: dict[str, View] = {}
        for k, v in zip(keys, vs):
            if k not in got and k not in todo:
                todo[k] = v
        if on_batch is not None and len(todo) != len(vs):   # a progress bar counts the views asked for
            on_batch = (lambda cb, share: (lambda n: cb(n * share)))(on_batch, len(vs) / max(1, len(todo)))
        if todo:
            got.update(zip(todo, self._run(list(todo.values()), on_batch)))
        if raw:
            return [list(got[k]) for k in keys]
        T, ui = enc.temperature, enc.unsafe_index
        return [_tempered(got[k], T, ui) for k in keys]

    def _run(self, vs: list[View], on_batch: Any = None) -> list[tuple[float, ...]]:
        """Per view (none cached), the raw logits of its riskiest window; cached when all are finite."""
        enc = self._m
        try:
            wins = enc.encode([(v.context, v.focus) for v in vs])
        except Exception as exc:  # noqa: BLE001
            raise RiskInferenceError(f"tokenisation failed: {exc}") from exc
        seqs, owner = _flatten(wins)
        if on_batch is not None and len(seqs) != len(vs):   # a progress bar counts views, not windows
            on_batch = (lambda cb, share: (lambda n: cb(n * share)))(on_batch, len(vs) / len(seqs))
        order = sorted(range(len(seqs)), key=lambda i: len(seqs[i]))
        results: list = [None] * len(seqs)
        k = len(self.labels)
        with self._lock:
            if self._trace_after is not None and self._rows + len(seqs) > self._trace_after:
                self.trace()          # lazily: before the pass that takes the count past trace_after
            self._rows += len(seqs)
            try:
                for idx in _batches(order, seqs, self._batch_size, exact=self.quantized != "int8"):
                    rows = enc.logits([seqs[i] for i in idx])
                    rows = rows.tolist() if hasattr(rows, "tolist") else rows
                    if len(rows) != len(idx):
                        raise ValueError(f"{len(rows)} rows of logits for {len(idx)} sequences")
                    for i, r in zip(idx, rows):
                        r = tuple(float(x) for x in r)
                        if len(r) != k:
                            raise ValueError(f"logits of {len(r)} classes; the model has {k} labels {self.labels}")
                        results[i] = r
                    if on_batch is not None:
                        on_batch(len(idx))
            except RiskInferenceError:
                raise
            except Exception as exc:  # noqa: BLE001 - fail closed on anything
                raise RiskInferenceError(f"risk inference failed: {type(exc).__name__}: {exc}") from exc
            for r in results:
                if not all(math.isfinite(v) for v in r):
                    raise RiskInferenceError("risk inference produced NaN/inf; treat the command as unsafe")
            T, ui = self._m.temperature, self._m.unsafe_index
            out = []
            for ids in owner:   # per view, its riskiest window (most views have one)
                best = ids[0] if len(ids) == 1 else max(ids, key=lambda j: _tempered(results[j], T, ui)[_at(ui, k)])
                out.append(results[best])
            if self._views_size > 0:
                for v, r in zip(vs, out):
                    self._views[v.key()] = r
                    self._views.move_to_end(v.key())
                while len(self._views) > self._views_size:
                    self._views.popitem(last=False)
        return out


def _flatten(wins: list[list[list[int]]]) -> tuple[list[list[int]], list[list[int]]]:
    seqs: list[list[int]] = []
    owner: list[list[int]] = []  # per view, the indices of its windows in seqs
    for w in wins:
        if not w:
            raise RiskInferenceError("a view encoded to no token sequence")
        owner.append(list(range(len(seqs), len(seqs) + len(w))))
        seqs += w
    return seqs, owner


#: one more forward pass, in tokens: each pass streams all encoder weights (~42 MB fp32) before its first
#: token, a padding token costs a real one (2 shared AVX2 cores: ~0.8-1 ms a token, ~1.5-4 ms a pass)
RUN_COST_TOKENS = 4
#: int8 keeps the cut of before issue 30's speed round (at this share of padding): dynamic int8 quantises
#: activations per batch tensor, so another cut would move int8 scores
PAD_WASTE = 0.3


def _batches(order: list[int], seqs: list[list[int]], size: int, exact: bool = True) -> list[list[int]]:
    """Length-sorted ``order`` cut into batches of at most ``size`` rows, each padded to its longest, at the
    least cost (padded tokens + :data:`RUN_COST_TOKENS` a batch; a DP over the sorted lengths): a plan's
    views range from one step to the whole plan. Which rows share a pass never changes what a row reads
    (fp32 logits agree within ~1e-7). ``exact=False`` (int8): cut where padding passes :data:`PAD_WASTE`."""
    lens = [len(seqs[i]) for i in order]
    if not exact:
        cuts, total = [0], 0
        for j, n in enumerate(lens):
            k = j - cuts[-1]
            if k and (k >= size or n * (k + 1) > (1 + PAD_WASTE) * (total + n)):
                cuts.append(j)
                total = 0
            total += n
        return [order[a:b] for a, b in zip(cuts, cuts[1:] + [len(order)]) if b > a]
    best, cut = [0] * (len(order) + 1), [0] * (len(order) + 1)
    for j in range(1, len(order) + 1):          # best[j]: the cheapest cover of the j shortest rows
        best[j], cut[j] = min((best[i] + RUN_COST_TOKENS + (j - i) * lens[j - 1], -i)
                              for i in range(max(0, j - size), j))
        cut[j] = -cut[j]
    out, j = [], len(order)
    while j > 0:
        out.append(order[cut[j]:j])
        j = cut[j]
    return out[::-1]


def _tempered(logits: Sequence[float], temperature: float, unsafe_index: int) -> tuple[float, ...]:
    """The K probabilities of one row of raw logits at ``temperature`` (a stable softmax).

    Two classes: exactly ``(1 - p_unsafe, p_unsafe)``, whichever index the unsafe class has (what
    every estimator has returned: ``p[1]`` is p_unsafe, the spec's default ``unsafe_index`` -1).
    K > 2 classes: the K probabilities in the model's class order (``p[unsafe_index]`` is p_unsafe).
    """
    z = [x / temperature for x in logits]
    top = max(z)
    e = [math.exp(x - top) for x in z]
    total = sum(e)
    pu = e[unsafe_index] / total
    if not math.isfinite(pu):
        raise RiskInferenceError("risk inference produced NaN/inf; treat the command as unsafe")
    if len(e) == 2:
        return (1.0 - pu, pu)
    return tuple(x / total for x in e)


def _at(unsafe_index: int, k: int) -> int:
    """Where p_unsafe is in what :func:`_tempered` returns for ``k`` classes."""
    return 1 if k == 2 else unsafe_index % k


def load_estimator(model_dir: str | Path | None = None, *, quantize: str | None = None,
                   max_length: int | None = None, cache_size: int = 4096, batch_size: int = 32,
                   num_threads: int | None = None, temperature: float | None = None,
                   jit: bool | None = None, backend: str = "auto", reading: str = "steps") -> RiskEstimator:
    """Load a risk estimator from a local model directory (default: the shipped one).

    Args:
        model_dir: an ethimon adapter directory (``ethimon_model.json``) or a
            Hugging Face sequence-classification directory (safetensors). ``None``
            loads the shipped default (MiniLM-L6 + LoRA).
        quantize: ``None`` or ``"fp32"`` (full precision) or ``"int8"`` (dynamic
            int8 Linear layers). ``"fp32"`` lets :func:`load_estimator_for`
            override a spec that asks for int8.
        backend: ``"auto"`` (default): ONNX Runtime when onnxruntime and tokenizers
            are installed and the model has an ONNX form (the shipped model and any
            BERT/DistilBERT directory: built from its safetensors weights at load,
            ~0.3 s; any other family: a ``model.onnx`` written by ``ethimon export``),
            else torch. ``"onnx"``: ONNX Runtime or an error (no torch, no
            transformers in the process). ``"torch"``: torch + transformers.
        max_length: token budget, special tokens included (default: the model's).
        cache_size: LRU entries keyed on normalised text; 0 disables the cache.
        batch_size: rows per forward pass in :meth:`RiskEstimator.probs_batch`.
        num_threads: torch: if given, ``torch.set_num_threads`` (process-wide);
            ONNX: the session's intra-op threads (default 1: one sentence is too
            small to split).
        temperature: softmax temperature replacing the model's own, e.g. one
            fitted on validation rows of your deployment domain
            (``ethimon evaluate --calibrate-on``); must be finite and > 0.
        jit: torch only (an ONNX graph is optimised when its session starts);
            run a TorchScript-frozen copy of the model (checked against the
            eager one; per sentence on 2 CPU cores fp32 8.7 → 7.2 ms, int8
            3.9 → 1.7 ms). ``True``: trace now, at load (a control loop or a
            service: no pause later; :class:`ethimon.loop.ProcessEstimator`
            asks for it); ``None`` (default): trace lazily, before the forward
            pass that takes the rows scored past :data:`JIT_AFTER_ROWS` (one
            call of that many rows traces first; a one-shot command that scores
            a few texts never pays the ~0.5 s); ``False``: never.
            If tracing fails or disagrees, the eager model is used and
            ``RiskEstimator.jit`` is ``False``.
        reading: ``"steps"`` (default): a numbered or code-call plan is scored step
            by step in context (the scene, the earlier steps), a scene + instruction
            as a text pair and the instruction alone, and the riskiest view counts
            (``ethimon.risk._reading``; a one-line command is read as before);
            ``"flat"``: the whole text only (the reading before issue 19).

    Returns:
        A :class:`RiskEstimator`.

    Raises:
        DependencyNotInstalled: the backend's packages (onnxruntime + tokenizers, or
            torch + transformers) or the base weights are missing.
        ModelError: the directory is unusable (sha256 mismatch, pickle-only
            weights, missing tokenizer, ...) or not to be trusted: anything
            that would make transformers import code (``auto_map``, a
            ``model_type`` it does not ship, a ``*.py`` file), a classifier whose
            head (or any weight) would be randomly initialised, a manifest
            field of the wrong type or range. Nothing in the directory runs.
        ValueError: bad ``quantize``/``max_length``/``cache_size``.

    Example:
        >>> est = load_estimator()                                      # doctest: +SKIP
        >>> p_safe, p_unsafe = est.probs("Hand the knife to the child blade first.")  # doctest: +SKIP
    """
    if quantize not in QUANTIZE_MODES:
        raise ValueError(f"quantize={quantize!r}; expected None, 'fp32' or 'int8'")
    if quantize == "fp32":
        quantize = None
    if max_length is not None and (not isinstance(max_length, int) or max_length < 8):
        raise ValueError(f"max_length={max_length!r}; expected an int >= 8")
    if reading not in READINGS:
        raise ValueError(f"reading={reading!r}; expected one of {READINGS}")
    if cache_size < 0 or batch_size < 1:
        raise ValueError(f"cache_size={cache_size!r}, batch_size={batch_size!r} out of range")
    if temperature is not None and (isinstance(temperature, bool) or not (isinstance(temperature, (int, float))
                                        and math.isfinite(temperature) and temperature > 0)):
        raise ValueError(f"temperature={temperature!r}; expected a finite number > 0")
    from ._encoder import encoder_names
    if backend != "auto" and backend not in encoder_names():
        raise ValueError(f"backend={backend!r}; expected one of {('auto',) + encoder_names()}")
    if model_dir is None:
        model_dir = default_model_dir()
        check_default_manifest(Path(model_dir))
    from ._encoder import load_encoder
    loaded = load_encoder(model_dir, backend, quantize=quantize, max_length=max_length, num_threads=num_threads)
    if temperature is not None:
        loaded.temperature = float(temperature)
    est = RiskEstimator(loaded, cache_size=cache_size, batch_size=batch_size, quantized=quantize,
                        trace_after=JIT_AFTER_ROWS if jit is None else None, reading=reading)
    if jit:
        est.trace()
    return est


def estimator_kwargs(spec: Any) -> dict[str, Any]:
    """:func:`load_estimator` keyword arguments from a spec's ``risk.estimator`` block (its plan's
    ``estimator``, defaults filled in by the compiler).

    A relative ``model`` is resolved against the spec file's folder.
    """
    from ..compiler import plan_of
    cfg = plan_of(spec).estimator
    model = cfg.model
    if model is not None and not Path(model).is_absolute() and spec.path:
        model = str((Path(spec.path).resolve().parent / model).resolve())
    return {"model_dir": model, "quantize": cfg.quantize, "temperature": cfg.temperature,
            "max_length": cfg.max_length, "backend": cfg.backend}


def load_estimator_for(spec: Any, **overrides: Any) -> RiskEstimator:
    """The estimator a spec asks for (``risk.estimator``); ``overrides`` win over the spec.

    Example:
        >>> est = load_estimator_for(load_spec("specs/cobot_cell.yaml"))   # doctest: +SKIP
    """
    kwargs = {**estimator_kwargs(spec), **{k: v for k, v in overrides.items() if v is not None}}
    if kwargs.get("model_dir") is not None and not Path(kwargs["model_dir"]).is_dir():
        from ..errors import ModelError
        raise ModelError(f"model directory {kwargs['model_dir']} (risk.estimator.model of "
                         f"{spec.path or spec.name}) does not exist")
    return load_estimator(**kwargs)
