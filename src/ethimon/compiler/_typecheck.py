"""The type checker: resolve names, check types, units and windows, and build the :class:`Plan`.

The plan's data types live in ``compiler/_plan.py``; this module is the checker that fills them.
"""

from __future__ import annotations

import difflib
import math

from ..errors import SpecError
from ..language._expr import (FUNCTIONS, SEPARATION_PARAMS, Binary, BoolLit, Call, ExprSyntaxError, Name,
                          Node, Num, Seconds, Unary, parse_expr, separation_distance)
from ..language import Constant, Response, Spec, seconds_to_cycles
from ._plan import BOOL, MAX_WINDOW, RISK_NAME, ObligationPlan, Plan, RuleRelease, SignalSlot, Ty
from ._risk_formula import release_bound
from ._units import DIMENSIONLESS, Unit, div, format_unit, mul, parse_unit, sqrt_unit

__all__ = ["compile_plan"]


class _Checker:
    def __init__(self, spec: Spec) -> None:
        self.spec = spec
        self.smap = spec.source
        self.types: dict[int, Ty] = {}
        self.windows: dict[int, int | None] = {}
        self.temporal: list[Call] = []
        self.names: dict[str, Ty] = {}
        self.consts: dict[str, float] = {}
        self.loc: tuple = ()
        self.text = ""
        self.folded: dict[int, float] = {}  # id(node) -> value, for constant numeric subexpressions
        self.seconds: dict[int, float] = {}  # id(window node) -> the seconds the author wrote (a window in s)
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
        got = self.types.get(id(node))
        if got is not None:
            return got
        if not self._checking:
            return self._check_tree(node)
        ty = self._check(node)
        self.types[id(node)] = ty
        return ty

    _checking = False

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
        return self.types[id(root)]

    def fold(self, node: Node, value: float) -> None:
        """Record the value of a constant subexpression (refusing overflow to inf/nan)."""
        if not math.isfinite(value):
            raise self.err(node, f"the constant expression {self.snippet(node)!r} is not a finite number "
                                 f"(it evaluates to {value})", hint="check the constants and the arithmetic")
        self.folded[id(node)] = value

    def _check(self, node: Node) -> Ty:
        if isinstance(node, Seconds):
            raise self.err(node, f"a time in seconds ({self.snippet(node)!r}) is only a window of held(), once() "
                                 "or since()", hint="declare a constant with a unit instead, e.g. "
                                 "'t_stop: {value: 0.5, unit: s}', and use its name")
        if isinstance(node, Num):
            if not math.isfinite(node.value):
                raise self.err(node, "number is not finite")
            self.folded[id(node)] = node.value
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
                elif node.id in FUNCTIONS:
                    hint = f"{node.id} is a function: {node.id}(...)"
                else:
                    hint = "declare it under 'signals:' or 'constants:'" + (
                        f"; known names: {', '.join(known)}" if len(known) <= 12 else "")
                raise self.err(node, f"unknown signal {node.id!r}", hint=hint)
            if node.id in self.consts:
                self.folded[id(node)] = self.consts[node.id]
            return ty
        if isinstance(node, Unary):
            if node.op == "not":
                self.need(node.operand, "bool", "'not'")
                return BOOL
            ty = self.need(node.operand, "num", "unary '-'")
            if id(node.operand) in self.folded:
                self.fold(node, -self.folded[id(node.operand)])
            return ty
        if isinstance(node, Binary):
            op = node.op
            if op in ("and", "or", "implies"):
                self.need(node.left, "bool", f"'{op}'")
                self.need(node.right, "bool", f"'{op}'")
                return BOOL
            if op in ("==", "!="):
                a, b = self.check(node.left), self.check(node.right)
                if a.kind != b.kind:
                    raise self.err(node, f"cannot compare {a.show()} with {b.show()} in {self.snippet(node)!r}")
                if a.kind == "num":
                    self.same_unit(node, a, b, f"'{op}'")
                return BOOL
            if op in ("<", "<=", ">", ">="):
                a = self.need(node.left, "num", f"'{op}'")
                b = self.need(node.right, "num", f"'{op}'")
                self.same_unit(node, a, b, f"'{op}'")
                return BOOL
            a = self.need(node.left, "num", f"'{op}'")
            b = self.need(node.right, "num", f"'{op}'")
            x, y = self.folded.get(id(node.left)), self.folded.get(id(node.right))
            if op == "/" and y == 0:
                what = "" if isinstance(node.right, Num) else f": {self.snippet(node.right)!r} is always {y}"
                raise self.err(node.right, f"division by zero{what}",
                               hint="the divisor is a constant 0, so every cycle would fail closed")
            if x is not None and y is not None:
                self.fold(node, x + y if op == "+" else x - y if op == "-" else x * y if op == "*" else x / y)
            if op in ("+", "-"):
                return Ty("num", self.same_unit(node, a, b, f"'{op}'"))
            if op == "*":
                return Ty("num", mul(a.unit, b.unit) if a.unit is not None and b.unit is not None
                          else (a.unit if b.unit is None and _is_literal(node.right) else
                                b.unit if a.unit is None and _is_literal(node.left) else None))
            if op == "/":
                if a.unit is not None and b.unit is not None:
                    return Ty("num", div(a.unit, b.unit))
                if b.unit is None and _is_literal(node.right):
                    return Ty("num", a.unit)
                return Ty("num", None)
            raise self.err(node, f"unknown operator {op!r}")  # pragma: no cover
        if isinstance(node, Call):
            return self.check_call(node)
        raise self.err(node, "unsupported expression")  # pragma: no cover

    def bound(self, node: Call, arg: Node, fname: str) -> int:
        if isinstance(arg, Seconds) or (isinstance(arg, Name) and arg.id in self.consts
                                        and self.names[arg.id].unit == _SECOND):
            return self.bound_seconds(node, arg, fname)
        if isinstance(arg, Num):
            value = arg.value
        elif isinstance(arg, Name) and arg.id in self.consts:
            value = self.consts[arg.id]
            self.types[id(arg)] = Ty("num", None)
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
        self.types[id(arg)] = Ty("num", None)
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
        self.types[id(arg)] = Ty("num", _SECOND)
        self.seconds[id(node)] = float(value)
        return n

    def check_separation(self, node: Call) -> Ty:
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
            v = self.folded.get(id(arg))
            if v is not None and v < 0:
                raise self.err(arg, f"separation_distance() parameter {sym} ({meaning}) is a negative constant: "
                                    f"{self.snippet(arg)!r} is always {v}",
                               hint="speeds, times and distances of the separation distance are magnitudes >= 0; "
                                    "a negative one fails at run time, so every cycle would fail closed")
            vals.append(v)
        if all(v is not None for v in vals):
            self.fold(node, separation_distance(*vals))
        return Ty("num", _SEPARATION_UNITS["S_s"])

    def check_call(self, node: Call) -> Ty:
        f = node.func
        if f not in FUNCTIONS:
            close = difflib.get_close_matches(f, list(FUNCTIONS), n=1)
            hint = f"did you mean {close[0]!r}?" if close else f"functions: {', '.join(FUNCTIONS)}"
            raise self.err(node, f"unknown function {f!r}", hint=hint)
        lo, hi = FUNCTIONS[f]
        nargs = len(node.args)
        if not lo <= nargs <= hi:
            want = str(lo) if lo == hi else f"{lo} to {hi}"
            raise self.err(node, f"{f}() takes {want} arguments, got {nargs}",
                           hint=_SEPARATION_HINT if f == "separation_distance" else None)
        args = node.args
        if f == "abs":
            ty = self.need(args[0], "num", "abs()")
            if id(args[0]) in self.folded:
                self.fold(node, abs(self.folded[id(args[0])]))
            return ty
        if f == "sqrt":
            ty = self.need(args[0], "num", "sqrt()")
            v = self.folded.get(id(args[0]))
            if v is not None:
                if v < 0:
                    raise self.err(args[0], f"square root of a negative constant: {self.snippet(args[0])!r} "
                                            f"is always {v}",
                                   hint="sqrt() of a negative number fails, so every cycle would fail closed")
                self.fold(node, math.sqrt(v))
            try:
                return Ty("num", sqrt_unit(ty.unit))
            except ValueError as exc:
                raise self.err(node, str(exc)) from None
        if f == "separation_distance":
            return self.check_separation(node)
        if f in ("min", "max"):
            tys = [self.need(a, "num", f"{f}()") for a in args]
            unit = tys[0].unit
            for a, t in zip(args[1:], tys[1:]):
                unit = self.same_unit(a, Ty("num", unit), t, f"{f}()")
            vals = [self.folded.get(id(a)) for a in args]
            if all(v is not None for v in vals):
                self.fold(node, (min if f == "min" else max)(vals))
            return Ty("num", unit)
        # temporal operators
        if f == "prev":
            ty = self.check(args[0])
            if nargs == 2:
                ity = self.check(args[1])
                if ity.kind != ty.kind:
                    raise self.err(args[1], f"prev() initial value must be {ty.show()}, got {ity.show()}")
                if ty.kind == "num":
                    self.same_unit(args[1], ty, ity, "prev()")
            self.windows[id(node)] = 1
        elif f in ("held", "once"):
            self.need(args[0], "bool", f"{f}()")
            self.windows[id(node)] = self.bound(node, args[1], f)
            ty = BOOL
        else:  # since
            self.need(args[0], "bool", "since()")
            self.need(args[1], "bool", "since()")
            self.windows[id(node)] = self.bound(node, args[2], f) if nargs == 3 else None
            ty = BOOL
        self.temporal.append(node)  # children were checked (and appended) first
        return ty


