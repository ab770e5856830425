"""Reference interpreter: slow, obviously correct, for cross-checking the compiler.

It keeps the whole history since the last reset or fault and evaluates every
expression by walking the AST, with the temporal operators written straight
from their definitions (look back over the history). It shares nothing with
the compiled closures except the checked :class:`Plan`. Tests and the property
suite check that it and :class:`Monitor` agree on random traces.

Semantics (the definition both implementations follow), for a history
``h[0..t]`` of valid cycles since the last reset or fault:

* ``prev(e, i)``: ``e`` at ``t-1``; at ``t = 0`` it is ``i`` at ``t`` (without
  ``i``: ``false`` for a condition, ``e`` itself for a number).
* ``held(e, n)``: ``e`` at each of ``t-n+1 .. t`` (needs ``n`` cycles of history).
* ``once(e, n)``: ``e`` at some cycle of ``max(0, t-n+1) .. t``.
* ``since(a, b[, n])``: some ``j`` (with ``t - j < n``) has ``b`` at ``j`` and ``a``
  at every cycle of ``j+1 .. t``.
* ``separation_distance(v_h, v_r, T_r, T_s, S_s, C, Z_d, Z_r)``: every argument is
  evaluated; if one is not ``>= 0`` (negative or NaN) the evaluation raises (a
  fault, like ``sqrt`` of a negative); else
  ``v_h*(T_r + T_s) + v_r*T_r + S_s + C + Z_d + Z_r``, summed left to right.
* Every temporal operator's arguments are evaluated at every cycle (so an
  error such as a division by zero inside one is a fault even if a
  surrounding ``and`` would short-circuit).
* An obligation ``when ⇒ require`` without ``within_cycles`` (or 0) is violated
  at ``t`` if ``when`` and not ``require``; with ``within_cycles = n`` it is
  violated if some ``j ≤ t`` with ``t - j ≥ n`` had ``when`` (``true`` if absent)
  and ``require`` was false at every cycle of ``j .. t``.
* A bad input or an evaluation error makes a fault cycle: override with
  ``on_fault`` (or the risk response if R_e ≥ τ and more severe), history cleared.
  On a bad-input cycle the *stateless* obligations (no temporal operator, no
  ``within_cycles``) whose inputs are all valid are still judged, and a more
  severe response they demand wins (a stale risk estimate must not hide a
  stop 0 on a contact force); one that raises is skipped.
* Latches, one per rule: each obligation, the risk rule and the fault rule. A
  rule's latch is set at a cycle where it fires (the obligation is violated;
  R_e ≥ τ; the cycle faults). Its release condition at a valid cycle: the
  obligation is not violated; R_e < τ − δ (exact: the decimals the spec writes,
  so 0.27 − 0.05 is 0.22; R_e compared as a rational); for the fault rule, any
  valid cycle. A latched rule's count is the number of consecutive cycles, up to
  this one, at which its condition held (a cycle where it fires, or a fault
  cycle, makes it 0). An ``auto`` rule releases at the cycle where its count
  reaches its ``hold_cycles``; a ``manual`` rule only by ``acknowledge()``,
  which releases every latched manual rule if each has a count ≥ its
  ``hold_cycles`` and otherwise releases nothing; ``release()`` and ``reset()``
  clear every latch. Defaults: obligations with stop_0/stop_1 and the fault rule
  are manual, the others auto; the hold defaults to ``risk.release.hold_cycles``;
  the risk rule follows ``risk.release``.
* The tiers (only with ``risk.judge`` / ``risk.confirm_threshold``): the ``judge`` input is the
  judge's p_unsafe (absent or ``None``: no judgement; anything else outside [0, 1]: a bad input).
  At a valid cycle, the rule ``judge`` fires if p_judge ≥ ``unsafe_from`` (any R_e); else the rule
  ``confirm`` (stop 2, auto release, hold ``risk.release.hold_cycles``) fires if τ_confirm ≤ R_e < τ,
  the judge did not say safe (p_judge < ``safe_below``) and no confirmation holds. ``acknowledge()``
  releases a latched ``confirm`` with no count needed and confirms the ``task_id`` input of the last
  band cycle; the confirmation ends at a cycle with another ``task_id``, R_e outside the band, or a
  fault. The ``judge`` rule releases like the risk rule (mode and hold of ``risk.release``).
* The decision overrides while any latch is set, with the most severe response
  among the latched rules; ``latched`` when none fired and the cycle did not fault;
  ``awaiting_release`` when some manual rule is latched and every latched manual
  rule's count reached its hold. ``Monitor.fault(decision=d)`` latches the fault
  rule after ``d``'s cycle and restarts every count.
* Inputs are read through :mod:`ethimon.runtime._inputs` (the one boundary rule:
  a finite built-in float, or a bool for a bool signal, converted once).
* Margins: robustness of ``require`` (``max(−when, require)`` with a ``when``);
  with ``within_cycles = n`` the minimum over the triggers ``j ≤ t − n`` of
  ``max(−when(j), max over k in j..t of require(k))``, +inf if there is none.
  A margin whose evaluation raises is NaN.
"""

