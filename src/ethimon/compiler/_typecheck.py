"""The type checker: resolve names, check types, units and windows, and build the :class:`Plan`.

The plan's data types live in ``compiler/_plan.py``; this module is the checker that fills them.
"""

from __future__ import annotations

import difflib
import math

from ..errors import SpecError
from ..language._expr import (SEPARATION_PARAMS, UNIT_RULES, Binary, BoolLit, Call, ExprSyntaxError, Name,
                          Node, Num, Seconds, Unary, parse_expr, separation_distance)
from ..language import Constant, Response, Spec, seconds_to_cycles
from ..language import OPERATORS, Operator
from ._plan import (BOOL, MAX_WINDOW, RISK_NAME, Annotation, EstimatorPlan, JudgePlan, LatchRule, ObligationPlan, Plan,
                    RestartPlan, RiskPlan, SignalSlot, Tiers, Ty)
from ._risk_formula import release_bound
from ._units import DIMENSIONLESS, Unit, div, format_unit, mul, parse_unit, sqrt_unit

__all__ = ["compile_plan"]


class _Checker:
    def __init__(self, spec: Spec) -> None:
        self.spec = spec
        self.smap = spec.source
        self.temporal: list[Call] = []
        self.names: dict[str, Ty] = {}
        self.consts: dict[str, float] = {}
        self.loc: tuple = ()
        self.text = ""
        # what is found out about the node being checked (its Annotation's fields but the type), set
        # on the node once its check is done: the tree is annotated in place, children first
        self.note: dict = {}
        self.count = 0  # nodes annotated so far: the next one's serial
        for name, sig in spec.signals.items():
            try:
                unit = parse_unit(sig.unit) if sig.type == "number" else None
            except ValueError as exc:
                raise self.smap.error(str(exc), ("signals", name, "unit"),
                                      hint="units look like m, m/s, m/s^2, N, rad/s or 1") from None
            self.names[name] = BOOL if sig.type == "bool" else Ty("num", unit)
        for name, c in spec.constants.items():
            if isinstance(c, Constant):
                try:
                    unit = parse_unit(c.unit)
                except ValueError as exc:
                    raise self.smap.error(str(exc), ("constants", name, "unit")) from None
                self.names[name] = Ty("num", unit)
                self.consts[name] = float(c.value)
            else:
                self.names[name] = Ty("num", None)
                self.consts[name] = float(c)
        self.names[RISK_NAME] = Ty("num", DIMENSIONLESS)

    # -- errors -----------------------------------------------------------
    def err(self, node: Node | None, msg: str, hint: str | None = None) -> SpecError:
        index = node.start if node is not None else 0
        return self.smap.error(msg, self.loc, hint=hint, index=index, text=self.text)

    def snippet(self, node: Node) -> str:
        s = self.text[node.start:node.end]
        return s if len(s) <= 50 else s[:47] + "..."

    # -- expressions -------------------------------------------------------
    def parse(self, text: str, loc: tuple) -> Node:
        self.loc, self.text = loc, text
        try:
            return parse_expr(text)
        except ExprSyntaxError as exc:
            raise self.smap.error(f"syntax error in {loc[-1]!r}: {exc.message}", loc, hint=exc.hint,
                                  index=exc.index, text=text) from None

    def check_bool(self, node: Node, role: str) -> None:
        ty = self.check(node)
        if ty.kind != "bool":
            raise self.err(node, f"{role} must be a condition (true/false), but {self.snippet(node)!r} is {ty.show()}",
                           hint="compare it, e.g. 'x > 0.5'")

    def need(self, node: Node, kind: str, what: str) -> Ty:
        ty = self.check(node)
        if ty.kind != kind:
            want = "a boolean" if kind == "bool" else "a number"
            raise self.err(node, f"{what} needs {want}, but {self.snippet(node)!r} is {ty.show()}")
        return ty

    def same_unit(self, node: Node, a: Ty, b: Ty, what: str) -> Unit | None:
        if a.unit is not None and b.unit is not None and a.unit != b.unit:
            raise self.err(node, f"unit mismatch in {what}: [{format_unit(a.unit)}] vs [{format_unit(b.unit)}] "
                                 f"in {self.snippet(node)!r}",
                           hint="both sides must have the same unit; declare constants with a unit")
        return a.unit if a.unit is not None else b.unit

    def check(self, node: Node) -> Ty:
        got = node.ann
        if got is not None:
            return got.ty
        if not self._checking:
            return self._check_tree(node)
        outer, self.note = self.note, {}
        try:
            ty = self._check(node)
            node.annotate(Annotation(ty, serial=self.serial(), **self.note))
        finally:
            self.note = outer
        return ty

    _checking = False

    def serial(self) -> int:
        self.count += 1
        return self.count - 1

    def _check_tree(self, root: Node) -> Ty:
        """Check ``root`` bottom-up without deep recursion.

        Nodes are visited children first, left to right (the order the recursive
        rules would meet them), so that each :meth:`check` call finds its
        operands' types already computed and recurses one level only. The
        window argument of ``held``/``once``/``since`` is left to :meth:`bound`.
        """
        order: list[Node] = []
        stack: list[tuple[Node, bool]] = [(root, False)]
        while stack:
            node, expanded = stack.pop()
            if expanded:
                order.append(node)
                continue
            stack.append((node, True))
            for child in reversed(_children(node)):
                stack.append((child, False))
        self._checking = True
        try:
            for node in order:
                self.check(node)
        finally:
            self._checking = False
        return root.ann.ty

    def fold(self, node: Node, value: float) -> None:
        """Record the value of a constant subexpression (refusing overflow to inf/nan)."""
        if not math.isfinite(value):
            raise self.err(node, f"the constant expression {self.snippet(node)!r} is not a finite number "
                                 f"(it evaluates to {value})", hint="check the constants and the arithmetic")
        self.note["value"] = value

    def _check(self, node: Node) -> Ty:
        if isinstance(node, Seconds):
            raise self.err(node, f"a time in seconds ({self.snippet(node)!r}) is only a window of held(), once() "
                                 "or since()", hint="declare a constant with a unit instead, e.g. "
                                 "'t_stop: {value: 0.5, unit: s}', and use its name")
        if isinstance(node, Num):
            if not math.isfinite(node.value):
                raise self.err(node, "number is not finite")
            self.note["value"] = node.value
            return Ty("num", None)
        if isinstance(node, BoolLit):
            return BOOL
        if isinstance(node, Name):
            ty = self.names.get(node.id)
            if ty is None:
                known = sorted(self.names)
                close = difflib.get_close_matches(node.id, known, n=1, cutoff=0.6)
                if close:
                    hint = f"did you mean {close[0]!r}?"
                elif node.id in _functions():
                    hint = f"{node.id} is a function: {node.id}(...)"
                else:
                    hint = "declare it under 'signals:' or 'constants:'" + (
                        f"; known names: {', '.join(known)}" if len(known) <= 12 else "")
                raise self.err(node, f"unknown signal {node.id!r}", hint=hint)
            if node.id in self.consts:
                self.note["value"] = self.consts[node.id]
            return ty
        row = node.row
        if row is None and isinstance(node, Call):
            functions = _functions()
            close = difflib.get_close_matches(node.func, functions, n=1)
            hint = f"did you mean {close[0]!r}?" if close else f"functions: {', '.join(functions)}"
            raise self.err(node, f"unknown function {node.func!r}", hint=hint)
        if row is None:
            raise self.err(node, "unsupported expression")  # pragma: no cover
        return self.check_row(node, row)

    # -- the rows of the operator table --------------------------------------
    def check_row(self, node: Node, row: Operator) -> Ty:
        """Check an operator or call by its row: arity, then its unit rule (which checks the
        operands' kinds and sets the windows), then, for a temporal row, its window."""
        args = node.children
        if row.kind == "call" and not row.min_args <= len(args) <= row.max_args:
            lo, hi = row.min_args, row.max_args
            want = str(lo) if lo == hi else f"{lo} to {hi}"
            raise self.err(node, f"{row.symbol}() takes {want} arguments, got {len(args)}",
                           hint=_SEPARATION_HINT if row.unit == "separation" else None)
        ty = _UNIT_RULES[row.unit](self, node, row)
        if row.family == "temporal":
            self.note["slot"] = len(self.temporal)  # its state's index in plan.temporal
            self.temporal.append(node)  # children were checked (and appended) first
        return ty

    def operands(self, node: Node, row: Operator) -> list[Ty | None]:
        """Each operand checked against its kind in the row (``any``: checked, any type); a window
        bound checked and its cycles recorded (``None`` in the result)."""
        out: list[Ty | None] = []
        windowed = False
        for i, arg in enumerate(node.children):
            kind = row.arg_kind(i)
            if kind == "window":
                self.note["window"] = self.bound(node, arg, row.symbol)  # type: ignore[arg-type]
                windowed = True
                out.append(None)
            else:
                out.append(self.check(arg) if kind == "any" else self.need(arg, kind, row.label))
        if row.lookback == "window" and not windowed:
            self.note["window"] = None  # an optional window left out: unbounded
        elif row.lookback == "one":
            self.note["window"] = 1
        return out

    def fold_row(self, node: Node, row: Operator) -> None:
        """Fold a numeric row's value when every operand is a constant."""
        vals = [_value(a) for a in node.children]
        if row.fn is not None and row.result == "num" and all(v is not None for v in vals):
            self.fold(node, row.fn(*vals))

    def rule_none(self, node: Node, row: Operator) -> Ty:
        self.operands(node, row)
        return BOOL

    def rule_keep(self, node: Node, row: Operator) -> Ty:
        ty = self.operands(node, row)[0]
        self.fold_row(node, row)
        return ty  # type: ignore[return-value]

    def rule_same(self, node: Node, row: Operator) -> Ty:
        """Operands in one unit: a comparison is a condition, arithmetic and min/max keep the unit."""
        tys = self.operands(node, row)
        self.fold_row(node, row)
        unit = tys[0].unit  # type: ignore[union-attr]
        for arg, ty in zip(node.children[1:], tys[1:]):
            unit = self.same_unit(node if row.kind == "binary" else arg, Ty("num", unit), ty, row.label)  # type: ignore[arg-type]
        return BOOL if row.result == "bool" else Ty("num", unit)

    def rule_compare(self, node: Node, row: Operator) -> Ty:
        a, b = self.operands(node, row)
        if a.kind != b.kind:  # type: ignore[union-attr]
            raise self.err(node, f"cannot compare {a.show()} with {b.show()} in {self.snippet(node)!r}")  # type: ignore[union-attr]
        if a.kind == "num":  # type: ignore[union-attr]
            self.same_unit(node, a, b, row.label)  # type: ignore[arg-type]
        return BOOL

    def rule_mul(self, node: Node, row: Operator) -> Ty:
        a, b = self.operands(node, row)
        self.fold_row(node, row)
        left, right = node.children
        return Ty("num", mul(a.unit, b.unit) if a.unit is not None and b.unit is not None  # type: ignore[union-attr]
                  else (a.unit if b.unit is None and _is_literal(right) else  # type: ignore[union-attr]
                        b.unit if a.unit is None and _is_literal(left) else None))  # type: ignore[union-attr]

    def rule_div(self, node: Node, row: Operator) -> Ty:
        a, b = self.operands(node, row)
        right = node.children[1]
        y = _value(right)
        if y == 0:
            what = "" if isinstance(right, Num) else f": {self.snippet(right)!r} is always {y}"
            raise self.err(right, f"division by zero{what}",
                           hint="the divisor is a constant 0, so every cycle would fail closed")
        self.fold_row(node, row)
        if a.unit is not None and b.unit is not None:  # type: ignore[union-attr]
            return Ty("num", div(a.unit, b.unit))  # type: ignore[union-attr]
        if b.unit is None and _is_literal(right):  # type: ignore[union-attr]
            return Ty("num", a.unit)  # type: ignore[union-attr]
        return Ty("num", None)

    def rule_sqrt(self, node: Node, row: Operator) -> Ty:
        (ty,) = self.operands(node, row)
        arg = node.children[0]
        v = _value(arg)
        if v is not None and v < 0:
            raise self.err(arg, f"square root of a negative constant: {self.snippet(arg)!r} is always {v}",
                           hint="sqrt() of a negative number fails, so every cycle would fail closed")
        self.fold_row(node, row)
        try:
            return Ty("num", sqrt_unit(ty.unit))  # type: ignore[union-attr]
        except ValueError as exc:
            raise self.err(node, str(exc)) from None

    def rule_prev(self, node: Node, row: Operator) -> Ty:
        """``prev(e[, init])``: the operand's type; the initial value of the same kind and unit."""
        tys = self.operands(node, row)
        ty = tys[0]
        if len(tys) == 2:
            ity = tys[1]
            init = node.children[1]
            if ity.kind != ty.kind:  # type: ignore[union-attr]
                raise self.err(init, f"prev() initial value must be {ty.show()}, got {ity.show()}")  # type: ignore[union-attr]
            if ty.kind == "num":  # type: ignore[union-attr]
                self.same_unit(init, ty, ity, "prev()")  # type: ignore[arg-type]
        return ty  # type: ignore[return-value]

    def bound(self, node: Call, arg: Node, fname: str) -> int:
        if isinstance(arg, Seconds) or (isinstance(arg, Name) and arg.id in self.consts
                                        and self.names[arg.id].unit == _SECOND):
            return self.bound_seconds(node, arg, fname)
        if isinstance(arg, Num):
            value = arg.value
        elif isinstance(arg, Name) and arg.id in self.consts:
            value = self.consts[arg.id]
        else:
            raise self.err(arg, f"the window of {fname}() must be a whole number of cycles, "
                                f"not {self.snippet(arg)!r}", hint=f"e.g. {fname}(x, 3)")
        if not math.isfinite(value) or value > MAX_WINDOW:
            raise self.err(arg, f"window {self.snippet(arg)} of {fname}() is too long (at most {MAX_WINDOW} cycles)",
                           hint="a window counts control cycles")
        if value != int(value):
            raise self.err(arg, f"the window of {fname}() must be a whole number of cycles, got {value}")
        n = int(value)
        if n < 1:
            raise self.err(arg, f"a window of {n} cycles makes no sense in {fname}()",
                           hint="windows count the current cycle, so the smallest is 1")
        if n > MAX_WINDOW:
            raise self.err(arg, f"window {n} is too long (at most {MAX_WINDOW} cycles)",
                           hint="a window counts control cycles")
        arg.annotate(Annotation(Ty("num", None), serial=self.serial()))  # a window bound: a count of cycles
        return n

    def bound_seconds(self, node: Call, arg: Node, fname: str) -> int:
        """A window in seconds (``0.5 s``, or a constant in s) as whole cycles at the spec's ``rate_hz``."""
        value = arg.value if isinstance(arg, Num) else self.consts[arg.id]  # type: ignore[union-attr]
        if not value > 0:
            raise self.err(arg, f"a window of {self.snippet(arg)} makes no sense in {fname}()",
                           hint="windows count the current cycle, so the smallest is one cycle (1 / rate_hz s)")
        try:
            n = seconds_to_cycles(value, self.spec.rate_hz, f"the window of {fname}()" if isinstance(arg, Num)
                                  else f"the window {arg.id} of {fname}()")  # type: ignore[union-attr]
        except ValueError as exc:  # not whole cycles, or no rate_hz: its msg and hint, located here
            raise self.err(arg, getattr(exc, "msg", str(exc)), hint=getattr(exc, "hint", None)) from None
        if n < 1:
            raise self.err(arg, f"a window of {self.snippet(arg)} is less than one cycle in {fname}()",
                           hint="windows count the current cycle, so the smallest is one cycle (1 / rate_hz s)")
        if n > MAX_WINDOW:
            raise self.err(arg, f"window {self.snippet(arg)} of {fname}() is {n} cycles: too long (at most "
                                f"{MAX_WINDOW} cycles)", hint="a window counts control cycles")
        arg.annotate(Annotation(Ty("num", _SECOND), serial=self.serial()))
        self.note["seconds"] = float(value)
        return n

    def check_separation(self, node: Call, row: Operator | None = None) -> Ty:
        """``separation_distance(v_h, v_r, T_r, T_s, S_s, C, Z_d, Z_r)``: each argument a number in its
        parameter's unit (speeds m/s, times s, distances m; an unknown unit passes) and not a negative
        constant; the result is a distance [m]."""
        vals = []
        for arg, (sym, unit_text, meaning) in zip(node.args, SEPARATION_PARAMS):
            ty = self.check(arg)
            if ty.kind != "num":
                raise self.err(arg, f"separation_distance() parameter {sym} ({meaning}) needs a number, but "
                                    f"{self.snippet(arg)!r} is {ty.show()}", hint=_SEPARATION_HINT)
            want = _SEPARATION_UNITS[sym]
            if ty.unit is not None and ty.unit != want:
                raise self.err(arg, f"separation_distance() parameter {sym} ({meaning}) is in [{unit_text}], "
                                    f"but {self.snippet(arg)!r} is [{format_unit(ty.unit)}]",
                               hint=_SEPARATION_HINT)
            v = _value(arg)
            if v is not None and v < 0:
                raise self.err(arg, f"separation_distance() parameter {sym} ({meaning}) is a negative constant: "
                                    f"{self.snippet(arg)!r} is always {v}",
                               hint="speeds, times and distances of the separation distance are magnitudes >= 0; "
                                    "a negative one fails at run time, so every cycle would fail closed")
            vals.append(v)
        if all(v is not None for v in vals):
            self.fold(node, separation_distance(*vals))
        return Ty("num", _SEPARATION_UNITS["S_s"])



