"""``--record DIR``: frames with an overlay at every event, a trace, a plot and ``summary.json``.

Events (each with its cycle and time; :func:`trace_events` defines them on the per-cycle
trace, so a recording and a test compute the same list):

- ``first_violation``: the first cycle whose decision names a violated rule;
- ``first_fault``: the first cycle with a fail-closed fault;
- ``override``: every cycle whose override is true after one without (the first, and any after
  a release);
- ``escalation``: a cycle where the controller commanding the arm becomes more severe
  than every controller before it, after the first response (e.g. ``safe_pose → stop_0``);
- ``closest_approach``: the smallest simulated human distance of the run (first such cycle);
- ``peak_contact_force``: the largest simulated contact force of the run (when any was measured);
- ``standstill``: after the first stop controller (``stop_0/1/2``), the first cycle in which
  every joint stayed below 0.01 rad/s in every physics substep;
- ``power_off``: the first cycle after which motor power is off (stop 0, the end of a stop 1);
- ``object_dropped``: every cycle in which a held object left the gripper other than by the
  task's release (detail: ``"knife (power_off)"`` or ``"(slipped)"``);
- ``task_stopped``: the cycle the task found the object it should carry not in the gripper
  and stopped (a stop 2; it is not resumed);
- ``safe_pose``: the first cycle the safe-pose controller ends within the spec's tolerance;
- ``release``: every cycle whose override is false after an override.

A recording adds (issue 32; from the simulator and the run's result, not the trace):
``power_off_refused`` (a stop 0/1 whose power-off the brakes could not hold, with the reason),
``payload_fall`` (the grasp point 0.02 m below where it was at a power-off),
``ack_accepted`` / ``ack_refused`` (every acknowledgement, with its message).

A frame shows the state after its cycle's physics. Frames of events known only at the
end (closest approach, peak force) are rendered after the run from a snapshot of every
body's pose and joint positions taken when the running extreme was reached.
"""

from __future__ import annotations

import csv
import json
import math
import os
import time
from collections.abc import Sequence
from typing import Any

import numpy as np

from ._control import SEVERITY
from ._plot import EVENT_LABELS, plot_trace
from ._result import check_sim_expectations
from ._rules import near_human_speed_rule

__all__ = ["Recorder", "plot_trace", "trace_events", "EVENT_LABELS", "STANDSTILL_RAD_S", "bounds_broken"]

_SIGNALS = ("human_distance", "ee_speed", "contact_force", "joint_speed_max", "hazard_distance")
#: standstill: every joint below this in every physics substep (the sim expectation's definition)
STANDSTILL_RAD_S = 0.01
#: a grasp point this far below its height at a power-off has fallen (event ``payload_fall``)
FALL_M = 0.02
_STOPS = ("stop_0", "stop_1", "stop_2")


def _clean(v: Any) -> Any:
    if isinstance(v, float) and not math.isfinite(v):
        return None
    return v


def _sev(controller: str) -> int:
    return SEVERITY.get(controller, 0)


def _num(v: Any) -> float:
    try:
        f = float(v)
    except (TypeError, ValueError):
        return math.nan
    return f


