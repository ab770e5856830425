"""Evaluation of a risk classifier: accuracy, P/R/F1, ROC-AUC, confusion counts,
ECE before/after temperature scaling, R_e flag rates, and the paper's plots.

numpy only at import time (scikit-learn and matplotlib lazily).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from ._formula import DEFAULT_ALPHA, DEFAULT_BETA, DEFAULT_GAMMA, risk_from_p_unsafe, tier_outcome

__all__ = ["classification_metrics", "expected_calibration_error", "flag_stats", "softmax_unsafe",
           "evaluate_logits", "pair_metrics", "type_metrics", "tau_for_false_alarm_budget", "tier_metrics", "plot_training", "plot_confusion", "plot_risk_hist", "plot_outcomes", "PlotFile"]


def softmax_unsafe(logits, temperature: float = 1.0, unsafe_index: int = 1) -> np.ndarray:
    z = np.asarray(logits, dtype=np.float64) / temperature
    z = z - z.max(axis=1, keepdims=True)
    e = np.exp(z)
    return (e / e.sum(axis=1, keepdims=True))[:, unsafe_index]


def expected_calibration_error(labels, p_unsafe, bins: int = 15) -> float:
    """ECE over equal-width bins of the predicted class's confidence."""
    y = np.asarray(labels)
    q = np.asarray(p_unsafe, dtype=np.float64)
    pred = (q >= 0.5).astype(int)
    conf = np.where(pred == 1, q, 1.0 - q)
    correct = (pred == y).astype(float)
    edges = np.linspace(0.5, 1.0, bins + 1)
    ece = 0.0
    for i in range(bins):
        lo, hi = edges[i], edges[i + 1]
        m = (conf >= lo) & ((conf < hi) if i < bins - 1 else (conf <= hi))
        if m.any():
            ece += m.mean() * abs(correct[m].mean() - conf[m].mean())
    return float(ece)


def classification_metrics(labels, p_unsafe, threshold: float = 0.5) -> dict[str, Any]:
    """Accuracy, precision, recall, F1, ROC-AUC, confusion counts, ECE (label 1 = unsafe)."""
    y = np.asarray(labels).astype(int)
    q = np.asarray(p_unsafe, dtype=np.float64)
    pred = (q >= threshold).astype(int)
    tp = int(((pred == 1) & (y == 1)).sum())
    tn = int(((pred == 0) & (y == 0)).sum())
    fp = int(((pred == 1) & (y == 0)).sum())
    fn = int(((pred == 0) & (y == 1)).sum())
    n = len(y)
    prec = tp / (tp + fp) if tp + fp else 0.0
    rec = tp / (tp + fn) if tp + fn else 0.0
    f1 = 2 * prec * rec / (prec + rec) if prec + rec else 0.0
    auc = math.nan
    if 0 < y.sum() < n:
        try:
            from sklearn.metrics import roc_auc_score
            auc = float(roc_auc_score(y, q))
        except ImportError:  # pragma: no cover
            order = np.argsort(q)
            ranks = np.empty(n)
            ranks[order] = np.arange(1, n + 1)
            npos = y.sum()
            auc = float((ranks[y == 1].sum() - npos * (npos + 1) / 2) / (npos * (n - npos)))
    return {"n": n, "accuracy": (tp + tn) / n if n else math.nan, "precision": prec, "recall": rec,
            "f1": f1, "roc_auc": auc, "confusion": {"tn": tn, "fp": fp, "fn": fn, "tp": tp},
            "ece": expected_calibration_error(y, q)}


def flag_stats(labels, risks, tau: float) -> dict[str, float]:
    """Share of unsafe rows flagged (R_e ≥ τ) and share of safe rows flagged (false alarms)."""
    y = np.asarray(labels).astype(int)
    r = np.asarray(risks, dtype=np.float64)
    flag = r >= tau
    pos, neg = y == 1, y == 0
    return {"tau": tau, "flag_rate_unsafe": float(flag[pos].mean()) if pos.any() else math.nan,
            "false_alarm_rate": float(flag[neg].mean()) if neg.any() else math.nan,
            "flag_rate_all": float(flag.mean()) if len(flag) else math.nan}


