"""Training of the risk classifier (LoRA on a BERT-family encoder + linear head).

The paper's pipeline (ETHICS CSV, stratified 80/20 split with a fixed seed,
cross-entropy, AdamW) plus what it lacked: best checkpoint on validation loss
with early stopping, a small LoRA adapter, temperature scaling fitted on the
validation set, seeds, and a run directory with config, per-epoch metrics and
plots. Imports torch at module level: import it lazily.
"""

from __future__ import annotations

import json
import math
import random
import sys
import time
from pathlib import Path
from typing import Any, Callable

from . import _backend as B
from ._recipe import Recipe
from ._data import stratified_split  # noqa: F401 - re-exported for callers

torch = B.torch
nn = B.nn


def _batches(lengths: list[int], batch_size: int, rng: random.Random) -> list[list[int]]:
    """Length-bucketed batches: shuffle, sort inside chunks of 50 batches, shuffle batches."""
    idx = list(range(len(lengths)))
    rng.shuffle(idx)
    chunk = batch_size * 50
    out = []
    for s in range(0, len(idx), chunk):
        part = sorted(idx[s:s + chunk], key=lambda i: lengths[i])
        out += [part[j:j + batch_size] for j in range(0, len(part), batch_size)]
    rng.shuffle(out)
    return out


def predict_logits(module, seqs: list[list[int]], pad_id: int, batch_size: int = 64):
    """Logits (N×K tensor) in input order, length-sorted batches, eval mode."""
    was = module.training
    module.eval()
    order = sorted(range(len(seqs)), key=lambda i: len(seqs[i]))
    out = [None] * len(seqs)
    with torch.inference_mode():
        for s in range(0, len(order), batch_size):
            idx = order[s:s + batch_size]
            ids, mask = B.collate([seqs[i] for i in idx], pad_id)
            lg = module(ids, mask).float()
            for i, row in zip(idx, lg):
                out[i] = row
    module.train(was)
    return torch.stack(out) if out else torch.zeros((0, 2))


def fit_temperature(logits, labels) -> float:
    """Temperature T minimising validation NLL of softmax(logits / T) (grid + refine)."""
    y = torch.as_tensor(labels, dtype=torch.long)
    lg = torch.as_tensor(logits, dtype=torch.float32)

    def nll(t: float) -> float:
        return float(nn.functional.cross_entropy(lg / t, y))

    grid = [math.exp(x / 40.0) for x in range(-80, 121)]  # 0.135 .. 20
    best = min(grid, key=nll)
    lo, hi = best / 1.03, best * 1.03
    for _ in range(40):  # golden-section refine
        m1, m2 = lo + (hi - lo) * 0.382, lo + (hi - lo) * 0.618
        if nll(m1) < nll(m2):
            hi = m2
        else:
            lo = m1
    return float((lo + hi) / 2)


def _warm_start(encoder, model, d: Path, base_dir: Path, r: int, alpha: float, targets: list[str]) -> None:
    """Copy the LoRA factors and head of the ethimon model directory ``d`` into a fresh model."""
    manifest = B.read_manifest(d)
    if manifest is None:
        raise B.ModelError(f"{d}: --init-from needs an ethimon LoRA model directory (no {B.MANIFEST})")
    lo = manifest.get("lora") or {}
    if lo.get("r") != r or float(lo.get("alpha", -1)) != float(alpha) or list(lo.get("targets", [])) != targets:
        raise B.ModelError(f"{d}: its LoRA (r={lo.get('r')}, alpha={lo.get('alpha')}) differs from this run's "
                           f"(r={r}, alpha={alpha}) or adapts other layers")
    if manifest.get("base_sha256") != B.sha256_file(base_dir / "model.safetensors"):
        raise B.ModelError(f"{d}: trained on another base model (base_sha256 differs)")
    adapter, _ = B.checked_adapter(d, manifest)
    state = B.load_adapter_tensors(adapter)  # safetensors only, finite floats
    try:
        with torch.no_grad():
            for n_, mod in encoder.named_modules():
                if isinstance(mod, B.LoRALinear):
                    mod.lora_A.copy_(state[f"lora.{n_}.A"].float())
                    mod.lora_B.copy_(state[f"lora.{n_}.B"].float())
            model.head.weight.copy_(state["head.weight"].float())
            model.head.bias.copy_(state["head.bias"].float())
    except (KeyError, RuntimeError) as exc:
        raise B.ModelError(f"{adapter}: tensor missing or of the wrong shape for a warm start: {exc}") from None


