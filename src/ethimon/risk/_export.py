"""``ethimon export MODEL_DIR``: write ``model.onnx`` and its pinning sidecar (needs torch, once).

For encoder families the ONNX backend does not build itself (MPNet, RoBERTa, ...), or to ship
a graph file with a directory: the torch model is exported with ``torch.onnx.export`` (the
TorchScript exporter, standard operators only), checked by ``_onnx.check_graph`` as any graph
file is, run by ONNX Runtime against torch on probe texts (|Δlogit| ≤ 1e-4 or nothing is
written), and pinned in ``ethimon_onnx.json``: the graph's sha256 and the sha256 of the weights
it was made from (the adapter, or the one weights file of a plain directory), so a graph left
behind by a retrained model is refused as stale.
"""

from __future__ import annotations

import hashlib
import json
import os
import warnings
from pathlib import Path

from ..errors import ModelError
from . import _backend as B
from . import _onnx as O

PROBES = ("Hand the kitchen knife to the child blade first.", "Put the fork in the drawer.",
          "I took the money from the blind man's wallet while he slept and bought candy with it.")
TOLERANCE = 1e-4


def export_onnx(model_dir: str | os.PathLike, *, file: str = "model.onnx") -> dict:
    """Export ``model_dir``'s classifier to ``model_dir/file`` and pin it; return the sidecar written.

    Raises:
        ModelError: the directory is refused, the export fails or ONNX Runtime disagrees with torch.
    """
    import numpy as np
    import onnx
    torch = B.torch
    d = Path(model_dir)
    if not (file.endswith(".onnx") and file == Path(file).name):
        raise ModelError(f"--file {file!r}: a .onnx file name inside the model directory expected")
    loaded = B.load_model(d)
    module = loaded.module.eval()
    _tokenizer_json(d, loaded)
    pad = loaded.tokenizer.pad_token_id or 0
    ids, mask = B.collate(B.encode(loaded.tokenizer, list(PROBES[:2]), loaded.max_length, loaded.truncation), pad)
    dyn = {"input_ids": {0: "batch", 1: "seq"}, "attention_mask": {0: "batch", 1: "seq"}, "logits": {0: "batch"}}
    import io
    buf = io.BytesIO()
    try:
        with warnings.catch_warnings(), torch.no_grad():
            warnings.simplefilter("ignore")
            torch.onnx.export(module, (ids, mask), buf, input_names=list(O.INPUTS), output_names=[O.OUTPUT],
                              dynamic_axes=dyn, opset_version=O.OPSET, dynamo=False, do_constant_folding=True)
    except Exception as exc:  # noqa: BLE001
        raise ModelError(f"{d}: torch.onnx.export failed: {type(exc).__name__}: {str(exc)[:300]}") from None
    data = buf.getvalue()
    O.check_graph(onnx.load_model_from_string(data), f"{d / file} (exported)", None)
    session = O._session(data, 1)
    for batch in ([PROBES[0]], list(PROBES), [PROBES[2], PROBES[1]] * 3):
        i, k = B.collate(B.encode(loaded.tokenizer, batch, loaded.max_length, loaded.truncation), pad)
        with torch.no_grad():
            want = module(i, k).float().numpy()
        got = session.run([O.OUTPUT], {"input_ids": i.numpy(), "attention_mask": k.numpy()})[0]
        if got.shape != want.shape or not np.allclose(got, want, atol=TOLERANCE, rtol=TOLERANCE):
            raise ModelError(f"{d}: the exported graph disagrees with torch (max |Δlogit| "
                             f"{float(np.abs(got - want).max()) if got.shape == want.shape else 'shape'}); "
                             "nothing written")
    (d / file).write_bytes(data)
    manifest = B.read_manifest(d)
    side = {"format": O.GRAPH_FORMAT,
            "graphs": {"fp32": {"file": file, "sha256": hashlib.sha256(data).hexdigest()}},
            "source_sha256": O._source_sha(d, manifest), "max_length": loaded.max_length,
            "truncation": loaded.truncation, "temperature": loaded.temperature,
            "unsafe_index": loaded.unsafe_index, "num_labels": int(want.shape[1]),
            "exported_with": f"torch {torch.__version__}, opset {O.OPSET}"}
    O.check_graph_manifest(d / O.GRAPH_MANIFEST, side)
    (d / O.GRAPH_MANIFEST).write_text(json.dumps(side, indent=2) + "\n", encoding="utf-8")
    return side


def _tokenizer_json(d: Path, loaded) -> Path:
    """Where the ONNX backend will read ``tokenizer.json`` (the tokenizer torch reads: ``d``'s, else the
    base's); written into ``d`` from the fast tokenizer if that directory has none."""
    from . import _modeldir as M
    manifest = M.read_manifest(d)
    tok_dir = d if manifest is None or any((d / n).is_file() for n in M.TOKENIZER_FILES) \
        else M.resolve_base(d, manifest)
    if (tok_dir / "tokenizer.json").is_file():
        return tok_dir
    backend = getattr(loaded.tokenizer, "backend_tokenizer", None)
    if backend is None:
        raise ModelError(f"{tok_dir}: no tokenizer.json and the tokenizer has no fast form to write one from")
    backend.save(str(d / "tokenizer.json"))
    return d