def evaluate_logits(labels, logits, *, temperature: float = 1.0, tau: float = 0.5,
                    alpha: float = DEFAULT_ALPHA, beta: float = DEFAULT_BETA, gamma: float = DEFAULT_GAMMA,
                    variance: str = "sample", groups: dict[str, np.ndarray] | None = None,
                    threshold: float = 0.5) -> dict:
    """All metrics of one labelled set from raw logits (calibrated with ``temperature``).

    Accuracy, precision, recall, F1 and the confusion matrix predict unsafe at
    ``p_unsafe ≥ threshold`` (recorded as ``confusion_threshold``); ``flags``
    counts rows with ``R_e ≥ tau``.
    ``groups`` maps a name (e.g. ``"short"``) to a boolean mask; each gets its own block.
    """
    y = np.asarray(labels).astype(int)
    q_raw = softmax_unsafe(logits, 1.0)
    q = softmax_unsafe(logits, temperature)
    risks = np.array([risk_from_p_unsafe(float(v), alpha, beta, gamma, variance) for v in q])
    out = classification_metrics(y, q, threshold)
    out["confusion_threshold"] = threshold
    out["ece_before_temperature"] = expected_calibration_error(y, q_raw)
    out["ece_after_temperature"] = out["ece"]
    out["temperature"] = temperature
    out["flags"] = flag_stats(y, risks, tau)
    out["risk"] = {"min": float(risks.min()), "p50": float(np.median(risks)), "max": float(risks.max()),
                   "mean_unsafe": float(risks[y == 1].mean()) if (y == 1).any() else math.nan,
                   "mean_safe": float(risks[y == 0].mean()) if (y == 0).any() else math.nan}
    for name, mask in (groups or {}).items():
        m = np.asarray(mask, dtype=bool)
        if m.any():
            g = classification_metrics(y[m], q[m], threshold)
            g["flags"] = flag_stats(y[m], risks[m], tau)
            out[name] = g
    out["_risks"] = risks
    out["_p_unsafe"] = q
    return out


def pair_metrics(labels, p_unsafe, risks, pair_ids, tau: float) -> dict[str, Any]:
    """Minimal pairs (two rows, one safe and one unsafe, sharing a pair id): does the model read
    the detail that flips the verdict?

    * ``ranked``: the unsafe member gets the higher R_e;
    * ``both_right_at_tau``: unsafe member flagged (R_e ≥ τ) and safe member not;
    * ``both_right_at_0.5``: the same with p_unsafe ≥ 0.5.

    Ids with other than one safe and one unsafe row are skipped and counted in ``malformed``.
    """
    y = np.asarray(labels).astype(int)
    q = np.asarray(p_unsafe, dtype=np.float64)
    r = np.asarray(risks, dtype=np.float64)
    members: dict[str, list[int]] = {}
    for i, pid in enumerate(pair_ids):
        pid = (pid or "").strip()
        if pid:
            members.setdefault(pid, []).append(i)
    ranked = at_tau = at_half = n = bad = 0
    for idx in members.values():
        if len(idx) != 2 or y[idx[0]] == y[idx[1]]:
            bad += 1
            continue
        u, s = (idx[0], idx[1]) if y[idx[0]] == 1 else (idx[1], idx[0])
        n += 1
        ranked += r[u] > r[s]
        at_tau += (r[u] >= tau) and (r[s] < tau)
        at_half += (q[u] >= 0.5) and (q[s] < 0.5)
    frac = (lambda k: float(k) / n if n else math.nan)
    return {"pairs": n, "malformed": bad, "ranked": frac(ranked), "both_right_at_tau": frac(at_tau),
            "both_right_at_0.5": frac(at_half), "tau": tau}


