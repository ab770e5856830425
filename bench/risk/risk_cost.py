"""What capacity and the step reading cost on this machine (issue 19 items 3 and 4).

    python -m bench.risk.risk_cost [--steps 6] [--runs 200]

1. Seconds per training step (batch 32 + 8 minimal pairs, the shipped recipe's batch; texts of
   the corpus's length) for MiniLM-L6 with LoRA r16, MiniLM-L6 fully fine-tuned, and an
   MPNet-base-shaped encoder (12 layers, 768 wide, randomly initialised: the cost of a step
   does not depend on the weights' values) fully fine-tuned, torch threads 2. From it the
   minutes one epoch of the issue's corpus would take.
2. Scoring latency of the shipped estimator, the step reading against the flat one, in one
   process, interleaved: a short command, a scene of ~150 words + instruction, a numbered plan
   of 8 steps, a code-call plan of 8 steps (p50/p90 over --runs calls, cache off, 1 thread
   as a one-shot command and a control loop use it; traced with TorchScript as a long-running
   service is).

Writes bench/results/risk/risk_cost.json (``--tag T``: risk_cost_T.json) with the machine facts and the load average.
"""

from __future__ import annotations

import argparse
import json
import statistics
import time

from bench import results_dir
from bench._machine import machine_facts

SHORT = "Hand the chef's knife to Maria blade first, with the point aimed at her stomach."
SCENE = ("The kitchen is small and bright. A toddler sits in a high chair next to the counter, "
         "banging a spoon. On the counter there is a cutting board with a chef's knife, a bowl of "
         "apples, a kettle that has just boiled, and a roll of paper towels. The parent is on the "
         "phone by the window with their back to the room. The floor near the sink is wet because "
         "the dishwasher leaked earlier, and a yellow sign stands next to it. The robot stands at the "
         "far end of the counter with its gripper empty. Music plays from a speaker on the shelf. "
         "The cat sleeps on a chair. The back door is open and a breeze moves the curtains. ")
PLAN8 = "\n".join(f"{i}. {s}" for i, s in enumerate([
    "Move to the counter.", "Pick up the kettle by its handle.", "Carry it over the high chair.",
    "Tilt the kettle toward the toddler.", "Pour slowly.", "Put the kettle back on its base.",
    "Wipe the counter with a paper towel.", "Return to the dock."], start=1))
CODE8 = "\n".join([
    'move_to("counter")', 'pick("kettle", grasp="handle")', 'move_to("high_chair", height=0.3)',
    'tilt("kettle", angle=70)  # toward the toddler', 'wait(2.0)', 'place("kettle", "base")',
    'wipe("counter")', 'dock()'])


def train_step_times(steps: int) -> dict:
    import torch
    from ethimon.risk import _backend as B
    from bench.risk import risk_data as D
    torch.set_num_threads(2)
    tr, _va = D.natural_train_splits()
    texts = tr.texts[:48]
    base = B.base_package_dir()
    tok = B.load_tokenizer(base)
    out = {}
    import transformers
    ids, mask = B.collate(B.encode(tok, texts, 256, "head_tail"), tok.pad_token_id or 0)
    y = torch.tensor([i % 2 for i in range(len(texts))])

    def build(encoder, lora: bool, lr: float):
        for p in encoder.parameters():
            p.requires_grad_(False)
        if lora:
            B.inject_lora(encoder, 16, 32.0, 0.05)
            params = [p for n, p in encoder.named_parameters() if "lora_" in n]
        else:
            params = [encoder.get_submodule(n).weight for n in B.lora_target_names(encoder)]
            for p in params:
                p.requires_grad_(True)
        model = B.PooledClassifier(encoder, 2)
        params = params + list(model.head.parameters())
        model.train()
        return model, torch.optim.AdamW(params, lr=lr), sum(p.numel() for p in params)

    cfg = transformers.MPNetConfig(vocab_size=30527, hidden_size=768, num_hidden_layers=12, num_attention_heads=12,
                                   intermediate_size=3072, max_position_embeddings=514)
    torch.manual_seed(0)
    models = {"minilm_l6_lora_r16": build(B.load_encoder(base), True, 5e-4),
              "minilm_l6_full": build(B.load_encoder(base), False, 3e-5),
              "mpnet_base_shape_full": build(transformers.MPNetModel(cfg), False, 2e-5)}
    times: dict = {k: [] for k in models}
    mp_ids = ids.clamp(max=30526)  # MiniLM's token ids fit MPNet's (random) embedding table
    for s in range(steps + 1):     # interleaved, so a busy spell on the shared cores hits all three
        for name, (model, opt, _n) in models.items():
            t0 = time.perf_counter()
            loss = torch.nn.functional.cross_entropy(model(mp_ids if "mpnet" in name else ids, mask), y)
            opt.zero_grad(set_to_none=True)
            loss.backward()
            opt.step()
            if s:  # the first step warms up the allocator
                times[name].append(time.perf_counter() - t0)
    for name, (_m, _o, n_params) in models.items():
        med = statistics.median(times[name])
        out[name] = {"s_per_step": med, "steps": steps, "trainable_params": n_params, "rows_per_step": len(texts),
                     "tokens_per_row_padded": int(ids.shape[1]), "all_s": [round(x, 3) for x in times[name]]}
        print(f"{name:<28} {med:7.2f} s/step  ({n_params / 1e6:.1f} M trainable, {len(texts)} rows x "
              f"{ids.shape[1]} tokens)", flush=True)
    return out


