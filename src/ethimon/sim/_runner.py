"""``GovernedArm`` and ``run_sim``: the monitor in the PyBullet loop.

Each control cycle: read the signals from the physics state, call
``monitor.step``, and in that same cycle command the controller the decision
names (task, safe pose, stop 0/1/2) before the physics substeps run.
"""

from __future__ import annotations

import math
import time
import zlib
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from .._robot import PANDA_HOME_JOINTS_RAD
from ._arm import ArmSim
from ._control import (SEVERITY, StopController, TaskController, plan_task, restart_margin_m, start_refused,
                       stop_incomplete)
from ._limits import out_of_range, safe_pose_problem
from ._model import SimBlock
from ._rules import RETREAT_NEAR_HUMAN_DEFAULT, near_human_grace_cycles, near_human_speed_rule
from ._safe_pose import SafePoseController
from ._record import Recorder
from ._result import CycleRecord, SimResult, check_sim_expectations
from ..runtime import Acknowledgement

__all__ = ["GovernedArm", "CycleRecord", "SimResult", "run_sim", "check_sim_expectations"]

_DEFAULT_SAFE_POSE = PANDA_HOME_JOINTS_RAD


def _response_name(resp: Any) -> str:
    return str(getattr(resp, "value", resp))


class GovernedArm:
    """An :class:`ArmSim` whose every control cycle goes through a ``Monitor``.

    ``step()`` = read signals → ``monitor.step`` → command the controller the
    decision names (same cycle) → physics. On override the arm leaves the
    task for the response controller (never de-escalating while the override
    lasts); when the monitor releases the override the task resumes from where
    the arm is.

    Args:
        sim: the simulated cell.
        monitor: an ``ethimon.Monitor`` (anything with ``step(mapping) -> Decision``).
        segments: the task as planned segments (default: none, the arm holds still).
        safe_pose: joint angles; default ``monitor.spec.safe_pose``.
        inputs: constant extra inputs each cycle (``p_unsafe``, ``p``, ``risk``…).
        signal_filter: ``f(t_s, signals) -> signals`` applied before the monitor sees
            them (sensor faults).
        task_joint_speed_rad_s, stop_ramp_s, standstill_tolerance_rad: see
            :class:`~ethimon.sim.SimBlock`.
        near_human: ``(distance_m, speed_m_s)`` the safe-pose retreat obeys near people;
            default: the spec's own near-human speed rule (``when: human_distance < D``,
            ``require: ee_speed <= V``), else the retreat's own limit
            ``RETREAT_NEAR_HUMAN_DEFAULT`` (0.25 m/s within 1.5 m); ``None``: uncapped.

    A stop 0 or 1 runs to power-off even if the monitor releases the override meanwhile.

    Raises:
        SpecError: the safe pose has not 7 joints or lies outside the Panda's rated range.

    Example:
        >>> sim = ArmSim()                                      # doctest: +SKIP
        >>> arm = GovernedArm(sim, ethimon.Monitor(spec), inputs={"p_unsafe": 0.9})  # doctest: +SKIP
        >>> rec = arm.step(); rec.override, rec.controller      # doctest: +SKIP
        (True, 'safe_pose')
    """

    def __init__(self, sim: ArmSim, monitor: Any, *, segments: Sequence = (),
                 safe_pose: Any = None, inputs: Mapping[str, Any] | None = None,
                 signal_filter=None, task_joint_speed_rad_s: float = 0.8,
                 stop_ramp_s: float = 0.25, standstill_tolerance_rad: float = 0.02,
                 near_human: Any = "spec", release_dwell_s: float = 1.0,
                 acknowledge_clear_m: Any = "spec", sensor_latency_s: float = 0.0, audit: Any = None) -> None:
        self.sim = sim
        self.monitor = monitor
        sp = safe_pose if safe_pose is not None else getattr(getattr(monitor, "spec", None),
                                                               "safe_pose", None)
        if sp is None or isinstance(sp, (list, tuple, np.ndarray)):
            self.safe_joints = np.array(sp if sp is not None else _DEFAULT_SAFE_POSE, dtype=float)
            self.safe_speed = 1.0
            self.safe_tol = 0.02
        else:
            self.safe_joints = np.array(sp.joints_rad, dtype=float)
            self.safe_speed = float(sp.max_joint_speed_rad_s)
            self.safe_tol = float(sp.tolerance_rad)
        robot = getattr(getattr(monitor, "spec", None), "robot", "panda")
        if isinstance(robot, str) and robot != "panda":  # the simulated arm is a Franka Panda (issue 34)
            from ..errors import SpecError
            src = getattr(getattr(monitor, "spec", None), "source", None)
            msg = f"the simulation is Franka Panda only; this spec's robot is {robot!r}"
            hint = "check it without --sim (lint and verify read its robot), or simulate a Panda spec"
            raise src.error(msg, ("robot",), hint=hint) if src is not None else SpecError(msg, hint=hint)
        if self.safe_joints.shape != (7,):
            from ..errors import SpecError
            raise SpecError(f"safe_pose.joints_rad has {len(self.safe_joints)} values; the Panda arm "
                            "needs 7", hint="give 7 joint angles in the spec's safe_pose")
        problem = safe_pose_problem(self.safe_joints)
        if problem is not None:
            from ..errors import SpecError
            hint = ("the simulated arm is a Franka Panda; keep every safe-pose joint inside its rated "
                    "range (FCI 'Limits for Panda', see the sim README)")
            spec = getattr(monitor, "spec", None)
            src = getattr(spec, "source", None) if safe_pose is None else None
            if src is not None:  # point at the first joint outside its range in the spec file
                raise src.error(problem, ("safe_pose", "joints_rad", out_of_range(self.safe_joints)[0][0] - 1),
                                hint=hint)
            raise SpecError(problem, hint=hint)
        spec_rule = None
        if near_human == "spec":
            spec = getattr(monitor, "spec", None)
            spec_rule = near_human_speed_rule(spec) if spec is not None else None
            # the retreat's own limit when the spec states none (issue 32 item 5)
            near_human = spec_rule or RETREAT_NEAR_HUMAN_DEFAULT
        else:
            spec_rule = near_human
        self.near_human = near_human
        #: an acknowledgement is refused while the monitor's human_distance is below this (m);
        #: default the spec's near-human zone (none without such a rule: then only "no rule
        #: fires", which includes a separation rule)
        self.acknowledge_clear_m = (spec_rule[0] if spec_rule else None) \
            if acknowledge_clear_m == "spec" else acknowledge_clear_m
        self.release_dwell_s = float(release_dwell_s)
        self._clear_since: float | None = None   # monitor released (no override) since
        self._acked = False                      # an accepted start since the acknowledgement
        #: an ``ethimon.audit.AuditLog`` (anything with ``append(kind, **fields)``) or ``None``
        self.audit = audit
        #: ``(t_s, accepted, message)`` of every acknowledgement and every start, in order
        self.acks: list[tuple[float, bool, str]] = []
        self.starts: list[tuple[float, bool, str]] = []
        # issue 32 item 4: an accepted acknowledgement (a reset) waits for the spec's start condition
        spec = getattr(monitor, "spec", None)
        self.start_condition = getattr(getattr(spec, "restart", None), "start", "command")
        self.awaiting_start = False
        self._start_prev = False
        #: after a restart the task keeps the zone's speed this far beyond the zone (m): the distance
        #: sensor's latency, the near-human rule's grace and the task's slow-down at walking speed
        self.restart_margin_m = restart_margin_m(sensor_latency_s, near_human_grace_cycles(spec),
                                                 1.0 / sim.dt)
        self._resume_retreat_since: float | None = None   # a stop 2 over a retreat released since
        #: sim times at which a stop 2 handed the arm back to the retreat (its rule released)
        self.retreat_resumed: list[float] = []
        self._fed: dict[str, Any] = {}
        self.standstill_tolerance_rad = standstill_tolerance_rad
        self.inputs = dict(inputs or {})
        self.signal_filter = signal_filter
        self.stop_ramp_s = stop_ramp_s
        q0, _ = sim.joint_state()
        self.task = TaskController(segments, q0, task_joint_speed_rad_s, holding=sim.held)
        #: why the task was stopped for good (the object it should carry is not in the gripper)
        self.task_stopped: str | None = None
        self.controller: Any = self.task
        self.active = "none"       # response being executed
        self.last_decision = None
        self.last_safe_pose: SafePoseController | None = None

    def step(self) -> CycleRecord:
        """Run one control cycle; returns what happened."""
        sim = self.sim
        t = sim.time_s
        cycle = sim.cycle
        n_dropped = len(sim.dropped)
        sig = sim.signals()
        true_dist = sig["human_distance"]
        true_force = sig["contact_force"]
        true_hazard = sig["hazard_distance"]
        speed_start = sig["joint_speed_max"]
        fed = {**self.inputs, **sig}  # the simulation's own signals always win
        if self.signal_filter is not None:
            fed = self.signal_filter(t, fed)
        d = self.monitor.step(fed)
        self.last_decision = d
        self._fed = fed
        if self.start_condition != "command":  # a start input: its rising edge after the reset
            now = fed.get(self.start_condition) is True or _num(fed.get(self.start_condition)) == 1.0
            if self.awaiting_start and now and not self._start_prev:
                self.start()
            self._start_prev = now
        self.task.distance_reading = _num(fed.get("human_distance", math.nan))
        resp = _response_name(d.response)
        if d.override:
            self._clear_since = None
            if resp == "none":
                resp = "safe_pose"
            if SEVERITY[resp] > SEVERITY[self.active]:
                self._switch(resp)
                self._resume_retreat_since = None
            elif self._stop2_may_hand_back(resp):
                # the stop 2 that interrupted a retreat: its own rule has released; once it has
                # stayed released for the dwell, the retreat goes on, planned afresh from here
                if self._resume_retreat_since is None:
                    self._resume_retreat_since = t
                if t - self._resume_retreat_since >= self.release_dwell_s - 1e-9:
                    self._switch("safe_pose")
                    self.retreat_resumed.append(round(t, 6))
                    self._resume_retreat_since = None
            else:
                self._resume_retreat_since = None
        elif self.active != "none" and not self._must_finish():
            if self._clear_since is None:
                self._clear_since = t
            # an automatic release resumes the task only after the minimum dwell (the response
            # carries on meanwhile); an operator's accepted acknowledgement resumes at once
            if self.awaiting_start:
                pass  # a reset never starts motion: the response holds until the start condition
            elif self._acked or t - self._clear_since >= self.release_dwell_s - 1e-9:
                q, _ = sim.joint_state()
                if self.near_human is not None:  # a restart keeps the zone's speed (issue 32 item 4)
                    self.task.restart_cap = (*self.near_human, self.restart_margin_m)
                self.task.resume(q)
                self.controller = self.task
                self.active = "none"
                self._acked = False
        stopped_now = ""
        if self.controller is self.task and self.task_stopped is None:
            missing = self.task.missing_object(sim)
            if missing is not None:  # dropped (power off, slipped): carrying on would carry nothing
                why = next((f"dropped at {tt:g} s, {w}" for n, tt, w in reversed(sim.dropped)
                            if n == missing), "not in the gripper")
                self.task_stopped = stopped_now = (f"{missing} not in the gripper at step "
                                                   f"{self.task.label} ({why}): stop 2, task not resumed")
                self._switch("stop_2")
        sp = self.controller if isinstance(self.controller, SafePoseController) else None
        n_replans = len(sp.replans) if sp is not None else 0
        n_brake = len(sim.brake_log)
        self.controller.command(sim)        # same cycle as the decision
        label = self.controller.name if self.controller is not self.task else "task"
        escalated = "; ".join(w for _, w in sim.brake_log[n_brake:] if "refused" in w)
        for tb, what in sim.brake_log[n_brake:] if self.audit is not None else ():
            self.audit.append("brakes", t_s=tb, cycle=cycle, escalated="refused" in what, response=resp,
                              controller=label, reason=what)
        if label in SEVERITY and SEVERITY[label] > SEVERITY[self.active]:
            self.active = label  # a stop 2 escalated (standstill lost), a retreat that holds
        decel = sp is not None and sp.decelerating
        task_step = self.task.label
        sim.step()
        q, _ = sim.joint_state()
        # the retreat's own target: the spec's safe pose, the wrist turned for a held hazard
        target = (self.controller.q_safe if isinstance(self.controller, SafePoseController)
                  and self.controller.route != "turn" else self.safe_joints)
        return CycleRecord(
            cycle=cycle, monitor_cycle=int(d.cycle), t_s=t,
            signals={k: _num(v) for k, v in fed.items() if not isinstance(v, (list, tuple))},
            override=bool(d.override), response=_response_name(d.response),
            violations=tuple(d.violations), risk=d.risk, faults=tuple(str(f) for f in d.faults),
            latched=bool(getattr(d, "latched", False)), controller=label, task_step=task_step,
            joint_speed_max_rad_s=sim.max_joint_speed_substep,
            safe_pose_error_rad=float(np.max(np.abs(q - target))),
            human_distance_true_m=true_dist, joint_speed_start_rad_s=speed_start,
            accel_ratio=sim.max_accel_ratio_substep, link_speed_max_m_s=sim.link_speed_max,
            contact_force_true_n=true_force, powered=bool(sim.powered),
            retreat_decelerating=decel, hazard_distance_true_m=true_hazard,
            dropped=tuple(f"{n} ({w})" for n, _, w in sim.dropped[n_dropped:]),
            task_stopped=stopped_now,
            retreat_rate=(round(sp.rate, 4) if sp is not None and sp.holding is None
                          and not decel else None),
            replanned="; ".join(w for _, w in sp.replans[n_replans:]) if sp is not None else "",
            escalated=escalated)

    def acknowledge(self) -> Acknowledgement:
        """An operator's acknowledgement (a manual reset), checked before the monitor sees it.

        Refused, and not remembered, until the stop it would end has completed (standstill,
        brakes engaged, power state settled: :func:`~._control.stop_incomplete`), while the last
        cycle's decision had a rule firing or a fault, or while the monitor's ``human_distance``
        reading is missing or below
        ``acknowledge_clear_m`` (a person inside the protective zone; the spec's near-human
        zone by default). Otherwise :meth:`Monitor.acknowledge` decides (it releases the
        manual latches whose condition has held). ISO 13849-1:2015 5.2.2 (manual reset: the
        stop condition is kept until safe conditions for restarting exist). An accepted one
        never starts motion: the arm waits for the spec's ``restart.start`` (:meth:`start`).
        """
        d = self.last_decision
        why = ""
        if d is None:
            why = "no cycle judged yet"
        elif d.violations:
            why = "rules still fire: " + ", ".join(d.violations)
        elif d.faults:
            why = f"a fault is reported: {d.faults[0]}"
        elif (why := stop_incomplete(self.controller, self.sim) or ""):
            pass
        elif self.acknowledge_clear_m is not None:
            v = _num(self._fed.get("human_distance", math.nan))
            if math.isnan(v):
                why = "no human_distance reading"
            elif v < self.acknowledge_clear_m:
                why = (f"a person is {v:.2f} m away, inside the {self.acknowledge_clear_m:g} m "
                       "protective zone")
        if why:
            return self._audited("acknowledge", Acknowledgement(False, (), "refused: " + why))
        a = self.monitor.acknowledge() if hasattr(self.monitor, "acknowledge") else \
            Acknowledgement(False, (), "the monitor takes no acknowledgement")
        if a.released:
            self.awaiting_start = True
            self._start_prev = True  # a start input already on does not count: it must rise
        return self._audited("acknowledge", a)

    def _audited(self, kind: str, a: Acknowledgement) -> Acknowledgement:
        (self.acks if kind == "acknowledge" else self.starts).append((round(self.sim.time_s, 6), bool(a.released),
                                                                      a.message))
        if self.audit is not None:
            self.audit.append(kind, t_s=round(self.sim.time_s, 6), accepted=bool(a.released), message=a.message)
        return a

    def start(self) -> Acknowledgement:
        """The separate start after an accepted acknowledgement (``restart.start: command``, or
        the rising edge of the spec's start input): motion resumes from the next cycle.

        Refused, and not remembered, when no acknowledged stop awaits a start, while the monitor
        overrides (a rule fires, a latch holds, a fault), or while a person is inside the
        protective zone (as for the acknowledgement).
        """
        why = start_refused(self.awaiting_start, self.last_decision,
                            _num(self._fed.get("human_distance", math.nan)), self.acknowledge_clear_m)
        if why:
            return self._audited("start", Acknowledgement(False, (), "start refused: " + why))
        self.awaiting_start = False
        self._acked = True
        return self._audited("start", Acknowledgement(True, (), "started"))

    def _stop2_may_hand_back(self, resp: str) -> bool:
        """A powered stop 2 (not escalated, at standstill, not the hold of a task that lost its
        object) while the monitor now asks only for the safe pose: the separation stop that
        paused a retreat has released (issue 32 item 5)."""
        c = self.controller
        return (resp == "safe_pose" and self.active == "stop_2" and self.task_stopped is None
                and isinstance(c, StopController) and c.category == 2 and not c.escalated
                and c.done and c.standstill_s is not None)

    def _must_finish(self) -> bool:
        if self.task_stopped is not None:
            return True  # the task lost its object: it holds until someone looks, never resumes
        """A stop 0/1 in progress is never cut short by a release: it runs to power-off."""
        c = self.controller
        if isinstance(c, SafePoseController) and c.holding is not None:
            c = c.holding  # a retreat that holds, possibly escalated to stop 0
        return isinstance(c, StopController) and c.category in (0, 1) and not c.done

    def _switch(self, resp: str) -> None:
        q, qd = self.sim.joint_state()
        if resp == "safe_pose":
            self.controller = SafePoseController(q, self.safe_joints, self.safe_speed,
                                                 near_human=self.near_human,
                                                 path_back=self.task.path_back())
        else:
            self.controller = StopController(int(resp[-1]), q, qd, self.stop_ramp_s,
                                             standstill_tol_rad=self.standstill_tolerance_rad)
        self.active = resp
        if isinstance(self.controller, SafePoseController):
            self.last_safe_pose = self.controller


