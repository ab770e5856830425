"""Every exception class of ethimon lives in ``ethimon.errors`` under ``EthimonError`` (issue 13)."""

from __future__ import annotations

import ast
import pickle
from pathlib import Path

import pytest

import ethimon.errors as errors

SRC = Path(__file__).resolve().parents[2] / "src" / "ethimon"

#: private exception classes that never leave their module (each raised and caught inside it)
PRIVATE_INTERNAL = {
    ("language/_errors.py", "_LocError"),        # a pydantic validator's ValueError, turned into a SpecError by the loader
    ("scenario/_session.py", "_SpecLoadError"),  # wraps a spec's error so the row names the spec; unwrapped there
    ("risk/_onnx_build.py", "_NoGraph"),    # "no ONNX form here": load_estimator falls back to torch or raises ModelError
    ("risk/_encoder.py", "NoFormHere"),     # a registered loader's "no form of this model here": load_encoder tries the next
}


def _exception_classes() -> list[tuple[str, str, list[str]]]:
    out = []
    for path in sorted(SRC.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.ClassDef):
                bases = [ast.unparse(b) for b in node.bases]
                if any(b.endswith(("Error", "Exception", "Tampered", "DependencyNotInstalled")) for b in bases):
                    out.append((str(path.relative_to(SRC)), node.name, bases))
    return out


def test_every_exception_class_is_defined_in_errors_py_or_is_private():
    found = _exception_classes()
    assert found, "the scan found no exception classes"
    outside = [(f, n) for f, n, _ in found if f != "errors.py" and (f, n) not in PRIVATE_INTERNAL]
    assert outside == [], f"define these in src/ethimon/errors.py: {outside}"


def test_every_public_exception_derives_from_ethimon_error():
    for name in errors.__all__:
        cls = getattr(errors, name)
        assert issubclass(cls, errors.EthimonError), name


@pytest.mark.parametrize("name, builtin", [("SpecError", ValueError), ("ExprSyntaxError", ValueError),
                                           ("SimError", ValueError), ("AuditFormatError", ValueError),
                                           ("AuditTampered", ValueError), ("DependencyNotInstalled", ImportError)])
def test_builtin_bases_kept_for_callers_that_catch_them(name, builtin):
    assert issubclass(getattr(errors, name), builtin)


def test_packages_re_export_the_same_classes():
    from ethimon import audit, language, risk, sim
    from ethimon.replay import BagError
    from ethimon.language._expr import ExprSyntaxError
    assert audit.AuditFormatError is errors.AuditFormatError
    assert audit.AuditTampered is errors.AuditTampered
    assert risk.RiskInferenceError is errors.RiskInferenceError
    assert sim.SimError is errors.SimError
    assert BagError is errors.BagError
    assert ExprSyntaxError is errors.ExprSyntaxError
    assert language.ExprSyntaxError is errors.ExprSyntaxError


def test_parse_expr_raises_an_ethimon_error():
    from ethimon.language import parse_expr
    with pytest.raises(errors.EthimonError) as info:
        parse_expr("human_distance >")
    assert isinstance(info.value, errors.ExprSyntaxError) and info.value.index > 0


def test_errors_with_fields_survive_pickling():
    e = pickle.loads(pickle.dumps(errors.ExprSyntaxError("unexpected ')'", 4, "remove it")))
    assert (e.message, e.index, e.hint) == ("unexpected ')'", 4, "remove it")
    b = pickle.loads(pickle.dumps(errors.BagError("corrupt", "a.mcap", "re-record it")))
    assert (b.message, b.path, b.hint, str(b)) == ("corrupt", "a.mcap", "re-record it", "a.mcap: corrupt (re-record it)")


def test_read_log_raises_audit_tampered_on_a_broken_chain(tmp_path):
    from ethimon.audit import AuditLog, read_log
    p = tmp_path / "run.jsonl"
    with AuditLog(str(p), fsync="never") as log:
        log.append("decision", cycle=0, override=False)
        log.append("decision", cycle=1, override=True)
    lines = p.read_text().splitlines(keepends=True)
    lines[1] = lines[1].replace('"override":false', '"override":true')
    assert lines[1] != p.read_text().splitlines(keepends=True)[1]
    p.write_text("".join(lines))
    with pytest.raises(errors.AuditTampered) as info:
        read_log(str(p))
    assert isinstance(info.value, ValueError) and str(p) in str(info.value)