_UNIT_RULES = {"none": _Checker.rule_none, "same": _Checker.rule_same, "keep": _Checker.rule_keep,
               "mul": _Checker.rule_mul, "div": _Checker.rule_div, "sqrt": _Checker.rule_sqrt,
               "compare": _Checker.rule_compare, "separation": _Checker.check_separation,
               "prev": _Checker.rule_prev}
assert set(_UNIT_RULES) == set(UNIT_RULES), "every unit rule of the operator table has its method here"


_SEPARATION_UNITS = {sym: parse_unit(u) for sym, u, _ in SEPARATION_PARAMS}
_SECOND = parse_unit("s")
_SEPARATION_HINT = ("separation_distance(" + ", ".join(f"{sym} [{u}]" for sym, u, _ in SEPARATION_PARAMS)
                    + "): S_p = v_h*(T_r + T_s) + v_r*T_r + S_s + C + Z_d + Z_r (ISO/TS 15066)")


def _functions() -> list[str]:
    """The functions of the operator table as it is now, in its order."""
    return [op.symbol for op in OPERATORS.values() if op.kind == "call"]


def _children(node: Node) -> tuple[Node, ...]:
    """Operands the type rules check through :meth:`_Checker.check` (not window bounds)."""
    row = node.row
    if row is None:
        return node.children
    return tuple(a for i, a in enumerate(node.children) if row.arg_kind(i) != "window")