def _collect(res: SimResult, rec: CycleRecord, near_m: float, dt: float) -> None:
    """Fold one cycle into the run's response figures."""
    res.max_contact_force_n = max(res.max_contact_force_n, rec.contact_force_true_n)
    if res.first_override_cycle is not None:
        res.min_hazard_distance_after_override_m = min(
            res.min_hazard_distance_after_override_m if res.min_hazard_distance_after_override_m is not None
            else math.inf, rec.hazard_distance_true_m)
    if rec.controller != "task" and rec.contact_force_true_n <= 0.0:
        res.max_accel_ratio = max(res.max_accel_ratio or 0.0, rec.accel_ratio)
    if rec.controller == "safe_pose":
        d = rec.human_distance_true_m
        if not math.isnan(d):
            res.retreat_min_separation_m = min(res.retreat_min_separation_m
                                               if res.retreat_min_separation_m is not None else math.inf, d)
        if not rec.retreat_decelerating and d < near_m:
            res.retreat_max_link_speed_near_human_m_s = max(
                res.retreat_max_link_speed_near_human_m_s or 0.0, rec.link_speed_max_m_s)


def _swing(res: SimResult, sim: ArmSim, axis0: dict[str, float]) -> None:
    """Per person: how far a held hazard's axis has turned toward them below its angle at the
    first override (``axis0``, filled at the first call), the worst cycle so far."""
    ang = sim.hazard_axis_angles_deg(each=True)
    if not ang:
        return
    for n, a in ang[0].items():
        a0 = axis0.setdefault(n, a)
        res.hazard_axis_min_swing_deg[n] = round(max(res.hazard_axis_min_swing_deg.get(n, 0.0), a0 - a), 2)


