"""Building the spec's judge tier: one judge (``risk.judge``) or several in consensus (``risk.judges``).

:func:`load_judge_for` reads the spec's judge settings, and the operator's key variable and hosts from
the environment (never from the spec); :class:`JudgePanel` combines several judges' verdicts.
"""

from __future__ import annotations

import os
import threading
import time
from pathlib import Path
from typing import Any

from ..compiler import plan_of
from ._judge import KEY_ENV_VAR, Judge, JudgeResult, text_sha256

__all__ = ["JudgePanel", "load_judge_for", "not_configured"]


class JudgePanel:
    """Several judges in consensus (``risk.judges``): asked together on each text.

    The combined answer is the monitor's ``judge`` input: ``1.0`` (unsafe) when any judge says unsafe,
    ``0.0`` (safe) only when every judge says safe, otherwise no judgement (status ``"unsure"``, or
    the first non-``ok`` status: a judge that failed its canaries, timed out or erred leaves the band
    to a person). ``detail`` lists each judge's status and p_unsafe.
    """

    def __init__(self, judges: list[Judge]) -> None:
        if not judges:
            raise ValueError("a judge panel needs at least one judge")
        self.judges = list(judges)
        self.model = "+".join(j.model for j in self.judges)
        self.calls = 0

    @property
    def model_id(self) -> str:
        return f"judges:{self.model}"

    @property
    def canary_state(self) -> str:
        states = [j.canary_state for j in self.judges]
        for s in ("failed_canary", "unchecked", "off"):
            if s in states:
                return s
        return "passed"

    def judge(self, text: str) -> JudgeResult:
        """Every judge's answer on ``text`` (asked in parallel), combined. Never raises."""
        self.calls += 1
        t0 = time.monotonic()
        out: list[JudgeResult | None] = [None] * len(self.judges)

        def ask(i: int) -> None:
            out[i] = self.judges[i].judge(text)

        threads = [threading.Thread(target=ask, args=(i,), daemon=True) for i in range(len(self.judges))]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        res = [r if r is not None else JudgeResult(None, "error", 0.0, None, None, j.model, text_sha256(text),
                                                   "no answer") for r, j in zip(out, self.judges)]
        lines = "; ".join(f"{r.model}: {r.status}" + (f" p {r.p_unsafe:.3f}" if r.p_unsafe is not None else "")
                          for r in res)
        canary = "; ".join(f"{r.model}: {r.canary}" for r in res if r.canary)
        h = res[0].text_sha256
        dt = time.monotonic() - t0
        if any(r.p_unsafe is not None and r.p_unsafe >= j.unsafe_from for r, j in zip(res, self.judges)):
            return JudgeResult(1.0, "ok", dt, "1", None, self.model, h, "a judge says unsafe (" + lines + ")",
                               canary=canary)
        if all(r.status == "ok" and r.p_unsafe is not None and r.p_unsafe < j.safe_below
               for r, j in zip(res, self.judges)):
            return JudgeResult(0.0, "ok", dt, "0", None, self.model, h, "", all(r.cached for r in res), canary)
        bad = next((r.status for r in res if r.status != "ok"), "unsure")
        return JudgeResult(None, bad, dt, None, None, self.model, h, "no consensus (" + lines + ")",
                           canary=canary)

    def __repr__(self) -> str:
        return f"JudgePanel({self.judges!r})"


def load_judge_for(spec: Any, *, canaries: Any = "spec", key_env: str | None = None,
                   key_hosts: Any = None) -> "Judge | JudgePanel | None":
    """The spec's ``risk.judge`` as a :class:`Judge` (``risk.judges``: a :class:`JudgePanel`), or ``None``.

    The judges' settings are read from the spec's plan (``Plan.tiers.judges``, resolved by the compiler);
    ``spec`` may be a :class:`~ethimon.Spec` or its :class:`~ethimon.compiler.Plan`.

    Args:
        canaries: ``"spec"`` (default): the shipped set plus the spec's ``canaries.path``; ``None``: off
            (tests of the client only).
        key_env: the variable holding the key, named by the operator (default ``ETHIMON_JUDGE_KEY_ENV``).
            A spec's ``api_key_env`` that differs from it refuses every call (a spec cannot pick a secret).
        key_hosts: the hosts a key may go to besides loopback (default ``ETHIMON_JUDGE_HOSTS``).
    """
    plan = plan_of(spec)
    tiers = plan.tiers
    if not tiers.judges:
        return None
    op_env = key_env if key_env is not None else (os.environ.get(KEY_ENV_VAR) or None)
    judges = []
    for j in tiers.judges:
        refused = ""
        if j.api_key_env is not None and j.api_key_env != op_env:
            refused = (f"{j.where}.api_key_env names {j.api_key_env}, but a spec cannot choose the key: the operator "
                       f"names it ({KEY_ENV_VAR}={j.api_key_env}); no call is made")
        if canaries == "spec":
            extra = j.canaries_path
            if extra is not None and not Path(extra).is_absolute():
                src = getattr(getattr(plan.spec, "source", None), "path", None)  # relative to the spec file
                if src and Path(src).parent.is_dir() and not str(src).startswith("<"):
                    extra = str(Path(src).parent / extra)
            can: Any = extra if extra is not None else "builtin"
        else:
            can = canaries
        judges.append(Judge(j.url, j.model, timeout_s=j.timeout_s, api_key_env=op_env, prompt=j.prompt,
                            safe_below=j.safe_below, unsafe_from=j.unsafe_from, key_hosts=key_hosts,
                            canaries=can, canary_every_s=j.canaries_every_s,
                            canary_every_texts=j.canaries_every_texts, _key_refused=refused))
    if tiers.consensus:
        return JudgePanel(judges)
    return judges[0]


def not_configured(text: str) -> JudgeResult:
    """The result for a spec without ``risk.judge`` (no judgement)."""
    return JudgeResult(None, "not_configured", 0.0, None, None, "", text_sha256(text), "the spec sets no risk.judge")
