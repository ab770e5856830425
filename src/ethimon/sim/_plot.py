"""The recording's ``plot.png``: signals, the spec's limits, events and a controller lane.

The limits are read from the spec's own obligations: every comparison ``signal OP bound``
(in ``when`` or ``require``, also inside ``held``/``once``/...) whose bound is arithmetic
over constants and signals (``+ - * /``, ``abs``, ``min``, ``max``, ``sqrt``). A bound that
is one named constant is drawn as a horizontal line (``v_slow = 0.25``); a bound that
depends on signals (the separation rule's protective distance) is evaluated cycle by cycle
from the monitor's inputs and drawn as a curve. Comparisons between two signals, or with a
temporal function or an unknown function in the bound, are not drawn (listed as skipped).
A bound ``separation_distance(...)`` (the language's ISO/TS 15066 S_p) is drawn as "S_p".
The risk panel gets τ (``risk.threshold``) and, for an automatic release, τ − δ.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["Limit", "spec_limits", "build_figure", "plot_trace", "PANELS", "EVENT_LABELS"]

#: panel -> the signals drawn on it (with a limit from the spec when it has one)
PANELS: dict[str, tuple[str, ...]] = {
    "risk": ("risk",),
    "human_distance": ("human_distance",),
    "ee_speed": ("ee_speed",),
    "joint_speed": ("joint_speed_max",),
    "joint_accel": (),
    "contact_force": ("contact_force",),
    "hazard_distance": ("hazard_distance",),
    "controller": (),
}
_YLABEL = {"payload": "height (m)", "risk": "risk R_e", "human_distance": "human dist. (m)", "ee_speed": "ee speed (m/s)",
           "joint_speed": "joint speed (rad/s)", "joint_accel": "joint accel.\n(× rated)",
           "contact_force": "contact force (N)", "hazard_distance": "hazard–person (m)",
           "controller": "controller"}
#: event name -> how captions, frames and the plot call it
EVENT_LABELS = {
    "first_violation": "first violation", "first_fault": "first fault", "override": "override",
    "escalation": "escalation", "closest_approach": "closest approach",
    "peak_contact_force": "peak contact force", "standstill": "standstill", "power_off": "power off",
    "object_dropped": "object dropped", "task_stopped": "task stopped (object missing)",
    "safe_pose": "safe pose reached", "release": "release",
    "power_off_refused": "power-off refused (brakes cannot hold)", "payload_fall": "payload fell",
    "ack_accepted": "acknowledgement accepted", "ack_refused": "acknowledgement refused",
}
_LANE = ("task", "safe_pose", "stop_2", "stop_1", "stop_0")
_LANE_COLOR = {"task": "tab:green", "safe_pose": "tab:blue", "stop_2": "gold", "stop_1": "tab:orange",
               "stop_0": "tab:red"}
_NONE_M = 10.0  # human_distance / hazard_distance when there is no person / hazard (ArmSim)
_CMP_FLIP = {"<": ">", "<=": ">=", ">": "<", ">=": "<=", "==": "==", "!=": "!="}
_ARITH = {"+": np.add, "-": np.subtract, "*": np.multiply, "/": np.divide}
_FUNCS = {"abs": lambda a: np.abs(a[0]), "sqrt": lambda a: np.sqrt(a[0]),
          "min": lambda a: np.minimum.reduce(a), "max": lambda a: np.maximum.reduce(a)}


@dataclass(frozen=True)
class Limit:
    """One ``signal OP bound`` comparison of a spec obligation.

    Attributes:
        rule: the obligation id.
        part: ``"when"`` or ``"require"``.
        signal: the signal compared (on the left of ``op``).
        op: the comparison with the signal on its left.
        bound: the bound's source text.
        constant: the constant's name when the bound is one named constant.
        value: the bound when it is constant (``None``: it depends on signals).
    """

    rule: str
    part: str
    signal: str
    op: str
    bound: str
    constant: str | None
    value: float | None
    _node: Any = None
    signals_used: frozenset[str] = frozenset()

    @property
    def label(self) -> str:
        if self.value is not None:
            name = self.constant or self.bound
            return f"{name} = {self.value:g} ({self.rule})"
        uses = sorted(n for n in _names(self._node) if n in self.signals_used) if self._node is not None else []
        what = "S_p" if getattr(self._node, "func", None) == "separation_distance" else "bound"
        return f"{what} ({self.rule}: {self.signal} {self.op} f({', '.join(uses)}))"

    def values(self, columns: Mapping[str, np.ndarray], constants: Mapping[str, float], n: int) -> np.ndarray:
        """The bound per cycle (``n`` values) from the signal ``columns``."""
        if self.value is not None:
            return np.full(n, self.value)
        with np.errstate(all="ignore"):
            return np.broadcast_to(np.asarray(_eval(self._node, columns, constants), dtype=float), (n,)).copy()

    def as_dict(self) -> dict[str, Any]:
        return {"rule": self.rule, "part": self.part, "signal": self.signal, "op": self.op,
                "bound": self.bound, "constant": self.constant, "value": self.value}


def spec_constants(spec: Any) -> dict[str, float]:
    """The spec's constants as ``name -> value``."""
    out = {}
    for k, v in (getattr(spec, "constants", None) or {}).items():
        out[k] = float(getattr(v, "value", v))
    return out