class _PeopleWatch:
    """How honestly the people followed their scripts: measured speed (true positions, cycle
    to cycle) over the script's fastest, and overshoot past the last waypoint."""

    def __init__(self, sim: ArmSim) -> None:
        self.sim = sim
        self.last = sim.human_xy()
        self.ratio: float | None = None
        self.over: float | None = None
        self.moving = {n: float(np.max(hb.speeds())) for n, hb in sim.humans.items()
                       if hb.speeds().size and float(np.max(hb.speeds())) > 0}
        self._last_walk: dict[str, int] = {}

    def observe(self) -> None:
        sim = self.sim
        now = sim.human_xy()
        for n, vmax in self.moving.items():
            v = float(np.linalg.norm(now[n] - self.last[n])) / sim.dt
            self.ratio = max(self.ratio or 0.0, v / vmax)
            hb = sim.humans[n]
            k = self._last_walk.get(n)
            if k is None:  # the script's last walking segment (fixed: worked out once per person)
                k = self._last_walk[n] = int(np.flatnonzero(hb.speeds() > 0)[-1])
            u = hb.xy[k + 1] - hb.xy[k]
            u = u / float(np.linalg.norm(u))
            if sim.time_s >= hb.times[k + 1] - 1e-9:
                self.over = max(self.over or 0.0, float(np.dot(now[n] - hb.xy[k + 1], u)))
            elif self.over is None:
                self.over = 0.0
        self.last = now

    def result(self) -> tuple[float | None, float | None]:
        return (None if self.ratio is None else round(self.ratio, 4),
                None if self.over is None else round(self.over, 4))


