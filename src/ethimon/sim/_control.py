"""Task planning (motion primitives → joint segments) and the arm's controllers.

Every controller has ``command(sim)``, called once per control cycle before
the physics substeps, and a ``done`` flag. They never import PyBullet
themselves; they only talk to :class:`~ethimon.sim.ArmSim`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ._arm import ArmSim
from ._cell import Segment, _half_height, _half_width
from ._limits import (BRAKE_ENGAGE_S, LIMIT_MARGIN_RAD, RATED_DDDQ_MAX, RATED_DDQ_MAX, RATED_DQ_MAX, RATED_Q_MAX,
                      RATED_Q_MIN)
from ..language import SEVERITY_ORDER
from ._model import SimError, HandOver, Pick, Place, Pour, Reach, SimBlock, Wait, Wipe

__all__ = ["plan_task", "TaskController", "StopController", "SEVERITY", "stop_incomplete", "start_refused",
           "restart_margin_m",
           "WALKING_SPEED_M_S"]

#: Response name -> severity (the spec's one order, ``ethimon.language.SEVERITY_ORDER``); the arm never
#: de-escalates while overridden.
SEVERITY = {r.value: r.severity for r in SEVERITY_ORDER}

_MIN_SEGMENT_S = 0.25
_IK_TOLERANCE_M = 0.02
_GRIP_S = 0.3
#: planned motions use at most this share of the rated acceleration and jerk (the servo's
#: rate limiter is the hard bound; the share leaves it room to track)
_LIMIT_SHARE = 0.8
_DQ = np.array(RATED_DQ_MAX)
_DDQ = np.array(RATED_DDQ_MAX)
_DDDQ = np.array(RATED_DDDQ_MAX)
_Q_MIN, _Q_MAX = np.array(RATED_Q_MIN), np.array(RATED_Q_MAX)


#: the speed a person is assumed to approach with (ISO 13855's walking speed K, 1.6 m/s)
WALKING_SPEED_M_S = 1.6
#: the time a resumed task takes to shed its speed down to the near-human cap (s; the rate may
#: fall by this share per second of the planned speed)
_TASK_SLOWDOWN_S = 0.3
#: below this every joint is at standstill (rad/s), as a stop judges it
_STANDSTILL_RAD_S = 0.01


def restart_margin_m(latency_s: float, grace_cycles: int, control_hz: float) -> float:
    """How far beyond the slow zone a restarted task already keeps the zone's speed (m): a person
    walking at :data:`WALKING_SPEED_M_S` covers this during the distance sensor's latency, the
    rule's grace (``within_cycles``) and one cycle, and the task's own slow-down."""
    return WALKING_SPEED_M_S * (max(latency_s, 0.0) + (max(grace_cycles, 0) + 1) / control_hz
                                + _TASK_SLOWDOWN_S)


def stop_incomplete(controller, sim: ArmSim) -> str | None:
    """Why the stop an acknowledgement would end has not completed (``None``: it has).

    Completed (issue 32 item 4): every joint at standstill; a stop 0/1 has removed power and its
    brakes have engaged (or its power-off was refused and it holds powered); a stop 2 has
    decelerated and holds. A retreat counts as completed once the arm stands still (arrived, or
    holding). The running task has no stop to end.
    """
    c = controller
    if isinstance(c, TaskController):
        return None
    c = getattr(c, "holding", None) or c  # a retreat that holds: its stop
    if isinstance(c, StopController):
        if c.category in (0, 1):
            if not c.done:
                return f"the {c.name} has not completed: still braking, motor power still on"
            if not sim.powered and sim.brakes and not sim.brakes_engaged:
                return f"the {c.name} has not completed: the brakes have not engaged yet"
        elif not c.done:
            return "the stop 2 has not completed: still decelerating"
    _, qd = sim.joint_state()
    v = float(np.max(np.abs(qd)))
    if v >= _STANDSTILL_RAD_S:
        return f"the arm is not at standstill ({v:.3f} rad/s)"
    return None


def start_refused(awaiting: bool, decision, distance_m: float, clear_m: float | None) -> str:
    """Why an operator's start is refused (``""``: accepted): no accepted acknowledgement awaits
    one, the monitor overrides (a rule fires, a latch holds, a fault), or the distance reading is
    missing or inside the protective zone ``clear_m`` (as for the acknowledgement)."""
    d = decision
    if not awaiting:
        return "no acknowledged stop awaits a start"
    if d is None:
        return "no cycle judged yet"
    if d.override or d.violations or d.faults:
        return "the monitor overrides: " + (", ".join(d.violations) or (str(d.faults[0]) if d.faults
                                                                        else "a latch holds"))
    if clear_m is not None:
        if math.isnan(distance_m):
            return "no human_distance reading"
        if distance_m < clear_m:
            return f"a person is {distance_m:.2f} m away, inside the {clear_m:g} m protective zone"
    return ""


def _min_jerk(u: float) -> tuple[float, float]:
    """Position fraction and its derivative (per unit time fraction) of a min-jerk profile."""
    u = min(max(u, 0.0), 1.0)
    s = u * u * u * (10 - 15 * u + 6 * u * u)
    ds = 30 * u * u * (1 - u) * (1 - u)
    return s, ds


def _timed(q_from: np.ndarray, q_to: np.ndarray, duration_s: float | None, v_task: float) -> float:
    """Duration of a min-jerk move: at least ``duration_s``, with every joint's peak speed
    within ``v_task`` and its rated speed, and its peak acceleration and jerk within
    ``_LIMIT_SHARE`` of the rated ones (min-jerk peaks: 1.875 d/T, 5.774 d/T², 60 d/T³)."""
    d = np.abs(np.asarray(q_to, dtype=float) - np.asarray(q_from, dtype=float))
    v = np.minimum(v_task, 0.98 * _DQ)
    need = max(float(np.max(1.875 * d / v)),
               float(np.max(np.sqrt(5.7735 * d / (_LIMIT_SHARE * _DDQ)))),
               float(np.max(np.cbrt(60.0 * d / (_LIMIT_SHARE * _DDDQ)))))
    return max(duration_s or 0.0, need, _MIN_SEGMENT_S)


def plan_task(sim: ArmSim, block: SimBlock) -> list[Segment]:
    """Turn the block's primitives into joint-space segments (IK solved once, up front).

    Deterministic: IK is seeded by the previous segment's solution.
    """
    v = block.task_joint_speed_rad_s
    q_prev, _ = sim.joint_state()
    grip = sim.gripper_cmd
    segs: list[Segment] = []
    held_half_h = 0.0  # grasp point above the held object's resting centre

    def add(q, dur=None, label="", attach=None, detach=False, gripper=None, hold=False):
        nonlocal q_prev, grip
        q = np.asarray(q, dtype=float)
        if gripper is not None:
            grip = gripper
        d = dur if hold else _timed(q_prev, q, dur, v)
        segs.append(Segment(q=q, duration_s=max(d, 1e-3), gripper_m=grip, attach=attach,
                            detach=detach, label=label))
        q_prev = q

    where = ""

    def ik(xyz, rpy=None):
        q = sim.solve_ik(xyz, rpy, seed=q_prev)
        miss = float(np.linalg.norm(sim.fk(q) - np.asarray(xyz, dtype=float)))
        if miss > _IK_TOLERANCE_M:
            raise SimError(f"sim.task[{where}: the Panda cannot reach {list(xyz)} "
                           f"(inverse kinematics misses by {miss:.3f} m; keep targets within "
                           "about 0.8 m of the shoulder at (0, 0, 0.33))")
        return q

    for i, prim in enumerate(block.task):
        tag = f"{i}:{prim.primitive}"
        where = f"{i}] ({prim.primitive})"
        if isinstance(prim, Reach):
            q = prim.joints_rad if prim.joints_rad is not None else ik(prim.xyz_m, prim.rpy_rad)
            add(q, prim.duration_s, tag)
        elif isinstance(prim, Pick):
            sim.set_graspable(prim.object)
            o = sim.object_specs[prim.object]
            x, y, z = o.xyz_m
            top = _half_height(o)
            grasp_z = z + max(top - 0.02, 0.0)
            held_half_h = grasp_z - z
            add(ik((x, y, grasp_z + prim.approach_height_m)), prim.duration_s, tag + ":approach")
            add(ik((x, y, grasp_z)), prim.duration_s, tag + ":descend")
            width = min(_half_width(o), 0.04)
            add(q_prev, _GRIP_S, tag + ":grasp", attach=prim.object, gripper=width, hold=True)
            add(ik((x, y, grasp_z + prim.approach_height_m)), prim.duration_s, tag + ":lift")
        elif isinstance(prim, Place):
            x, y, z = prim.xyz_m
            gz = z + held_half_h
            add(ik((x, y, gz + prim.approach_height_m)), prim.duration_s, tag + ":carry")
            add(ik((x, y, gz)), prim.duration_s, tag + ":lower")
            add(q_prev, _GRIP_S, tag + ":release", detach=True, gripper=0.04, hold=True)
            add(ik((x, y, gz + prim.approach_height_m)), prim.duration_s, tag + ":retreat")
        elif isinstance(prim, HandOver):
            add(ik(prim.xyz_m), prim.duration_s, tag + ":offer")
            if prim.hold_s > 0:
                add(q_prev, prim.hold_s, tag + ":hold", hold=True)
            if prim.release:
                add(q_prev, _GRIP_S, tag + ":release", detach=True, gripper=0.04, hold=True)
        elif isinstance(prim, Pour):
            x, y, z = prim.xyz_m
            add(ik((x, y, z)), prim.duration_s, tag + ":above")
            tilted = ik((x, y, z), (math.pi, prim.tilt_rad, 0.0))
            add(tilted, prim.duration_s, tag + ":tilt")
            if prim.hold_s > 0:
                add(q_prev, prim.hold_s, tag + ":hold", hold=True)
            add(ik((x, y, z)), prim.duration_s, tag + ":untilt")
        elif isinstance(prim, Wipe):
            x, y, z = prim.xyz_m
            hl, hw = prim.length_m / 2, prim.width_m / 2
            add(ik((x - hl, y - hw, z + 0.1)), prim.duration_s, tag + ":approach")
            ys = np.linspace(y - hw, y + hw, prim.passes)
            for k, yy in enumerate(ys):
                xa, xb = (x - hl, x + hl) if k % 2 == 0 else (x + hl, x - hl)
                add(ik((xa, yy, z)), None, f"{tag}:pass{k}a")
                add(ik((xb, yy, z)), None, f"{tag}:pass{k}b")
            add(ik((x, y, z + 0.1)), prim.duration_s, tag + ":lift")
        elif isinstance(prim, Wait):
            add(q_prev, prim.duration_s, tag, hold=True)
    return segs


class TaskController:
    """Plays the planned segments; pauses on override and resumes from where the arm is."""

    name = "task"

    def __init__(self, segments: Sequence[Segment], q_start: np.ndarray, v_task: float,
                 holding: str | None = None) -> None:
        self.segments = list(segments)
        #: per segment: the object the gripper should hold while it plays (``holding`` at the
        #: start, then what the segments before it attached and did not let go)
        self.carrying: list[str | None] = []
        held = holding
        for seg in self.segments:
            self.carrying.append(held)
            if seg.detach:
                held = None
            if seg.attach:
                held = seg.attach
        self.v_task = v_task
        self.index = 0
        self.t = 0.0
        self._from = np.asarray(q_start, dtype=float)
        self.q_initial = self._from.copy()
        self._dur = self.segments[0].duration_s if self.segments else 0.0
        self.setpoint = self._from.copy()
        #: after a restart (issue 32 item 4): ``(zone_m, speed_m_s, margin_m)``: while the distance
        #: reading (:attr:`distance_reading`) is under ``zone_m + margin_m`` (or missing) no link
        #: moves faster than 0.8 x ``speed_m_s``; ``None``: the task as planned
        self.restart_cap: tuple[float, float, float] | None = None
        #: the monitor's human_distance reading this cycle (set by its caller)
        self.distance_reading = math.inf
        self.rate = 1.0          # path-time rate (1: as planned)
        self._gain: float | None = None   # link speed (m/s) per unit path speed of this segment

    @property
    def done(self) -> bool:
        """All segments played."""
        return self.index >= len(self.segments)

    @property
    def label(self) -> str:
        return self.segments[self.index].label if not self.done else "done"

    def missing_object(self, sim: ArmSim) -> str | None:
        """The object the current segment should carry when it is not in the gripper (it was
        dropped: power removed, or slipped out); ``None`` when all is as planned."""
        if self.done:
            return None
        want = self.carrying[self.index]
        return want if want is not None and sim.held != want else None

    def path_back(self, most: int = 3) -> list[np.ndarray]:
        """The way the arm came in, most recent first: where the current motion started, then
        where each earlier one did (joint-space segment starts; at most ``most``)."""
        out = [self._from.copy()]
        for k in range(min(self.index, len(self.segments)) - 1, -1, -1):
            out.append((self.segments[k - 1].q if k > 0 else self.q_initial).copy())
            if len(out) >= most:
                break
        return out

    def resume(self, q_now: np.ndarray) -> None:
        """Restart the current segment from the measured pose ``q_now`` (after a release)."""
        self._from = np.asarray(q_now, dtype=float)
        self.t = 0.0
        self.rate, self._gain = 0.0 if self.restart_cap is not None else 1.0, None
        if not self.done:
            seg = self.segments[self.index]
            self._dur = _timed(self._from, seg.q, seg.duration_s, self.v_task)

    def command(self, sim: ArmSim) -> None:
        if self.done:
            last = self.segments[-1] if self.segments else None
            sim.command_joints(self.setpoint, np.zeros(7), last.gripper_m if last else None)
            return
        seg = self.segments[self.index]
        rate0 = self.rate
        if self.restart_cap is not None or rate0 != 1.0:
            self.rate = self._rate(sim, seg)
        s, ds = _min_jerk(min(self.t / self._dur, 1.0))
        q = self._from + s * (seg.q - self._from)
        qd = (ds / self._dur) * self.rate * (seg.q - self._from)
        self.setpoint = q
        sim.command_joints(q, qd, seg.gripper_m)
        self.t += (0.5 * (rate0 + self.rate) if self.rate != 1.0 or rate0 != 1.0 else 1.0) * sim.dt
        if self.t >= self._dur - 1e-9:
            if seg.attach:
                sim.attach(seg.attach)
            if seg.detach:
                sim.detach()
            self._from = seg.q
            self.index += 1
            self.t = 0.0
            self._gain = None
            if not self.done:
                nxt = self.segments[self.index]
                self._dur = nxt.duration_s


    def _rate(self, sim: ArmSim, seg: Segment) -> float:
        """This cycle's path-time rate: 1 as planned; after a restart, with someone within the
        slow zone plus the margin (or no reading), low enough that no link frame passes 0.8 x the
        zone's speed at this point of the profile; changed by at most ``dt / _TASK_SLOWDOWN_S``."""
        target = 1.0
        cap = self.restart_cap
        d = self.distance_reading
        if cap is not None and not (d >= cap[0] + cap[2]):  # NaN: no reading, keep the cap
            if self._gain is None:
                pts = sim.link_points_at([self._from + (k / 10) * (seg.q - self._from) for k in range(11)])
                step = max(float(np.max(np.linalg.norm(b - a, axis=1))) for a, b in zip(pts, pts[1:]))
                self._gain = 1.3 * 10.0 * step  # per unit path; 1.3: chord vs arc, sampling
            u = min(self.t / self._dur, 1.0) if self._dur > 0 else 1.0
            _, ds = _min_jerk(u)
            # the speed at the profile's peak ahead bounds it too, so the rate never lags a rise
            peak = ds if u >= 0.5 else max(ds, _min_jerk(min(u + 0.1, 0.5))[1])
            v = self._gain * peak / self._dur if self._dur > 0 else 0.0
            if v > 0:
                target = min(1.0, 0.8 * cap[1] / v)
        step = sim.dt / _TASK_SLOWDOWN_S
        return max(target, self.rate - step) if target < self.rate else min(target, self.rate + step)


