"""Building a :class:`~ethimon.runtime.Monitor`: the compiled machine, signal slots, the one-call
tuples, one latch per rule, the tiers, the risk formula's weights and the age limit of the estimate."""

from __future__ import annotations

import math
import re

from ..compiler import Plan, stateless_slots
from ..compiler._closures import build_machine  # the compiler's closures: runtime is their one caller
from ..compiler._risk_formula import risk_range
from ..language import Response
from ._calls import _all_margins, _tuple_of_calls
from ._fault import Fault


_READS_RISK = re.compile(r"\brisk\b")


class _Construction:
    """The monitor's construction and its age limit (a base of :class:`~ethimon.runtime.Monitor`)."""

    __slots__ = ()

    def _build(self, plan: Plan, margins: bool, max_age_s: float | None) -> None:
        """Resolve everything ``step`` reads, once: ``plan`` is compiled already."""
        self.plan = plan
        self.spec = plan.spec
        m = build_machine(plan)
        self._m = m
        self._vals = m.vals
        self._sig = tuple((s.name, s.slot, s.kind == "bool", s.lo, s.hi,
                           Fault("missing", f"signal {s.name!r} is missing", s.name))  # built once, not per cycle
                          for s in plan.signals)
        # the fast reading: (index, name, slot, is_bool, lo, hi); the first input that is not a
        # built-in float in range (or a bool) hands over to _read_rest, which judges it as before
        self._fsig = tuple((k, s.name, s.slot, s.kind == "bool", s.lo, s.hi) for k, s in enumerate(plan.signals))
        self._rslot = plan.risk_slot
        # one call each per cycle: every temporal update (inner operators first), then every
        # obligation's verdict (all of them, in order: bounded responses keep state), as one tuple
        self._ucall = m.updates[0] if len(m.updates) == 1 else _tuple_of_calls(m.updates)
        self._vcall = _tuple_of_calls(m.violated)
        self._obs = tuple((fn, ob.id, ob.response.severity, i)
                          for i, (fn, ob) in enumerate(zip(m.violated, plan.obligations)))
        self._stateless = tuple((fn, ob.id, ob.response.severity, slots, i)
                                for i, (fn, ob) in enumerate(zip(m.violated, plan.obligations))
                                if (slots := stateless_slots(plan, ob)) is not None)
        self.obligation_ids: tuple[str, ...] = tuple(ob.id for ob in plan.obligations)
        self._margins_on = margins
        self._margin_fns = m.margins
        # every margin once per cycle: unguarded in one tuple when none can raise (chosen at compile
        # time: no division, sqrt or separation_distance), else each guarded (NaN where one raises)
        self._mcall = _tuple_of_calls(m.margins) if not m.margins_raise else (
            lambda fns=m.margins: _all_margins(fns))
        self._nan_margins = tuple(math.nan for _ in plan.obligations)
        r = plan.risk
        # τ, the release cut and every rule's release: resolved once in the plan
        self._tau = plan.threshold
        self._risk_sev = plan.risk_rule.severity
        self._fault_sev = plan.fault_rule.severity
        self._release_cut = plan.release_cut  # exact: 0.27 - 0.05 is 0.22
        # one latch per rule, in preallocated slots: the obligations in order, then the risk
        # rule, the fault latch, the judge's unsafe verdict and the confirm band (the last two
        # never latch unless the spec sets risk.judge / risk.confirm_threshold).
        # _lat[k]: the rule's severity while latched, else 0;
        # _run[k]: consecutive cycles its release condition has held (-1: it fired this cycle)
        n = len(plan.obligations)
        # ... and the pending hold (stop 2: an input awaited after the start or a new task text, see
        # Monitor.step's ``pending_s``), released by itself on the first cycle with every input usable
        self._ri, self._fi, self._ji, self._ci, self._pi, self._nsrc = n, n + 1, n + 2, n + 3, n + 4, n + 5
        self._names = tuple(ob.id for ob in plan.obligations) + ("risk", "fault", "judge", "confirm", "pending")
        # the confirm latch is released automatically once the band no longer holds the text (the
        # judge said safe, R_e left the band) or at once by acknowledge(): the confirmation itself
        rules = plan.rules()  # obligations, risk, fault, judge, confirm: the order above
        self._holds = tuple(rule.hold for rule in rules) + (1,)
        self._manual = tuple(rule.manual for rule in rules) + (False,)
        self._sevs = tuple(rule.severity for rule in rules) + (Response.STOP_2.severity,)
        self._since = [0] * (n + 5)  # the cycle at which each latch was set
        self._lat = [0] * (n + 5)
        self._run = [0] * (n + 5)
        # a pending cycle with every signal usable keeps the temporal history when no obligation reads R_e
        # (the word ``risk`` in no condition; a false positive only takes the fault path's evaluation)
        self._risk_free = not any(_READS_RISK.search(t) for ob in plan.obligations
                                  for t in (ob.when_text or "", ob.require_text))
        self._hist0 = 0  # the cycle from which the temporal history runs (set by a reset)
        # the tiers (risk.confirm_threshold, risk.judge): off for specs without them
        self._tc = None if r.confirm_threshold is None else float(r.confirm_threshold)
        cuts = r.judge_cuts()  # risk.judge, or risk.judges (their consensus is the judge input)
        self._judge_on = cuts is not None
        self._jsafe, self._junsafe = (float(cuts[0]), float(cuts[1])) if cuts is not None else (-1.0, 2.0)
        # risk.judge_may_hold_above_tau: a safe verdict turns tau <= R_e < ceiling into a confirm hold
        hold = r.judge_may_hold_above_tau
        self._hold_hi = float(hold.ceiling) if (hold is not None and self._judge_on) else None
        self._tiers = self._judge_on or self._tc is not None
        self._confirmed = False  # acknowledge() confirmed the text in the band (bound to _ctask)
        self._ctask = None
        self._last_task = None
        self._nlat = 0
        self._alpha, self._beta, self._gamma = float(r.alpha), float(r.beta), float(r.gamma)
        self._sample = r.variance == "sample"
        self._k = int(r.classes)
        self._p2 = self._k == 2
        self._uidx = int(r.unsafe_index)
        lo, hi = risk_range(r.alpha, r.beta, r.gamma, r.variance, r.classes)  # exact, any K
        self._rlo, self._rhi = min(0.0, lo), max(1.0, hi)
        self._max_age = None
        self._age_missing = None
        self.set_max_age(max_age_s)
        self._cycle = 0

    def set_max_age(self, fallback: float | None) -> None:
        """Set the one age limit of the risk input: the spec's ``risk.max_age_s`` if it sets one, else
        ``fallback`` seconds (``None``: no limit, ``risk_age_s`` is not required).

        The constructor's ``max_age_s`` goes through here; :class:`~ethimon.loop.GovernedLoop` calls it with
        its ``max_risk_age_s`` when it feeds the monitor from a risk source and neither the spec nor the
        monitor set a limit. With a limit, a cycle without ``risk_age_s`` or with an older estimate is a fault.

        Raises:
            ValueError: ``fallback`` is not a positive, finite number of seconds or ``None``.
        """
        spec_age = self.plan.risk.max_age_s
        if spec_age is not None:
            self._max_age, why = float(spec_age), "the spec sets risk.max_age_s"
        elif fallback is not None:
            if not (isinstance(fallback, (int, float)) and not isinstance(fallback, bool) and fallback > 0
                    and math.isfinite(fallback)):
                raise ValueError(f"max_age_s={fallback!r}; expected a positive number of seconds or None")
            self._max_age, why = float(fallback), "an estimate age limit is set"
        else:
            self._max_age, why = None, ""
        self._age_missing = Fault("missing", f"risk_age_s is missing ({why})", "risk_age_s") if why else None

    @property
    def max_age_s(self) -> float | None:
        """The age limit in force for risk estimates (the spec's ``risk.max_age_s`` first), or ``None``."""
        return self._max_age