def _num(v: Any) -> float:
    try:
        return float(v)
    except (TypeError, ValueError):
        return math.nan


def _signal_filter(block: SimBlock):
    """``f(t, fed) -> fed``: what the monitor's sensors make of the simulated signals.

    Per signal, in this order: ``sensors`` latency (the reading of ``round(latency_s ×
    control_hz)`` cycles earlier; the first reading until there is one that old), Gaussian
    ``noise`` (seeded per signal, clipped at 0), ``stuck_at`` (a fixed ``value`` or the reading
    frozen at ``from_s``), then ``dropouts`` (NaN or missing); ``inputs_at`` changes the other
    inputs. ``None`` when the block asks for none of these."""
    drops = block.dropouts
    changes = sorted(block.inputs_at, key=lambda c: c.t_s)
    sensors = dict(block.sensors)
    stuck = block.stuck_at
    if not drops and not changes and not sensors and not stuck:
        return None
    hz = block.control_hz
    history: dict[str, list[float]] = {n: [] for n in sensors}
    lag = {n: int(round(s.latency_s * hz)) for n, s in sensors.items()}
    rngs = {n: np.random.default_rng([s.seed, zlib.crc32(n.encode())]) for n, s in sensors.items()}
    frozen: dict[int, float] = {}

    def apply(t: float, fed: dict) -> dict:
        for ch in changes:
            if ch.t_s <= t + 1e-9:
                fed.update(ch.inputs)
        for name, sen in sensors.items():
            if name not in fed:
                continue
            h = history[name]
            h.append(float(fed[name]))
            k = lag[name]
            if len(h) > k + 1:
                del h[0]
            v = h[0] if len(h) <= k else h[-1 - k]
            if sen.noise > 0.0:
                v = max(0.0, v + float(rngs[name].normal(0.0, sen.noise)))
            fed[name] = v
        for i, st in enumerate(stuck):
            if st.from_s <= t + 1e-9 and (st.to_s is None or t < st.to_s - 1e-9) and st.signal in fed:
                if st.value is not None:
                    fed[st.signal] = float(st.value)
                else:
                    fed[st.signal] = frozen.setdefault(i, float(fed[st.signal]))
        for dr in drops:
            if dr.from_s <= t < dr.to_s:
                if dr.mode == "missing":
                    fed.pop(dr.signal, None)
                else:
                    fed[dr.signal] = math.nan
        return fed

    return apply


