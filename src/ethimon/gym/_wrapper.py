"""``MonitorWrapper``: an ethimon ``Monitor`` as a shield around any ``gymnasium.Env``.

Order within one ``step(action)`` (the monitor judges the action *before* it
reaches the environment)::

    s = signals(obs, info, action)     # obs, info: from the previous reset()/step()
    d = monitor.step({**inputs, **s})  # one monitor cycle per env step
    if d.override:                     # violation, fault or latch
        "replace":   action := safe_action(obs)   (then env.step(action))
        "terminate": the env is NOT stepped; the episode ends (terminated=True)
    obs, reward, terminated, truncated, info = env.step(action)

So an override replaces the action of *this* step: the proposed action never
reaches the environment. The proposed action is read once, into a copy of the
action space's type (``_convert``); ``signals`` gets a copy of it and the env that
very value, so the env never reads the caller's object a second time (an action
that cannot be read is a fault: override). Signals therefore describe the current state plus
what the proposed action would do (e.g. the commanded joint speed).
"""

from __future__ import annotations

import copy
import inspect
import os
from collections.abc import Callable, Mapping
from typing import Any

import gymnasium
import numpy as np

from .._api import load_spec
from ..runtime import Decision, Fault, Monitor
from ..language import Spec

__all__ = ["MonitorWrapper"]

_MODES = ("replace", "terminate")


def _arity(fn: Callable, what: str, choices: tuple[int, ...]) -> int:
    """How many positional arguments ``fn`` takes among ``choices`` (largest that fits)."""
    try:
        sig = inspect.signature(fn)
    except (TypeError, ValueError):  # a builtin without a signature: pass the fewest
        return min(choices)
    for n in sorted(choices, reverse=True):
        try:
            sig.bind(*range(n))
            return n
        except TypeError:
            continue
    names = " or ".join(f"{n} positional arguments" for n in choices)
    raise TypeError(f"{what} must take {names}; {fn!r} has signature {sig}")