def _identity_factors(delta, r: int):
    """LoRA factors ``(A, B)`` with ``B @ A == delta`` exactly: one of them the r×r identity (fp16).

    ``delta`` is out × in; one of its sides must be ``r`` (the hidden size: every
    matrix of a BERT-family layer maps from or to it).
    """
    out_f, in_f = delta.shape
    eye = torch.eye(r, dtype=torch.float16)
    if in_f == r:
        return eye.contiguous(), delta.contiguous()          # A = I (r×in), B = ΔW (out×r)
    if out_f == r:
        return delta.contiguous(), eye.contiguous()          # A = ΔW (r×in), B = I (out×r)
    raise B.ModelError(f"full fine-tuning: a {out_f}x{in_f} matrix has no side of the hidden size {r}")


def _warm_start_merged(encoder, model, d: Path, base_dir: Path) -> None:
    """Full fine-tuning from an ethimon LoRA model: its update merged into the weights, its head copied."""
    manifest = B.read_manifest(d)
    if manifest is None:
        raise B.ModelError(f"{d}: --init-from needs an ethimon LoRA model directory (no {B.MANIFEST})")
    if manifest.get("base_sha256") != B.sha256_file(base_dir / "model.safetensors"):
        raise B.ModelError(f"{d}: trained on another base model (base_sha256 differs)")
    adapter, _ = B.checked_adapter(d, manifest)
    state = B.load_adapter_tensors(adapter)
    lo = manifest.get("lora") or {}
    try:
        if lo:
            B.merge_lora(encoder, state, float(lo["alpha"]) / float(lo["r"]))
        with torch.no_grad():
            model.head.weight.copy_(state["head.weight"].float())
            model.head.bias.copy_(state["head.bias"].float())
    except (KeyError, RuntimeError) as exc:
        raise B.ModelError(f"{adapter}: tensor missing or of the wrong shape for a warm start: {exc}") from None


class _Run:
    """One training run's state between :func:`_setup`, :func:`_epoch` and :func:`_save`."""


