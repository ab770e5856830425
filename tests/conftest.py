from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
#: the corpora of bench/risk (ETHICS, SafeAgentBench), beside the checkout; not shipped
SHARED_DATA = ROOT.parent / "shared" / "data"


@pytest.fixture
def root() -> Path:
    return ROOT


@pytest.fixture
def shared_data() -> Path:
    """``../shared/data``; tests that need it (mark them ``data``) skip, with the reason, without it."""
    if not SHARED_DATA.is_dir():
        pytest.skip(f"{SHARED_DATA} is absent (the ETHICS/SafeAgentBench corpora live beside the checkout)")
    return SHARED_DATA