from __future__ import annotations

import math
from typing import Any

from ..compiler._plan import RISK_NAME, Plan
from ..compiler import plan_of
from ..language._expr import (BINARY_OPS, COMPARISON_MARGINS, CONNECTIVE_MARGINS, Binary, BoolLit, Call,
                          Name, Node, Num, Unary, comparison_margin, connective_margin, separation_distance,
                          is_temporal, walk)
from ..language._visit import ExprVisitor
from ..language import SEVERITY_ORDER, Response, Spec
from ..compiler._risk_formula import decimal_reading, risk_from_p_unsafe, risk_from_probs
from ..runtime import Decision, Fault
# the monitor's own input rules (what counts as a number, a flag, a probability vector): the
# reference must read inputs exactly as the monitor does, so it uses the same private helpers
from ..runtime._inputs import as_bool, as_number, as_probs

__all__ = ["ReferenceMonitor"]

_BY_SEV = SEVERITY_ORDER  # severity -> Response
_NO_TASK = object()  # acknowledge() without a task_id
# the reference tells that a cycle faulted, not the compiled monitor's wording
_BAD_INPUT = (Fault("invalid", "fault: a bad or missing input (reference interpreter)"),)
_EVAL_ERROR = (Fault("internal", "fault: an evaluation error (reference interpreter)"),)


class _Semantics(ExprVisitor):
    """The reference back-end of the interpreter protocol: each ``visit_*(node, t)`` is the value of
    its node at cycle ``t`` of ``monitor.history``, straight from the definitions above (the
    temporal operators look back over the history)."""

    def __init__(self, monitor: "ReferenceMonitor") -> None:
        self.m = monitor
        self.plan = monitor.plan

    def visit_num(self, node: Num, t: int) -> float:
        return node.value

    def visit_bool(self, node: BoolLit, t: int) -> bool:
        return node.value

    def visit_name(self, node: Name, t: int) -> Any:
        if node.id in self.plan.constants:
            return self.plan.constants[node.id]
        return self.m.history[t][node.id]

    def visit_neg(self, node: Unary, t: int) -> float:
        return -self.visit(node.operand, t)

    def visit_not(self, node: Unary, t: int) -> bool:
        return not self.visit(node.operand, t)

    def _apply(self, node: Binary, t: int) -> Any:
        """A comparison or arithmetic: the operator's function of ``BINARY_OPS`` on both values."""
        return BINARY_OPS[node.op][1](self.visit(node.left, t), self.visit(node.right, t))

    visit_lt = visit_le = visit_gt = visit_ge = visit_eq = visit_ne = _apply
    visit_add = visit_sub = visit_mul = visit_div = _apply

    def visit_and(self, node: Binary, t: int) -> bool:
        return bool(self.visit(node.left, t)) and bool(self.visit(node.right, t))

    def visit_or(self, node: Binary, t: int) -> bool:
        return bool(self.visit(node.left, t)) or bool(self.visit(node.right, t))

    def visit_implies(self, node: Binary, t: int) -> bool:
        return (not self.visit(node.left, t)) or bool(self.visit(node.right, t))

    def visit_abs(self, node: Call, t: int) -> float:
        return abs(self.visit(node.args[0], t))

    def visit_sqrt(self, node: Call, t: int) -> float:
        return math.sqrt(self.visit(node.args[0], t))

    def visit_min(self, node: Call, t: int) -> float:
        return min(self.visit(a, t) for a in node.args)

    def visit_max(self, node: Call, t: int) -> float:
        return max(self.visit(a, t) for a in node.args)

    def visit_separation_distance(self, node: Call, t: int) -> float:
        vals = [self.visit(a, t) for a in node.args]
        if not all(v >= 0 for v in vals):  # negative or NaN: an evaluation error
            raise ValueError("separation_distance() of a negative argument")
        return separation_distance(*vals)

    def visit_prev(self, node: Call, t: int) -> Any:
        args = node.args
        if t == 0:
            if len(args) == 2:
                return self.visit(args[1], 0)
            return False if self.plan.type_of(node).kind == "bool" else self.visit(args[0], 0)
        return self.visit(args[0], t - 1)

    def visit_held(self, node: Call, t: int) -> bool:
        n = node.ann.window
        if t + 1 < n:
            return False
        return all(self.visit(node.args[0], j) for j in range(t - n + 1, t + 1))

    def visit_once(self, node: Call, t: int) -> bool:
        n = node.ann.window
        return any(self.visit(node.args[0], j) for j in range(max(0, t - n + 1), t + 1))

    def visit_since(self, node: Call, t: int) -> bool:
        n = node.ann.window
        a, b = node.args[0], node.args[1]
        first = 0 if n is None else max(0, t - n + 1)
        for j in range(first, t + 1):
            if self.visit(b, j) and all(self.visit(a, k) for k in range(j + 1, t + 1)):
                return True
        return False