def _sp_function():
    from ..language import _expr  # the language's own S_p (ISO/TS 15066), + and * only: arrays work
    return getattr(_expr, "separation_distance", None)


def _drawable(node: Any, names: set[str]) -> bool:
    """``node`` is arithmetic over ``names`` (constants and signals) that :func:`_eval` computes."""
    from ..language._expr import Binary, Call, Name, Num, Unary
    if isinstance(node, Num):
        return True
    if isinstance(node, Name):
        return node.id in names
    if isinstance(node, Unary):
        return node.op == "-" and _drawable(node.operand, names)
    if isinstance(node, Binary):
        return node.op in _ARITH and _drawable(node.left, names) and _drawable(node.right, names)
    if isinstance(node, Call):
        known = node.func in _FUNCS or (node.func == "separation_distance" and _sp_function() is not None)
        return known and all(_drawable(a, names) for a in node.args)
    return False


def _eval(node: Any, columns: Mapping[str, np.ndarray], constants: Mapping[str, float]) -> Any:
    """The value of a :func:`_drawable` bound (numpy arrays for signal columns)."""
    from ..language._expr import Binary, Name, Num, Unary
    if isinstance(node, Num):
        return float(node.value)
    if isinstance(node, Name):
        return constants[node.id] if node.id in constants else columns.get(node.id, math.nan)
    if isinstance(node, Unary):
        return np.negative(_eval(node.operand, columns, constants))
    if isinstance(node, Binary):
        return _ARITH[node.op](_eval(node.left, columns, constants), _eval(node.right, columns, constants))
    args = [np.asarray(_eval(a, columns, constants), dtype=float) for a in node.args]
    if node.func in _FUNCS:
        return _FUNCS[node.func](args)
    return _sp_function()(*args)


def _names(node: Any) -> set[str]:
    from ..language._expr import Name, walk
    return {n.id for n in walk(node) if isinstance(n, Name)}


def spec_limits(spec: Any) -> tuple[list[Limit], list[str]]:
    """``(limits, skipped)``: the drawable comparisons of ``spec``'s obligations and, as text,
    the comparisons on a signal that were not drawable."""
    from ..language._expr import Binary, Name, parse_expr, to_source, walk
    if spec is None:
        return [], []
    constants = spec_constants(spec)
    signals = set(getattr(spec, "signals", None) or ())
    limits: list[Limit] = []
    skipped: list[str] = []
    for ob in getattr(spec, "obligations", ()):
        for part in ("when", "require"):
            src = getattr(ob, part, None)
            if not src:
                continue
            try:
                tree = parse_expr(src)
            except Exception:  # noqa: BLE001 - a loaded spec parses; never let the plot fail a run
                continue
            for n in walk(tree):
                if not (isinstance(n, Binary) and n.op in _CMP_FLIP):
                    continue
                if isinstance(n.left, Name) and n.left.id in signals:
                    sig, op, other = n.left.id, n.op, n.right
                elif isinstance(n.right, Name) and n.right.id in signals:
                    sig, op, other = n.right.id, _CMP_FLIP[n.op], n.left
                else:
                    continue
                text = to_source(other)
                if (sig in _names(other) or (isinstance(other, Name) and other.id in signals)
                        or not _drawable(other, set(constants) | signals)):
                    skipped.append(f"{ob.id}.{part}: {sig} {op} {text}")
                    continue
                const = other.id if isinstance(other, Name) and other.id in constants else None
                value = None
                if not (_names(other) & signals):
                    value = float(_eval(other, {}, constants))
                limits.append(Limit(ob.id, part, sig, op, text, const, value, other,
                                    frozenset(_names(other) & signals)))
    return limits, skipped