def _setup(train_texts, train_labels, val_texts, recipe: Recipe, base_dir: Path, out: Path, train_weights,
           aux_tasks, init_from, num_threads, progress) -> _Run:
    """Seeds, tokenizer, encoder with its LoRA factors (or trainable matrices), heads, warm start, the
    encoded rows (auxiliary ones appended), optimiser and schedule."""
    k = _Run()
    seed, init_seed, full = recipe.seed, recipe.init_seed, recipe.full_finetune
    r, alpha = recipe.lora_r, recipe.lora_alpha_used()
    if num_threads:
        torch.set_num_threads(num_threads)
    random.seed(seed)
    torch.manual_seed(seed if init_seed is None else init_seed)
    k.rng = random.Random(seed)
    out.mkdir(parents=True, exist_ok=True)
    tok = B.load_tokenizer(base_dir)
    encoder = B.load_encoder(base_dir)
    for p in encoder.parameters():
        p.requires_grad_(False)
    k.base_w0 = None
    if full:
        targets = B.lora_target_names(encoder)
        r = alpha = int(encoder.config.hidden_size)
        for name in targets:
            encoder.get_submodule(name).weight.requires_grad_(True)
        k.base_w0 = {name: encoder.get_submodule(name).weight.detach().clone() for name in targets}
    else:
        targets = B.inject_lora(encoder, r, alpha, recipe.lora_dropout)
    model = B.PooledClassifier(encoder, 2, recipe.pooling)
    aux_tasks = list(aux_tasks or [])
    heads = nn.ModuleList([model.head] + [nn.Linear(encoder.config.hidden_size, 2) for _ in aux_tasks])
    if init_from is not None and full:
        _warm_start_merged(encoder, model, Path(init_from), base_dir)
    elif init_from is not None:
        _warm_start(encoder, model, Path(init_from), base_dir, r, alpha, targets)
    if init_seed is not None:
        torch.manual_seed(seed)  # the rest (dropout) follows the run's own seed
    model.train()
    k.pad = tok.pad_token_id or 0
    ml, trunc = recipe.max_length, recipe.truncation
    tr = B.encode(tok, train_texts, ml, trunc)
    k.va = B.encode(tok, val_texts, ml, trunc)
    labels = list(train_labels)
    weights = list(train_weights if train_weights is not None else [1.0] * len(tr))
    task = [0] * len(tr)
    for j, (_name, a_texts, a_labels) in enumerate(aux_tasks, start=1):
        tr += B.encode(tok, a_texts, ml, trunc)
        labels += list(a_labels)
        weights += [recipe.aux_weight] * len(a_texts)
        task += [j] * len(a_texts)
    k.ytr = torch.tensor(labels, dtype=torch.long)
    k.wtr = torch.tensor(weights)
    k.ttr = torch.tensor(task, dtype=torch.long)
    k.lora_params = ([encoder.get_submodule(n).weight for n in targets] if full
                     else [p for n, p in model.named_parameters() if "lora_" in n])
    k.head_params = list(heads.parameters())
    k.opt = torch.optim.AdamW([{"params": k.lora_params, "lr": recipe.encoder_lr_used()},
                               {"params": k.head_params, "lr": recipe.head_lr_used()}],
                              weight_decay=recipe.weight_decay)
    k.lengths = [len(s) for s in tr]
    steps_per_epoch = math.ceil(len(tr) / recipe.batch_size)
    max_steps, epochs = recipe.max_steps, recipe.epochs
    total = steps_per_epoch * epochs if max_steps is None else min(max_steps, steps_per_epoch * epochs)
    wu = max(1, int(recipe.warmup * total))
    k.sched = torch.optim.lr_scheduler.LambdaLR(
        k.opt, lambda s: min(1.0, (s + 1) / wu) * max(0.0, (total - s) / max(1, total - wu)))
    k.tr, k.model, k.encoder, k.heads, k.targets, k.r, k.alpha, k.aux_tasks = (
        tr, model, encoder, heads, targets, r, alpha, aux_tasks)
    k.history, k.train_curve = [], []
    k.best = (math.inf, None, -1)
    k.bad = k.step = 0
    k.t_start = time.time()
    k.tqdm = None
    if progress:
        try:
            from tqdm import tqdm
            k.tqdm = tqdm
        except ImportError:  # pragma: no cover
            pass
    return k


