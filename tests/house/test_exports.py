"""Public vs internal (issue 13): every package says what it exports, and the exported set is reviewed.

A package's public names are its ``__all__``; everything else (modules and names
with a leading underscore, names a package imports for its own use) is
internal and may change without notice. Adding a public name is a conscious
change: add it to :data:`PUBLIC` below in the same commit (and document it).
"""

from __future__ import annotations

import importlib
import importlib.util
from pathlib import Path

import pytest

import ethimon

SRC = Path(ethimon.__file__).resolve().parent

#: the reviewed public API, package by package
PUBLIC: dict[str, list[str]] = {
    "ethimon": ["AsyncRiskSource", "Decision", "DependencyNotInstalled", "EthimonError", "Fault", "GovernedLoop",
                "ModelError", "Monitor", "ProcessEstimator", "Response", "Spec", "SpecError", "__version__",
                "load_spec", "load_spec_text", "risk_from_p_unsafe", "risk_from_probs"],
    "ethimon.errors": ["AuditFormatError", "AuditTampered", "BagError", "DependencyNotInstalled", "EthimonError",
                       "ExprSyntaxError", "ModelError", "RiskInferenceError", "Ros2Error", "SimError", "SpecError"],
    "ethimon.audit": ["AuditFormatError", "AuditLag", "AuditLog", "AuditReport", "AuditTampered", "FSYNC_POLICIES",
                      "KEY_ENV", "KEY_FILE_ENV", "MAX_RECORD_BYTES", "bounded", "key_from_env", "read_log",
                      "spec_hash", "verify_log"],
    "ethimon.cli": ["main"],
    "ethimon.compiler": ["ObligationPlan", "Plan", "SignalSlot", "compile_plan", "plan_of", "stateless_slots"],
    "ethimon.fleet": ["DEFAULT_LOCAL_CPUS", "Failure", "check_address", "check_file_timeout", "check_paths",
                      "map_files", "plain", "replay_records"],
    "ethimon.gym": ["MonitorWrapper", "PANDA_ENV_ID", "PANDA_RATED_JOINT_SPEED_RAD_S", "PANDA_SPEC_PATH",
                    "PandaCellEnv", "panda_signals", "panda_spec"],
    "ethimon.language": ["Constant", "DEFAULT_ALPHA", "DEFAULT_BETA", "DEFAULT_GAMMA", "ExprSyntaxError", "Obligation",
                     "OnFault", "Release", "Response", "RiskConfig", "RuleRelease", "SEVERITY_ORDER", "SafePose",
                     "Signal", "VARIANCE_MODES", "Spec", "parse_expr", "parse_spec_file", "parse_spec_text",
                     "seconds_to_cycles"],
    "ethimon.loop": ["AsyncJudgeSource", "AsyncRiskSource", "CANNOT_TELL", "GovernedLoop", "LoopStats", "ProcessEstimator",
                     "ReloadResult", "RiskReading", "Watchdog", "weakenings"],
    "ethimon.offline": ["OfflineResult", "check_trace", "iter_rows"],
    "ethimon.io": ["AckRequest", "ByName", "Channel", "FIELD_PATH", "FUTURE_TOLERANCE_S", "Frame", "Hold", "LiveMonitor", "MAX_CYCLES", "MISSING", "MSGTYPE", "Mapping", "MemoryChannel", "OK", "REDUCTIONS", "RISK_INPUTS", "Recording", "Ros2Map", "STALE", "Sample", "SignalMap", "TASK_TEXT", "TaskMap", "bool_mismatch", "check_against_spec", "cycle_grid", "decision_json", "follow", "hold", "is_truth", "judged", "lint_mapping", "load_mapping", "load_mapping_text", "mapping_error", "mapping_json_schema", "msgtype_key", "numbers_of", "parse_field_path", "rate_between", "reduce_array", "reduce_value"],
    "ethimon.replay": ["BagData", "BagError", "BagReplay", "CheckResult", "CycleResults", "Mapping", "ReplayReport",
                       "Series", "SignalMap", "TaskMap", "TaskScorer", "TopicInfo", "check_against_spec",
                       "check_columns", "cycle_grid", "hold", "lint_mapping", "list_topics", "load_mapping",
                       "load_mapping_text", "mapping_json_schema", "read_bag", "recorded_data", "replay_bag", "replay_data",
                       "replay_paths", "resample", "write_mcap"],
    "ethimon.risk": ["DEFAULT_TAU", "ProbsEstimator", "RiskEstimate", "RiskEstimator", "RiskInferenceError",
                     "VARIANCE_MODES", "default_model_dir", "default_threads", "estimator_kwargs", "load_estimator",
                     "load_estimator_for", "risk_bounds", "risk_from_p_unsafe", "risk_from_probs",
                     "OUTCOMES", "judge_verdict", "tier_outcome", "BUILTIN_JUDGE_PROMPT", "JUDGE_STATUSES", "Judge",
                     "JudgePanel", "JudgeResult", "injection_signs", "load_canaries", "load_judge_for", "parse_judge_reply",
                     "text_sha256"],
    "ethimon.ros2": ["ACK_RESULT_TOPIC", "ACK_TOPIC", "DECISION_TOPIC", "DEFAULT", "ENCLAVE_FILES", "MessageTypes",
                     "OVERRIDE_TOPIC", "QosProfile", "Ros2Monitor", "SENSOR_DATA", "cyclone_config", "dds_topic",
                     "dds_type", "decision_json", "normalize_type", "ros_topic", "run_ros2", "security_available",
                     "to_cyclone"],
    "ethimon.runtime": ["Acknowledgement", "Decision", "FAULT_KINDS", "Fault", "Monitor"],
    "ethimon.view": ["DECISION", "DEFAULT_HOST", "DEFAULT_PORT", "FAULTS", "FoxgloveView", "INPUTS", "MARGINS", "RISK",
                     "TOPICS", "VerdictChannels", "parse_address"],
    "ethimon.scenario": ["BUILTIN_INPUTS", "CheckOutcome", "CheckReport", "Expect", "Scenario", "ScenarioResult",
                         "ScenarioSession", "TimelineEntry", "build_inputs", "check_expectations",
                         "check_input_names", "check_paths", "error_line", "find_scenarios", "load_scenario",
                         "load_scenario_text", "run_scenario", "sim_risk_inputs", "simulate_paths"],
    "ethimon.sim": ["ArmSim", "CycleRecord", "Dropout", "GovernedArm", "HOME_JOINTS_RAD", "HandOver", "Human",
                    "InputChange", "PHYSICS_HZ", "Pick", "Place", "Pour", "Reach", "SIGNAL_NAMES", "SimBlock",
                    "SimError", "SimExpect", "SimObject", "SimResult", "Wait", "Waypoint", "Wipe",
                    "check_sim_expectations", "run_sim"],
    "ethimon.testing": ["ReferenceMonitor"],
    "ethimon.verify": ["Counterexample", "DEFAULT_BUDGET_S", "DEFAULT_MAX_UNROLL", "DEFAULT_TIMEOUT_S", "Finding",
                       "SpecReport", "exit_code", "find_specs", "format_table", "reports_to_json", "require_z3",
                       "verify_paths", "verify_spec"],
    "ethimon.zenoh": ["ZenohChannel", "ZenohMonitor", "run_zenoh", "topic_key", "zenoh_config"],
}