def _column(trace: Sequence[Any], name: str) -> np.ndarray:
    return np.array([_f(r.signals.get(name, math.nan)) for r in trace], dtype=float)


def _f(v: Any) -> float:
    try:
        return float(v)
    except (TypeError, ValueError):
        return math.nan


def _segments(t: np.ndarray, dt: float, values: Sequence[Any]) -> list[tuple[Any, float, float]]:
    """Runs of equal ``values`` as ``(value, start, width)``."""
    out: list[tuple[Any, float, float]] = []
    start = 0
    for i in range(1, len(values) + 1):
        if i == len(values) or values[i] != values[start]:
            out.append((values[start], float(t[start]), float(t[i - 1] + dt - t[start])))
            start = i
    return out


def _letters(i: int) -> str:
    s = ""
    i += 1
    while i:
        i, r = divmod(i - 1, 26)
        s = chr(65 + r) + s
    return s


def _draw_controller_lane(a: Any, t: np.ndarray, dt: float, trace: Sequence[Any],
                          extra: Mapping[str, Any] | None = None) -> None:
    """The bottom panel: which controller commanded the arm when; override, faults and rules beneath
    (with ``extra``: motor power, the brakes and the acknowledgements too)."""
    # controller lane: which controller commanded the arm when; override and faults beneath
    ctrl = [r.controller for r in trace]
    rows = list(_LANE) + [c for c in dict.fromkeys(ctrl) if c not in _LANE]
    names = ["rule fires", "fault", "override", *rows]
    if extra is not None:
        names = ["acknowledge", "brakes", "power", *names]
    ypos = {name: i for i, name in enumerate(names)}
    for c, x0, w in _segments(t, dt, ctrl):
        a.broken_barh([(x0, w)], (ypos[c] - 0.35, 0.7), facecolors=_LANE_COLOR.get(c, "tab:gray"),
                      gid=f"lane:{c}")
    for v, x0, w in _segments(t, dt, [bool(r.override) for r in trace]):
        if v:
            a.broken_barh([(x0, w)], (ypos["override"] - 0.35, 0.7), facecolors="tab:red", alpha=0.5)
    for v, x0, w in _segments(t, dt, [bool(r.faults) for r in trace]):
        if v:
            a.broken_barh([(x0, w)], (ypos["fault"] - 0.35, 0.7), facecolors="tab:orange", alpha=0.7)
    # every cycle a rule fires: grey while the task runs, red during a response (a rule firing
    # while the arm already responds is what a reviewer looks for)
    for (fires, resp), x0, w in _segments(t, dt, [(bool(r.violations), r.controller != "task")
                                                  for r in trace]):
        if fires:
            a.broken_barh([(x0, w)], (ypos["rule fires"] - 0.35, 0.7),
                          facecolors="tab:red" if resp else "0.6",
                          gid="rules:response" if resp else "rules:task")
    if extra is not None:
        powered = list(extra.get("powered") or [])
        for v, x0, w in _segments(t[:len(powered)], dt, powered):
            a.broken_barh([(x0, w)], (ypos["power"] - 0.35, 0.7), facecolors="tab:green" if v else "0.85",
                          gid="power:on" if v else "power:off")
        brakes = list(extra.get("brakes") or [])
        color = {"engaged": "0.25", "refused": "tab:red", "engaging": "0.6"}
        for v, x0, w in _segments(t[:len(brakes)], dt, brakes):
            if v in color:
                a.broken_barh([(x0, w)], (ypos["brakes"] - 0.35, 0.7), facecolors=color[v],
                              hatch="//" if v == "refused" else None, gid=f"brakes:{v}")
        for ts, ok, _msg in extra.get("acks") or ():
            a.plot([ts], [ypos["acknowledge"]], marker="^" if ok else "x", ms=8, ls="none",
                   color="tab:green" if ok else "tab:red", gid="ack:accepted" if ok else "ack:refused")
    a.set_yticks(range(len(names)))
    a.set_yticklabels(names, fontsize=7)
    a.set_ylim(-0.6, len(names) - 0.4)
    a.set_xlabel("simulated time (s)")


