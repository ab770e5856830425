"""Scenarios: scripted input timelines with expectations, run by ``ethimon check``."""

from ._model import Expect, Scenario, TimelineEntry
from ._run import (BUILTIN_INPUTS, ScenarioResult, build_inputs, check_expectations, check_input_names,
                   find_scenarios, find_yaml_files, load_scenario, load_scenario_text, require_regular_file,
                   run_scenario)

__all__ = ["BUILTIN_INPUTS", "Expect", "Scenario", "ScenarioResult", "TimelineEntry", "build_inputs",
           "check_expectations", "check_input_names", "find_scenarios", "find_yaml_files", "load_scenario",
           "load_scenario_text", "require_regular_file", "run_scenario"]
