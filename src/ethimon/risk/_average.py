"""Average several trained LoRA runs into one adapter (a "model soup").

Runs of one recipe that differ only in seed share the pretrained base, so each
is ``W0 + s_i·B_i·A_i`` per adapted layer plus its own linear head. Their
weight average ``W0 + Σ w_i·s_i·B_i·A_i`` is written *exactly* as one LoRA
adapter of rank ``Σ r_i``: the ``A`` factors are stacked, the ``B`` factors are
concatenated and scaled by ``w_i·s_i`` (scale 1 in the manifest), the heads are
averaged. Inference merges LoRA into the base weights at load, so the average
costs what one run costs, unlike an ensemble of forward passes.

Averaging is only meaningful for runs of one base and architecture; anything
else is refused with a :class:`ModelError` naming the run. The temperature of
the average is not the average of temperatures: fit it on validation rows
(``calibrate``) or pass it.

Measured on the shipped recipe (MODEL_CARD.md), an average of 2–3 runs scored
about the mean of its runs on the ETHICS hold-out, for runs from different
initialisations and from a shared one (``train_lora(init_seed=...)``) alike,
and about what a probability ensemble of the same runs scored.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path
from typing import Sequence

from . import _backend as B

# manifest keys every averaged run must agree on
_SAME = ("base", "base_sha256", "pooling", "num_labels", "unsafe_index", "labels", "max_length", "truncation")


def _read_run(d: Path) -> tuple[dict, dict]:
    if not d.is_dir():
        raise B.ModelError(f"run directory {d} does not exist")
    manifest = B.read_manifest(d)
    if manifest is None or manifest.get("format") != B.ADAPTER_FORMAT:
        raise B.ModelError(f"{d}: not an ethimon LoRA run ({B.MANIFEST} with format "
                           f"{B.ADAPTER_FORMAT!r} expected); only LoRA runs can be averaged")
    adapter, _ = B.checked_adapter(d, manifest)
    if not manifest.get("lora"):
        raise B.ModelError(f"{d}: manifest has no 'lora' block")
    return manifest, B.load_adapter_tensors(adapter)


def average_runs(run_dirs: Sequence[str | os.PathLike], out_dir: str | os.PathLike, *,
                 weights: Sequence[float] | None = None, temperature: float | None = None,
                 calibrate: tuple[list[str], list[int]] | None = None,
                 name: str | None = None, max_length: int | None = None,
                 rank: int | None = None) -> dict:
    """Write the weight average of ``run_dirs`` to ``out_dir``; return its manifest.

    ``weights`` default to uniform and are normalised to sum to 1. The
    temperature is ``temperature`` if given, else fitted on ``calibrate``
    (texts, labels) with the averaged model, else 1.0. ``max_length`` lets runs
    trained at different truncation lengths be averaged (it is an inference
    setting); without it they must agree. ``rank`` (optional) compresses each
    averaged update to its best rank-``rank`` approximation (truncated SVD) to
    keep the adapter small; the largest relative Frobenius error over the layers
    is recorded in the manifest (``svd_rel_error``). Without it the average is exact.
    """
    dirs = [Path(d) for d in run_dirs]
    if len(dirs) < 2:
        raise B.ModelError("averaging needs at least two runs")
    if weights is None:
        weights = [1.0] * len(dirs)
    if len(weights) != len(dirs) or any(not (math.isfinite(w) and w > 0) for w in weights):
        raise B.ModelError("weights: one finite positive number per run expected")
    if temperature is not None and not (math.isfinite(temperature) and temperature > 0):
        raise B.ModelError(f"temperature {temperature!r}: a finite number > 0 expected")
    if any(Path(out_dir).resolve() == d.resolve() for d in dirs):
        raise B.ModelError(f"--out {out_dir} is one of the runs; write the average elsewhere")
    total = float(sum(weights))
    ws = [float(w) / total for w in weights]
    runs = [_read_run(d) for d in dirs]
    m0, t0 = runs[0]
    targets = list(m0["lora"].get("targets") or
                   sorted(k[len("lora."):-len(".A")] for k in t0 if k.startswith("lora.") and k.endswith(".A")))
    for d, (m, t) in zip(dirs[1:], runs[1:]):
        for key in _SAME:
            if key == "max_length" and max_length is not None:
                continue
            if m.get(key) != m0.get(key):
                raise B.ModelError(f"{d}: {key} = {m.get(key)!r} differs from {dirs[0]}'s {m0.get(key)!r}; "
                                   "only runs of one base and architecture can be averaged")
        if sorted(k for k in t if k.startswith("lora.")) != sorted(k for k in t0 if k.startswith("lora.")):
            raise B.ModelError(f"{d}: adapts other layers than {dirs[0]}")
    if rank is not None and (isinstance(rank, bool) or not isinstance(rank, int) or rank < 1):
        raise B.ModelError(f"rank={rank!r}: a positive integer expected")
    torch = B.torch
    out_t: dict = {}
    svd_err = 0.0
    for tgt in targets:
        a_parts, b_parts = [], []
        for (m, t), w in zip(runs, ws):
            scale = float(m["lora"]["alpha"]) / float(m["lora"]["r"])
            try:
                a_parts.append(t[f"lora.{tgt}.A"].float())
                b_parts.append(t[f"lora.{tgt}.B"].float() * (w * scale))
            except KeyError as exc:
                raise B.ModelError(f"adapter tensors for {tgt!r} missing in one run: {exc}") from exc
        a_cat, b_cat = torch.cat(a_parts, 0), torch.cat(b_parts, 1)
        if rank is not None and rank < a_cat.shape[0]:
            delta = b_cat.double() @ a_cat.double()
            u, sv, vh = torch.linalg.svd(delta, full_matrices=False)
            root = sv[:rank].sqrt()
            b_cat, a_cat = (u[:, :rank] * root).float(), (root[:, None] * vh[:rank]).float()
            lost = float((sv[rank:] ** 2).sum().sqrt() / (sv ** 2).sum().sqrt().clamp_min(1e-30))
            svd_err = max(svd_err, lost)
        out_t[f"lora.{tgt}.A"] = a_cat.half().contiguous()
        out_t[f"lora.{tgt}.B"] = b_cat.half().contiguous()
    for key in ("head.weight", "head.bias"):
        try:
            out_t[key] = sum(t[key].float() * w for (_, t), w in zip(runs, ws)).contiguous()
        except (KeyError, RuntimeError) as exc:
            raise B.ModelError(f"head weights missing or of different shapes: {exc}") from exc
    total_rank = sum(int(m["lora"]["r"]) for m, _ in runs)
    rank = min(rank, total_rank) if rank is not None else total_rank
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    B.save_adapter(out_t, out / "adapter.safetensors")
    manifest = {k: m0[k] for k in ("format",) + _SAME if k in m0}
    manifest.update({
        "name": name or f"{m0.get('name', 'run')}-avg{len(dirs)}",
        "adapter_file": "adapter.safetensors",
        "adapter_sha256": B.sha256_file(out / "adapter.safetensors"),
        "lora": {"r": rank, "alpha": float(rank), "targets": targets},
        "max_length": int(max_length or m0.get("max_length", 128)),
        "temperature": 1.0,
        **({"svd_rel_error": round(svd_err, 6)} if rank < total_rank else {}),
        "averaged_from": [{"run": d.name, "adapter_sha256": m["adapter_sha256"], "weight": round(w, 6)}
                          for d, (m, _), w in zip(dirs, runs, ws)],
    })
    if temperature is None and calibrate is not None:
        temperature = _fit_temperature_for(out, manifest, *calibrate)
    manifest["temperature"] = round(float(temperature if temperature is not None else 1.0), 6)
    (out / B.MANIFEST).write_text(json.dumps(manifest, indent=2) + "\n", encoding="utf-8")
    return manifest


def _fit_temperature_for(out: Path, manifest: dict, texts: list[str], labels: list[int]) -> float:
    from ._train import fit_temperature, predict_logits

    (out / B.MANIFEST).write_text(json.dumps(manifest, indent=2) + "\n", encoding="utf-8")
    lm = B.load_model(out)
    seqs = B.encode(lm.tokenizer, texts, lm.max_length, lm.truncation)
    logits = predict_logits(lm.module, seqs, lm.tokenizer.pad_token_id or 0)
    return fit_temperature(logits, labels)
