"""Gymnasium: shield an RL policy with an ethimon monitor, and the Panda cell as an env.

``pip install "ethimon[gym]"`` (Gymnasium; the Panda env also needs ``ethimon[sim]``).
``import ethimon`` never imports this package; ``import ethimon.gym`` imports
Gymnasium and registers ``ethimon/PandaCell-v0`` (PyBullet loads only when the
env is built)::

    import gymnasium, numpy as np
    from ethimon.gym import MonitorWrapper, panda_signals, panda_spec

    env = MonitorWrapper(gymnasium.make("ethimon/PandaCell-v0"), panda_spec(),
                         signals=panda_signals, safe_action=np.zeros(7, np.float32),
                         inputs={"p_unsafe": 0.0})
    obs, info = env.reset(seed=0)
    obs, reward, terminated, truncated, info = env.step(env.action_space.sample())
    info["cost"], info["decision"]["override"], info["shield"]["replaced"]

Without importing this package first: ``gymnasium.make("ethimon.gym:ethimon/PandaCell-v0")``.
"""

from __future__ import annotations

from ..errors import DependencyNotInstalled

try:
    import gymnasium
except ImportError as exc:  # pragma: no cover - depends on the environment
    raise DependencyNotInstalled('ethimon.gym needs Gymnasium: pip install "ethimon[gym]"') from exc

from ._panda import PANDA_RATED_JOINT_SPEED_RAD_S, PandaCellEnv
from ._signals import PANDA_SPEC_PATH, panda_signals, panda_spec
from ._wrapper import MonitorWrapper

__all__ = ["MonitorWrapper", "PANDA_ENV_ID", "PandaCellEnv", "panda_signals", "panda_spec"]

#: The registered id of :class:`PandaCellEnv` (200 steps = 10 s at 20 Hz per episode).
PANDA_ENV_ID = "ethimon/PandaCell-v0"

if PANDA_ENV_ID not in gymnasium.registry:
    gymnasium.register(id=PANDA_ENV_ID, entry_point="ethimon.gym._panda:PandaCellEnv", max_episode_steps=200)