def _draw_extra(ax: Mapping[str, Any], t: np.ndarray, dt: float, trace: Sequence[Any],
                cols: Mapping[str, np.ndarray], extra: Mapping[str, Any], meta: dict[str, Any]) -> None:
    """The payload panel, the slow-zone breaches and the per-person hazard angles (issue 32)."""
    if "payload" in ax:
        a = ax["payload"]
        gz = np.asarray(extra["grasp_z"], dtype=float)
        a.plot(t[:len(gz)], gz, color="0.3", label="grasp point")
        for name, zs in (extra.get("objects_z") or {}).items():
            a.plot(t[:len(zs)], zs, "--", label=f"{name} (centre)")
        powered = list(extra.get("powered") or [])
        for v, x0, w in _segments(t[:len(powered)], dt, powered):
            if not v:  # how far the grasp point fell from where power went off
                i0 = int(round((x0 - t[0]) / dt))
                z_off = float(gz[max(i0 - 1, 0)])
                low = float(np.min(gz[i0:i0 + int(round(w / dt))]))
                a.axhline(z_off, color="tab:red", ls=":", lw=0.8, gid="power_off_height")
                if z_off - low > 0.005:
                    a.annotate(f"fell {z_off - low:.3f} m after power-off", (x0, low), fontsize=7,
                               color="tab:red", xytext=(4, -10), textcoords="offset points", gid="fall")
        a.set_ylabel("height (m)", fontsize=9)
    sz = extra.get("slow_zone")
    meta["slow_zone_breach_cycles"] = 0
    if sz is not None:
        d_lim, v_lim = sz
        d = np.array([r.human_distance_true_m for r in trace], dtype=float)
        v = cols["ee_speed"]
        bad = (d < d_lim) & (v > v_lim + 1e-9)
        meta["slow_zone_breach_cycles"] = int(np.sum(bad))
        if bad.any():
            ax["ee_speed"].plot(t[bad], v[bad], "o", ms=3, color="tab:red", gid="slow_zone_breach",
                                label=f"over {v_lim:g} m/s within {d_lim:g} m ({int(np.sum(bad))} cycles)")
    for person, angles in (extra.get("hazard_angles") or {}).items():  # hook: per-person hazard angles
        if "hazard_twin" not in meta:
            meta["hazard_twin"] = ax["hazard_distance"].twinx()
            meta["hazard_twin"].set_ylabel("axis from person (°)", fontsize=8)
        meta["hazard_twin"].plot(t[:len(angles)], angles, ":", lw=1, label=f"axis vs {person}",
                                 gid=f"hazard_angle:{person}")
    meta.pop("hazard_twin", None)


def _draw_events(ax: Mapping[str, Any], events: Sequence[Mapping[str, Any]], meta: dict[str, Any]) -> list[str]:
    """The events on every panel (lettered above the top one); returns the legend lines under the plot."""
    # events: one dashed line per distinct time on every panel, lettered above the top panel
    by_time: dict[float, list[Mapping[str, Any]]] = {}
    for ev in events:
        by_time.setdefault(round(float(ev["t_s"]), 9), []).append(ev)
    lines = []
    for i, (te, evs) in enumerate(sorted(by_time.items())):
        letter = _letters(i)
        for p, a in ax.items():
            a.axvline(te, color="k", ls="--", lw=0.8, alpha=0.55, gid=f"event:{letter}")
        ax["risk"].annotate(letter, (te, 1.0), xycoords=("data", "axes fraction"), xytext=(0, 3),
                            textcoords="offset points", ha="center", va="bottom", fontsize=8,
                            fontweight="bold")
        what = ", ".join(EVENT_LABELS.get(e["event"], e["event"])
                         + (f" ({e['detail']})" if e.get("detail") else "") for e in evs)
        lines.append(f"{letter}  {te:.3f} s: {what}")
        meta["event_marks"].append({"letter": letter, "t_s": te, "events": [e["event"] for e in evs]})
    return lines