class _EventTracker:
    """Finds the events cycle by cycle (:func:`trace_events` is this over a whole trace)."""

    def __init__(self, safe_tol: float, has_humans: bool = True) -> None:
        self.safe_tol = safe_tol
        self.has_humans = has_humans
        self.events: list[dict[str, Any]] = []
        self._seen: set[str] = set()
        self._max_sev = 0
        self._max_ctrl = "none"
        self._prev_override = False
        self._overridden = False
        self._released = False
        self._stop_started = False
        self.closest: dict[str, Any] | None = None
        self.peak: dict[str, Any] | None = None

    def _once(self, name: str, rec: Any, detail: str, value: float | None = None) -> list[dict]:
        if name in self._seen:
            return []
        self._seen.add(name)
        return [self._add(name, rec, detail, value)]

    def _add(self, name: str, rec: Any, detail: str, value: float | None = None) -> dict[str, Any]:
        ev = {"event": name, "cycle": rec.cycle, "t_s": round(float(rec.t_s), 6), "detail": detail,
              "value": value}
        self.events.append(ev)
        return ev

    def update(self, rec: Any) -> tuple[list[dict[str, Any]], list[str]]:
        """``(events at this cycle, running extremes improved at this cycle)``."""
        out: list[dict[str, Any]] = []
        if rec.violations:
            out += self._once("first_violation", rec, ", ".join(rec.violations))
        if rec.faults:
            out += self._once("first_fault", rec, str(rec.faults[0]))
        if rec.override:
            if not self._prev_override:  # every rising edge: the first, and any after a release
                out.append(self._add("override", rec, rec.response + (" (again, after a release)"
                                                                      if self._released else "")))
            self._overridden = True
        elif self._prev_override:
            out.append(self._add("release", rec, ""))
            self._released = True
        self._prev_override = bool(rec.override)
        sev = _sev(rec.controller)
        if sev > self._max_sev:
            if self._max_sev > 0:
                out.append(self._add("escalation", rec, f"{self._max_ctrl} → {rec.controller}"
                                     + (" (after a release)" if self._released else "")))
            self._max_sev, self._max_ctrl = sev, rec.controller
        if rec.controller in _STOPS:
            self._stop_started = True
        if self._stop_started and rec.joint_speed_max_rad_s < STANDSTILL_RAD_S:
            out += self._once("standstill", rec, f"{rec.controller}, max joint speed "
                                                 f"{rec.joint_speed_max_rad_s:.4f} rad/s",
                              float(rec.joint_speed_max_rad_s))
        for what in getattr(rec, "dropped", ()):
            out.append(self._add("object_dropped", rec, what))
        if getattr(rec, "task_stopped", ""):
            out.append(self._add("task_stopped", rec, rec.task_stopped))
        if not getattr(rec, "powered", True):
            out += self._once("power_off", rec, rec.controller)
        if (self._overridden and rec.controller == "safe_pose"
                and rec.safe_pose_error_rad <= self.safe_tol):
            out += self._once("safe_pose", rec, f"error {rec.safe_pose_error_rad:.4f} rad",
                              float(rec.safe_pose_error_rad))
        improved = []
        d = _num(rec.human_distance_true_m)
        if self.has_humans and math.isfinite(d) and (self.closest is None or d < self.closest["value"]):
            self.closest = {"event": "closest_approach", "cycle": rec.cycle, "t_s": round(float(rec.t_s), 6),
                            "detail": f"{d:.3f} m", "value": d}
            improved.append("closest_approach")
        f = _num(getattr(rec, "contact_force_true_n", rec.signals.get("contact_force", math.nan)))
        if math.isfinite(f) and f > 0 and (self.peak is None or f > self.peak["value"]):
            self.peak = {"event": "peak_contact_force", "cycle": rec.cycle, "t_s": round(float(rec.t_s), 6),
                         "detail": f"{f:.1f} N", "value": f}
            improved.append("peak_contact_force")
        return out, improved

    def finish(self) -> list[dict[str, Any]]:
        """Every event, the extremes included, in order of cycle."""
        evs = list(self.events) + [e for e in (self.closest, self.peak) if e is not None]
        order = {name: i for i, name in enumerate(EVENT_LABELS)}
        return sorted(evs, key=lambda e: (e["cycle"], order.get(e["event"], 99)))


def trace_events(trace: Sequence[Any], *, safe_tol: float = 0.02, has_humans: bool = True) -> list[dict[str, Any]]:
    """The events of a run from its per-cycle trace (see the module docstring).

    Args:
        trace: :class:`~ethimon.sim.CycleRecord` list.
        safe_tol: the spec's safe-pose tolerance (rad).
        has_humans: the scene has people (else no closest approach).

    Returns:
        Dicts ``{event, cycle, t_s, detail, value}`` ordered by cycle.
    """
    tr = _EventTracker(safe_tol, has_humans)
    for r in trace:
        tr.update(r)
    return tr.finish()


