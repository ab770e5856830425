"""The monitor's latches, an object of their own: one per rule, what holds them, their release count
after a valid cycle, what an acknowledgement may release, and carrying latches over a reload."""

from __future__ import annotations

from ..compiler import Plan
from ..language import SEVERITY_ORDER, Response
from ._decision import Acknowledgement


class Latches:
    """One latch per rule in preallocated slots, owned here (a part of :class:`~ethimon.runtime.Monitor`).

    The rules in order: the obligations, then ``risk``, ``fault``, ``judge``, ``confirm`` and
    ``pending`` (the last three never latch unless the spec sets ``risk.judge``,
    ``risk.confirm_threshold`` or the loop passes ``pending_s``). ``lat[k]``: the rule's severity
    while latched, else 0; ``run[k]``: consecutive cycles its release condition has held (-1: it
    fired this cycle); ``since[k]``: the cycle it latched at; ``n``: how many are latched.
    ``Monitor.step`` binds the lists to locals and latches in place (the hot path).
    """

    __slots__ = ("lat", "run", "since", "n", "sevs", "holds", "manual", "names",
                 "ri", "fi", "ji", "ci", "pi", "nsrc", "risk_sev", "fault_sev")

    def __init__(self, plan: Plan) -> None:
        n = len(plan.obligations)
        self.ri, self.fi, self.ji, self.ci, self.pi, self.nsrc = n, n + 1, n + 2, n + 3, n + 4, n + 5
        self.names = tuple(ob.id for ob in plan.obligations) + ("risk", "fault", "judge", "confirm", "pending")
        # the confirm latch is released automatically once the band no longer holds the text (the
        # judge said safe, R_e left the band) or at once by acknowledge(): the confirmation itself;
        # the pending hold (stop 2: an input awaited after the start or a new task text, see
        # Monitor.step's ``pending_s``) releases by itself on the first cycle with every input usable
        rules = plan.rules()  # obligations, risk, fault, judge, confirm: the order above
        self.holds = tuple(rule.hold for rule in rules) + (1,)
        self.manual = tuple(rule.manual for rule in rules) + (False,)
        self.sevs = tuple(rule.severity for rule in rules) + (Response.STOP_2.severity,)
        self.risk_sev = plan.risk_rule.severity
        self.fault_sev = plan.fault_rule.severity
        self.since = [0] * (n + 5)
        self.lat = [0] * (n + 5)
        self.run = [0] * (n + 5)
        self.n = 0

    def rules(self) -> tuple[str, ...]:
        """The names of the rules latched now."""
        return tuple(name for name, s in zip(self.names, self.lat) if s)

    def holding(self) -> tuple[dict, ...]:
        """What holds the override now, the most severe first (see :meth:`Monitor.holding`)."""
        if not self.n:
            return ()
        lat, run, holds, manual, names, since = self.lat, self.run, self.holds, self.manual, self.names, self.since
        out = []
        for k in range(self.nsrc):
            s = lat[k]
            if not s:
                continue
            n, c = holds[k], max(run[k], 0)
            if k == self.pi:
                how, text = "estimate", ("by itself on the first cycle with every awaited input usable (the task "
                                         "text's risk estimate, a signal not seen since the start)")
            elif k == self.ci:
                how, text = "confirm", ("an acknowledgement confirms the text in the band; or by itself once the "
                                        "band no longer holds it (the judge said safe, R_e left the band)")
            elif manual[k]:
                how, text = "acknowledge", (f"an acknowledgement once its condition has held {n} cycles in a row "
                                            f"({c} of {n} now)")
            else:
                how, text = "auto", f"by itself after {n} clean cycles in a row ({c} of {n} now)"
            out.append({"rule": names[k], "response": SEVERITY_ORDER[s].value, "since_cycle": since[k],
                        "release": how, "hold_cycles": n, "held_cycles": c,
                        "acknowledge": bool(manual[k]) or k == self.ci, "how": text, "_sev": s})
        out.sort(key=lambda h: -h["_sev"])
        for h in out:
            del h["_sev"]
        return tuple(out)

    def carry(self, rules, cycle: int, spec_name: str) -> None:
        """Latch ``rules`` (by name) at ``cycle``, each release count at 0 (see :meth:`Monitor.carry_latches`).

        Raises:
            ValueError: a name that is no rule here (nothing is latched then).
        """
        idx = {n: k for k, n in enumerate(self.names)}
        missing = [n for n in rules if n not in idx]
        if missing:
            raise ValueError(f"no rule {', '.join(map(repr, missing))} in spec {spec_name!r}")
        for n in rules:
            k = idx[n]
            self.latch(k, cycle)
            self.run[k] = 0

    def latch(self, k: int, cycle: int) -> None:
        """Latch rule ``k`` with its own response, unless it is latched already (then its cycle stays)."""
        if not self.lat[k]:
            self.lat[k] = self.sevs[k]
            self.since[k] = cycle
            self.n += 1

    def clear(self) -> None:
        """Release every latch, counts at 0."""
        for k in range(self.nsrc):
            self.lat[k] = 0
            self.run[k] = 0
        self.n = 0

    def latch_fault(self, k: int | None, cycle: int) -> int:
        """Latch the fault rule (or rule ``k``: the pending hold) at ``cycle``; every release count restarts
        (the cycle is not a clean one). Returns the most severe latched response."""
        lat, run = self.lat, self.run
        fi = self.fi if k is None else k
        if not lat[fi]:
            lat[fi] = self.fault_sev if k is None else self.sevs[k]
            self.since[fi] = cycle
            self.n += 1
        sev = 0
        for k in range(self.nsrc):
            run[k] = 0
            if lat[k] > sev:
                sev = lat[k]
        return sev

    def refusal(self) -> Acknowledgement | None:
        """The refused acknowledgement while a manual rule has not met its release condition, else ``None``."""
        lat, run, holds, manual, names = self.lat, self.run, self.holds, self.manual, self.names
        waiting = [k for k in range(self.nsrc) if lat[k] and manual[k] and run[k] < holds[k]]
        if not waiting:
            return None
        return Acknowledgement(False, tuple(names[k] for k in waiting), "refused: " + "; ".join(
            f"{names[k]} still fails" if run[k] <= 0 else
            f"{names[k]} has held {run[k]} of {holds[k]} cycles" for k in waiting))

    def ready(self) -> list[int]:
        """The manual rules an acknowledgement releases now (each met its release condition)."""
        lat, run, holds, manual = self.lat, self.run, self.holds, self.manual
        return [k for k in range(self.nsrc) if lat[k] and manual[k] and run[k] >= holds[k]]

    def unlatch(self, ks: list[int]) -> None:
        """Release the latched rules ``ks`` (an acknowledgement's)."""
        for k in ks:
            self.lat[k] = 0
            self.run[k] = 0
        self.n -= len(ks)

    def release_pass(self, below: bool) -> tuple[int, bool]:
        """After a valid cycle: count each latched rule's release condition, release the
        automatic ones whose count reached their hold. O(rules), only while latched.

        ``below``: R_e is below the release cut τ − δ (or the confirm latch holds the text).

        Returns:
            ``(severity still latched, awaiting_release)``.
        """
        lat, run, holds, manual = self.lat, self.run, self.holds, self.manual
        ri, ci = self.ri, self.ci
        sev = 0
        n_manual = ready = 0
        for k in range(self.nsrc):
            s = lat[k]
            if not s:
                continue
            c = run[k]
            if c < 0 or (k == ri and not below):  # fired this cycle, or R_e not below τ − δ
                c = 0
            else:
                c += 1
                if c >= holds[k]:
                    if not manual[k]:
                        lat[k] = 0
                        run[k] = 0
                        self.n -= 1
                        continue
                    c = holds[k]  # a manual count stops at its hold: ready for acknowledge()
            run[k] = c
            if s > sev:
                sev = s
            if manual[k]:
                n_manual += 1
                if c >= holds[k]:
                    ready += 1
            elif k == ci:  # auto-released once the band stops holding; acknowledge() releases it at once
                n_manual += 1
                ready += 1
        return sev, n_manual > 0 and ready == n_manual