def _epoch(k: _Run, ep: int, recipe: Recipe, val_labels, pairs, log: Callable[[str], Any]) -> bool:
    """One epoch: the steps (``max_steps`` counted), then validation and the best state kept; ``True``
    when the run stops here (early stop, or ``max_steps`` reached)."""
    model, tr, pad, max_steps, full = k.model, k.tr, k.pad, recipe.max_steps, recipe.full_finetune
    batches = _batches(k.lengths, recipe.batch_size, k.rng)
    it = k.tqdm(batches, desc=f"epoch {ep + 1}/{recipe.epochs}", file=sys.stderr, mininterval=5,
                disable=False) if k.tqdm is not None else batches
    run_loss, n_seen = 0.0, 0
    pair_weight = recipe.pair_weight
    for bidx in it:
        if max_steps is not None and k.step >= max_steps:
            break
        ids, mask = B.collate([tr[i] for i in bidx], pad)
        if k.aux_tasks:
            x = model.dropout(model.pool(ids, mask))
            tb = k.ttr[bidx]
            # every head on every row (a 384x2 matmul each), then each row's own task
            logits = torch.stack([h(x) for h in k.heads])[tb, torch.arange(len(bidx))]
        else:
            logits = model(ids, mask)
        loss_vec = nn.functional.cross_entropy(logits, k.ytr[bidx], reduction="none")
        w = k.wtr[bidx]
        loss = (loss_vec * w).sum() / w.sum()
        if pairs and pair_weight > 0:
            chosen = [pairs[k.rng.randrange(len(pairs))] for _ in range(recipe.pairs_per_step)]
            idx = [u for u, _ in chosen] + [v for _, v in chosen]
            pids, pmask = B.collate([tr[i] for i in idx], pad)
            pl = model(pids, pmask)
            z = pl[:, 1] - pl[:, 0]
            n = len(chosen)
            loss = loss + pair_weight * nn.functional.relu(recipe.pair_margin - (z[:n] - z[n:])).mean()
        k.opt.zero_grad(set_to_none=True)
        loss.backward()
        torch.nn.utils.clip_grad_norm_(k.lora_params + k.head_params, 1.0)
        k.opt.step()
        k.sched.step()
        k.step += 1
        k.train_curve.append(float(loss.detach()))
        run_loss += float(loss.detach()) * len(bidx)
        n_seen += len(bidx)
    va = k.va
    vlog = predict_logits(model, va, pad)
    yv = torch.tensor(val_labels, dtype=torch.long)
    vloss = float(nn.functional.cross_entropy(vlog, yv)) if len(va) else math.nan
    vacc = float((vlog.argmax(-1) == yv).float().mean()) if len(va) else math.nan
    rec = {"epoch": ep + 1, "train_loss": run_loss / max(1, n_seen), "val_loss": vloss,
           "val_acc": vacc, "steps": k.step, "elapsed_s": round(time.time() - k.t_start, 1)}
    k.history.append(rec)
    log(json.dumps(rec))
    if vloss < k.best[0] - 1e-4 or k.best[1] is None:
        encoder = k.encoder
        weights_now = ({f"full.{n}": encoder.get_submodule(n).weight.detach().clone() for n in k.targets}
                       if full else B.lora_state(encoder))
        k.best = (vloss, {**weights_now, "head.weight": model.head.weight.detach().clone(),
                          "head.bias": model.head.bias.detach().clone()}, ep + 1)
        k.bad = 0
    else:
        k.bad += 1
        if k.bad > recipe.patience:
            log(f"early stop after epoch {ep + 1} (best epoch {k.best[2]})")
            return True
    return max_steps is not None and k.step >= max_steps


def _restore_best(k: _Run, full: bool) -> dict:
    """Put the best epoch's weights back in the model (full fine-tuning: ΔW as saved, in fp16); its state."""
    state = k.best[1]
    encoder, model = k.encoder, k.model
    with torch.no_grad():
        if full:
            # ΔW as saved (fp16), exactly as the loader will merge it, before the temperature is fitted
            factors = {}
            for n_ in k.targets:
                delta = (state.pop(f"full.{n_}") - k.base_w0[n_]).half()
                a, b = _identity_factors(delta, k.r)
                factors[f"lora.{n_}.A"], factors[f"lora.{n_}.B"] = a, b
                encoder.get_submodule(n_).weight.copy_(k.base_w0[n_] + delta.float())
            state = {**factors, **state}
        for n_, mod in encoder.named_modules():
            if isinstance(mod, B.LoRALinear):
                mod.lora_A.copy_(state[f"lora.{n_}.A"])
                mod.lora_B.copy_(state[f"lora.{n_}.B"])
        model.head.weight.copy_(state["head.weight"])
        model.head.bias.copy_(state["head.bias"])
    return state