def _value(node: Node) -> float | None:
    """The folded value of a checked operand (``None``: not a constant, or a window bound)."""
    ann = node.ann
    return None if ann is None else ann.value


def _is_literal(node: Node) -> bool:
    return isinstance(node, Num) or (isinstance(node, Unary) and isinstance(node.operand, Num))


def compile_plan(spec: Spec) -> Plan:
    """Check a spec's expressions and build its :class:`Plan`.

    Raises:
        SpecError: unknown names, type or unit errors, bad windows, with
            file:line:column of the offending text and a hint.
    """
    ck = _Checker(spec)
    obligations = []
    for i, ob in enumerate(spec.obligations):
        when = None
        if ob.when is not None:
            when = ck.parse(ob.when, ("obligations", i, "when"))
            ck.check_bool(when, f"'when' of obligation {ob.id!r}")
        require = ck.parse(ob.require, ("obligations", i, "require"))
        ck.check_bool(require, f"'require' of obligation {ob.id!r}")
        mode, hold = spec.obligation_release(ob)
        obligations.append(ObligationPlan(i, ob.id, ob.description, when, require, ob.within_cycles,
                                          Response(ob.response), ob.when, ob.require, mode, int(hold)))
    signals = []
    big = 1.7976931348623157e308
    for slot, (name, sig) in enumerate(spec.signals.items()):
        lo, hi = (sig.range if sig.range is not None else (-big, big))
        ty = ck.names[name]
        signals.append(SignalSlot(name, slot, sig.type, float(lo), float(hi), ty.unit))
    slots = {s.name: s.slot for s in signals}
    slots[RISK_NAME] = len(signals)
    # every rule's release resolved here, once: consumers read the plan, never the spec again
    r = spec.risk
    exact, cut = release_bound(r.threshold, r.release.hysteresis)
    fmode, fhold = spec.fault_release()
    risk_rule = LatchRule("risk", Response(r.response), r.release.mode == "manual", int(r.release.hold_cycles))
    risk_plan = RiskPlan(float(r.threshold), exact, cut, float(r.alpha), float(r.beta), float(r.gamma), int(r.classes),
                         int(r.unsafe_index), r.variance, None if r.max_age_s is None else float(r.max_age_s),
                         risk_rule, float(r.release.hysteresis))
    cuts = r.judge_cuts()  # risk.judge, or risk.judges (their consensus is the judge input)
    hold = r.judge_may_hold_above_tau
    tiers = Tiers(None if r.confirm_threshold is None else float(r.confirm_threshold),
                  None if cuts is None else (float(cuts[0]), float(cuts[1])),
                  float(hold.ceiling) if hold is not None and cuts is not None else None,
                  _judges(r), bool(r.judges))
    e = r.estimator
    estimator = EstimatorPlan(e.model, e.quantize, None if e.temperature is None else float(e.temperature),
                              e.max_length, e.backend)
    restart = RestartPlan(spec.restart.start, spec.restart.standstill) if "restart" in spec.model_fields_set else None
    return Plan(spec=spec, signals=tuple(signals), risk_slot=len(signals), constants=dict(ck.consts),
                obligations=tuple(obligations), temporal=tuple(ck.temporal), rate_hz=spec.rate_hz, slots=slots,
                on_fault=Response(spec.on_fault), threshold=float(r.threshold), release_exact=exact,
                release_cut=cut, risk_rule=risk_rule,
                fault_rule=LatchRule("fault", Response(spec.on_fault), fmode == "manual", int(fhold)),
                risk_plan=risk_plan, tiers=tiers, estimator=estimator, restart=restart)


def _judges(r) -> tuple[JudgePlan, ...]:
    """Every judge of a spec's ``risk:`` block with where it is written: ``risk.judges[k]`` (a panel,
    even of one) or ``risk.judge``."""
    many = bool(r.judges)
    return tuple(JudgePlan(f"risk.judges[{k}]" if many else "risk.judge", j.url, j.model, float(j.timeout_s),
                           j.api_key_env, j.prompt, float(j.safe_below), float(j.unsafe_from), j.canaries.path,
                           float(j.canaries.every_s), int(j.canaries.every_texts))
                 for k, j in enumerate(r.judge_list))