def _fixed_inputs(inputs: Mapping[str, Any] | None, *, p: Sequence[float] | None, p_unsafe: float | None,
                  risk: float | None) -> dict[str, Any]:
    """The inputs given to the monitor every cycle besides the simulated signals."""
    fixed: dict[str, Any] = dict(inputs or {})
    if p is not None:
        fixed["p"] = tuple(float(x) for x in p)
    if p_unsafe is not None:
        fixed["p_unsafe"] = float(p_unsafe)
    if risk is not None:
        fixed["risk"] = float(risk)
    fixed.setdefault("risk_age_s", 0.0)  # the task text does not change: the estimate is current
    return fixed


def _summarize(res: SimResult, arm: GovernedArm, sim: ArmSim, people: _PeopleWatch, *, first_cmd: int | None,
               max_sp: float | None, ack_log: list[tuple[float, bool, str]], fired: dict[str, None],
               loop_wall: float) -> None:
    """Fill in what ``res`` says about the whole run, once its loop has ended."""
    res.task_completed = arm.task.done
    if res.first_override_cycle is not None and first_cmd is not None:
        res.override_reaction_cycles = first_cmd - res.first_override_cycle
    res.max_joint_speed_safe_pose_rad_s = max_sp
    res.powered_at_end = bool(sim.powered)
    sp = arm.controller if isinstance(arm.controller, SafePoseController) else arm.last_safe_pose
    res.route = sp.route if sp is not None else None
    res.dropped = tuple(sim.dropped)
    res.task_stopped = arm.task_stopped
    ang = sim.hazard_axis_angles_deg(each=True)
    res.hazard_axis_angles_end_deg = {n: round(a, 2) for n, a in ang[0].items()} if ang else {}
    res.hazard_axis_angle_end_deg = min(res.hazard_axis_angles_end_deg.values()) if ang else None
    res.wrist_turn_rad = round(sp.wrist_turn_rad, 4) if sp is not None else None
    res.object_end_z_m = {n: round(z, 4) for n, z in sim.object_z().items()}
    res.max_human_speed_ratio, res.human_overshoot_m = people.result()
    res.acknowledgements, res.starts = tuple(ack_log), tuple(arm.starts)
    res.max_past_limit_mrad = round(1000.0 * sim.max_past_limit_rad, 4)
    res.brake_log, res.brakes_escalated = tuple(sim.brake_log), any("refused" in w for _, w in sim.brake_log)
    res.max_travel_unpowered_rad = round(sim.max_travel_unpowered_rad, 5)
    res.max_drop_unpowered_m = round(sim.max_drop_unpowered_m, 5)
    res.fired = tuple(fired)
    res.sim_time_s = round(sim.time_s, 6)
    res.realtime_factor = res.sim_time_s / loop_wall if loop_wall > 0 else math.inf