_SEPARATION_UNITS = {sym: parse_unit(u) for sym, u, _ in SEPARATION_PARAMS}
_SECOND = parse_unit("s")
_SEPARATION_HINT = ("separation_distance(" + ", ".join(f"{sym} [{u}]" for sym, u, _ in SEPARATION_PARAMS)
                    + "): S_p = v_h*(T_r + T_s) + v_r*T_r + S_s + C + Z_d + Z_r (ISO/TS 15066)")


def _children(node: Node) -> tuple[Node, ...]:
    """Operands the type rules check through :meth:`_Checker.check` (not window bounds)."""
    if isinstance(node, Unary):
        return (node.operand,)
    if isinstance(node, Binary):
        return (node.left, node.right)
    if isinstance(node, Call):
        if node.func in ("held", "once"):
            return node.args[:1]
        if node.func == "since":
            return node.args[:2]
        return node.args
    return ()


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
    return Plan(spec=spec, signals=tuple(signals), risk_slot=len(signals), constants=dict(ck.consts),
                obligations=tuple(obligations), temporal=tuple(ck.temporal), types=ck.types,
                windows=ck.windows, window_seconds=ck.seconds, rate_hz=spec.rate_hz, slots=slots, risk=r, on_fault=Response(spec.on_fault),
                threshold=float(r.threshold), release_exact=exact,
                release_cut=cut,
                risk_rule=RuleRelease("risk", Response(r.response), r.release.mode == "manual",
                                      int(r.release.hold_cycles)),
                fault_rule=RuleRelease("fault", Response(spec.on_fault), fmode == "manual", int(fhold)))