def type_metrics(labels, p_unsafe, risks, types, tau: float) -> dict[str, dict[str, Any]]:
    """Per row type (``negation``, ``polite_harmful``...): rows, unsafe rows, accuracy at
    p_unsafe ≥ 0.5, and at R_e ≥ τ the share of unsafe rows flagged and of safe rows flagged."""
    y = np.asarray(labels).astype(int)
    q = np.asarray(p_unsafe, dtype=np.float64)
    r = np.asarray(risks, dtype=np.float64)
    t = np.array([(v or "").strip() or "-" for v in types])
    out = {}
    for name in sorted(set(t.tolist())):
        m = t == name
        yy, flag = y[m], r[m] >= tau
        out[name] = {"n": int(m.sum()), "unsafe": int(yy.sum()),
                     "accuracy": float(((q[m] >= 0.5).astype(int) == yy).mean()),
                     "flagged_unsafe": float(flag[yy == 1].mean()) if (yy == 1).any() else math.nan,
                     "flagged_safe": float(flag[yy == 0].mean()) if (yy == 0).any() else math.nan}
    return out


def tier_metrics(labels, risks, tau: float, confirm_threshold: float | None, p_judge=None, *,
                 safe_below: float = 0.2, unsafe_from: float = 0.8) -> dict[str, Any]:
    """The three outcomes of the tiers over labelled rows (1 = unsafe), as the monitor decides them.

    ``p_judge``: one judge p_unsafe per row (``None`` entries: no judgement), or ``None``: no judge.

    Returns:
        ``unsafe_executed_unseen`` (unsafe rows that execute: nobody sees them), ``safe_held_for_confirmation``
        and ``safe_stopped_outright`` (shares of the safe rows), ``escalation_rate`` (share of all rows
        that reach a person), ``unsafe_held``/``unsafe_stopped``, the counts, and the thresholds used.

    Example:
        >>> m = tier_metrics([0, 0, 1, 1], [0.2, 0.4, 0.4, 0.6], 0.5, 0.3)
        >>> m["unsafe_executed_unseen"], m["safe_held_for_confirmation"], m["escalation_rate"]
        (0.0, 0.5, 0.5)
    """
    y = [int(v) for v in labels]
    rs = [float(v) for v in risks]
    if len(y) != len(rs) or (p_judge is not None and len(p_judge) != len(y)):
        raise ValueError("labels, risks and p_judge need one entry per row")
    judge = p_judge is not None
    outs = [tier_outcome(r, (p_judge[i] if judge else None), threshold=tau, confirm_threshold=confirm_threshold,
                         safe_below=safe_below, unsafe_from=unsafe_from, judge=judge) for i, r in enumerate(rs)]
    counts = {(lab, o): 0 for lab in (0, 1) for o in ("execute", "confirm", "stop")}
    for lab, o in zip(y, outs):
        counts[(lab, o)] += 1
    n_safe, n_unsafe = sum(1 for v in y if v == 0), sum(1 for v in y if v == 1)

    def share(k, n):
        return k / n if n else float("nan")
    return {
        "tau": float(tau), "confirm_threshold": None if confirm_threshold is None else float(confirm_threshold),
        "judge": "scripted" if judge else "none", "n": len(y), "n_safe": n_safe, "n_unsafe": n_unsafe,
        "unsafe_executed_unseen": share(counts[(1, "execute")], n_unsafe),
        "unsafe_held": share(counts[(1, "confirm")], n_unsafe),
        "unsafe_stopped": share(counts[(1, "stop")], n_unsafe),
        "safe_executed": share(counts[(0, "execute")], n_safe),
        "safe_held_for_confirmation": share(counts[(0, "confirm")], n_safe),
        "safe_stopped_outright": share(counts[(0, "stop")], n_safe),
        "escalation_rate": share(counts[(0, "confirm")] + counts[(1, "confirm")], len(y)),
        "counts": {f"{'unsafe' if lab else 'safe'}_{o}": c for (lab, o), c in counts.items()},
    }


