"""ethimon: a formal-spec-checked runtime safety monitor for robot manipulation.

The one loop::

    spec = ethimon.load_spec("specs/governor.yaml")
    monitor = ethimon.Monitor(spec)
    decision = monitor.step({"risk": 0.62, "human_distance": 0.4, "ee_speed": 0.1})
    if decision.override:
        ...  # drive to spec.safe_pose now

Many files at once: ``ethimon.run(units, executor=ethimon.Serial() | ethimon.Ray(...), on_progress)``.

``import ethimon`` never imports torch, pybullet or ray.
"""

from __future__ import annotations

from ._api import load_spec, load_spec_text
from ._batch import Outcome, Report, Serial, Unit, run
from .errors import DependencyNotInstalled, EthimonError, ModelError, SpecError
from .compiler._risk_formula import risk_from_p_unsafe, risk_from_probs
from .runtime import Decision, Fault, Monitor
from .language import Response, Spec

__version__ = "0.1.0"

__all__ = ["Decision", "DependencyNotInstalled", "EthimonError", "Fault", "GovernedLoop", "ModelError",
           "Monitor", "Outcome", "ProcessEstimator", "Ray", "Report", "Response", "Serial", "Spec",
           "SpecError", "Unit", "__version__", "load_spec", "load_spec_text", "run"]

#: names served on first use: from :mod:`ethimon.loop` (it starts threads and pulls in the audit log) and
#: the Ray executor of :func:`run` from :mod:`ethimon.fleet` (Ray itself is imported when a run starts)
_LAZY = {"AsyncRiskSource": "loop", "GovernedLoop": "loop", "ProcessEstimator": "loop", "Ray": "fleet"}


def __getattr__(name: str):
    if name in _LAZY:
        import importlib
        value = getattr(importlib.import_module(f"{__name__}.{_LAZY[name]}"), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
