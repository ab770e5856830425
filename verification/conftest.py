"""Hypothesis profiles for the property suite.

* ``ci`` (default): derandomized, few examples, the whole suite in about a minute on 2 cores.
* ``thorough``: ``HYPOTHESIS_PROFILE=thorough pytest verification/`` — many more
  examples, random seeds, failing examples kept in ``.hypothesis/`` (git-ignored).
"""

from __future__ import annotations

import os
import sys

from hypothesis import HealthCheck, settings

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

_SLOW = [HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much]

settings.register_profile("ci", max_examples=40, derandomize=True, deadline=None, database=None,
                          suppress_health_check=_SLOW, print_blob=True)
settings.register_profile("thorough", max_examples=1500, deadline=None, suppress_health_check=_SLOW,
                          print_blob=True, stateful_step_count=80)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))


def pytest_configure(config):
    # the expression strategies are lambdas over lambdas; their repr is large and useless
    config.addinivalue_line("filterwarnings", "ignore:Generating overly large repr")