#: packages whose import needs an optional extra
_NEEDS = {"ethimon.gym": "gymnasium"}


def _packages() -> list[str]:
    return ["ethimon"] + sorted(f"ethimon.{p.name}" for p in SRC.iterdir() if (p / "__init__.py").exists())


def test_every_package_is_reviewed():
    assert set(_packages()) | {"ethimon.errors"} == set(PUBLIC), \
        "a package was added or removed: give it an __all__ and a row in PUBLIC"


@pytest.mark.parametrize("name", sorted(PUBLIC))
def test_exports_are_reviewed_exist_and_are_public(name):
    if name in _NEEDS and importlib.util.find_spec(_NEEDS[name]) is None:
        pytest.skip(f"{name} needs {_NEEDS[name]}")
    mod = importlib.import_module(name)
    exported = getattr(mod, "__all__", None)
    assert exported is not None, f"{name} has no __all__"
    assert len(exported) == len(set(exported)), f"{name}.__all__ lists a name twice"
    private = [n for n in exported if n.startswith("_") and n != "__version__"]
    assert private == [], f"{name} exports private names {private}"
    missing = [n for n in exported if not hasattr(mod, n)]
    assert missing == [], f"{name}.__all__ names what it does not have: {missing}"
    assert sorted(exported) == sorted(PUBLIC[name]), (
        f"{name}.__all__ changed: added {sorted(set(exported) - set(PUBLIC[name]))}, "
        f"removed {sorted(set(PUBLIC[name]) - set(exported))}; review it and update PUBLIC")


def test_internals_named_by_issue_13_are_not_exported():
    from ethimon import audit, compiler, runtime
    assert "Machine" not in compiler.__all__ and "build_machine" not in compiler.__all__
    assert "plan_of" not in runtime.__all__ and "ReferenceMonitor" not in runtime.__all__
    assert "jsonable" not in audit.__all__
    assert "ReferenceMonitor" not in ethimon.__all__