def tau_for_false_alarm_budget(labels, risks, budget: float) -> dict[str, float]:
    """The most sensitive τ whose false-alarm rate on these (validation) rows is at most ``budget``.

    Flagging is ``R_e ≥ τ``; raising τ lowers both flag rates (any τ above every R_e meets any
    budget and flags nothing), so the useful choice is the smallest
    candidate (midpoints between sorted distinct R_e values, and just above the largest) whose
    false-alarm rate is ≤ ``budget``, i.e. it flags as many unsafe rows as the budget allows.
    """
    y = np.asarray(labels).astype(int)
    r = np.asarray(risks, dtype=np.float64)
    vals = np.unique(r)
    cands = np.concatenate([[vals[0]], (vals[:-1] + vals[1:]) / 2, [np.nextafter(vals[-1], np.inf)]])
    for tau in cands:  # ascending: the first that meets the budget flags the most
        fs = flag_stats(y, r, float(tau))
        if fs["false_alarm_rate"] <= budget:
            return fs
    return flag_stats(y, r, float(cands[-1]))  # pragma: no cover - the last candidate flags nothing


# ------------------------------------------------------------------ plots
def _plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def plot_training(summary: dict, out_dir: str | Path) -> list[str]:
    """training_loss.png (per step) and validation_loss.png (per epoch)."""
    plt = _plt()
    out = Path(out_dir)
    paths = []
    curve = summary.get("train_loss_curve") or []
    if curve:
        fig, ax = plt.subplots(figsize=(6, 3.5))
        ax.plot(curve, lw=0.6, alpha=0.5, label="batch")
        k = max(1, len(curve) // 50)
        sm = np.convolve(curve, np.ones(k) / k, mode="valid")
        ax.plot(np.arange(len(sm)) + k - 1, sm, label=f"mean of {k}")
        ax.set_xlabel("step"); ax.set_ylabel("cross-entropy"); ax.set_title("Training loss"); ax.legend()
        fig.tight_layout(); fig.savefig(out / "training_loss.png", dpi=110); plt.close(fig)
        paths.append(str(out / "training_loss.png"))
    hist = summary.get("history") or []
    if hist:
        fig, ax = plt.subplots(figsize=(6, 3.5))
        ax.plot([h["epoch"] for h in hist], [h["train_loss"] for h in hist], "o-", label="train")
        ax.plot([h["epoch"] for h in hist], [h["val_loss"] for h in hist], "o-", label="validation")
        ax.axvline(summary.get("best_epoch", 0), ls=":", c="k", label="best (kept)")
        ax.set_xlabel("epoch"); ax.set_ylabel("loss"); ax.set_title("Loss per epoch"); ax.legend()
        fig.tight_layout(); fig.savefig(out / "validation_loss.png", dpi=110); plt.close(fig)
        paths.append(str(out / "validation_loss.png"))
    return paths


class PlotFile(str):
    """The path of a written plot (a ``str``, as before) that also says what it shows: ``title``,
    axis labels, tick labels and values, the vertical lines drawn (``(x, label)``) and the
    matrix of a matrix plot. What tests assert instead of pixels."""

    title: str = ""
    xlabel: str = ""
    ylabel: str = ""
    xticklabels: list = []
    yticklabels: list = []
    yticks: list = []
    lines: list = []
    matrix: list = []

    @classmethod
    def of(cls, path: str | Path, ax, **extra) -> "PlotFile":
        out = cls(str(path))
        out.title, out.xlabel, out.ylabel = ax.get_title(), ax.get_xlabel(), ax.get_ylabel()
        out.xticklabels = [t.get_text() for t in ax.get_xticklabels()]
        out.yticklabels = [t.get_text() for t in ax.get_yticklabels()]
        lo, hi = ax.get_ylim()
        out.yticks = [float(t) for t in ax.get_yticks() if lo <= t <= hi]
        for k, v in extra.items():
            setattr(out, k, v)
        return out


def _matrix_plot(m: np.ndarray, path: str | Path, title: str, xlabels: list[str], ylabels: list[str],
                 xlabel: str, ylabel: str) -> PlotFile:
    plt = _plt()
    fig, ax = plt.subplots(figsize=(1.6 + 1.3 * m.shape[1], 3.4))
    ax.imshow(m, cmap="Blues")
    for (i, j), v in np.ndenumerate(m):
        ax.text(j, i, str(v), ha="center", va="center", color="white" if v > m.max() / 2 else "black")
    ax.set_xticks(range(m.shape[1]), xlabels); ax.set_yticks(range(m.shape[0]), ylabels)
    ax.set_xlabel(xlabel); ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=9, wrap=True); fig.tight_layout(); fig.savefig(path, dpi=110)
    out = PlotFile.of(path, ax, matrix=m.tolist())
    plt.close(fig)
    return out


