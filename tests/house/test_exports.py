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
    "ethimon": ["Decision", "DependencyNotInstalled", "EthimonError", "Fault", "GovernedLoop", "ModelError",
                "Monitor", "Outcome", "ProcessEstimator", "Ray", "Report", "Response", "Serial", "Spec",
                "SpecError", "Unit", "__version__", "load_spec", "load_spec_text", "run"],
    "ethimon.errors": ["AuditFormatError", "AuditTampered", "BagError", "DependencyNotInstalled", "EthimonError",
                       "ExprSyntaxError", "ModelError", "RiskInferenceError", "Ros2Error", "SimError", "SpecError"],
    "ethimon.audit": ["AuditLog", "AuditReport", "bounded", "read_log", "verify_log"],
    "ethimon.cli": ["main"],
    "ethimon.compiler": ["Plan", "compile_plan"],
    "ethimon.fleet": ["Ray", "check_paths", "plain", "replay_records"],
    "ethimon.gym": ["MonitorWrapper", "PANDA_ENV_ID", "PandaCellEnv", "panda_signals", "panda_spec"],
    "ethimon.language": ["Constant", "Obligation", "Operator", "OPERATORS", "parse_expr", "parse_spec_file", "parse_spec_text", "Release", "Response", "SafePose", "Signal", "Spec"],
    "ethimon.loop": ["AckGate", "AsyncJudgeSource", "AsyncRiskSource", "GovernedLoop", "LoopConfig", "LoopStats", "ProcessEstimator", "Reloader", "ReloadResult"],
    "ethimon.offline": ["OfflineResult", "check_trace", "iter_rows"],
    "ethimon.io": ["AckRequest", "ByName", "Channel", "Frame", "Hold", "LiveMonitor", "LiveNode", "Mapping",
                   "MemoryChannel", "Outlet", "Sample", "SignalMap", "TopicPlan", "hold", "judged", "load_mapping",
                   "load_mapping_text"],
    "ethimon.replay": ["BagReplay", "CheckResult", "Mapping", "ReplayReport", "check_columns", "list_topics",
                       "load_mapping", "replay_bag", "replay_paths", "write_mcap"],
    "ethimon.risk": ["as_estimator", "BUILTIN_JUDGE_PROMPT", "Encoder", "injection_signs", "Judge", "JudgePanel", "JudgeResult", "load_estimator", "load_estimator_for", "ProbsEstimator", "register_encoder", "risk_from_p_unsafe", "risk_from_probs", "RiskEstimator", "text_sha256"],
    "ethimon.ros2": ["DEFAULT", "MessageTypes", "Ros2Monitor", "SENSOR_DATA"],
    "ethimon.runtime": ["Acknowledgement", "Decision", "FAULT_KINDS", "Fault", "Monitor"],
    "ethimon.view": ["FoxgloveView", "TOPICS", "VerdictChannels"],
    "ethimon.scenario": ["CheckOutcome", "CheckReport", "Scenario", "ScenarioResult", "check_paths",
                         "load_scenario", "load_scenario_text", "run_scenario", "simulate_paths"],
    "ethimon.sim": ["ArmSim", "CycleRecord", "GovernedArm", "Place", "SimBlock", "SimResult", "run_sim"],
    "ethimon.testing": ["ReferenceMonitor"],
    "ethimon.verify": ["Counterexample", "Finding", "SpecReport", "verify_paths", "verify_spec"],
    "ethimon.zenoh": ["ZenohMonitor", "zenoh_config"],
}

#: the most public names the package may have in all (issue 33 item 5: the front door is what docs/ teaches):
#: the sum over every package's __all__ (a name exported by two packages counts twice)
MAX_PUBLIC_NAMES = 150

#: packages whose import needs an optional extra
_NEEDS = {"ethimon.gym": "gymnasium"}


def _packages() -> list[str]:
    return ["ethimon"] + sorted(f"ethimon.{p.name}" for p in SRC.iterdir() if (p / "__init__.py").exists())


def test_the_front_door_stays_small():
    total = sum(len(names) for names in PUBLIC.values())
    assert total <= MAX_PUBLIC_NAMES, (f"{total} public names (at most {MAX_PUBLIC_NAMES}): export what docs/ "
                                       "teaches; the rest stays importable from its package, unlisted")


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
    "replay._record": ({"cli", "fleet"}, "one bag's record and replay_records, the unit function of a replay run "
                                         "(serial or on Ray)"),
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