def _save(k: _Run, recipe: Recipe, state: dict, val_labels, n_train: int, base_dir: Path, out: Path,
          base_ref, name: str, init_from, pairs, extra_meta, log: Callable[[str], Any]) -> dict:
    """Fit the temperature on the validation logits; write the adapter, the manifest, metrics.json and
    the plots; return the run summary."""
    full, va, r, alpha = recipe.full_finetune, k.va, k.r, k.alpha
    temperature = 1.0
    if len(va):
        vlog = predict_logits(k.model, va, k.pad)
        temperature = fit_temperature(vlog, val_labels)
    # LoRA factors in fp16 (half the size; merged in fp32 at load), head in fp32
    tensors = {key: (v.half() if key.startswith("lora.") else v.float()).contiguous()
               for key, v in state.items()}
    B.save_adapter(tensors, out / "adapter.safetensors")
    base_w = base_dir / "model.safetensors"
    manifest = {
        "format": B.ADAPTER_FORMAT,
        "name": name + ("-full" if full and not name.endswith("-full") else ""),
        "base": base_ref or {"path": str(base_dir.resolve())},
        "base_sha256": B.sha256_file(base_w),
        "adapter_file": "adapter.safetensors",
        "adapter_sha256": B.sha256_file(out / "adapter.safetensors"),
        "lora": {"r": r, "alpha": alpha, "targets": k.targets},
        "pooling": recipe.pooling, "num_labels": 2, "unsafe_index": 1,
        "labels": ["acceptable", "unsafe"],
        "max_length": recipe.max_length, "truncation": recipe.truncation,
        "temperature": round(temperature, 6),
    }
    (out / B.MANIFEST).write_text(json.dumps(manifest, indent=2) + "\n", encoding="utf-8")
    summary = {
        "config": {"epochs": recipe.epochs, "lr": recipe.encoder_lr_used(), "head_lr": recipe.head_lr_used(),
                   "batch_size": recipe.batch_size, "r": r,
                   "alpha": alpha, "lora_dropout": recipe.lora_dropout, "max_length": recipe.max_length,
                   "truncation": recipe.truncation, "pooling": recipe.pooling, "seed": recipe.seed,
                   "init_seed": recipe.init_seed, "patience": recipe.patience,
                   "weight_decay": recipe.weight_decay, "n_train": n_train, "n_val": len(va),
                   "aux_tasks": {n: len(t) for n, t, _ in k.aux_tasks}, "aux_weight": recipe.aux_weight,
                   "init_from": str(init_from) if init_from is not None else None,
                   "pairs": len(pairs or []), "pair_weight": recipe.pair_weight, "pair_margin": recipe.pair_margin,
                   "pairs_per_step": recipe.pairs_per_step, "full": full,
                   "base_dir": str(base_dir), **(extra_meta or {})},
        "history": k.history, "best_epoch": k.best[2], "best_val_loss": k.best[0],
        "temperature": temperature, "train_loss_curve": k.train_curve,
        "train_time_s": round(time.time() - k.t_start, 1),
    }
    (out / "metrics.json").write_text(json.dumps(summary, indent=1) + "\n", encoding="utf-8")
    try:
        from ._evaluate import plot_training
        plot_training(summary, out)
    except Exception as exc:  # noqa: BLE001 - plots are optional
        log(f"(plots skipped: {exc})")
    return summary


