"""A random policy on the Panda cell, bare and under an ethimon shield, side by side.

    pip install "ethimon[gym,sim]"
    python examples/gym_shield.py --episodes 5

Both runs of an episode see the same seed (same start pose, target and walking
person) and the same sequence of proposed actions, so the only difference is
the shield: on an override it replaces the proposed action by a zero joint
velocity target (hold the current setpoint).

Columns:
  return       the episode return (reward = -distance to the target, per step)
  cost         Σ info["cost"]: steps whose proposed action the monitor overrode
               (bare: the monitor only watches, the action runs anyway)
  unsafe       steps ending in a state that violates the spec on *measured*
               signals only (a second, passive monitor): what actually happened
  min dist     the closest any person came to the arm (m)
"""

from __future__ import annotations

import argparse
import sys
from collections import Counter

import gymnasium
import numpy as np

import ethimon
from ethimon.gym import MonitorWrapper, panda_signals, panda_spec

NO_RISK = {"p_unsafe": 0.0}  # no language instruction in this task: stated, not assumed


def measured(info: dict) -> dict:
    """The spec's inputs on the measured state alone (no commanded speed)."""
    return {**NO_RISK, **panda_signals(None, info, np.zeros(7))}


def run_episode(seed: int, steps: int, shielded: bool) -> dict:
    spec = panda_spec()
    env = gymnasium.make("ethimon/PandaCell-v0", max_episode_steps=steps)
    if shielded:
        env = MonitorWrapper(env, spec, signals=panda_signals, safe_action=np.zeros(7, np.float32), inputs=NO_RISK)
    watcher = ethimon.Monitor(spec)  # bare run: would the shield have stepped in?
    audit = ethimon.Monitor(spec)    # both runs: was the state reached unsafe?
    policy = gymnasium.spaces.Box(env.action_space.low, env.action_space.high, dtype=np.float32, seed=seed)
    obs, info = env.reset(seed=seed)
    ret = cost = 0.0
    unsafe = 0
    by_rule: Counter = Counter()
    min_dist = info["human_distance"]
    try:
        while True:
            action = policy.sample()
            if not shielded:
                cost += float(watcher.step({**NO_RISK, **panda_signals(obs, info, action)}).override)
            obs, reward, terminated, truncated, info = env.step(action)
            ret += reward
            if shielded:
                cost += info["cost"]
            seen = audit.step(measured(info)).violations
            unsafe += bool(seen)
            by_rule.update(seen)
            min_dist = min(min_dist, info["human_distance"])
            if terminated or truncated:
                break
    finally:
        env.close()
    return {"return": ret, "cost": cost, "unsafe": unsafe, "min_dist": min_dist, "steps": audit.cycle,
            "by_rule": by_rule}


def row(r: dict) -> str:
    return f"{r['steps']:>5} {r['return']:>8.1f} {r['cost']:>5.0f} {r['unsafe']:>6} {r['min_dist']:>8.3f}"


def tot_row(t: np.ndarray) -> str:
    return f"{t[0]:>5.0f} {t[1]:>8.1f} {t[2]:>5.0f} {t[3]:>6.0f} {'':>8}"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--episodes", type=int, default=5)
    ap.add_argument("--steps", type=int, default=200, help="steps per episode (20 per simulated second)")
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args(argv)
    cols = f"{'steps':>5} {'return':>8} {'cost':>5} {'unsafe':>6} {'min dist':>8}"
    head = f"{'episode':>7} | {cols} | {cols}"
    print(f"{'':>7}   {'bare random policy':^36}   {'shielded (ethimon)':^36}")
    print(head)
    print("-" * len(head))
    tot = {"bare": np.zeros(4), "shield": np.zeros(4)}
    rules = {"bare": Counter(), "shield": Counter()}
    for ep in range(args.episodes):
        seed = args.seed + ep
        b = run_episode(seed, args.steps, shielded=False)
        s = run_episode(seed, args.steps, shielded=True)
        for k, r in (("bare", b), ("shield", s)):
            tot[k] += (r["steps"], r["return"], r["cost"], r["unsafe"])
            rules[k].update(r["by_rule"])
        print(f"{seed:>7} | {row(b)} | {row(s)}")
    print("-" * len(head))
    b, s = tot["bare"], tot["shield"]
    print(f"{'total':>7} | {tot_row(b)} | {tot_row(s)}")
    print("\nunsafe steps by rule (measured):")
    for k, name in (("bare", "bare"), ("shield", "shielded")):
        print(f"  {name:>8}: " + (", ".join(f"{r} {n}" for r, n in sorted(rules[k].items())) or "none"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
