"""PyBullet arm in the loop: a Franka Panda cell governed by an ethimon ``Monitor``.

``import ethimon.sim`` is light: PyBullet is imported only when a simulation
is built (``pip install "ethimon[sim]"``). The one obvious loop::

    import ethimon
    from ethimon.sim import ArmSim, GovernedArm

    monitor = ethimon.Monitor(ethimon.load_spec("specs/cobot_cell.yaml"))
    with ArmSim(control_hz=60) as sim:
        arm = GovernedArm(sim, monitor, inputs={"p_unsafe": 0.05})
        for _ in range(600):
            rec = arm.step()      # signals -> monitor.step -> controller, same cycle
            if rec.override:
                ...               # rec.controller is 'safe_pose' / 'stop_N' already

or run a scenario's ``sim:`` block in one call with :func:`run_sim`, and
compare it with its ``expect:`` using :func:`check_sim_expectations`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ._model import (
    PHYSICS_HZ,
    SIGNAL_NAMES,
    Dropout,
    InputChange,
    HandOver,
    Human,
    Pick,
    Place,
    Pour,
    Reach,
    SimBlock,
    SimError,
    SimExpect,
    SimObject,
    Wait,
    Waypoint,
    Wipe,
)

if TYPE_CHECKING:  # pragma: no cover
    from ._arm import HOME_JOINTS_RAD, ArmSim
    from ._runner import CycleRecord, GovernedArm, SimResult, check_sim_expectations, run_sim

__all__ = ["ArmSim", "CycleRecord", "GovernedArm", "Place", "SimBlock", "SimResult", "run_sim"]

_LAZY = {
    "ArmSim": "._arm", "HOME_JOINTS_RAD": "._arm",
    "GovernedArm": "._runner", "CycleRecord": "._runner", "SimResult": "._runner",
    "run_sim": "._runner", "check_sim_expectations": "._runner",
}


def __getattr__(name: str):
    # the modules behind these names need numpy only; PyBullet itself loads when
    # an ArmSim is built, and raises DependencyNotInstalled if it is missing
    mod = _LAZY.get(name)
    if mod is None:
        raise AttributeError(f"module 'ethimon.sim' has no attribute {name!r}")
    import importlib

    value = getattr(importlib.import_module(mod, __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(__all__)