class ReferenceMonitor:
    """Same contract as :class:`~ethimon.Monitor`, implemented by AST walking."""

    def __init__(self, spec: Spec | Plan) -> None:
        self.plan = plan_of(spec)
        self.spec = self.plan.spec
        self.obligation_ids = tuple(ob.id for ob in self.plan.obligations)
        self._semantics = _Semantics(self)
        self.reset()

    def reset(self) -> None:
        self.history: list[dict[str, Any]] = []
        self.cycle = 0
        self.release()

    def release(self) -> None:
        #: rule name -> its count while latched (absent: not latched)
        self.latches: dict[str, int] = {}
        #: the task_id whose band hold an operator confirmed, as a 1-tuple (None: no confirmation)
        self.confirmed: tuple | None = None
        self.last_task = None

    @property
    def latched(self) -> bool:
        return bool(self.latches)

    @property
    def latched_rules(self) -> tuple[str, ...]:
        return self._order(self.latches)

    def _rules(self) -> dict[str, tuple[int, bool, int]]:
        """Every rule: name -> (severity, manual, hold_cycles), as the plan resolved them."""
        return {r.name: (r.severity, r.manual, r.hold) for r in self.plan.rules()}

    def acknowledge(self, task_id=_NO_TASK):
        from ..runtime import Acknowledgement
        rules = self._rules()
        manual = [k for k in self.latches if rules[k][1] or k == "confirm"]
        waiting = tuple(k for k in self._order(manual) if k != "confirm" and self.latches[k] < rules[k][2])
        if waiting:
            return Acknowledgement(False, waiting, "refused: " + "; ".join(
                f"{k} still fails" if self.latches[k] == 0 else
                f"{k} has held {self.latches[k]} of {rules[k][2]} cycles" for k in waiting))
        if "confirm" in manual and task_id is not _NO_TASK and task_id != self.last_task:
            return Acknowledgement(False, ("confirm",), "refused: confirm is for the task in the band now, "
                                   "not the one acknowledged (the task text changed since it was shown)")
        if "confirm" in manual and self.last_task is None:
            return Acknowledgement(False, ("confirm",), "refused: confirm needs the task_id of the text in the "
                                   "band (none was given this cycle) to bind the confirmation to")
        if not manual:
            return Acknowledgement(False, (), "nothing awaits an acknowledgement" + (
                " (the override is held by automatic releases)" if self.latches else ""))
        for k in manual:
            del self.latches[k]
        if "confirm" in manual:
            self.confirmed = (self.last_task,)
        return Acknowledgement(True, self._order(manual), "released: " + ", ".join(self._order(manual)))

    def _order(self, names) -> tuple[str, ...]:
        order = list(self.obligation_ids) + ["risk", "fault", "judge", "confirm"]
        return tuple(sorted(names, key=order.index))

    def _decide(self, fired: list[str], faulted: bool, below: bool) -> tuple[int, bool]:
        """Update the latches after a cycle; ``(latched severity, awaiting_release)``."""
        rules = self._rules()
        if faulted:
            for k in fired + ["fault"]:
                self.latches[k] = 0
            for k in self.latches:
                self.latches[k] = 0
        else:
            for k in list(self.latches):
                if k in fired or (k == "risk" and not below):
                    self.latches[k] = 0
                    continue
                sev, manual, hold = rules[k]
                self.latches[k] = min(self.latches[k] + 1, hold)
                if not manual and self.latches[k] >= hold:
                    del self.latches[k]
            for k in fired:
                self.latches[k] = 0
        sev = max((rules[k][0] for k in self.latches), default=0)
        manual = [k for k in self.latches if rules[k][1] or k == "confirm"]
        awaiting = bool(manual) and all(k == "confirm" or self.latches[k] >= rules[k][2] for k in manual)
        return sev, awaiting

    def fault(self, *reasons, decision: Decision | None = None) -> Decision:
        """Like :meth:`Monitor.fault`; the reference's own reasons are kept as given."""
        reasons = tuple(r if isinstance(r, Fault) else Fault("external", str(r)) for r in reasons) or (
            Fault("external", "external fault"),)
        if decision is None:
            cycle = self.cycle
            self.cycle += 1
            self.history = []
            sev, _ = self._decide([], True, False)
            return Decision(True, _BY_SEV[sev], (), (), None, cycle, False, reasons)
        sev, _ = self._decide([], True, False)
        sev = max(sev, decision.response.severity)
        return Decision(True, _BY_SEV[sev], decision.violations, decision.margins, decision.risk,
                        decision.cycle, decision.latched, decision.faults + reasons)

    # -- expression semantics -----------------------------------------------------
    def ev(self, node: Node, t: int) -> Any:
        """The value of ``node`` at cycle ``t`` of the history (:class:`_Semantics`)."""
        return self._semantics.visit(node, t)

    def rob(self, node: Node, t: int) -> float:
        """Quantitative robustness of a condition at ``t`` (> 0 true, < 0 false, ±inf for boolean leaves)."""
        if isinstance(node, Binary):
            op = node.op
            if op in COMPARISON_MARGINS and self.plan.type_of(node.left).kind == "num":
                return comparison_margin(op, self.ev(node.left, t), self.ev(node.right, t))
            if op in CONNECTIVE_MARGINS:
                return connective_margin(op, self.rob(node.left, t), self.rob(node.right, t))
        if isinstance(node, Unary) and node.op == "not":
            return -self.rob(node.operand, t)
        return math.inf if self.ev(node, t) else -math.inf

    def _rob_or_nan(self, node: Node, t: int) -> float:
        try:
            return self.rob(node, t)
        except Exception:
            return math.nan

    def margin(self, ob, t: int) -> float:
        """The obligation's margin at ``t`` (see the module docstring)."""
        n = ob.within_cycles
        if not n:
            try:
                r = self.rob(ob.require, t)
                return r if ob.when is None else max(-self.rob(ob.when, t), r)
            except Exception:
                return math.nan
        rr = [self._rob_or_nan(ob.require, k) for k in range(t + 1)]
        best = math.inf
        for j in range(0, t - n + 1):
            w = -self._rob_or_nan(ob.when, j) if ob.when is not None else -math.inf
            vals = [w] + rr[j:t + 1]
            if any(v != v for v in vals):
                return math.nan
            best = min(best, max(vals))
        return best

    def _names(self, ob) -> set[str]:
        names = {s.name for s in self.plan.signals} | {RISK_NAME}
        return {n.id for root in (ob.when, ob.require) if root is not None
                for n in walk(root) if isinstance(n, Name) and n.id in names}

    def _has_temporal(self, ob) -> bool:
        return any(is_temporal(n)
                   for root in (ob.when, ob.require) if root is not None for n in walk(root))

    def _touch_temporal(self, t: int) -> None:
        for node in self.plan.temporal:
            for a in node.args:
                self.ev(a, t)

    def _violated(self, ob, t: int) -> bool:
        n = ob.within_cycles
        if not n:
            if ob.when is None:
                return not self.ev(ob.require, t)
            return bool(self.ev(ob.when, t)) and not self.ev(ob.require, t)
        # a bounded-response obligation evaluates both conditions every cycle
        if ob.when is not None:
            self.ev(ob.when, t)
        req = [bool(self.ev(ob.require, j)) for j in range(t + 1)]
        for j in range(0, t - n + 1):
            if all(not req[k] for k in range(j, t + 1)):
                if ob.when is None or self.ev(ob.when, j):
                    return True
        return False

    # -- a cycle -------------------------------------------------------------------
    def _risk(self, signals) -> tuple[float | None, str | None]:
        r = self.plan.risk_plan  # the whole risk rule, resolved once (weights, K, variance, accepted range)
        lo, hi = self.plan.risk_plan.accepted  # the range the monitor accepts, resolved once by the plan
        if signals.get("risk") is not None:
            v = as_number(signals["risk"])
            if v is not None and lo <= v <= hi:
                return v, None
            return None, "bad risk"
        if signals.get("p_unsafe") is not None:
            q = as_number(signals["p_unsafe"])
            if r.classes == 2 and q is not None and 0 <= q <= 1:
                return risk_from_p_unsafe(q, r.alpha, r.beta, r.gamma, r.variance), None
            return None, "bad p_unsafe"
        if signals.get("p") is not None:
            p, why = as_probs(signals["p"], r.classes)
            if why is None:
                re = risk_from_probs(p, r.alpha, r.beta, r.gamma, r.variance, r.unsafe_index)
                return (re, None) if math.isfinite(re) else (None, "R_e not finite")
            return None, "bad p"
        return None, "no risk"

    def _value(self, sig, v) -> Any:
        """The converted input, or ``None`` if it is unusable."""
        if v is None:
            return None
        if sig.kind == "bool":
            return as_bool(v)
        f = as_number(v)
        return f if f is not None and sig.lo <= f <= sig.hi else None

    def step(self, signals: dict[str, Any]) -> Decision:
        cycle = self.cycle
        self.cycle += 1
        spec = self.spec
        tau = self.plan.threshold
        r, why = self._risk(signals)
        risk_ok = why is None
        if self.plan.risk_plan.max_age_s is not None:
            age = signals.get("risk_age_s")
            age = None if age is None else as_number(age)
            risk_ok = risk_ok and age is not None and 0 <= age <= self.plan.risk_plan.max_age_s
        conv = {s.name: self._value(s, signals.get(s.name)) for s in self.plan.signals}
        judge = spec.risk.judge
        jp = signals.get("judge") if judge is not None else None
        judge_ok = True
        if jp is not None:
            jp = as_number(jp)
            judge_ok = jp is not None and 0 <= jp <= 1
        ok = risk_ok and judge_ok and all(v is not None for v in conv.values())
        bad_input = not ok
        violations: list[str] = []
        margins: tuple[float, ...] = ()
        sev = 0
        if ok:
            env = dict(conv)
            env[RISK_NAME] = r
            self.history.append(env)
            t = len(self.history) - 1
            try:
                self._touch_temporal(t)
                for ob in self.plan.obligations:
                    if self._violated(ob, t):
                        violations.append(ob.id)
                        sev = max(sev, ob.response.severity)
                margins = tuple(self.margin(ob, t) for ob in self.plan.obligations)
            except Exception:
                ok = False
        if not ok:
            self.history = []
            self.confirmed = None
            fsev = self.plan.fault_rule.severity
            found = []
            if bad_input:
                # stateless obligations whose inputs are all valid are still judged
                valid = {name: v for name, v in conv.items() if v is not None}
                if risk_ok:
                    valid[RISK_NAME] = r
                for ob in self.plan.obligations:
                    if ob.within_cycles or not self._names(ob) <= set(valid) or self._has_temporal(ob):
                        continue
                    self.history = [valid]
                    try:
                        hit = self._violated(ob, 0)
                    except Exception:
                        hit = False
                    finally:
                        self.history = []
                    if hit:
                        found.append(ob.id)
                        fsev = max(fsev, ob.response.severity)
            if r is not None and r >= tau:
                found.append("risk")
                fsev = max(fsev, self.plan.risk_rule.severity)
            v: tuple[str, ...] = tuple(found)
            lsev, _ = self._decide(found, True, False)
            return Decision(True, _BY_SEV[lsev], v, (), r, cycle, False,
                            _BAD_INPUT if bad_input else _EVAL_ERROR)
        if r >= tau:
            violations.append("risk")
        # the tiers: an unsafe verdict stops at any R_e; in [τ_confirm, τ) only a safe verdict or a
        # confirmation of this task executes
        if spec.risk.confirm_threshold is not None:  # every cycle: the text it is about
            task = signals.get("task_id")
            in_band = spec.risk.confirm_threshold <= r < tau
            if self.confirmed is not None and (task is None or self.confirmed[0] != task or not in_band):
                self.confirmed = None
            self.last_task = task
        if judge is not None and jp is not None and jp >= judge.unsafe_from:
            violations.append("judge")
        elif spec.risk.confirm_threshold is not None:
            judged_safe = judge is not None and jp is not None and jp < judge.safe_below
            if in_band and self.confirmed is None and not judged_safe:
                violations.append("confirm")
        # one reading of numbers: R_e as the decimal it prints as, against the exact τ − δ
        below = decimal_reading(r) < self.plan.release_exact
        lsev, awaiting = self._decide(violations, False, below)
        if violations:
            return Decision(True, _BY_SEV[lsev], tuple(violations), margins, r, cycle, False, (), awaiting)
        if self.latches:
            return Decision(True, _BY_SEV[lsev], (), margins, r, cycle, True, (), awaiting)
        return Decision(False, Response.NONE, (), margins, r, cycle, False, ())