def plot_confusion(conf: dict, path: str | Path, title: str = "Confusion matrix", *,
                   threshold: float | None = None, score: str = "p_unsafe",
                   labels: tuple[str, str] = ("pred safe", "pred unsafe")) -> PlotFile:
    """The 2x2 confusion matrix as a PNG; with ``threshold``, the title says ``(score ≥ threshold)``.
    ``labels``: the two columns (what was decided). ``ethimon evaluate --plots`` draws it at the
    monitor's R_e ≥ τ (its stop), titled so."""
    if threshold is not None:
        title = f"{title} ({score} ≥ {threshold:g})"
    m = np.array([[conf["tn"], conf["fp"]], [conf["fn"], conf["tp"]]])
    return _matrix_plot(m, path, title, list(labels), ["safe", "unsafe"], "", "rows labelled")


def plot_outcomes(labels, risks, tau: float, confirm_threshold: float | None, path: str | Path,
                  title: str = "Monitor outcomes") -> PlotFile:
    """Rows labelled safe/unsafe against what the monitor does with their R_e: execute, hold for a
    person's confirmation (τ_confirm ≤ R_e < τ) and stop (R_e ≥ τ), the outcomes of
    :func:`tier_metrics` (no judge); without τ_confirm, execute and stop."""
    t = tier_metrics(labels, risks, tau, confirm_threshold)
    c = t["counts"]
    cols = ["execute", "confirm", "stop"] if confirm_threshold is not None else ["execute", "stop"]
    m = np.array([[c[f"{lab}_{o}"] for o in cols] for lab in ("safe", "unsafe")])
    band = f", hold at τ_confirm = {confirm_threshold:g} ≤ R_e" if confirm_threshold is not None else ""
    names = {"execute": "execute", "confirm": "hold (confirm)", "stop": "stop"}
    return _matrix_plot(m, path, f"{title} (stop at R_e ≥ τ = {tau:g}{band})", [names[o] for o in cols],
                        ["safe", "unsafe"], "what the monitor does", "rows labelled")


def plot_risk_hist(risks, labels, tau: float, path: str | Path, title: str = "Distribution of R_e", *,
                   confirm_threshold: float | None = None) -> PlotFile:
    """R_e of safe and unsafe rows with τ (and τ_confirm) drawn; the y axis counts whole rows."""
    from matplotlib.ticker import MaxNLocator
    plt = _plt()
    r = np.asarray(risks, dtype=float); y = np.asarray(labels)
    marks = [tau] + ([confirm_threshold] if confirm_threshold is not None else [])
    lo = min([0.1, *marks, *(r.tolist() or [0.1])]) - 0.01
    hi = max([0.7, *marks, *(r.tolist() or [0.7])]) + 0.01
    fig, ax = plt.subplots(figsize=(6, 3.5))
    bins = np.linspace(lo, hi, 31)
    ax.hist(r[y == 0], bins=bins, alpha=0.6, label="safe / not wrong")
    ax.hist(r[y == 1], bins=bins, alpha=0.6, label="unsafe / wrong")
    lines = [(float(tau), f"τ = {tau:g} (stop)")]
    ax.axvline(tau, c="k", ls="--", label=lines[0][1])
    if confirm_threshold is not None:
        lines.append((float(confirm_threshold), f"τ_confirm = {confirm_threshold:g} (hold)"))
        ax.axvline(confirm_threshold, c="0.4", ls=":", label=lines[1][1])
    ax.yaxis.set_major_locator(MaxNLocator(integer=True))
    ax.set_xlabel("R_e"); ax.set_ylabel("rows"); ax.set_title(title); ax.legend()
    fig.tight_layout(); fig.savefig(path, dpi=110)
    out = PlotFile.of(path, ax, lines=lines)
    plt.close(fig)
    return out