class MonitorWrapper(gymnasium.Wrapper):
    """Shield a Gymnasium environment with an ethimon monitor.

    Args:
        env: any ``gymnasium.Env``.
        spec: a :class:`~ethimon.Spec`, a spec file path, or a ready :class:`~ethimon.Monitor`.
        signals: ``signals(obs, info, action) -> Mapping`` (or ``signals(obs, info)``):
            the monitor's inputs for this cycle, from the observation and info of the
            *previous* ``reset``/``step`` (the state the action would act on) and the
            proposed action.
        safe_action: the action executed instead on an override: a fixed action (it
            must lie in ``env.action_space``), or ``safe_action(obs)`` /
            ``safe_action(obs, decision)`` returning one.
        on_override: ``"replace"`` (default): execute the safe action instead;
            ``"terminate"``: do not step the env and end the episode.
        inputs: constant inputs added every cycle under the signals (the signals win
            on a shared name), e.g. ``{"p_unsafe": 0.0}``: every spec has the risk rule,
            which needs a risk input (``risk``, ``p_unsafe`` or ``p``) each cycle; a
            task without a language instruction has to state one. Nothing is assumed:
            without it every cycle is a ``missing`` fault and overrides.

    Each ``step`` adds to ``info``:

    * ``decision``: ``Decision.as_dict()`` of this step's monitor cycle.
    * ``cost``: ``1.0`` when that decision overrides (a violated obligation, a
      fault, or a latched override), else ``0.0``: the Safety-Gymnasium
      convention of a per-step cost signal (``Σ cost`` per episode is the number
      of shielded steps). An ``info["cost"]`` from the environment itself is
      kept as ``info["env_cost"]``.
    * ``shield``: ``{"replaced": bool, "terminated": bool, "action": the action
      executed (None when the env was not stepped), "signals": the inputs given
      to the monitor}``.

    ``on_override="terminate"``: the step returns the *current* observation,
    reward ``0.0``, ``terminated=True``, ``truncated=False`` (the unsafe action
    is treated as reaching an absorbing failure state, not a time limit) and
    ``info`` with the keys above (the env's own info of the previous step
    otherwise). A safe action that cannot be computed (its callable raises or
    returns something outside the action space) ends the episode the same way.

    Faults fail closed: a ``signals`` callable that raises or returns a
    non-mapping is a monitor fault (``Fault("external", ..., "signals")``); NaN,
    missing or out-of-range values are faults of the monitor itself. Either way
    the step overrides. Exceptions leave ``step`` only from the env itself.

    ``reset()`` resets the monitor (cycle 0, no latch, empty temporal history).

    Example:
        >>> env = MonitorWrapper(gymnasium.make("ethimon/PandaCell-v0"), panda_spec(),  # doctest: +SKIP
        ...                      signals=panda_signals, safe_action=np.zeros(7, np.float32),
        ...                      inputs={"p_unsafe": 0.0})
    """

    def __init__(self, env: gymnasium.Env, spec: Spec | str | os.PathLike | Monitor, *,
                 signals: Callable[..., Mapping[str, Any]],
                 safe_action: Any,
                 on_override: str = "replace",
                 inputs: Mapping[str, Any] | None = None) -> None:
        super().__init__(env)
        if isinstance(spec, Monitor):
            self.monitor = spec
        elif isinstance(spec, Spec):
            self.monitor = Monitor(spec)
        elif isinstance(spec, (str, os.PathLike)):
            self.monitor = Monitor(load_spec(spec))
        else:
            raise TypeError(f"spec must be an ethimon Spec, a spec file path or a Monitor, got {type(spec).__name__}")
        if on_override not in _MODES:
            raise ValueError(f"on_override={on_override!r}; use 'replace' or 'terminate'")
        self.on_override = on_override
        if not callable(signals):
            raise TypeError(f"signals must be callable(obs, info[, action]) -> dict, got {type(signals).__name__}")
        self._signals = signals
        self._signals_n = _arity(signals, "signals", (2, 3))
        if callable(safe_action):
            self._safe_fn = safe_action
            self._safe_n = _arity(safe_action, "safe_action", (1, 2))
            self._safe_fixed = None
        else:
            fixed = self._as_action(safe_action)
            if fixed is None:
                raise ValueError(f"safe_action {safe_action!r} is not in the action space {env.action_space}")
            self._safe_fn = None
            self._safe_n = 0
            self._safe_fixed = fixed
        self.inputs = dict(inputs or {})
        self._obs: Any = None
        self._info: dict[str, Any] = {}

    # ------------------------------------------------------------ helpers

    def _as_action(self, a: Any) -> Any:
        """``a`` as an element of the action space, or ``None`` when it is not one."""
        space = self.env.action_space
        try:
            if isinstance(space, gymnasium.spaces.Box):
                arr = np.asarray(a, dtype=space.dtype)
                if arr.shape != space.shape:
                    arr = arr.reshape(space.shape)
                a = arr
            return a if space.contains(a) else None
        except Exception:
            return None

    def _convert(self, action: Any) -> tuple[Any, str | None]:
        """``action`` read exactly once into the copy the env will get: ``(copy, None)`` or ``(None, why)``.

        A ``Box``/``MultiDiscrete``/``MultiBinary`` action becomes a fresh array of the space's dtype and
        shape (bounds are not enforced: an env clips as it always did), a ``Discrete`` one a numpy integer,
        anything else a deep copy. So an action object that reads differently the second time (a
        lazy array, a view another thread writes, a ``__array__`` that changes) cannot show the
        shield one action and the env another.
        """
        space = self.env.action_space
        try:
            if isinstance(space, (gymnasium.spaces.Box, gymnasium.spaces.MultiDiscrete,
                                  gymnasium.spaces.MultiBinary)):
                arr = np.array(action, dtype=space.dtype, copy=True)
                if arr.shape != space.shape:
                    arr = arr.reshape(space.shape)
                return arr, None
            if isinstance(space, gymnasium.spaces.Discrete):
                a = np.asarray(action)
                if a.shape != () or a.dtype.kind not in "iub" and not (a.dtype.kind == "f" and float(a) == int(a)):
                    raise TypeError(f"expected one integer, got {a.dtype} of shape {a.shape}")
                return space.dtype.type(int(a)), None
            return copy.deepcopy(action), None
        except Exception as exc:  # noqa: BLE001 - an action that cannot be read is a fault, never passed on
            return None, f"action {type(action).__name__} cannot be read as an action of {space}: " \
                         f"{type(exc).__name__}: {exc}"[:300]

    @staticmethod
    def _fresh(a: Any) -> Any:
        return a.copy() if isinstance(a, np.ndarray) else a

    def _judge(self, action: Any) -> tuple[Decision, dict[str, Any]]:
        obs, info = self._obs, self._info
        try:
            got = (self._signals(obs, info, action) if self._signals_n == 3 else self._signals(obs, info))
            if not isinstance(got, Mapping):
                raise TypeError(f"returned {type(got).__name__}, not a mapping of signal names to values")
            sig = dict(self.inputs)
            sig.update(got)
        except Exception as exc:
            return self.monitor.fault(Fault("external", f"signals callable failed: {type(exc).__name__}: {exc}",
                                            "signals")), dict(self.inputs)
        return self.monitor.step(sig), sig

    def _safe(self, decision: Decision) -> tuple[Any, str | None]:
        if self._safe_fn is None:  # a fresh copy: an env that writes into its action cannot change it
            fixed = self._safe_fixed
            return (fixed.copy() if isinstance(fixed, np.ndarray) else fixed), None
        try:
            a = self._safe_fn(self._obs, decision) if self._safe_n == 2 else self._safe_fn(self._obs)
        except Exception as exc:
            return None, f"safe_action callable failed: {type(exc).__name__}: {exc}"
        ok = self._as_action(a)
        if ok is None:
            return None, f"safe_action returned {a!r}, not in the action space {self.env.action_space}"
        return ok, None

    @staticmethod
    def _cost(decision: Decision) -> float:
        return 1.0 if decision.override or decision.violations else 0.0

    def _annotate(self, info: dict[str, Any], decision: Decision, sig: dict[str, Any], replaced: bool,
                  terminated: bool, action: Any) -> dict[str, Any]:
        info = dict(info)
        if "cost" in info:
            info["env_cost"] = info["cost"]
        info["decision"] = decision.as_dict()
        info["cost"] = self._cost(decision)
        info["shield"] = {"replaced": replaced, "terminated": terminated, "action": action,
                          "signals": {k: (float(v) if isinstance(v, (float, np.floating)) else v)
                                      for k, v in sig.items()}}
        return info

    # ------------------------------------------------------------ gymnasium API

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        self.monitor.reset()
        obs, info = self.env.reset(seed=seed, options=options)
        self._obs, self._info = obs, info
        return obs, info

    def step(self, action):
        if self._obs is None:
            raise gymnasium.error.ResetNeeded("call reset() before step()")
        action, why = self._convert(action)  # read once; the shield and the env see this one value
        if why is not None:
            decision, sig = self.monitor.fault(Fault("external", why, "action")), dict(self.inputs)
        else:
            decision, sig = self._judge(self._fresh(action))  # a copy: signals() cannot edit what the env gets
        if not decision.override:
            obs, reward, terminated, truncated, info = self.env.step(action)
            self._obs, self._info = obs, info
            return obs, reward, terminated, truncated, self._annotate(info, decision, sig, False, False, action)
        if self.on_override == "replace":
            safe, why = self._safe(decision)
            if why is None:
                obs, reward, terminated, truncated, info = self.env.step(safe)
                self._obs, self._info = obs, info
                return obs, reward, terminated, truncated, self._annotate(info, decision, sig, True, False, safe)
            decision = self.monitor.fault(Fault("external", why, "safe_action"), decision=decision)
        # terminate: the proposed action never reaches the env; the episode ends here
        info = self._annotate(self._info, decision, sig, False, True, None)
        return self._obs, 0.0, True, False, info

    def __repr__(self) -> str:
        return f"<MonitorWrapper{self.env} spec={self.monitor.spec.name!r} on_override={self.on_override!r}>"

