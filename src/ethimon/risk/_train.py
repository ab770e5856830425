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


def train_lora(train_texts: list[str], train_labels: list[int], val_texts: list[str],
               val_labels: list[int], *, base_dir: str | Path, out_dir: str | Path,
               base_ref: dict | None = None, train_weights: list[float] | None = None,
               epochs: int = 4, lr: float = 5e-4, head_lr: float = 2e-3, batch_size: int = 32,
               r: int = 16, alpha: float = 32.0, lora_dropout: float = 0.05,
               max_length: int = 128, truncation: str = "head_tail", pooling: str = "mean",
               seed: int = 42, patience: int = 1, weight_decay: float = 0.01,
               warmup: float = 0.06, max_steps: int | None = None, name: str = "ethimon-risk",
               num_threads: int | None = None, progress: bool = True,
               log: Callable[[str], Any] = print, extra_meta: dict | None = None,
               aux_tasks: list[tuple[str, list[str], list[int]]] | None = None,
               aux_weight: float = 1.0, init_seed: int | None = None,
               init_from: str | Path | None = None, pairs: list[tuple[int, int]] | None = None,
               pair_weight: float = 0.0, pair_margin: float = 1.0, pairs_per_step: int = 8,
               full: bool = False) -> dict:
    """Train a LoRA adapter + head; write an ethimon model directory to ``out_dir``.

    ``aux_tasks`` (multi-task learning): ``(name, texts, labels)`` binary tasks
    that share the encoder and its LoRA factors but each get their own head;
    their rows are mixed into the training batches with loss weight
    ``aux_weight``. Only the main head is saved; early stopping and the
    temperature use the main validation rows only.

    ``seed`` drives everything; ``init_seed``, if given, drives only the
    initial LoRA factors and heads, so runs that differ in ``seed`` start from
    one point and differ in data order, dropout and auxiliary draw — the
    setting in which their weights can be averaged (``ethimon average``).

    ``init_from`` (warm start): an ethimon LoRA model directory on the same base with the
    same rank and adapted layers; its LoRA factors and head are the starting point (its
    sha256 is checked as at load time).

    ``pairs`` (pair-aware objective): ``(unsafe_row, safe_row)`` indices into the training
    rows, the two members of a minimal pair. Every step also draws ``pairs_per_step`` pairs
    and adds ``pair_weight · mean(relu(pair_margin − (z_unsafe − z_safe)))``, z being the
    unsafe-minus-safe logit: the unsafe member must outscore its safe twin by a margin, so
    the detail that flips the verdict has to move the score.

    ``full`` (full fine-tuning, issue 19 item 4): instead of LoRA factors, every weight
    matrix of the transformer layers (the ``nn.Linear`` layers LoRA would adapt) is trained
    at ``lr``; embeddings, biases and LayerNorms stay frozen, so the update is exactly
    a weight difference ΔW per matrix. It is saved in the same ``ethimon-lora/1`` format
    as an exact full-rank "LoRA" (r = hidden size, α = r, one factor the identity, the
    other ΔW in fp16), so every loader (and the ONNX graph builder) reads it unchanged;
    the temperature is fitted on the weights as saved. ``r``/``alpha`` are then ignored;
    ``init_from`` may be any ethimon LoRA model on the same base (merged as the start).

    Returns:
        The run summary (also written to ``out_dir/metrics.json``).
    """
    if num_threads:
        torch.set_num_threads(num_threads)
    random.seed(seed)
    torch.manual_seed(seed if init_seed is None else init_seed)
    rng = random.Random(seed)
    base_dir = Path(base_dir)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    tok = B.load_tokenizer(base_dir)
    encoder = B.load_encoder(base_dir)
    for p in encoder.parameters():
        p.requires_grad_(False)
    if full:
        targets = B.lora_target_names(encoder)
        r = alpha = int(encoder.config.hidden_size)
        for name in targets:
            encoder.get_submodule(name).weight.requires_grad_(True)
        base_w0 = {name: encoder.get_submodule(name).weight.detach().clone() for name in targets}
    else:
        targets = B.inject_lora(encoder, r, alpha, lora_dropout)
    model = B.PooledClassifier(encoder, 2, pooling)
    aux_tasks = list(aux_tasks or [])
    heads = nn.ModuleList([model.head] + [nn.Linear(encoder.config.hidden_size, 2) for _ in aux_tasks])
    if init_from is not None and full:
        _warm_start_merged(encoder, model, Path(init_from), base_dir)
    elif init_from is not None:
        _warm_start(encoder, model, Path(init_from), base_dir, r, alpha, targets)
    if init_seed is not None:
        torch.manual_seed(seed)  # the rest (dropout) follows the run's own seed
    model.train()
    pad = tok.pad_token_id or 0
    tr = B.encode(tok, train_texts, max_length, truncation)
    va = B.encode(tok, val_texts, max_length, truncation)
    labels = list(train_labels)
    weights = list(train_weights if train_weights is not None else [1.0] * len(tr))
    task = [0] * len(tr)
    for k, (_name, a_texts, a_labels) in enumerate(aux_tasks, start=1):
        tr += B.encode(tok, a_texts, max_length, truncation)
        labels += list(a_labels)
        weights += [aux_weight] * len(a_texts)
        task += [k] * len(a_texts)
    ytr = torch.tensor(labels, dtype=torch.long)
    wtr = torch.tensor(weights)
    ttr = torch.tensor(task, dtype=torch.long)
    lora_params = ([encoder.get_submodule(n).weight for n in targets] if full
                   else [p for n, p in model.named_parameters() if "lora_" in n])
    head_params = list(heads.parameters())
    opt = torch.optim.AdamW([{"params": lora_params, "lr": lr},
                             {"params": head_params, "lr": head_lr}], weight_decay=weight_decay)
    lengths = [len(s) for s in tr]
    steps_per_epoch = math.ceil(len(tr) / batch_size)
    total = steps_per_epoch * epochs if max_steps is None else min(max_steps, steps_per_epoch * epochs)
    wu = max(1, int(warmup * total))
    sched = torch.optim.lr_scheduler.LambdaLR(
        opt, lambda s: min(1.0, (s + 1) / wu) * max(0.0, (total - s) / max(1, total - wu)))
    history: list[dict] = []
    train_curve: list[float] = []
    best = (math.inf, None, -1)
    bad = 0
    step = 0
    t_start = time.time()
    use_bar = progress
    try:
        from tqdm import tqdm
    except ImportError:  # pragma: no cover
        use_bar = False
    for ep in range(epochs):
        batches = _batches(lengths, batch_size, rng)
        it = tqdm(batches, desc=f"epoch {ep + 1}/{epochs}", file=sys.stderr, mininterval=5,
                  disable=not use_bar) if use_bar else batches
        run_loss, n_seen = 0.0, 0
        for bidx in it:
            if max_steps is not None and step >= max_steps:
                break
            ids, mask = B.collate([tr[i] for i in bidx], pad)
            if aux_tasks:
                x = model.dropout(model.pool(ids, mask))
                tb = ttr[bidx]
                # every head on every row (a 384x2 matmul each), then each row's own task
                logits = torch.stack([h(x) for h in heads])[tb, torch.arange(len(bidx))]
            else:
                logits = model(ids, mask)
            loss_vec = nn.functional.cross_entropy(logits, ytr[bidx], reduction="none")
            w = wtr[bidx]
            loss = (loss_vec * w).sum() / w.sum()
            if pairs and pair_weight > 0:
                chosen = [pairs[rng.randrange(len(pairs))] for _ in range(pairs_per_step)]
                idx = [u for u, _ in chosen] + [v for _, v in chosen]
                pids, pmask = B.collate([tr[i] for i in idx], pad)
                pl = model(pids, pmask)
                z = pl[:, 1] - pl[:, 0]
                k = len(chosen)
                loss = loss + pair_weight * nn.functional.relu(pair_margin - (z[:k] - z[k:])).mean()
            opt.zero_grad(set_to_none=True)
            loss.backward()
            torch.nn.utils.clip_grad_norm_(lora_params + head_params, 1.0)
            opt.step()
            sched.step()
            step += 1
            train_curve.append(float(loss.detach()))
            run_loss += float(loss.detach()) * len(bidx)
            n_seen += len(bidx)
        vlog = predict_logits(model, va, pad)
        yv = torch.tensor(val_labels, dtype=torch.long)
        vloss = float(nn.functional.cross_entropy(vlog, yv)) if len(va) else math.nan
        vacc = float((vlog.argmax(-1) == yv).float().mean()) if len(va) else math.nan
        rec = {"epoch": ep + 1, "train_loss": run_loss / max(1, n_seen), "val_loss": vloss,
               "val_acc": vacc, "steps": step, "elapsed_s": round(time.time() - t_start, 1)}
        history.append(rec)
        log(json.dumps(rec))
        if vloss < best[0] - 1e-4 or best[1] is None:
            weights_now = ({f"full.{n}": encoder.get_submodule(n).weight.detach().clone() for n in targets}
                           if full else B.lora_state(encoder))
            best = (vloss, {**weights_now, "head.weight": model.head.weight.detach().clone(),
                            "head.bias": model.head.bias.detach().clone()}, ep + 1)
            bad = 0
        else:
            bad += 1
            if bad > patience:
                log(f"early stop after epoch {ep + 1} (best epoch {best[2]})")
                break
        if max_steps is not None and step >= max_steps:
            break
    # restore best state, fit temperature on the validation logits
    state = best[1]
    with torch.no_grad():
        if full:
            # ΔW as saved (fp16), exactly as the loader will merge it, before the temperature is fitted
            factors = {}
            for n_ in targets:
                delta = (state.pop(f"full.{n_}") - base_w0[n_]).half()
                a, b = _identity_factors(delta, r)
                factors[f"lora.{n_}.A"], factors[f"lora.{n_}.B"] = a, b
                encoder.get_submodule(n_).weight.copy_(base_w0[n_] + delta.float())
            state = {**factors, **state}
        for n_, mod in encoder.named_modules():
            if isinstance(mod, B.LoRALinear):
                mod.lora_A.copy_(state[f"lora.{n_}.A"])
                mod.lora_B.copy_(state[f"lora.{n_}.B"])
        model.head.weight.copy_(state["head.weight"])
        model.head.bias.copy_(state["head.bias"])
    temperature = 1.0
    if len(va):
        vlog = predict_logits(model, va, pad)
        temperature = fit_temperature(vlog, val_labels)
    # LoRA factors in fp16 (half the size; merged in fp32 at load), head in fp32
    tensors = {k: (v.half() if k.startswith("lora.") else v.float()).contiguous()
               for k, v in state.items()}
    B.save_adapter(tensors, out / "adapter.safetensors")
    base_w = base_dir / "model.safetensors"
    manifest = {
        "format": B.ADAPTER_FORMAT,
        "name": name + ("-full" if full and not name.endswith("-full") else ""),
        "base": base_ref or {"path": str(base_dir.resolve())},
        "base_sha256": B.sha256_file(base_w),
        "adapter_file": "adapter.safetensors",
        "adapter_sha256": B.sha256_file(out / "adapter.safetensors"),
        "lora": {"r": r, "alpha": alpha, "targets": targets},
        "pooling": pooling, "num_labels": 2, "unsafe_index": 1,
        "labels": ["acceptable", "unsafe"],
        "max_length": max_length, "truncation": truncation,
        "temperature": round(temperature, 6),
    }
    (out / B.MANIFEST).write_text(json.dumps(manifest, indent=2) + "\n", encoding="utf-8")
    summary = {
        "config": {"epochs": epochs, "lr": lr, "head_lr": head_lr, "batch_size": batch_size, "r": r,
                   "alpha": alpha, "lora_dropout": lora_dropout, "max_length": max_length,
                   "truncation": truncation, "pooling": pooling, "seed": seed, "init_seed": init_seed,
                   "patience": patience,
                   "weight_decay": weight_decay, "n_train": len(train_texts), "n_val": len(va),
                   "aux_tasks": {n: len(t) for n, t, _ in aux_tasks}, "aux_weight": aux_weight,
                   "init_from": str(init_from) if init_from is not None else None,
                   "pairs": len(pairs or []), "pair_weight": pair_weight, "pair_margin": pair_margin,
                   "pairs_per_step": pairs_per_step, "full": full,
                   "base_dir": str(base_dir), **(extra_meta or {})},
        "history": history, "best_epoch": best[2], "best_val_loss": best[0],
        "temperature": temperature, "train_loss_curve": train_curve,
        "train_time_s": round(time.time() - t_start, 1),
    }
    (out / "metrics.json").write_text(json.dumps(summary, indent=1) + "\n", encoding="utf-8")
    try:
        from ._evaluate import plot_training
        plot_training(summary, out)
    except Exception as exc:  # noqa: BLE001 - plots are optional
        log(f"(plots skipped: {exc})")
    return summary
