"""The default shield inputs for ``ethimon/PandaCell-v0`` and the spec that reads them."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from .._api import load_spec
from ..language import Spec

__all__ = ["panda_signals", "panda_spec", "PANDA_SPEC_PATH"]

#: The default shield spec for the Panda cell (speed and separation, speed caps, contact).
PANDA_SPEC_PATH = Path(__file__).with_name("panda_shield.yaml")

_RATED = np.array((2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61))


def panda_signals(obs: Any, info: dict[str, Any], action: Any) -> dict[str, float]:
    """Monitor inputs for one ``PandaCell-v0`` step, judged before the action runs.

    From the ``info`` of the previous ``reset``/``step`` (measured on the state the
    action will act on) and the proposed ``action`` (joint velocity targets, clipped
    to the rated limits as the env clips them):

    * ``human_distance`` (m): measured, closest arm link to any human.
    * ``ee_speed`` (m/s): the larger of the measured end-effector speed and the
      commanded one, ``‖J(q) · a‖`` (``info["ee_jacobian"]``).
    * ``joint_speed_max`` (rad/s): the larger of the measured ``max |q̇|`` and the
      commanded ``max |a|``.
    * ``contact_force`` (N): measured.

    A NaN in the action stays NaN in the signals (the monitor faults on it); a
    missing ``info`` key raises, which the wrapper turns into a fault.
    """
    a = np.clip(np.asarray(action, dtype=np.float64).reshape(7), -_RATED, _RATED)  # NaN stays NaN
    jac = np.asarray(info["ee_jacobian"], dtype=np.float64)
    commanded_ee = float(np.linalg.norm(jac @ a))
    commanded_joint = float(np.max(np.abs(a)))
    return {
        "human_distance": float(info["human_distance"]),
        "ee_speed": float(np.maximum(float(info["ee_speed"]), commanded_ee)),  # np.maximum keeps NaN
        "joint_speed_max": float(np.maximum(float(info["joint_speed_max"]), commanded_joint)),
        "contact_force": float(info["contact_force"]),
    }


def panda_spec() -> Spec:
    """The default shield spec for the Panda cell (:data:`PANDA_SPEC_PATH`), loaded and compiled."""
    return load_spec(PANDA_SPEC_PATH)
