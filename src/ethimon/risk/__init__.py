"""Ethical risk: the R_e formula (always available) and the learned estimator.

Scoring needs the optional extra ``ethimon[risk]`` (ONNX Runtime, tokenizers: no torch);
training and the torch backend need ``ethimon[train]`` (torch, transformers). Either is
imported only when a model is loaded, so ``import ethimon.risk`` stays light.
"""

from __future__ import annotations

from ._estimator import (DEFAULT_TAU, ProbsEstimator, RiskEstimate, RiskEstimator, RiskInferenceError, default_model_dir,
                         default_threads, estimator_kwargs, load_estimator, load_estimator_for)
from ._formula import OUTCOMES, VARIANCE_MODES, judge_verdict, risk_bounds, risk_from_p_unsafe, risk_from_probs, tier_outcome
from ._canaries import load_canaries
from ._encoder import Encoder, register_encoder
from ._provide import as_estimator
from ._judge import BUILTIN_JUDGE_PROMPT, JUDGE_STATUSES, Judge, JudgeResult, injection_signs, parse_judge_reply, text_sha256
from ._judge_tier import JudgePanel, load_judge_for

__all__ = ["as_estimator", "BUILTIN_JUDGE_PROMPT", "Encoder", "injection_signs", "Judge", "JudgePanel",
           "JudgeResult", "load_estimator", "load_estimator_for", "ProbsEstimator", "register_encoder",
           "risk_from_p_unsafe", "risk_from_probs", "RiskEstimator", "text_sha256"]
