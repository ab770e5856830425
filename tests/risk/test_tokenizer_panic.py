"""Issue 31 item 5: a panic in the tokenizers library (pyo3 ``PanicException``, a ``BaseException``
that ``except Exception`` lets through; a hostile ``tokenizer.json`` regex raises one) is a located
:class:`ModelError`, at load and at encode time, never a traceback."""

from __future__ import annotations

import pytest

from ethimon.errors import ModelError


class PanicException(BaseException):
    """What pyo3 raises for a Rust panic (``pyo3_runtime.PanicException`` derives from BaseException)."""


class _Encoding:
    ids = [5]


class _PanicOnLoad:
    @staticmethod
    def from_file(path):
        raise PanicException("called `Result::unwrap()` on an `Err` value: regex")


class _PanicOnEncode:
    calls = 0

    @classmethod
    def from_file(cls, path):
        return cls()

    def no_truncation(self):
        pass

    def no_padding(self):
        pass

    def encode(self, text, add_special_tokens=False):
        return _Encoding()

    def encode_batch(self, texts, add_special_tokens=False):
        raise PanicException("byte index 3 is not a char boundary")

    def token_to_id(self, t):
        return 0


@pytest.fixture
def model_dir(tmp_path):
    (tmp_path / "tokenizer.json").write_text("{}")
    return tmp_path


def test_a_panic_while_loading_tokenizer_json_is_a_located_model_error(model_dir, monkeypatch):
    from ethimon.risk import _onnx
    monkeypatch.setattr(_onnx, "Tokenizer", _PanicOnLoad)
    with pytest.raises(ModelError, match="tokenizer.json.*panicked"):
        _onnx.FastTokenizer(model_dir)


def test_a_panic_while_encoding_is_a_located_model_error(model_dir, monkeypatch):
    from ethimon.risk import _onnx
    monkeypatch.setattr(_onnx, "Tokenizer", _PanicOnEncode)
    tok = _onnx.FastTokenizer(model_dir)
    with pytest.raises(ModelError, match="tokenizer.json.*panicked while encoding"):
        tok.encode(["Place the red box on the second shelf."], 64, "head_tail")
    with pytest.raises(ModelError, match="tokenizer.json"):
        tok.encode_views([("a scene", "a step")], 64, "head_tail")


def test_interrupts_still_interrupt():
    from ethimon.risk._modeldir import tokenizer_call

    def stop():
        raise KeyboardInterrupt
    with pytest.raises(KeyboardInterrupt):
        tokenizer_call("x", "encoding", stop)
