"""A confirmation in the confirm band names the text it confirms (regression, found in review).

Before: a Monitor stepped without ``task_id`` bound the operator's confirmation to ``None``, so a
*different* text whose R_e also fell in the band executed on the first text's confirmation.
"""

import pathlib

import ethimon
from ethimon import Monitor
from ethimon.testing import ReferenceMonitor

SPEC = (pathlib.Path(__file__).resolve().parents[1] / "specs" / "governor.yaml").read_text().replace(
    "confirm_threshold: null", "confirm_threshold: 0.24")


def _monitors():
    spec = ethimon.load_spec_text(SPEC)
    return Monitor(spec), ReferenceMonitor(spec)


def test_without_task_id_a_confirmation_is_refused_and_every_band_text_holds():
    for m in _monitors():
        d = m.step({"p": (0.5, 0.5)})  # R_e 0.40: in the band [0.24, 0.47)
        assert d.override and "confirm" in d.violations
        ack = m.acknowledge()
        assert not ack.released and "task_id" in ack.message
        # another text in the band, still no task_id: held, never executed on a confirmation of nothing
        d = m.step({"p": (0.6, 0.4)})
        assert d.override and "confirm" in d.violations, type(m).__name__


def test_a_confirmation_holds_only_for_its_own_task_id():
    for m in _monitors():
        assert m.step({"p": (0.5, 0.5), "task_id": "a"}).override
        assert m.acknowledge().released
        assert not m.step({"p": (0.5, 0.5), "task_id": "a"}).override
        d = m.step({"p": (0.6, 0.4), "task_id": "b"})
        assert d.override and "confirm" in d.violations
        # the same text again after another one: confirmed anew, not remembered
        d = m.step({"p": (0.5, 0.5), "task_id": "a"})
        assert d.override, type(m).__name__


def test_a_task_id_that_disappears_ends_the_confirmation():
    for m in _monitors():
        m.step({"p": (0.5, 0.5), "task_id": "a"})
        assert m.acknowledge().released
        assert not m.step({"p": (0.5, 0.5), "task_id": "a"}).override
        d = m.step({"p": (0.5, 0.5)})
        assert d.override and "confirm" in d.violations, type(m).__name__
