import subprocess
import sys

import pytest

import ethimon


def test_all_names_import():
    for name in ethimon.__all__:
        assert hasattr(ethimon, name), name


@pytest.mark.slow
def test_import_and_step_do_not_load_torch_or_pybullet():
    code = (
        "import sys, ethimon\n"
        "m = ethimon.Monitor(ethimon.load_spec('specs/cobot_cell.yaml'))\n"
        "m.step({'p_unsafe': 0.1, 'human_distance': 3, 'ee_speed': 0.1, 'contact_force': 0, 'joint_speed_max': 0})\n"
        "import ethimon.risk, ethimon.sim, ethimon.verify, ethimon.cli\n"
        "bad = [m for m in ('torch', 'transformers', 'pybullet', 'z3', 'onnxruntime', 'onnx', 'tokenizers') if m in sys.modules]\n"
        "print(bad)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         cwd=str(__import__('pathlib').Path(__file__).resolve().parents[2]))
    assert out.stdout.strip() == "[]"


def test_errors_hierarchy():
    assert issubclass(ethimon.SpecError, ethimon.EthimonError)
    assert issubclass(ethimon.SpecError, ValueError)
    e = ethimon.SpecError("unknown signal 'x'", path="a.yaml", line=3, column=7, hint="did you mean 'y'?")
    assert str(e) == "a.yaml:3:7: unknown signal 'x' (did you mean 'y'?)"