def _latency(block: SimBlock) -> float:
    """The distance sensor's latency (s) in a ``sim:`` block."""
    return getattr(block.sensors.get("human_distance"), "latency_s", 0.0)


def run_sim(sim_block: SimBlock | Mapping[str, Any], monitor: Any, *,
            p: Sequence[float] | None = None, risk: float | None = None,
            p_unsafe: float | None = None, inputs: Mapping[str, Any] | None = None,
            record_dir: str | None = None, gui: bool = False,
            audit: Any = None) -> SimResult:
    """Run a scenario's ``sim:`` block with ``monitor`` in the loop.

    Args:
        sim_block: a :class:`SimBlock` (or a dict that validates as one).
        monitor: an ``ethimon.Monitor``; it is ``reset()`` first.
        p: the risk estimator's class probabilities for the task text (fed as ``p``; every risk
            keyword is named as the monitor's input it feeds).
        risk: R_e itself (fed as ``risk``).
        p_unsafe: the unsafe-class probability (fed as ``p_unsafe``).
        inputs: other constant inputs for every cycle; the simulated signals
            (human_distance, ee_speed, contact_force, joint_speed_max) always
            replace inputs of the same name.
        record_dir: write PNG frames, ``trace.jsonl``/``trace.csv`` and ``plot.png`` there.
        gui: show the PyBullet GUI (needs a display) and run in real time.
        audit: an ``AuditLog`` for the operator's actions and every power-off check (``GovernedArm``).

    Returns:
        A :class:`SimResult`.

    Raises:
        DependencyNotInstalled: PyBullet is missing (``pip install "ethimon[sim]"``).
    """
    block = sim_block if isinstance(sim_block, SimBlock) else SimBlock.model_validate(sim_block)
    wall0 = time.perf_counter()
    fixed = _fixed_inputs(inputs, p=p, p_unsafe=p_unsafe, risk=risk)
    if hasattr(monitor, "reset"):
        monitor.reset()
    recorder = None
    # nothing rendered (no recording, no GUI): the arm without its visual meshes, same physics
    with ArmSim.from_block(block, gui=gui, visuals=gui or record_dir is not None) as sim:
        segments = plan_task(sim, block)
        arm = GovernedArm(sim, monitor, segments=segments, inputs=fixed,
                          signal_filter=_signal_filter(block),
                          task_joint_speed_rad_s=block.task_joint_speed_rad_s,
                          stop_ramp_s=block.stop_ramp_s,
                          standstill_tolerance_rad=block.standstill_tolerance_rad,
                          release_dwell_s=block.release_dwell_s, audit=audit, sensor_latency_s=_latency(block))
        if record_dir is not None:
            recorder = Recorder(record_dir, sim, spec=getattr(monitor, "spec", None), block=block,
                                safe_tol=arm.safe_tol)
            recorder.frame("start")
        res = SimResult(joint_speed_limit_rad_s=arm.safe_speed)
        n_cycles = int(round(block.duration_s * block.control_hz))
        fired: dict[str, None] = {}
        first_cmd: int | None = None
        t_override: float | None = None
        max_sp = shown = None
        overridden_before = False
        extra_frames = sorted(block.record_at_s)
        loop0 = time.perf_counter()
        rec_s0 = recorder.seconds if recorder else 0.0
        stop_v0: float | None = None
        sp_v0: float | None = None
        t_stop: float | None = None
        near = block.expect.near_human_m
        actions = sorted([(t, "acknowledge") for t in block.acknowledge_at_s] + [(t, "start") for t in block.start_at_s])
        people = _PeopleWatch(sim)
        resp_since: float | None = None
        axis0: dict[str, float] = {}  # each person's hazard-axis angle at the first override
        for _ in range(n_cycles):
            while actions and sim.time_s >= actions[0][0] - 1e-9:  # the operator: acknowledge, start
                arm.acknowledge() if actions.pop(0)[1] == "acknowledge" else arm.start()
            prev_ctrl = res.trace[-1].controller if res.trace else "task"
            rec = arm.step()
            if rec.controller != "task" and prev_ctrl == "task":
                resp_since = rec.t_s
            elif rec.controller == "task" and prev_ctrl != "task" and resp_since is not None:
                res.task_resumes += 1
                res.observe_resume(arm.acks, arm.starts)
                dur = round(rec.t_s - resp_since, 6)
                res.min_response_s = dur if res.min_response_s is None else min(res.min_response_s, dur)
            if res.task_resumes and rec.controller == "task":
                res.observe_restart(rec, arm.near_human)
            people.observe()
            res.trace.append(rec)
            if recorder:
                recorder.observe(rec)  # events and their frames (time excluded from the loop)
            _collect(res, rec, near, sim.dt)
            if rec.controller == "safe_pose" and rec.retreat_decelerating:
                # the safe pose's deceleration is a controlled stop too: the speed never rises
                if sp_v0 is None:
                    sp_v0 = rec.joint_speed_start_rad_s
                if sp_v0 > 0.05:
                    res.stop_speed_gain = max(res.stop_speed_gain or 0.0,
                                              rec.joint_speed_max_rad_s / sp_v0)
            if rec.controller.startswith("stop_"):
                if t_stop is None:
                    t_stop, stop_v0 = rec.t_s, rec.joint_speed_start_rad_s
                if rec.controller != "stop_0" and stop_v0 > 0.05:  # controlled stops (stop 0: coasting)
                    gain = rec.joint_speed_max_rad_s / stop_v0
                    res.stop_speed_gain = max(res.stop_speed_gain or 0.0, gain)
                if res.time_to_standstill_s is None and rec.joint_speed_max_rad_s < 0.01:
                    res.time_to_standstill_s = round(rec.t_s + sim.dt - t_stop, 6)
            for v in rec.violations:
                fired.setdefault(v, None)
            if rec.faults:
                res.fault_cycles += 1
            if res.first_override_cycle is not None or rec.override:
                _swing(res, sim, axis0)
            if rec.override:
                if res.first_override_cycle is None:
                    res.first_override_cycle = rec.cycle
                    t_override = rec.t_s
                    if recorder:
                        recorder.frame("override", rec.cycle)  # time excluded from the loop
                overridden_before = True
            elif overridden_before and not res.released:
                res.released = True
                if recorder:
                    recorder.frame("release", rec.cycle)
            if recorder and extra_frames and rec.t_s + 1e-9 >= extra_frames[0]:
                recorder.frame(f"t{extra_frames.pop(0):g}s", rec.cycle)
            if gui and rec.controller != shown:
                shown = rec.controller
                sim.show_status(f"{shown}" + (f"  ({', '.join(rec.violations or rec.faults)})"
                                               if rec.override else ""))
            if rec.controller != "task" and first_cmd is None:
                first_cmd = rec.cycle
            if SEVERITY[rec.controller if rec.controller in SEVERITY else "none"] > \
                    SEVERITY[res.executed_response]:
                res.executed_response = rec.controller
            if rec.controller == "safe_pose" and not rec.retreat_decelerating:
                max_sp = max(max_sp or 0.0, rec.joint_speed_max_rad_s)
            if rec.controller == "safe_pose":
                if (res.time_to_safe_pose_s is None and t_override is not None
                        and rec.safe_pose_error_rad <= arm.safe_tol):
                    res.time_to_safe_pose_s = round(rec.t_s + sim.dt - t_override, 6)
                    if recorder:
                        recorder.frame("safe_pose", rec.cycle)
            if sim.humans:
                res.min_separation_m = min(res.min_separation_m, rec.human_distance_true_m)
            if gui:
                time.sleep(max(0.0, loop0 + sim.time_s - time.perf_counter()))
        loop_wall = time.perf_counter() - loop0 - (recorder.seconds - rec_s0 if recorder else 0.0)
        _summarize(res, arm, sim, people, first_cmd=first_cmd, max_sp=max_sp, ack_log=arm.acks, fired=fired,
                   loop_wall=loop_wall)
        if recorder:
            recorder.frame("end")
        # set before the recording is finished: its summary.json carries it (setup, loop and frames;
        # not the writing of the trace and plot files)
        res.wall_time_s = time.perf_counter() - wall0
        if recorder:
            res.files = recorder.finish(res)
    return res