#: another package's private module -> the floors allowed to reach into it, and why. A new reach is a
#: conscious change: prefer a public name (the package's __all__); add a row here only with a reason.
INTERNAL_REACHES: dict[str, tuple[set[str], str]] = {
    "language._expr": ({"compiler", "loop", "offline", "replay", "sim", "testing", "verify"},
                   "the expression AST each interpreter walks (sim: the recording's plot reads the "
                   "obligations' limits from it; loop: the names a reloaded obligation reads; replay: "
                   "which rules read R_e, NOT CHECKED under 'risk: none')"),
    "language._visit": ({"compiler", "offline", "testing", "verify"},
                    "ExprVisitor, the interpreter protocol the four back-ends implement"),
    "language._load": ({"io", "replay", "scenario"}, "the located YAML validation, for their own file formats"),
    "language._yaml": ({"io", "replay", "scenario"}, "the located YAML reader, for their own file formats"),
    "language._robots": ({"_lint", "verify"}, "robot_of: the spec's robot description, that lint and verify check "
                                             "the safe pose against (issue 34)"),
    "language._model": ({"io", "replay", "scenario", "verify"}, "field types and defaults (FiniteFloat, ACTIVE_RESPONSES, "
                                                      "MANUAL_BY_DEFAULT, the located-error helper)"),
    "compiler._plan": ({"testing", "verify"}, "RISK_NAME, the name R_e has in a plan"),
    "compiler._closures": ({"runtime"}, "the closures the monitor runs"),
    "compiler._risk_formula": ({"ethimon", "loop", "offline", "risk", "runtime", "testing", "verify"},
                               "the R_e formula, spec semantics on the compiler floor"),
    "runtime._inputs": ({"offline", "testing"}, "read inputs by the monitor's own rules"),
    "risk._average": ({"cli"}, "the CLI is the training/evaluation front end"),
    "risk._data": ({"cli"}, "the CLI is the training/evaluation front end"),
    "risk._evaluate": ({"cli"}, "the CLI is the training/evaluation front end"),
    "risk._recipe": ({"cli"}, "the CLI is the training/evaluation front end"),
    "risk._train": ({"cli"}, "the CLI is the training/evaluation front end"),
    "risk._export": ({"cli"}, "the CLI is the training/evaluation front end (ethimon export)"),
    "risk._estimator": ({"cli", "_lint"}, "the shipped model's tau pair (DEFAULT_TAU_CONFIRM, model_tau_warnings): "
                                         "ethimon risk's tiers without --spec, ethimon lint's pair warning"),
    "risk._reading": ({"cli"}, "check_length: ethimon risk's batch mode refuses an over-long line alone"),
    "sim._arm": ({"gym"}, "the Panda cell env drives the simulated arm directly"),
    "verify._policy": ({"_lint"}, "lint's release-policy warnings (no z3)"),
    "replay._record": ({"cli", "fleet"}, "one bag's record, shared by the serial loop and the Ray workers"),
    "scenario._session": ({"fleet"}, "the skipped-file rows of a check report"),
}


def test_reaches_into_other_packages_internals_are_reviewed():
    from tests.house.test_import_direction import _module_name, floor_of, imports_of
    bad = []
    for path in sorted(SRC.rglob("*.py")):
        here = floor_of(_module_name(path, SRC)[0])
        for line, target in imports_of(path, SRC):
            parts = target.split(".")
            if len(parts) < 3 or parts[1] == here or not any(p.startswith("_") for p in parts[2:]):
                continue
            key = ".".join(parts[1:3])
            allowed = INTERNAL_REACHES.get(key, (set(), ""))[0]
            if here not in allowed:
                bad.append(f"{path.relative_to(SRC.parent)}:{line}: {here} imports {target}")
    assert bad == [], "use the package's public names, or review the reach in INTERNAL_REACHES:\n" + "\n".join(bad)


def test_the_old_spec_module_serves_the_language_for_one_release():
    """``ethimon.spec`` (stage 1's name before ``ethimon.language``) imports silently and serves the same objects."""
    import warnings

    import ethimon.language
    import ethimon.spec
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        importlib.reload(ethimon.spec)  # importing it warns nothing
    assert ethimon.spec.__all__ == ethimon.language.__all__
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        assert ethimon.spec.Spec is ethimon.language.Spec and ethimon.spec.load_spec is ethimon.load_spec
        from ethimon.spec import parse_expr
    assert parse_expr is ethimon.language.parse_expr
    assert [w.category for w in caught] == [DeprecationWarning] * 3
    with pytest.raises(AttributeError):
        ethimon.spec.no_such_name  # noqa: B018