def build_figure(trace: Sequence[Any], *, spec: Any = None, events: Sequence[Mapping[str, Any]] = (),
                 title: str | None = None, dt: float | None = None, extra: Mapping[str, Any] | None = None):
    """The recording's figure and what was drawn on it.

    Args:
        trace: the run's :class:`~ethimon.sim.CycleRecord` list.
        spec: the monitor's spec (τ, limits); ``None`` draws none.
        events: dicts with ``event``, ``t_s`` (and ``detail``): a vertical line on every
            panel, one letter per distinct time, explained under the plot.
        title: the figure's title.
        dt: the control period (default: from the trace).
        extra: what an assessor needs beyond the trace (issue 32; the :class:`~._record.Recorder`
            collects it per cycle): ``powered`` and ``brakes`` (``"off"``, ``"engaged"``,
            ``"refused"``: a power-off refused because the brakes cannot hold) per cycle, ``grasp_z``
            (grasp point height, m) and ``objects_z`` (name -> height per cycle, the objects the arm
            held) for a ``payload`` panel, ``acks`` (``(t_s, accepted, message)``), ``slow_zone``
            (``(D, V)``: the spec's near-human speed rule; cycles within D over V are marked on the
            ee-speed panel) and ``hazard_angles`` (a hook: person -> angle (deg) per cycle between a
            held hazard's axis and the direction to that person, drawn on the hazard panel).
            Without it the figure is as before (eight panels).

    Returns:
        ``(figure, meta)``; ``meta`` has ``panels``, ``tau``, ``limits`` (drawn),
        ``limits_skipped``, ``event_marks`` (letter, time, events) and, with ``extra``,
        ``slow_zone_breach_cycles``.
    """
    import matplotlib

    matplotlib.use("Agg", force=False)
    from matplotlib.figure import Figure

    n = len(trace)
    t = np.array([r.t_s for r in trace], dtype=float)
    if dt is None:
        dt = float(t[1] - t[0]) if n > 1 else 1.0 / 60
    cols = {s: _column(trace, s) for s in ("human_distance", "ee_speed", "contact_force",
                                           "joint_speed_max", "hazard_distance")}
    for r in trace[:1]:
        for k in r.signals:
            cols.setdefault(k, _column(trace, k))
    constants = spec_constants(spec)
    limits, skipped = spec_limits(spec)
    panels = list(PANELS)
    if extra is not None and extra.get("grasp_z") is not None:
        panels.insert(panels.index("controller"), "payload")
    heights = [1.0] * (len(panels) - 1) + [0.9 if extra is None else 1.3]
    fig = Figure(figsize=(12, 17 if len(panels) == len(PANELS) else 19))
    axes = fig.subplots(len(panels), 1, sharex=True, gridspec_kw={"height_ratios": heights})
    ax = dict(zip(panels, axes))
    meta: dict[str, Any] = {"panels": panels, "tau": None, "limits": [], "limits_skipped": skipped,
                            "event_marks": []}

    a = ax["risk"]
    a.plot(t, [math.nan if r.risk is None else r.risk for r in trace], color="tab:purple", label="R_e")
    risk_cfg = getattr(spec, "risk", None)
    if risk_cfg is not None:
        tau = float(risk_cfg.threshold)
        a.axhline(tau, color="tab:red", ls="--", lw=1.2, label=f"τ = {tau:g}", gid="tau")
        meta["tau"] = tau
        rel = getattr(risk_cfg, "release", None)
        if rel is not None and getattr(rel, "mode", "") == "auto" and rel.hysteresis > 0:
            a.axhline(tau - rel.hysteresis, color="tab:red", ls=":", lw=1,
                      label=f"τ − δ = {tau - rel.hysteresis:g} (release)", gid="tau_release")
        a.set_ylim(-0.02, 1.02)
    a.set_ylabel(_YLABEL["risk"])

    a = ax["human_distance"]
    a.plot(t, cols["human_distance"], label="monitor input")
    a.plot(t, [r.human_distance_true_m for r in trace], "--", alpha=0.6, label="simulated")
    # one unit per axis: the end effector in m/s, the joints in rad/s, accelerations × rated
    ax["ee_speed"].plot(t, cols["ee_speed"], label="ee speed (monitor input)")
    ax["joint_speed"].plot(t, [r.joint_speed_max_rad_s for r in trace], color="tab:orange",
                           label="max |q̇| (physics steps)")
    a = ax["joint_accel"]
    a.plot(t, [getattr(r, "accel_ratio", math.nan) for r in trace], color="tab:olive",
           label="max |q̈_j| / rated q̈_max,j")
    a.axhline(1.0, color="tab:red", ls="--", lw=1.2, label="rated (FCI limits)", gid="rated_accel")
    ax["contact_force"].plot(t, cols["contact_force"], color="tab:brown", label="monitor input")
    ax["hazard_distance"].plot(t, cols["hazard_distance"], color="tab:red", label="monitor input")
    for p, attr in (("contact_force", "contact_force_true_n"), ("hazard_distance", "hazard_distance_true_m")):
        if trace and hasattr(trace[0], attr):  # the simulated value (also during a sensor dropout)
            ax[p].plot(t, [getattr(r, attr) for r in trace], "--", color="0.2", alpha=0.6, label="simulated")

    for p, note in (("human_distance", "no person in the scene"),
                    ("hazard_distance", "no hazard-tagged object near a person")):
        v = cols[p]
        v = v[np.isfinite(v)]
        if v.size and np.all(v >= _NONE_M - 1e-9):  # the sim's value for "none"
            ax[p].text(0.5, 0.3, f"{note} ({_NONE_M:g} m = none)", transform=ax[p].transAxes,
                       ha="center", va="center", fontsize=9, color="0.35")
    where = {s: p for p, sigs in PANELS.items() for s in sigs}
    styles = (":", "-.", (0, (5, 2)), (0, (1, 1)))
    drawn_per_panel: dict[str, int] = {}
    for lim in limits:
        p = where.get(lim.signal)
        if p is None:
            meta["limits_skipped"].append(f"{lim.rule}.{lim.part}: {lim.signal} {lim.op} {lim.bound} "
                                          "(no panel for this signal)")
            continue
        k = drawn_per_panel.get(p, 0)
        drawn_per_panel[p] = k + 1
        y = lim.values(cols, constants, n)
        ls = styles[k % len(styles)]
        gid = f"limit:{lim.rule}:{lim.part}:{lim.signal}"
        if lim.value is not None:
            ax[p].axhline(lim.value, color="0.35", ls=ls, lw=1, label=lim.label, gid=gid)
        else:
            ax[p].plot(t, y, color="0.35", ls=ls, lw=1, label=lim.label, gid=gid)
        meta["limits"].append({**lim.as_dict(), "panel": p})
    for p, a in ax.items():
        if p != "controller":
            a.set_ylabel(_YLABEL[p], fontsize=9)
            handles, labels = a.get_legend_handles_labels()
            if handles:  # beside the panel, never over the data; long labels wrapped to fit
                import textwrap
                a.legend(handles, ["\n".join(textwrap.wrap(lb, 34)) for lb in labels], loc="upper left",
                         bbox_to_anchor=(1.005, 1.0), fontsize=7, borderaxespad=0.0)

    if extra is not None:
        _draw_extra(ax, t, dt, trace, cols, extra, meta)
        for p in ("payload", "ee_speed", "hazard_distance"):
            if p in ax:
                handles, labels = ax[p].get_legend_handles_labels()
                if handles:
                    import textwrap
                    ax[p].legend(handles, ["\n".join(textwrap.wrap(lb, 34)) for lb in labels], loc="upper left",
                                 bbox_to_anchor=(1.005, 1.0), fontsize=7, borderaxespad=0.0)
    _draw_controller_lane(ax["controller"], t, dt, trace, extra)

    lines = _draw_events(ax, events, meta)
    if n:
        axes[-1].set_xlim(float(t[0]), float(t[-1] + dt))
    if title:  # wrapped to the figure's width: never cut off at its edges
        import textwrap
        fig.suptitle("\n".join(textwrap.wrap(title, 110)), fontsize=10)
    foot = 0.012 + 0.0125 * len(lines)
    if lines:
        fig.text(0.01, 0.005, "\n".join(lines), fontsize=7, va="bottom", ha="left", family="monospace")
    top = 1.0 - (0.012 * (1 + len(title) // 110) if title else 0.0)
    fig.tight_layout(rect=(0, foot, 1, top))
    fig.subplots_adjust(right=min(fig.subplotpars.right, 0.76))  # room for the legends
    return fig, meta


def plot_trace(trace: Sequence[Any], path: str, title: str | None = None, *, spec: Any = None,
               events: Sequence[Mapping[str, Any]] = (), dt: float | None = None,
               extra: Mapping[str, Any] | None = None) -> dict[str, Any]:
    """Draw :func:`build_figure` to ``path`` (PNG, Agg backend); returns its ``meta``."""
    fig, meta = build_figure(trace, spec=spec, events=events, title=title, dt=dt, extra=extra)
    fig.savefig(path, dpi=90)
    return meta