def _snapshot(sim: Any) -> list[tuple]:
    """Every body's base pose and joint positions (enough to render; velocities are not kept)."""
    p, cid = sim._p, sim.cid
    out = []
    for i in range(p.getNumBodies(physicsClientId=cid)):
        b = p.getBodyUniqueId(i, physicsClientId=cid)
        pos, orn = p.getBasePositionAndOrientation(b, physicsClientId=cid)
        nj = p.getNumJoints(b, physicsClientId=cid)
        qs = tuple(s[0] for s in p.getJointStates(b, range(nj), physicsClientId=cid)) if nj else ()
        out.append((b, pos, orn, qs))
    return out


def _restore(sim: Any, snap: list[tuple]) -> None:
    p, cid = sim._p, sim.cid
    for b, pos, orn, qs in snap:
        p.resetBasePositionAndOrientation(b, pos, orn, physicsClientId=cid)
        for j, q in enumerate(qs):
            p.resetJointState(b, j, q, physicsClientId=cid)


class Recorder:
    """Collects frames during a run and writes the trace, plot and summary at the end.

    Args:
        directory: where the recording goes (created).
        sim: the :class:`~ethimon.sim.ArmSim`.
        spec: the monitor's spec (τ, limits and name for the plot); optional.
        block: the scenario's :class:`~ethimon.sim.SimBlock` (for the plot's pass/fail title).
        safe_tol: the spec's safe-pose tolerance (rad), for the ``safe_pose`` event.
        name: the scenario's name (default: the directory's name).
    """

    def __init__(self, directory: str, sim: Any, *, spec: Any = None, block: Any = None,
                 safe_tol: float = 0.02, name: str | None = None) -> None:
        from ._overlay import frame_cameras

        self.dir = directory
        self.sim = sim
        self.spec = spec
        self.block = block
        self.name = name or os.path.basename(os.path.normpath(directory))
        os.makedirs(directory, exist_ok=True)
        self.files: list[str] = []
        self.seconds = 0.0  # time spent on frames and events (kept out of the realtime factor)
        self.cameras = frame_cameras(sim)
        self.tracker = _EventTracker(safe_tol, bool(getattr(sim, "humans", None)))
        self.last: Any = None
        self._frame_at: dict[int, str] = {}        # cycle -> frame after that cycle's physics
        self._caption_at: dict[int, list[str]] = {}
        self._snaps: dict[str, tuple[int, list[tuple]]] = {}
        self._parts: dict[str, dict[str, Any]] = {}  # frame path -> what it was composed from
        self.events: list[dict[str, Any]] = []
        #: per cycle, what the trace does not carry (power, brakes, payload heights): for the plot
        self.extra: dict[str, Any] = {"powered": [], "brakes": [], "grasp_z": [], "objects_z": {}}
        self._carried: set[str] = set()
        self._n_brake_log = 0
        self._off_z: float | None = None
        self._fell = False

    def _observe_power(self, rec: Any) -> list[dict[str, Any]]:
        """Power, brakes and payload height after this cycle; the events only the simulator sees."""
        sim, ex, evs = self.sim, self.extra, []
        if getattr(sim, "held", None):
            self._carried.add(sim.held)
        refused = getattr(sim, "power_off_refused", None)
        ex["powered"].append(bool(sim.powered))
        ex["brakes"].append("refused" if refused and sim.powered else "" if sim.powered else
                            "engaged" if getattr(sim, "brakes_engaged", False) else "engaging")
        z = float(sim._grasp_z()) if hasattr(sim, "_grasp_z") else math.nan
        ex["grasp_z"].append(z)
        zs = sim.object_z() if self._carried else {}
        for name in self._carried:
            col = ex["objects_z"].setdefault(name, [math.nan] * (len(ex["grasp_z"]) - 1))
            col.append(float(zs.get(name, math.nan)))
        log = getattr(sim, "brake_log", [])
        for _t, what in log[self._n_brake_log:]:
            if "refused" in what:
                evs.append(self.tracker._add("power_off_refused", rec, what))
        self._n_brake_log = len(log)
        if sim.powered:
            self._off_z, self._fell = None, False
        else:
            if self._off_z is None:
                self._off_z = ex["grasp_z"][-2] if len(ex["grasp_z"]) > 1 else z
            if not self._fell and self._off_z - z > FALL_M:
                self._fell = True
                evs.append(self.tracker._add("payload_fall", rec, f"grasp point {self._off_z - z:.3f} m "
                                             "below its height at power-off", round(self._off_z - z, 4)))
        return evs

    # -- during the run ---------------------------------------------------------------------------

    def observe(self, rec: Any) -> None:
        """Call once per cycle, right after ``GovernedArm.step()``: finds the events and
        renders a frame for those known now; snapshots the scene for running extremes."""
        t0 = time.perf_counter()
        self.last = rec
        evs, improved = self.tracker.update(rec)
        evs += self._observe_power(rec)
        for name in improved:
            self._snaps[name] = (rec.cycle, _snapshot(self.sim))
        if evs:
            self._render(rec.cycle, [e["event"] for e in evs], rec, evs)
        self.seconds += time.perf_counter() - t0

    def frame(self, moment: str, cycle: int | None = None) -> str:
        """Render the current scene to ``frame_<cycle>_<moment>.png`` (an event frame already
        taken at this cycle is reused for that event's own name)."""
        t0 = time.perf_counter()
        c = self.sim.cycle if cycle is None else cycle
        done = self._frame_at.get(c)
        if done is not None and moment in EVENT_LABELS and moment in self._caption_at.get(c, ()):
            return done
        # the state after the last observed cycle's physics (None: before the first cycle)
        rec = self.last if (self.last is not None and self.last.cycle in (c, c - 1)) else None
        path = self._render(c, [moment], rec, [], state_of=None if rec is None else rec.cycle)
        self.seconds += time.perf_counter() - t0
        return path

    def _render(self, cycle: int, names: list[str], rec: Any, evs: list[dict[str, Any]],
                state_of: int | None = -1) -> str:
        """Render, compose and save one frame; ``state_of``: the cycle whose post-physics state
        it shows (default ``cycle``; ``None``: no cycle's, e.g. the start)."""
        from ._overlay import MAIN_WH, SIDE_WH, closeup_camera, render_view, scene_marks

        sim = self.sim
        main_cam, top_cam = self.cameras
        main, view, proj = render_view(sim, main_cam, MAIN_WH)
        top, tview, tproj = render_view(sim, top_cam, SIDE_WH)
        ccam, what = closeup_camera(sim)
        close, _, _ = render_view(sim, ccam, SIDE_WH)
        top_marks = [{**m, "ring": min(m["ring"], 6), "size": 7, "view": (MAIN_WH[0], 0, *SIDE_WH)}
                     for m in scene_marks(sim, tview, tproj, SIDE_WH)]
        path = os.path.join(self.dir, f"frame_{cycle:05d}_{'-'.join(names)}.png")
        parts = {"views": (main, top, close), "marks": scene_marks(sim, view, proj, MAIN_WH) + top_marks,
                 "what": what, "lines": self._overlay_lines(cycle, rec), "evs": list(evs),
                 "name": names[0] if names and names[0] not in EVENT_LABELS else None}
        self._write(path, parts)
        self.files.append(path)
        state_of = cycle if state_of == -1 else state_of
        if state_of is not None:
            self._frame_at.setdefault(state_of, path)
            self._caption_at.setdefault(state_of, []).extend(names)
            self._parts.setdefault(path, parts)  # an event found later may join this frame
        for e in evs:
            e["frame"] = path
        return path

    @staticmethod
    def _write(path: str, parts: dict[str, Any]) -> None:
        from matplotlib import image as mpimg

        from ._overlay import compose_frame

        evs = parts["evs"]
        banner = parts["name"]
        if evs:
            items = [EVENT_LABELS.get(e["event"], e["event"]) + (f": {e['detail']}" if e.get("detail") else "")
                     for e in evs]
            banner = "  |  ".join(items)
            if len(banner) > 60:  # one event a line: the banner stays inside the main view
                banner = "\n".join(i if len(i) <= 70 else i[:67] + "..." for i in items)
        img = compose_frame(*parts["views"], lines=parts["lines"], banner=banner, marks=parts["marks"],
                            close_label=parts["what"])
        mpimg.imsave(path, img)

    def _overlay_lines(self, cycle: int, rec: Any) -> list[str]:
        sim = self.sim
        if rec is None:  # before the first monitor step
            return [f"{self.name}   t {sim.time_s:6.3f} s   cycle {cycle}",
                    "before the first monitor step"]
        sig = rec.signals
        d_true = _num(rec.human_distance_true_m)
        d_in = _num(sig.get("human_distance", math.nan))
        dist = "no person" if not sim.humans else f"{d_true:.3f} m ({self._nearest_person()})"
        if sim.humans and not (math.isfinite(d_in) and abs(d_in - d_true) < 1e-6):
            dist += f" (monitor input: {d_in:.3f})" if math.isfinite(d_in) else " (monitor input: missing)"
        rules = ", ".join(rec.violations) or "none"
        lines = [
            f"{self.name}   t {rec.t_s:6.3f} s   cycle {rec.cycle}",
            f"controller: {rec.controller:<9}  monitor: "
            + (f"OVERRIDE -> {rec.response}" if rec.override else "no override"),
            f"rule fired: {rules}",
            f"closest person: {dist}",
            f"contact force: {_num(sig.get('contact_force', math.nan)):.1f} N   "
            f"ee speed: {_num(sig.get('ee_speed', math.nan)):.3f} m/s",
        ]
        if sim.humans:  # each person's speed now (a walking person is the reason to re-plan)
            lines.append(("people: " + ", ".join(f"{n} {self._person_speed(n, rec.t_s):.2f} m/s"
                                                 for n in sim.humans))[:90])
        per = sim.hazard_axis_angles_deg(each=True) if hasattr(sim, "hazard_axis_angles_deg") else None
        if per:  # every person counts: the worst-placed one (issue 32)
            who = min(per[0], key=per[0].get)
            angles = [per[0][who]]
            lines.append(f"{sim.held} {sim.object_specs[sim.held].hazard or 'hazard'} axis: "
                         f"{angles[0]:.0f} deg from {who}" + (" (worst of all)" if len(per[0]) > 1 else "")
                         + ("  (pointed away)" if angles[0] >= 90 else "  (TOWARD them)"))
        if rec.faults:
            lines.append(f"fault: {rec.faults[0]}"[:90])
        if rec.risk is not None:
            lines[2] += f"   R_e {rec.risk:.3f}"
        return lines

    def _person_speed(self, name: str, t_s: float) -> float:
        """Horizontal speed (m/s) of a person at the frame's time ``t_s``: a compliant body's
        velocity, a scripted one's scripted velocity (kinematic bodies are placed, they carry
        none)."""
        sim = self.sim
        hb = sim.humans[name]
        if getattr(hb, "drive", None) is not None:
            v, _ = sim._p.getBaseVelocity(hb.body, physicsClientId=sim.cid)
            return float(math.hypot(v[0], v[1]))
        vel = hb.velocity_at(t_s) if hasattr(hb, "velocity_at") else (0.0, 0.0)
        return float(math.hypot(vel[0], vel[1]))

    def _nearest_person(self) -> str:
        """The name of the person nearest the arm (or what it holds) in the scene as drawn."""
        sim = self.sim
        held = sim.objects.get(sim.held) if getattr(sim, "held", None) else None
        best, name = math.inf, "?"
        for n, hb in sim.humans.items():
            d = sim.distance(sim.robot, hb.body)
            if held is not None:
                d = min(d, sim.distance(held, hb.body))
            if d < best:
                best, name = d, n
        return name

    # -- at the end -------------------------------------------------------------------------------

    def _deferred_frames(self, result: Any) -> None:
        """Frames of the extremes (closest approach, peak force) from their snapshots."""
        t0 = time.perf_counter()
        by_cycle = {r.cycle: r for r in result.trace}
        pending = [e for e in (self.tracker.closest, self.tracker.peak) if e is not None]
        now = None
        grown: dict[str, dict[str, Any]] = {}
        for ev in pending:
            c = ev["cycle"]
            if c in self._frame_at:  # a frame of that very state exists: its caption gets the event
                path = ev["frame"] = self._frame_at[c]
                parts = self._parts.get(path)
                if parts is not None:
                    parts["evs"].append(ev)
                    grown[path] = parts
                continue
            snap = self._snaps.get(ev["event"])
            if snap is None or snap[0] != c:
                continue
            if now is None:
                now = _snapshot(self.sim)
            _restore(self.sim, snap[1])
            self._render(c, [ev["event"]], by_cycle.get(c), [ev])
        if now is not None:
            _restore(self.sim, now)
        for path, parts in grown.items():
            self._write(path, parts)
        self._parts.clear()
        dt = time.perf_counter() - t0
        self.seconds += dt
        # rendered after run_sim took the wall time: they are frames of the run, count them
        result.wall_time_s = float(getattr(result, "wall_time_s", 0.0) or 0.0) + dt

    def _title(self, result: Any) -> str:
        spec_name = getattr(self.spec, "name", None) or "?"
        verdict = ""
        broken = bounds_broken(result.trace, self.spec, result)
        if self.block is not None or broken:
            problems = check_sim_expectations(self.block, result) if self.block is not None else []
            why = ([f"{len(problems)} sim expectation(s) not met"] if problems else []) + broken
            verdict = "PASS" if not why else f"FAIL ({'; '.join(why)})"
        ov = ("no override" if result.first_override_cycle is None
              else f"override at cycle {result.first_override_cycle}")
        return (f"{self.name}  ·  spec {spec_name}  ·  {verdict + '  ·  ' if verdict else ''}"
                f"{ov}, executed {result.executed_response}")

    def finish(self, result: Any) -> list[str]:
        """Write ``trace.jsonl``, ``trace.csv``, ``plot.png`` and ``summary.json``."""
        self._deferred_frames(result)
        self.events = self.tracker.finish()
        dt = float(getattr(self.sim, "dt", 0.0) or 0.0)
        for ts, ok, msg in getattr(result, "acknowledgements", ()) or ():
            self.events.append({"event": "ack_accepted" if ok else "ack_refused", "cycle": int(round(ts / dt)) if dt else None,
                                "t_s": float(ts), "detail": msg, "value": None, "frame": None})
        for ts, ok, msg in getattr(result, "starts", ()) or ():
            self.events.append({"event": "start_accepted" if ok else "start_refused",
                                "cycle": int(round(ts / dt)) if dt else None,
                                "t_s": float(ts), "detail": msg, "value": None, "frame": None})
        self.events.sort(key=lambda e: (e["t_s"], e["cycle"] if e["cycle"] is not None else -1))
        self.extra["acks"] = list(getattr(result, "acknowledgements", ()) or ())
        self.extra["slow_zone"] = near_human_speed_rule(self.spec) if self.spec is not None else None
        jl = os.path.join(self.dir, "trace.jsonl")
        with open(jl, "w", encoding="utf-8") as fh:
            for r in result.trace:
                row = {
                    "cycle": r.cycle, "t_s": round(r.t_s, 6),
                    "signals": {k: _clean(v) for k, v in r.signals.items()},
                    "override": r.override, "response": r.response,
                    "violations": list(r.violations), "risk": _clean(r.risk),
                    "faults": list(r.faults), "latched": r.latched, "controller": r.controller,
                    "task_step": r.task_step, "joint_speed_max_rad_s": r.joint_speed_max_rad_s,
                    "safe_pose_error_rad": r.safe_pose_error_rad,
                    "human_distance_true_m": _clean(r.human_distance_true_m),
                }
                if getattr(r, "escalated", ""):
                    row["escalated"] = r.escalated  # a refused power-off: why (issue 32)
                if r.cycle < len(self.extra["powered"]):
                    row.update(powered=self.extra["powered"][r.cycle], brakes=self.extra["brakes"][r.cycle],
                               grasp_z_m=_clean(round(self.extra["grasp_z"][r.cycle], 5)))
                fh.write(json.dumps(row) + "\n")
        cs = os.path.join(self.dir, "trace.csv")
        with open(cs, "w", newline="", encoding="utf-8") as fh:
            w = csv.writer(fh)
            w.writerow(["cycle", "t_s", *_SIGNALS, "risk", "override", "response", "controller",
                        "violations", "faults", "safe_pose_error_rad"])
            for r in result.trace:
                w.writerow([r.cycle, f"{r.t_s:.6f}", *(r.signals.get(s, "") for s in _SIGNALS),
                            "" if r.risk is None else r.risk, int(r.override), r.response,
                            r.controller, ";".join(r.violations), ";".join(r.faults),
                            f"{r.safe_pose_error_rad:.5f}"])
        sj = os.path.join(self.dir, "summary.json")
        pl = os.path.join(self.dir, "plot.png")
        self.files += [jl, cs, pl, sj]  # summary.json lists every file of the recording, itself included
        meta = plot_trace(result.trace, pl, title=self._title(result), spec=self.spec, events=self.events,
                          dt=getattr(self.sim, "dt", None), extra=self.extra)
        with open(sj, "w", encoding="utf-8") as fh:
            summ = result.summary()
            summ["files"] = list(self.files)
            summ["events"] = [{k: _clean(v) for k, v in e.items()} for e in self.events]
            summ["plot"] = {k: meta[k] for k in ("panels", "tau", "limits", "limits_skipped", "event_marks",
                                                 "slow_zone_breach_cycles")}
            summ["bounds_broken"] = bounds_broken(result.trace, self.spec, result)
            json.dump(_jsonable(summ), fh, indent=2)
        return list(self.files)


