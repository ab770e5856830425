"""Scenarios: scripted input timelines with expectations, run by ``ethimon check`` and ``ethimon simulate``."""

from ._session import CheckOutcome, CheckReport, ScenarioSession, check_paths, error_line, sim_risk_inputs, simulate_paths
from ._model import Expect, Scenario, TimelineEntry
from ._run import (BUILTIN_INPUTS, ScenarioResult, build_inputs, check_expectations, check_input_names,
                   find_scenarios, load_scenario, load_scenario_text, run_scenario)

__all__ = ["CheckOutcome", "CheckReport", "Scenario", "ScenarioResult", "check_paths", "load_scenario",
           "load_scenario_text", "run_scenario", "simulate_paths"]