# ---------------------------------------------------------------- response motions


class _Decel:
    """A rated-limited deceleration from the measured joint velocity ``qd0`` to rest.

    Every joint follows ``qd(t) = qd0 · g(t/T_j)`` with ``g(u) = 1 − 3u² + 2u³``: the speed
    only falls (nothing adds speed), the acceleration starts and ends at zero, its peak is
    ``1.5 |qd0| / T_j`` and the jerk peak ``6 |qd0| / T_j²``. ``T`` is the shortest time that
    keeps both within ``_LIMIT_SHARE`` of every joint's rated limits, and at least ``min_s``;
    every joint uses it (the stop keeps the path's direction) unless its stopping point
    ``q0 + qd0 · T / 2`` would lie past its rated position limit (less ``LIMIT_MARGIN_RAD``):
    that joint stops sooner, ``T_j = 2 · room / |qd0|``, down to the time its full rated
    acceleration and jerk allow (a stop never plans a joint past its limit when the ratings
    can prevent it). The joints come to rest at ``q0 + qd0 · T_j / 2``.
    """

    def __init__(self, q0: np.ndarray, qd0: np.ndarray, min_s: float = 0.0) -> None:
        self.q0 = np.asarray(q0, dtype=float).copy()
        self.qd0 = np.asarray(qd0, dtype=float).copy()
        v = np.abs(self.qd0)
        t_a = float(np.max(1.5 * v / (_LIMIT_SHARE * _DDQ)))
        t_j = float(np.max(np.sqrt(6.0 * v / (_LIMIT_SHARE * _DDDQ))))
        self.T = max(t_a, t_j, min_s) if float(np.max(v)) > 0 else 0.0
        Tj = np.full(7, self.T)
        end = self.q0 + 0.5 * self.qd0 * Tj
        lo, hi = _Q_MIN + LIMIT_MARGIN_RAD, _Q_MAX - LIMIT_MARGIN_RAD
        room = np.where(self.qd0 > 0, hi - self.q0, self.q0 - lo)
        over = ((end > hi) & (self.qd0 > 0)) | ((end < lo) & (self.qd0 < 0))
        if over.any():
            fastest = np.maximum(1.5 * v / _DDQ, np.sqrt(6.0 * v / _DDDQ))
            want = 2.0 * np.maximum(room, 0.0) / np.maximum(v, 1e-12)
            Tj = np.where(over, np.maximum(want, fastest), Tj)
        self.Tj = Tj
        self.q_end = self.q0 + 0.5 * self.qd0 * Tj

    def at(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        if self.T <= 0 or t >= self.T:
            return self.q_end.copy(), np.zeros(7)
        u = np.minimum(max(t, 0.0) / np.maximum(self.Tj, 1e-12), 1.0)
        g = 1.0 - 3.0 * u * u + 2.0 * u ** 3
        big_g = u - u ** 3 + 0.5 * u ** 4
        return self.q0 + self.qd0 * self.Tj * big_g, self.qd0 * g


class _Move:
    """A synchronised straight joint-space move ``qa → qb``, rest to rest.

    The path speed has a trapezoidal profile with sine-shaped acceleration phases
    (acceleration peak ``π v / (2 Ta)``, jerk peak ``π² v / (2 Ta²)``), sized so that every
    joint stays within ``v_max`` (per joint), ``a_max`` and the rated jerk share.
    """

    def __init__(self, qa: np.ndarray, qb: np.ndarray, v_max: np.ndarray, a_max: np.ndarray,
                 j_max: np.ndarray) -> None:
        self.qa = np.asarray(qa, dtype=float)
        self.qb = np.asarray(qb, dtype=float)
        delta = self.qb - self.qa
        self.L = float(np.max(np.abs(delta)))
        self.dir = delta / self.L if self.L > 0 else np.zeros(7)
        if self.L <= 0:
            self.v = self.Ta = self.T = 0.0
            return
        d = np.abs(self.dir)
        nz = d > 1e-12
        v = float(np.min(v_max[nz] / d[nz]))
        a = float(np.min(a_max[nz] / d[nz]))
        j = float(np.min(j_max[nz] / d[nz]))
        ta = max(math.pi * v / (2 * a), math.sqrt(math.pi ** 2 * v / (2 * j)))
        if v * ta > self.L:  # no cruise: lower the peak speed until both phases fit
            lo, hi = 0.0, v
            for _ in range(40):
                mid = 0.5 * (lo + hi)
                tm = max(math.pi * mid / (2 * a), math.sqrt(math.pi ** 2 * mid / (2 * j)))
                lo, hi = (mid, hi) if mid * tm <= self.L else (lo, mid)
            v = max(lo, 1e-9)
            ta = max(math.pi * v / (2 * a), math.sqrt(math.pi ** 2 * v / (2 * j)))
        self.v, self.Ta = v, ta
        self.T = 2 * ta + (self.L - v * ta) / v

    def _s(self, t: float) -> tuple[float, float]:
        v, ta, T = self.v, self.Ta, self.T
        if t <= 0:
            return 0.0, 0.0
        if t >= T:
            return self.L, 0.0
        if t < ta:
            return 0.5 * v * (t - ta / math.pi * math.sin(math.pi * t / ta)), \
                0.5 * v * (1 - math.cos(math.pi * t / ta))
        if t <= T - ta:
            return 0.5 * v * ta + v * (t - ta), v
        s, sd = self._s(T - t)
        return self.L - s, sd

    def at(self, t: float) -> tuple[np.ndarray, np.ndarray]:
        s, sd = self._s(t)
        return self.qa + s * self.dir, sd * self.dir


class StopController:
    """Stop categories (IEC 60204-1): 0 = power off at once; 1 = controlled stop, then
    power off at standstill; 2 = controlled stop, then hold position with power on.

    The controlled stop decelerates every joint from its measured velocity to rest
    (:class:`_Decel`: within the rated acceleration and jerk, never faster than at the
    command; ``ramp_s`` is the shortest deceleration time). Stop 1 then waits for
    standstill (every joint below ``standstill_speed_rad_s``, at most ``settle_s``),
    engages the brakes while the motors still hold, and removes motor power once they have
    engaged (``BRAKE_ENGAGE_S``): the arm does not sag. Stop 2 holds the pose with power on and
    monitors standstill: a drift of any joint beyond ``standstill_tol_rad`` from the held
    pose escalates to stop 0 (the monitored stop is no longer safe).

    Attributes:
        stop_time_s: the planned deceleration time.
        standstill_s: controller time at which every joint came below the standstill
            speed (``None``: not yet).
        escalated: a stop 2 whose standstill monitoring tripped (now a stop 0).
    """

    def __init__(self, category: int, q_now: np.ndarray, qd_now: np.ndarray, ramp_s: float, *,
                 standstill_tol_rad: float = 0.02, standstill_speed_rad_s: float = 0.01,
                 settle_s: float = 0.3) -> None:
        self.category = category
        self.name = f"stop_{category}"
        self.q = np.asarray(q_now, dtype=float).copy()
        self.qd0 = np.asarray(qd_now, dtype=float).copy()
        self.ramp_s = ramp_s
        self.decel = _Decel(self.q, self.qd0, ramp_s)
        self.stop_time_s = self.decel.T
        self.cap = np.abs(self.qd0) + 1e-3
        self.standstill_tol_rad = standstill_tol_rad
        self.standstill_speed_rad_s = standstill_speed_rad_s
        self.settle_s = settle_s
        self.t = 0.0
        self.powered_off = False
        self.standstill_s: float | None = None
        self.escalated = False
        self._hold: np.ndarray | None = None
        self._brakes_at: float | None = None
        self._started = False

    @property
    def done(self) -> bool:
        """Stop 0/1: power is off; stop 2: decelerated and holding."""
        if self.category in (0, 1):
            return self.powered_off
        return self.t >= self.decel.T

    def _power_off(self, sim: ArmSim) -> None:
        sim.command_torque_off()
        self.powered_off = True

    def command(self, sim: ArmSim) -> None:
        q_meas, qd_meas = sim.joint_state()
        if self.standstill_s is None and float(np.max(np.abs(qd_meas))) < self.standstill_speed_rad_s:
            self.standstill_s = self.t
        if self.category == 0 or self.powered_off:
            if not self.powered_off:
                self._power_off(sim)
            else:
                sim.command_torque_off()
            self.t += sim.dt
            return
        if not self._started:
            sim.rebase_reference()  # the servo starts from the measured state, not the task's
            self._started = True
        t_next = self.t + sim.dt
        if self.t >= self.decel.T:
            if self.category == 1:
                if self._brakes_at is None and (self.standstill_s is not None
                                                or self.t >= self.decel.T + self.settle_s):
                    self._brakes_at = self.t  # standstill: engage the brakes, motors still hold
                if self._brakes_at is not None and self.t >= self._brakes_at + BRAKE_ENGAGE_S - 1e-9:
                    sim.command_torque_off(brakes_already_engaged=True)
                    self.powered_off = True
                    self.t = t_next
                    return
            else:
                if self._hold is None:
                    self._hold = q_meas.copy()
                if float(np.max(np.abs(q_meas - self._hold))) > self.standstill_tol_rad:
                    self.escalated = True  # standstill monitoring tripped: safe operating stop lost
                    self.category = 0
                    self.name = "stop_0"
                    self._power_off(sim)
                    self.t = t_next
                    return
        q_ref, qd_ref = self.decel.at(t_next)
        if self._hold is not None:
            q_ref = self._hold
        sim.command_joints(q_ref, qd_ref, speed_cap=self.cap)
        self.t = t_next
