"""Scenarios: scripted input timelines with expectations, run by ``ethimon check``."""

from ._model import Expect, Scenario, TimelineEntry
from ._run import (ScenarioResult, build_inputs, check_expectations, find_scenarios, load_scenario,
                   load_scenario_text, run_scenario)

__all__ = ["Expect", "Scenario", "ScenarioResult", "TimelineEntry", "build_inputs", "check_expectations",
           "find_scenarios", "load_scenario", "load_scenario_text", "run_scenario"]
