"""The risk back-end protocol (issue 33 item 4): one estimator loop over any ``Encoder``, K probabilities,
encoders registered by name, a view read once, and ``as_estimator`` as the one way to hand one over."""

from __future__ import annotations

import math

import pytest

from ethimon.errors import ModelError, RiskInferenceError
from ethimon.risk import Encoder, RiskEstimator, as_estimator, register_encoder
from ethimon.risk import _encoder as E
from ethimon.risk._modeldir import check_manifest

PLAN = ["Move to the counter.", "Pick up the kettle by its handle.", "Carry it over the high chair.",
        "Tilt the kettle toward the toddler.", "Pour slowly."]


def plan(k: int) -> str:
    return "\n".join(f"{i}. {s}" for i, s in enumerate(PLAN[:k], start=1))


class FakeEncoder:
    """Pure Python: a token per word; logits grow with 'kettle' and 'toddler' in the sequence."""

    backend = "fake"
    jit = False
    max_length = 64
    truncation = "head_tail"
    temperature = 1.0

    def __init__(self, labels=("safe", "unsafe"), unsafe_index=1, bad=None) -> None:
        self.labels, self.unsafe_index, self.bad = tuple(labels), unsafe_index, bad
        self.model_id = "fake@0"
        self.seqs: list[list[int]] = []
        self.vocab: dict[str, int] = {}

    def _ids(self, s: str) -> list[int]:
        return [self.vocab.setdefault(w.lower().strip(".,"), len(self.vocab) + 3) for w in s.split()]

    def encode(self, views):
        return [[[1] + self._ids(c) + [2] + self._ids(f) + [2]] if c else [[1] + self._ids(f) + [2]]
                for c, f in views]

    def logits(self, seqs):
        self.seqs += seqs
        if self.bad == "raise":
            raise RuntimeError("boom")
        hot = {self.vocab.get("kettle"), self.vocab.get("toddler")}
        out = []
        for s in seqs:
            z = [0.0] * len(self.labels)
            z[self.unsafe_index] = sum(1.0 for t in s if t in hot) - 1.0 + 0.01 * len(s)
            if self.bad == "nan":
                z[0] = math.nan
            out.append(z[:-1] if self.bad == "short" else z)
        return out

    def trace(self) -> bool:
        return False


def test_a_fake_encoder_is_an_encoder_and_runs_the_one_loop():
    enc = FakeEncoder()
    assert isinstance(enc, Encoder)
    est = RiskEstimator(enc, cache_size=0)
    p = est.probs("Tilt the kettle toward the toddler.")
    assert len(p) == 2 and p[0] == 1.0 - p[1] and p[1] > 0.5
    assert est.estimate("Put the fork away.").p_unsafe == est.probs("Put the fork away.")[1]
    assert est.backend == "fake" and est.labels == ("safe", "unsafe")


def test_k_classes_give_k_probabilities_in_class_order():
    est = RiskEstimator(FakeEncoder(("safe", "unsafe", "unsure"), unsafe_index=1), cache_size=0)
    p = est.probs("Tilt the kettle toward the toddler.")
    assert len(p) == 3 and math.isclose(sum(p), 1.0) and p[1] == max(p)
    r = est.estimate("Tilt the kettle toward the toddler.")
    assert r.p_unsafe == p[1] and est.unsafe_at == 1
    two = "1. Move to the counter. 2. Tilt the kettle toward the toddler."
    assert est.explain(two)["p_unsafe"] == pytest.approx(est.probs(two)[1]) and len(est.explain(two)["p"]) == 3


@pytest.mark.parametrize("bad, what", [("nan", "NaN"), ("raise", "boom"), ("short", "classes")])
def test_the_loop_fails_closed_for_every_encoder(bad, what):
    est = RiskEstimator(FakeEncoder(bad=bad), cache_size=16)
    with pytest.raises(RiskInferenceError, match=what):
        est.probs("Tilt the kettle toward the toddler.")
    assert est.cache_info()["size"] == 0 and not est._views     # nothing cached for a failure


def test_a_plan_read_again_with_one_more_step_scores_only_its_new_views():
    enc = FakeEncoder()
    est = RiskEstimator(enc, cache_size=64)
    est.probs(plan(4))
    n = len(enc.seqs)
    est.probs(plan(5))
    assert len(enc.seqs) - n == 2      # step 5 alone and step 5 after steps 1-4: no earlier view again
    cold = RiskEstimator(FakeEncoder(), cache_size=0)
    assert est.probs(plan(5)) == cold.probs(plan(5))


def test_views_shared_by_texts_in_one_batch_are_scored_once():
    enc = FakeEncoder()
    est = RiskEstimator(enc, cache_size=64)
    est.probs_batch([plan(3), plan(4), "Pour slowly."])
    assert len(enc.seqs) == len({tuple(s) for s in enc.seqs})


def test_encoders_are_registered_by_name_and_a_manifest_names_one(tmp_path):
    made = []

    def loader(model_dir, **kw):
        made.append(model_dir)
        return FakeEncoder()
    register_encoder("fake_test", loader)
    try:
        from ethimon.risk import load_estimator
        est = load_estimator(str(tmp_path), backend="fake_test", cache_size=0)
        assert est.backend == "fake" and made == [str(tmp_path)]
        with pytest.raises(ValueError, match="expected one of"):
            load_estimator(str(tmp_path), backend="no_such")
    finally:
        E._REGISTRY.pop("fake_test")
    with pytest.raises(ValueError):
        register_encoder("os:system", loader)
    base = {"format": "ethimon-lora/1", "base": {"package": "x"}, "adapter_sha256": "0" * 64}
    assert check_manifest(tmp_path / "m.json", {**base, "encoder": "onnx"})["encoder"] == "onnx"
    with pytest.raises(ModelError, match="registered back-end"):
        check_manifest(tmp_path / "m.json", {**base, "encoder": "os:system"})


def test_as_estimator_is_the_one_way_to_hand_one_over(tmp_path):
    est = RiskEstimator(FakeEncoder(), cache_size=0)
    assert as_estimator(est) is est
    assert as_estimator(lambda: est) is est
    fn = as_estimator(lambda text: (0.25, 0.75))
    assert fn.probs("anything") == (0.25, 0.75)
    with pytest.raises(ModelError, match="never by code"):
        as_estimator("os:system")
    with pytest.raises(ModelError, match="not a model directory"):
        as_estimator(str(tmp_path / "missing"))
    with pytest.raises(TypeError, match="factory"):
        as_estimator(lambda a, b: None)
    with pytest.raises(TypeError, match="returned"):
        as_estimator(lambda: 42)
    with pytest.raises(TypeError):
        as_estimator(42)