def train_lora(train_texts: list[str], train_labels: list[int], val_texts: list[str],
               val_labels: list[int], recipe: Recipe, *, out_dir: str | Path,
               base_dir: str | Path, base_ref: dict | None = None, train_weights: list[float] | None = None,
               aux_tasks: list[tuple[str, list[str], list[int]]] | None = None,
               pairs: list[tuple[int, int]] | None = None, init_from: str | Path | None = None,
               name: str = "ethimon-risk", num_threads: int | None = None, progress: bool = True,
               log: Callable[[str], Any] = print, extra_meta: dict | None = None) -> dict:
    """Train a LoRA adapter + head with ``recipe``'s hyper-parameters; write an ethimon model directory to
    ``out_dir``.

    ``recipe`` (a :class:`~ethimon.risk._recipe.Recipe`) carries every hyper-parameter: epochs, the
    learning rates (:meth:`~ethimon.risk._recipe.Recipe.encoder_lr_used`, ``head_lr_used``), batch size,
    LoRA rank (``lora_r``), α and dropout, tokens, pooling, seeds, patience, weight decay, warm-up,
    ``max_steps``, the auxiliary and pair weights, ``full_finetune``; its data fields (``data``, ``aux``,
    ...) are :func:`train_recipe`'s, unused here. The keywords are the run's data and where it goes.

    ``aux_tasks`` (multi-task learning): ``(name, texts, labels)`` binary tasks
    that share the encoder and its LoRA factors but each get their own head;
    their rows are mixed into the training batches with loss weight
    ``recipe.aux_weight``. Only the main head is saved; early stopping and the
    temperature use the main validation rows only.

    ``recipe.seed`` drives everything; ``recipe.init_seed``, if given, drives only the
    initial LoRA factors and heads, so runs that differ in ``seed`` start from
    one point and differ in data order, dropout and auxiliary draw — the
    setting in which their weights can be averaged (``ethimon average``).

    ``init_from`` (warm start): an ethimon LoRA model directory on the same base with the
    same rank and adapted layers; its LoRA factors and head are the starting point (its
    sha256 is checked as at load time).

    ``pairs`` (pair-aware objective): ``(unsafe_row, safe_row)`` indices into the training
    rows, the two members of a minimal pair. Every step also draws ``recipe.pairs_per_step`` pairs
    and adds ``pair_weight · mean(relu(pair_margin − (z_unsafe − z_safe)))`` (the recipe's), z being the
    unsafe-minus-safe logit: the unsafe member must outscore its safe twin by a margin, so
    the detail that flips the verdict has to move the score.

    ``recipe.full_finetune`` (full fine-tuning, issue 19 item 4): instead of LoRA factors, every weight
    matrix of the transformer layers (the ``nn.Linear`` layers LoRA would adapt) is trained
    at the encoder's learning rate; embeddings, biases and LayerNorms stay frozen, so the update is exactly
    a weight difference ΔW per matrix. It is saved in the same ``ethimon-lora/1`` format
    as an exact full-rank "LoRA" (r = hidden size, α = r, one factor the identity, the
    other ΔW in fp16), so every loader (and the ONNX graph builder) reads it unchanged;
    the temperature is fitted on the weights as saved. the LoRA rank and α are then ignored;
    ``init_from`` may be any ethimon LoRA model on the same base (merged as the start).

    Returns:
        The run summary (also written to ``out_dir/metrics.json``).
    """
    base_dir, out = Path(base_dir), Path(out_dir)
    k = _setup(train_texts, train_labels, val_texts, recipe, base_dir, out, train_weights, aux_tasks, init_from,
               num_threads, progress)
    for ep in range(recipe.epochs):
        if _epoch(k, ep, recipe, val_labels, pairs, log):
            break
    state = _restore_best(k, recipe.full_finetune)
    return _save(k, recipe, state, val_labels, len(train_texts), base_dir, out, base_ref, name, init_from, pairs,
                 extra_meta, log)


def train_recipe(recipe: Recipe, out_dir: str | Path, *, num_threads: int | None = None,
                 progress: bool = False, log: Callable[[str], Any] = print) -> dict:
    """Load the recipe's data, split it, train a LoRA adapter into ``out_dir``; return the run summary.

    ``log`` gets one line with the row counts before training starts, then one per epoch.

    Raises:
        ValueError: an option out of range (see :meth:`Recipe.check`).
        EthimonError: a CSV or the base directory is unusable.
    """
    from ..errors import ModelError
    from ._data import concat_rows, load_labelled_csv

    recipe.check()
    data = concat_rows([load_labelled_csv(p) for p in recipe.data])
    extra = concat_rows([load_labelled_csv(p) for p in recipe.extra_train]) if recipe.extra_train else None
    aux = []
    for path in recipe.aux:
        rows = load_labelled_csv(path, any_ethics_layout=True).sample(recipe.aux_rows, recipe.seed)
        aux.append((Path(path).stem, rows.texts, rows.labels))
    tr_idx, va_idx = stratified_split(data.labels, recipe.val_frac, recipe.seed)
    tr, va = data.subset(tr_idx), data.subset(va_idx)
    if extra is not None:
        tr = concat_rows([tr, extra])
    if recipe.base:
        base, ref = Path(recipe.base), {"path": str(Path(recipe.base).resolve())}
        if not base.is_dir():
            raise ModelError(f"base directory {recipe.base!r} does not exist")
    else:
        base, ref = B.base_package_dir(), {"package": B.BASE_PACKAGE}
    log(f"train {len(tr)} rows, validation {len(va)} rows (dropped {data.dropped} unusable)"
        + "".join(f"; aux {n}: {len(t)} rows" for n, t, _ in aux))
    return train_lora(tr.texts, tr.labels, va.texts, va.labels, recipe, base_dir=base, out_dir=out_dir,
                      base_ref=ref, num_threads=num_threads, aux_tasks=aux, progress=progress, log=log)