def latency(runs: int) -> dict:
    from ethimon.risk import load_estimator
    texts = {"short": SHORT, "scene_150w_instruction": SCENE + SHORT, "plan_8_steps": PLAN8, "code_8_calls": CODE8}
    est = {r: load_estimator(cache_size=0, num_threads=1, reading=r, jit=True) for r in ("steps", "flat")}
    got: dict = {r: {k: [] for k in texts} for r in est}
    for _ in range(3):  # warm-up
        for r, e in est.items():
            for t in texts.values():
                e.probs(t)
    for _ in range(runs):
        for k, t in texts.items():
            for r, e in est.items():
                t0 = time.perf_counter()
                e.probs(t)
                got[r][k].append(time.perf_counter() - t0)
    from ethimon.risk._reading import views
    res = {}
    print(f"{'text':<24} {'views':>5} {'steps p50':>10} {'p90':>7} {'flat p50':>9} {'ratio':>6}")
    for k, t in texts.items():
        row = {}
        for r in est:
            xs = sorted(got[r][k])
            row[r] = {"p50_ms": 1e3 * xs[len(xs) // 2], "p90_ms": 1e3 * xs[int(len(xs) * 0.9)]}
        row["views"] = len(views(t))
        row["ratio_p50"] = row["steps"]["p50_ms"] / row["flat"]["p50_ms"]
        res[k] = row
        print(f"{k:<24} {row['views']:>5} {row['steps']['p50_ms']:>8.1f}ms {row['steps']['p90_ms']:>5.1f}ms "
              f"{row['flat']['p50_ms']:>7.1f}ms {row['ratio_p50']:>5.2f}x", flush=True)
    return res


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--steps", type=int, default=6, help="training steps timed per model (median)")
    ap.add_argument("--runs", type=int, default=200, help="scoring calls timed per text and reading")
    ap.add_argument("--skip-train", action="store_true")
    ap.add_argument("--tag", default=None, help="write risk_cost_<tag>.json (default: risk_cost.json)")
    a = ap.parse_args()
    import os
    load0 = os.getloadavg()
    res = {"load_at_start": load0}
    res["latency"] = latency(a.runs)
    if not a.skip_train:
        res["train_step"] = train_step_times(a.steps)
        per = res["train_step"]
        # one epoch of the corpus the issue asks for (robot corpus + writers' rows ~ 20,000 rows)
        for k, v in per.items():
            v["min_per_epoch_20k_rows"] = v["s_per_step"] * 20000 / v["rows_per_step"] / 60
    res["machine"] = machine_facts(threads=2)
    name = f"risk_cost_{a.tag}.json" if a.tag else "risk_cost.json"
    (results_dir("risk") / name).write_text(json.dumps(res, indent=1) + "\n")


if __name__ == "__main__":
    main()
