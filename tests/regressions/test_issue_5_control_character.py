"""Issue 5 (found by the parser fuzz in verification/): a control character in a spec gave a
SpecError without line/column whose message carried PyYAML's own multi-line position text."""

import pytest

import ethimon


@pytest.mark.parametrize("text, line, column", [("0\x1f", 1, 2), ("ethimon: 1\nname: a\x07b\n", 2, 8)])
def test_control_character_points_at_itself(text, line, column):
    with pytest.raises(ethimon.SpecError) as info:
        ethimon.load_spec_text(text, "f.yaml")
    err = info.value
    assert (err.path, err.line, err.column) == ("f.yaml", line, column)
    assert "\n" not in str(err) and "control character U+00" in str(err)
