"""ethimon's benchmarks: scripts that print a table and write JSON with the machine facts.

Run every script as a module from the repository root, e.g.::

    python -m bench.monitor.monitor_step --cycles 20000

Layout (see bench/README.md): ``bench/<concern>/<script>.py`` for the concerns monitor, risk,
sim and verify; results in ``bench/results/<concern>/``. Timings live here, never in tests.
"""

from __future__ import annotations

import importlib.util
import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
"""The repository root."""
RESULTS = ROOT / "bench" / "results"
"""Where every script writes: ``RESULTS / <concern> / <file>``."""


def results_dir(concern: str) -> Path:
    """``bench/results/<concern>/``, created if missing."""
    d = RESULTS / concern
    d.mkdir(parents=True, exist_ok=True)
    return d


def load_baseline(src: str):
    """The ``ethimon`` package under ``src`` (another tree's ``src/``, e.g. ``git archive base5 src``)
    imported as ``ethimon_baseline`` beside this tree's (its imports are relative): the scripts'
    ``--baseline``, timed in the same rounds."""
    pkg = os.path.join(src, "ethimon")
    spec = importlib.util.spec_from_file_location("ethimon_baseline", os.path.join(pkg, "__init__.py"),
                                                  submodule_search_locations=[pkg])
    mod = importlib.util.module_from_spec(spec)
    sys.modules["ethimon_baseline"] = mod
    spec.loader.exec_module(mod)
    return mod
