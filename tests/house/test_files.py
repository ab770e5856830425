"""One "regular files only" rule (ethimon._files), used by every reader and writer of user-named
files: specs and scenarios, audit logs, key files, reports (review of issue 11)."""

import os

import pytest
from tests._cli import ROOT
from tests._estimators import run_in_thread

import ethimon
from ethimon import _files
from ethimon.audit import AuditFormatError, AuditLog, verify_log
from ethimon.cli import main

needs_fifo = pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs here")


def _no_block(fn, timeout=10.0):
    blocked, out = run_in_thread(fn, timeout)
    assert not blocked, "blocked"
    return out


def test_file_kind(tmp_path):
    f = tmp_path / "a"
    f.write_text("x")
    assert _files.file_kind(f) is None and _files.file_kind(os.stat(f)) is None
    assert _files.file_kind(tmp_path) == "a directory"
    if os.path.exists("/dev/null"):
        assert _files.file_kind("/dev/null") == "a character device"


@needs_fifo
def test_every_reader_refuses_a_fifo_with_the_same_words_and_names_the_file(tmp_path):
    fifo = tmp_path / "x.yaml"
    os.mkfifo(fifo)
    spec_err = _no_block(lambda: ethimon.load_spec(fifo))["exc"]
    audit_err = _no_block(lambda: verify_log(fifo))["exc"]
    assert isinstance(spec_err, ethimon.SpecError) and isinstance(audit_err, AuditFormatError)
    for err in (spec_err, audit_err):
        assert str(fifo) in str(err) and "a named pipe (FIFO), not a regular file" in str(err)
        assert _files.NOT_REGULAR_HINT in str(err)


@needs_fifo
def test_open_regular_raises_the_callers_error_type(tmp_path):
    class Mine(Exception):
        def __init__(self, message, *, path, hint):
            super().__init__(f"{path}|{message}|{hint}")
    fifo = tmp_path / "f"
    os.mkfifo(fifo)
    err = _no_block(lambda: _files.open_regular(fifo, "rb", what="thing", error=Mine))["exc"]
    assert isinstance(err, Mine) and str(err).startswith(f"{fifo}|expected a thing, found a named pipe")
    err = _no_block(lambda: _files.open_regular(fifo, "w", what="report", error=Mine, special_ok=True))["exc"]
    assert isinstance(err, Mine) and "a named pipe (FIFO) with no reader" in str(err)
    err = _no_block(lambda: _files.open_regular(tmp_path / "missing", what="thing", error=Mine))["exc"]
    assert isinstance(err, Mine) and "thing not found" in str(err)
    err = _no_block(lambda: _files.open_regular(tmp_path, what="thing", error=Mine))["exc"]
    assert isinstance(err, Mine) and "found a directory" in str(err)


def test_check_loads_the_spec_once_without_a_separate_pre_check(tmp_path, monkeypatch, capsys):
    calls = []
    real = _files.require_regular  # the one discovery rule (_files.scan_yaml_files) calls it

    def spy(path, what="file"):
        calls.append((os.fspath(path), what))
        return real(path, what)
    monkeypatch.setattr(_files, "require_regular", spy)
    spec = tmp_path / "spec.yaml"
    spec.write_text((ROOT / "specs" / "governor.yaml").read_text())
    (tmp_path / "a.yaml").write_text(f"ethimon: 1\nname: a\nspec: {spec}\ncycles: 3\ninputs: {{risk: 0.2}}\n")
    assert main(["check", str(tmp_path / "a.yaml")]) == 0
    assert calls == [(str(tmp_path / "a.yaml"), "scenario")], calls  # the spec: load_spec checks it, no second stat


def test_audit_verify_cli_does_not_stat_before_verify_log(tmp_path, monkeypatch, capsys):
    def boom(*a, **k):
        raise AssertionError("redundant pre-check")
    monkeypatch.setattr(_files, "require_regular", boom)
    log = AuditLog(tmp_path / "l.jsonl")
    log.close()
    assert main(["audit", "verify", str(tmp_path / "l.jsonl")]) == 0
    assert main(["audit", "verify", str(tmp_path)]) == 2
    assert f"{tmp_path}: expected an audit log, found a directory" in capsys.readouterr().err



@needs_fifo
def test_a_model_config_that_is_a_fifo_is_a_model_error_without_blocking(tmp_path, monkeypatch):
    import ethimon.risk._modeldir as modeldir  # the torch-free model-directory checks
    from ethimon.errors import ModelError
    from ethimon.risk._modeldir import read_json_object
    monkeypatch.setattr(modeldir, "MAX_JSON_BYTES", 1000)
    fifo = tmp_path / "config.json"
    os.mkfifo(fifo)
    err = _no_block(lambda: read_json_object(fifo))["exc"]
    assert isinstance(err, ModelError) and str(err).startswith(f"{fifo}: expected a file, found a named pipe")
    big = tmp_path / "big.json"
    big.write_bytes(b" " * 2000 + b"{}")
    with pytest.raises(ModelError, match="bytes; a model configuration file is at most"):
        read_json_object(big)
    ok = tmp_path / "ok.json"
    ok.write_text('{"a": 1}')
    assert read_json_object(ok) == {"a": 1}