def bounds_broken(trace: Sequence[Any], spec: Any, result: Any = None) -> list[str]:
    """The stated bounds a run broke, one phrase each (the recording's title says FAIL for any):
    the spec's near-human speed rule (``ee_speed`` over V while the simulated distance is under D)
    for longer than the rule's own grace (``within_cycles``), and a joint past its rated position
    limit."""
    out = []
    rule = near_human_speed_rule(spec) if spec is not None else None
    if rule is not None:
        d_lim, v_lim = rule
        grace = max([int(getattr(ob, "within_cycles", 0) or 0) for ob in getattr(spec, "obligations", ())
                     if "human_distance" in (getattr(ob, "when", "") or "")
                     and "ee_speed" in (getattr(ob, "require", "") or "")] or [0])
        run = over = 0
        peak = (0.0, 0.0)
        for r in trace:
            v = _num(r.signals.get("ee_speed", math.nan))
            if r.human_distance_true_m < d_lim and v > v_lim + 1e-9:
                run += 1
                if run > grace:
                    over += 1
                    peak = max(peak, (v, r.human_distance_true_m))
            else:
                run = 0
        if over:
            out.append(f"slow zone: {over} cycle(s) over {v_lim:g} m/s within {d_lim:g} m after the "
                       f"{grace}-cycle grace (peak {peak[0]:.3f} m/s at {peak[1]:.2f} m)")
    past = float(getattr(result, "max_past_limit_mrad", 0.0) or 0.0) if result is not None else 0.0
    if past > 0.0:
        out.append(f"a joint {past:.1f} mrad past its rated limit")
    return out


def _jsonable(v: Any) -> Any:
    if isinstance(v, dict):
        return {k: _jsonable(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_jsonable(x) for x in v]
    if isinstance(v, (np.floating, np.integer)):
        v = v.item()
    return _clean(v)
