"""The tiers below τ, an object of their own: the judge's verdict and the confirm band
(``risk.judge``, ``risk.confirm_threshold``, ``risk.judge_may_hold_above_tau``) and the operator's
confirmation of one task text."""

from __future__ import annotations

from typing import Any

from ..compiler import Plan
from ._fault import Fault


class Tiers:
    """The judge and confirm-band cuts and the confirmation state (a part of :class:`~ethimon.runtime.Monitor`).

    Off (``on`` false) for specs without a judge or a confirm band: ``Monitor.step`` then never calls
    :meth:`tier`. ``ji`` and ``ci`` are the latch indices of the ``judge`` and ``confirm`` rules.
    """

    __slots__ = ("on", "judge_on", "tc", "tau", "jsafe", "junsafe", "hold_hi", "ji", "ci",
                 "confirmed", "ctask", "last_task")

    def __init__(self, plan: Plan, ji: int, ci: int) -> None:
        t = plan.tiers  # resolved once by the compiler (compiler.Tiers)
        self.tau = plan.threshold
        self.ji, self.ci = ji, ci
        self.tc = None if t.confirm_threshold is None else float(t.confirm_threshold)
        cuts = t.judge_cuts  # risk.judge, or risk.judges (their consensus is the judge input)
        self.judge_on = cuts is not None
        self.jsafe, self.junsafe = (float(cuts[0]), float(cuts[1])) if cuts is not None else (-1.0, 2.0)
        # risk.judge_may_hold_above_tau: a safe verdict turns tau <= R_e < ceiling into a confirm hold
        self.hold_hi = float(t.hold_ceiling) if (t.hold_ceiling is not None and self.judge_on) else None
        self.on = self.judge_on or self.tc is not None
        self.confirmed = False  # acknowledge() confirmed the text in the band (bound to ctask)
        self.ctask = None
        self.last_task = None

    @staticmethod
    def judge_fault(jin: Any) -> Fault:
        """The fault of a judge input that is not a p_unsafe in [0, 1] (``None`` is no judgement, no fault)."""
        return Fault("invalid", f"judge input {jin!r} is not a p_unsafe in [0, 1] (null: no judgement)", "judge")

    def tier(self, r: float, jp: float | None, get) -> tuple[str, int] | None:
        """The judge tier and the confirm band on a valid cycle (R_e = ``r``, judge p_unsafe ``jp``).

        An unsafe verdict (``jp >= unsafe_from``) fires ``"judge"`` at any R_e: below τ the judge can
        only raise the risk. In the band [τ_confirm, τ) only a safe verdict (``jp < safe_below``)
        or an operator's confirmation of this task (``acknowledge()``, bound to ``task_id``) lets the arm
        execute; anything else (unsure, no judgement) fires ``"confirm"`` (stop 2). R_e ≥ τ is the
        risk rule's, whatever the judge says, except with ``risk.judge_may_hold_above_tau``: there a safe
        verdict at τ ≤ R_e < ceiling fires ``"confirm"`` instead (a person releases it, never the judge).
        """
        tc = self.tc
        hi = self.hold_hi
        if tc is not None or hi is not None:  # first, on every cycle (the judge's too): the text this cycle is about
            task = get("task_id")
            lo = tc if tc is not None else self.tau
            if self.confirmed and (task != self.ctask or not lo <= r < (hi if hi is not None else self.tau)):
                self.confirmed = False  # a confirmation is for one text while it stays in the band
            self.last_task = task
        if jp is not None and jp >= self.junsafe:
            return "judge", self.ji
        if r >= self.tau:  # the risk rule's, unless held (risk.judge_may_hold_above_tau, a safe verdict)
            held = hi is not None and r < hi and jp is not None and jp < self.jsafe  # as in Monitor.step()
            return ("confirm", self.ci) if held and not self.confirmed else None
        if tc is None:
            return None
        if tc <= r < self.tau and not self.confirmed and not (jp is not None and jp < self.jsafe):
            return "confirm", self.ci
        return None

    def end(self) -> None:
        """End a confirmation (a fault, a reset, a release, a pending cycle): the next band cycle asks again."""
        self.confirmed = False

    def refusal(self, task_id: Any, any_task: object) -> str | None:
        """Why an acknowledgement may not confirm the text in the band now, or ``None`` (``task_id`` is
        ``any_task`` when the operator named none: the last cycle's text)."""
        if task_id is not any_task and task_id != self.last_task:
            return ("refused: confirm is for the task in the band now, "
                    "not the one acknowledged (the task text changed since it was shown)")
        if self.last_task is None:  # bound to nothing, it would hold for every text in the band
            return ("refused: confirm needs the task_id of the text "
                    "in the band (none was given this cycle) to bind the confirmation to")
        return None

    def confirm(self) -> None:
        """The operator confirmed the text in the band: it executes until it changes or leaves the band."""
        self.confirmed = True
        self.ctask = self.last_task
