"""What a governed run returns and how it is judged: one :class:`CycleRecord` per control cycle,
the run's :class:`SimResult`, and :func:`check_sim_expectations` against the block's ``expect:``
(used by ``run_sim``'s callers and by the recording's title; no PyBullet)."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field, replace
from typing import Any

from ._model import SimBlock

__all__ = ["CycleRecord", "SimResult", "check_sim_expectations"]


@dataclass(frozen=True)
class CycleRecord:
    """One control cycle of a governed run.

    Attributes:
        cycle: control-cycle index (0-based; the monitor's ``Decision.cycle`` is ``monitor_cycle``).
        t_s: simulated time at which the signals were read.
        signals: what the monitor was given (after dropouts; NaN for a dropped value).
        override, response, violations, risk, faults, latched: the monitor's decision (each fault
            as its message, ``str(fault)``).
        controller: the controller that commanded the arm in this same cycle.
        joint_speed_max_rad_s: the largest |joint velocity| over this cycle's physics substeps.
        safe_pose_error_rad: max |q − q_safe| after the cycle's physics.
        human_distance_true_m: the simulated distance (also during a sensor dropout).
        joint_speed_start_rad_s: the largest |joint velocity| when the cycle began (measured,
            before the controller's command).
        accel_ratio: the largest |joint acceleration| / rated acceleration over this cycle's
            physics substeps.
        link_speed_max_m_s: the fastest link frame or held object at the end of the cycle.
        contact_force_true_n: the simulated contact force (also during a sensor dropout).
        powered: motor power on after the cycle.
        dropped: ``"object (why)"`` for each held object that left the gripper in this cycle
            other than by the task's release.
        task_stopped: in the cycle the task found its object missing and stopped, why.
        escalated: in the cycle a stop 0/1's power-off was refused because the brakes cannot
            hold arm + payload (held powered, a stop 2 instead), why (issue 32 item 1).
    """

    cycle: int
    monitor_cycle: int
    t_s: float
    signals: dict[str, float]
    override: bool
    response: str
    violations: tuple[str, ...]
    risk: float | None
    faults: tuple[str, ...]
    latched: bool
    controller: str
    task_step: str
    joint_speed_max_rad_s: float
    safe_pose_error_rad: float
    human_distance_true_m: float
    joint_speed_start_rad_s: float = 0.0
    accel_ratio: float = 0.0
    link_speed_max_m_s: float = 0.0
    contact_force_true_n: float = 0.0
    powered: bool = True
    retreat_decelerating: bool = False
    hazard_distance_true_m: float = 10.0
    dropped: tuple[str, ...] = ()
    task_stopped: str = ""
    retreat_rate: float | None = None
    replanned: str = ""
    escalated: str = ""


@dataclass
class SimResult:
    """The outcome of :func:`run_sim`.

    Attributes:
        trace: one :class:`CycleRecord` per control cycle.
        first_override_cycle: first cycle with ``override`` (``None``: never).
        override_reaction_cycles: cycles from that decision to the first cycle a
            response controller commanded the arm (0 = same cycle; ``None``: no override).
        time_to_safe_pose_s: simulated seconds from the first override to every joint
            within the spec's tolerance of the safe pose (``None``: not reached / not asked).
        max_joint_speed_safe_pose_rad_s: largest |joint velocity| (per physics step)
            while the safe-pose controller drove the arm (``None``: it never did).
        joint_speed_limit_rad_s: the spec's safe-pose joint-speed limit.
        min_separation_m: smallest simulated human–robot distance of the run
            (``inf`` when the scene has no humans).
        task_completed: every task primitive finished.
        released: an override was released (override went back to false) before the end.
        executed_response: the most severe response the arm executed ("none" if none).
        fired: ids of every obligation violated at least once.
        fault_cycles: cycles whose decision carried fail-closed faults.
        sim_time_s, wall_time_s, realtime_factor: simulated time; wall-clock time of the run
            (setup, loop and recorded frames); simulated over wall-clock time of the loop alone.
        files: every path written to ``record_dir`` (frames, traces, ``summary.json``, ``plot.png``).
        stop_speed_gain: peak joint speed while a stop controller ran, or the safe pose
            decelerated from the task's speed, over the largest joint speed at its command
            (``None``: no stop, or the arm was at rest).
        max_accel_ratio: peak |q̈_j| / rated q̈_max,j while a response controller drove the
            arm, contact cycles left out (``None``: no response).
        time_to_standstill_s: from the first stop command to every joint below 0.01 rad/s.
        powered_at_end: motor power on at the end of the run.
        retreat_max_link_speed_near_human_m_s: fastest link frame or held object during the
            safe-pose retreat (after its deceleration) while a person was within ``near_human_m``.
        retreat_min_separation_m: closest approach to a person during the retreat.
        max_contact_force_n: peak simulated contact force of the run.
        route: the route the safe-pose planner took (``None``: no safe pose).
        min_hazard_distance_after_override_m: closest a hazard-tagged object came to a person
            from the first override on (``None``: no override).
        dropped: ``(object, t_s, why)`` for every held object that left the gripper other than by
            the task's release (``power_off``: a gripper that is not self-locking lost power;
            ``slipped``: pulled out beyond the fingers' friction).
        object_end_z_m: height of every object's centre at the end of the run.
        hazard_axis_angle_end_deg: at the end, the angle between the held object's declared
            ``hazard_axis`` and the direction to the worst-placed person: the smallest over every
            person present, not only the nearest (``None``: none held/declared).
        hazard_axis_angles_end_deg: the same angle per person at the end (``{}``: none).
        hazard_axis_min_swing_deg: per person, how far (deg) the axis turned toward them below
            the angle it had at the first override, at the worst cycle from then on (0: never;
            ``{}``: none held/declared).
        max_human_speed_ratio: the largest measured horizontal speed of a person (from its true
            position, cycle to cycle) over the fastest speed its waypoints script (``None``: no
            moving person).
        human_overshoot_m: the furthest a person went past its last waypoint, along the last
            segment it walked, from the time it should have arrived (``None``: no moving person).
        max_past_limit_mrad: the furthest any joint went past its rated position limit (mrad,
            every physics step of the run; 0 = never outside).
        acknowledgements: ``(t_s, accepted, message)`` for every operator acknowledgement.
        brake_log: ``(t_s, what)`` for every power-off: the brakes' check of arm + payload, and a
            refused power-off's reason (issue 32); ``brakes_escalated``: any was refused.
        max_travel_unpowered_rad, max_drop_unpowered_m: the furthest any joint travelled, and the
            grasp point fell, from where they were at a power-off, while unpowered.
        task_resumes: how often the task resumed after a response.
        starts: ``(t_s, accepted, message)`` for every operator start command (``sim.start_at_s``).
        reset_started_motion: the task resumed after an accepted acknowledgement with no accepted
            start since (the reset itself started motion).
        restart_max_speed_in_zone_m_s: after the first restart, the fastest link frame (m/s) in a
            task cycle with a person within the near-human zone (true distance); ``None``: none.
        restart_zone_breaches: such cycles above the zone's speed.
        min_response_s: the shortest time a response drove the arm before the task resumed
            (``None``: the task never resumed).
        task_stopped: why the task stopped for good (the object it should carry was not in the
            gripper; the arm held in a stop 2), ``None`` when it did not.
        wrist_turn_rad: how far the retreat turned joint 7 from the spec's safe pose to point
            a held hazard away from people (``None``: no retreat).
    """

    trace: list[CycleRecord] = field(default_factory=list)
    first_override_cycle: int | None = None
    override_reaction_cycles: int | None = None
    time_to_safe_pose_s: float | None = None
    max_joint_speed_safe_pose_rad_s: float | None = None
    joint_speed_limit_rad_s: float = 1.0
    min_separation_m: float = math.inf
    task_completed: bool = False
    released: bool = False
    executed_response: str = "none"
    fired: tuple[str, ...] = ()
    fault_cycles: int = 0
    sim_time_s: float = 0.0
    wall_time_s: float = 0.0
    realtime_factor: float = 0.0
    files: list[str] = field(default_factory=list)
    stop_speed_gain: float | None = None
    max_accel_ratio: float | None = None
    time_to_standstill_s: float | None = None
    powered_at_end: bool = True
    retreat_max_link_speed_near_human_m_s: float | None = None
    retreat_min_separation_m: float | None = None
    max_contact_force_n: float = 0.0
    route: str | None = None
    min_hazard_distance_after_override_m: float | None = None
    dropped: tuple[tuple[str, float, str], ...] = ()
    hazard_axis_angle_end_deg: float | None = None
    hazard_axis_angles_end_deg: dict[str, float] = field(default_factory=dict)
    hazard_axis_min_swing_deg: dict[str, float] = field(default_factory=dict)
    wrist_turn_rad: float | None = None
    task_stopped: str | None = None
    object_end_z_m: dict[str, float] = field(default_factory=dict)
    max_human_speed_ratio: float | None = None
    human_overshoot_m: float | None = None
    acknowledgements: tuple[tuple[float, bool, str], ...] = ()
    max_past_limit_mrad: float = 0.0
    brake_log: tuple[tuple[float, str], ...] = ()
    brakes_escalated: bool = False
    max_travel_unpowered_rad: float = 0.0
    max_drop_unpowered_m: float = 0.0
    task_resumes: int = 0
    starts: tuple[tuple[float, bool, str], ...] = ()
    reset_started_motion: bool = False
    restart_max_speed_in_zone_m_s: float | None = None
    restart_zone_breaches: int = 0

    def observe_resume(self, acks: list, starts: list) -> None:
        """The task resumed: did the reset itself start it (an accepted acknowledgement, in
        ``acks``, with no accepted start since, in ``starts``: ``(t_s, accepted, message)``)?"""
        last_ack = max((t for t, ok, _ in acks if ok), default=None)
        last_start = max((t for t, ok, _ in starts if ok), default=None)
        if last_ack is not None and (last_start is None or last_start < last_ack):
            self.reset_started_motion = True

    def observe_restart(self, rec: CycleRecord, zone: tuple[float, float] | None) -> None:
        """A task cycle after a restart: with a person within the zone ``(distance_m, speed_m_s)``
        (true distance), its fastest link frame (at least the end effector) counts."""
        if zone is not None and rec.human_distance_true_m < zone[0]:
            v = rec.link_speed_max_m_s
            self.restart_max_speed_in_zone_m_s = max(self.restart_max_speed_in_zone_m_s or 0.0, round(v, 4))
            self.restart_zone_breaches += int(v > zone[1])
    min_response_s: float | None = None

    @property
    def override(self) -> bool:
        """The monitor overrode at least once."""
        return self.first_override_cycle is not None

    def summary(self) -> dict[str, Any]:
        """The scalar results as a JSON-ready dict (no trace)."""
        # asdict of a copy without the trace: asdict deep-copies every field, and the trace's
        # thousands of records were most of the time a summary took
        d = {k: v for k, v in asdict(replace(self, trace=[])).items() if k not in ("trace",)}
        d["override"] = self.override
        d["fired"] = list(self.fired)
        if d["min_separation_m"] == math.inf:
            d["min_separation_m"] = None
        return d


def check_sim_expectations(sim_block: SimBlock, result: SimResult) -> list[str]:
    """Compare a run with the block's ``expect:`` (and the always-on rules).

    Always checked: the response controller took over in the override's own
    cycle (``max_reaction_cycles``, default 0), and the safe-pose move kept every
    joint at or under the spec's speed limit (+1 % for physics jitter) once it had
    decelerated from the task's speed.

    Returns:
        Problems as one-line messages; an empty list means the run passed.
    """
    ex = sim_block.expect
    out: list[str] = []
    r = result
    if r.override_reaction_cycles is not None and r.override_reaction_cycles > ex.max_reaction_cycles:
        out.append(f"sim: response controller took over {r.override_reaction_cycles} cycle(s) after "
                   f"the override at cycle {r.first_override_cycle} (allowed {ex.max_reaction_cycles})")
    lim = r.joint_speed_limit_rad_s
    if r.max_joint_speed_safe_pose_rad_s is not None and r.max_joint_speed_safe_pose_rad_s > lim * 1.01:
        out.append(f"sim: joint speed {r.max_joint_speed_safe_pose_rad_s:.3f} rad/s on the way to the "
                   f"safe pose exceeds the limit {lim:g} rad/s")
    if ex.safe_pose_within_s is not None:
        if r.first_override_cycle is None:
            out.append(f"sim: expected the safe pose within {ex.safe_pose_within_s:g} s, "
                       "but the monitor never overrode")
        elif r.time_to_safe_pose_s is None:
            out.append(f"sim: safe pose not reached (override at cycle {r.first_override_cycle}, "
                       f"response {r.executed_response})")
        elif r.time_to_safe_pose_s > ex.safe_pose_within_s + 1e-9:
            out.append(f"sim: safe pose reached after {r.time_to_safe_pose_s:.3f} s, "
                       f"expected within {ex.safe_pose_within_s:g} s")
    if ex.min_separation_m is not None and r.min_separation_m < ex.min_separation_m:
        out.append(f"sim: human-robot separation fell to {r.min_separation_m:.3f} m, "
                   f"expected never below {ex.min_separation_m:g} m")
    if ex.task_completed is not None and r.task_completed != ex.task_completed:
        out.append(f"sim: task_completed is {str(r.task_completed).lower()}, "
                   f"expected {str(ex.task_completed).lower()}")
    if ex.released is not None and r.released != ex.released:
        out.append(f"sim: override {'was' if r.released else 'was not'} released, "
                   f"expected released: {str(ex.released).lower()}")
    if ex.response is not None and r.executed_response != ex.response:
        out.append(f"sim: the arm executed {r.executed_response!r}, expected {ex.response!r}")
    if ex.max_stop_speed_gain is not None and r.stop_speed_gain is not None \
            and r.stop_speed_gain > ex.max_stop_speed_gain + 1e-9:
        out.append(f"sim: a stop sped the arm up to {r.stop_speed_gain:.2f} x the joint speed at its "
                   f"command, expected at most {ex.max_stop_speed_gain:g} x")
    if ex.max_accel_ratio is not None and r.max_accel_ratio is not None \
            and r.max_accel_ratio > ex.max_accel_ratio + 1e-9:
        out.append(f"sim: a joint accelerated at {r.max_accel_ratio:.2f} x its rated acceleration during "
                   f"the response, expected at most {ex.max_accel_ratio:g} x")
    if ex.standstill_within_s is not None:
        if r.time_to_standstill_s is None:
            out.append(f"sim: the arm never came to standstill after a stop (expected within "
                       f"{ex.standstill_within_s:g} s)")
        elif r.time_to_standstill_s > ex.standstill_within_s + 1e-9:
            out.append(f"sim: standstill {r.time_to_standstill_s:.3f} s after the stop command, expected "
                       f"within {ex.standstill_within_s:g} s")
    if ex.powered_off is not None and (not r.powered_at_end) != ex.powered_off:
        out.append(f"sim: motor power is {'on' if r.powered_at_end else 'off'} at the end, expected "
                   f"powered_off: {str(ex.powered_off).lower()}")
    if ex.retreat_max_link_speed_m_s is not None and r.retreat_max_link_speed_near_human_m_s is not None \
            and r.retreat_max_link_speed_near_human_m_s > ex.retreat_max_link_speed_m_s + 1e-9:
        out.append(f"sim: the retreat moved a link at {r.retreat_max_link_speed_near_human_m_s:.3f} m/s within "
                   f"{ex.near_human_m:g} m of a person, expected at most {ex.retreat_max_link_speed_m_s:g} m/s")
    if ex.retreat_min_separation_m is not None and r.retreat_min_separation_m is not None \
            and r.retreat_min_separation_m < ex.retreat_min_separation_m:
        out.append(f"sim: the retreat came to {r.retreat_min_separation_m:.3f} m of a person, expected "
                   f"never below {ex.retreat_min_separation_m:g} m")
    if ex.max_contact_force_n is not None and r.max_contact_force_n > ex.max_contact_force_n:
        out.append(f"sim: contact force reached {r.max_contact_force_n:.1f} N, expected at most "
                   f"{ex.max_contact_force_n:g} N")
    if ex.min_hazard_distance_m is not None and r.min_hazard_distance_after_override_m is not None \
            and r.min_hazard_distance_after_override_m < ex.min_hazard_distance_m:
        out.append(f"sim: a hazardous object came to {r.min_hazard_distance_after_override_m:.3f} m of a person "
                   f"after the override, expected never below {ex.min_hazard_distance_m:g} m")
    if ex.min_hazard_axis_angle_deg is not None:
        a = r.hazard_axis_angle_end_deg
        if a is None:
            out.append("sim: expected a held object with a hazard_axis and a person at the end "
                       "(min_hazard_axis_angle_deg), found none")
        elif a < ex.min_hazard_axis_angle_deg - 1e-9:
            who = min(r.hazard_axis_angles_end_deg, key=r.hazard_axis_angles_end_deg.get,
                      default="a person")
            out.append(f"sim: at the end the held object's hazard axis is {a:.1f} deg from the "
                       f"direction to {who} (the worst-placed person; every person counts), expected "
                       f"at least {ex.min_hazard_axis_angle_deg:g} deg (pointed away)")
    if ex.max_human_speed_ratio is not None and r.max_human_speed_ratio is not None \
            and r.max_human_speed_ratio > ex.max_human_speed_ratio + 1e-9:
        out.append(f"sim: a person moved at {r.max_human_speed_ratio:.2f} x the fastest speed its "
                   f"waypoints script, expected at most {ex.max_human_speed_ratio:g} x")
    if ex.max_human_overshoot_m is not None and r.human_overshoot_m is not None \
            and r.human_overshoot_m > ex.max_human_overshoot_m + 1e-9:
        out.append(f"sim: a person went {r.human_overshoot_m:.3f} m past its last waypoint, expected "
                   f"at most {ex.max_human_overshoot_m:g} m")
    if ex.max_drop_after_power_off_m is not None and r.max_drop_unpowered_m > ex.max_drop_after_power_off_m:
        out.append(f"sim: after power-off the grasp point fell {r.max_drop_unpowered_m:.3f} m, expected "
                   f"at most {ex.max_drop_after_power_off_m:g} m")
    if ex.brakes_escalated is not None and r.brakes_escalated != ex.brakes_escalated:
        out.append(f"sim: brakes_escalated {r.brakes_escalated}, expected {ex.brakes_escalated}"
                   + (f" ({r.brake_log[-1][1]})" if r.brake_log else ""))
    if ex.max_past_limit_mrad is not None and r.max_past_limit_mrad > ex.max_past_limit_mrad + 1e-9:
        out.append(f"sim: a joint went {r.max_past_limit_mrad:.2f} mrad past its rated position limit, "
                   f"expected at most {ex.max_past_limit_mrad:g} mrad")
    if ex.acknowledgements is not None:
        got = tuple(a for _, a, _ in r.acknowledgements)
        if got != tuple(ex.acknowledgements):
            said = "; ".join(f"{t:g} s {'accepted' if a else 'refused'} ({m})"
                             for t, a, m in r.acknowledgements) or "none"
            out.append(f"sim: acknowledgements {[str(a).lower() for a in got]} ({said}), expected "
                       f"{[str(a).lower() for a in ex.acknowledgements]}")
    if ex.starts is not None:
        got = tuple(a for _, a, _ in r.starts)
        if got != tuple(ex.starts):
            said = "; ".join(f"{t:g} s {'accepted' if a else 'refused'} ({m})" for t, a, m in r.starts) or "none"
            out.append(f"sim: starts {[str(a).lower() for a in got]} ({said}), expected "
                       f"{[str(a).lower() for a in ex.starts]}")
    if ex.reset_started_motion is not None and r.reset_started_motion != ex.reset_started_motion:
        out.append(f"sim: reset_started_motion is {str(r.reset_started_motion).lower()}, expected "
                   f"{str(ex.reset_started_motion).lower()} (an acknowledgement must not start motion)")
    if ex.max_restart_speed_in_zone_m_s is not None and r.restart_max_speed_in_zone_m_s is not None \
            and r.restart_max_speed_in_zone_m_s > ex.max_restart_speed_in_zone_m_s * 1.01:
        out.append(f"sim: after a restart a link reached {r.restart_max_speed_in_zone_m_s:.3f} m/s with a person "
                   f"inside the slow zone ({r.restart_zone_breaches} cycles over the zone's speed), expected at "
                   f"most {ex.max_restart_speed_in_zone_m_s:g} m/s")
    if ex.min_response_s is not None and r.min_response_s is not None \
            and r.min_response_s < ex.min_response_s - 1e-9:
        out.append(f"sim: a response lasted only {r.min_response_s:.3f} s before the task resumed "
                   f"({r.task_resumes} resumptions), expected at least {ex.min_response_s:g} s")
    if ex.task_stopped_object_missing is not None and \
            (r.task_stopped is not None) != ex.task_stopped_object_missing:
        out.append(f"sim: task stopped for a missing object: {r.task_stopped or 'no'}; expected "
                   f"task_stopped_object_missing: {str(ex.task_stopped_object_missing).lower()}")
    if ex.object_dropped is not None and bool(r.dropped) != ex.object_dropped:
        what = ", ".join(f"{n} at {t:g} s ({why})" for n, t, why in r.dropped) or "none"
        out.append(f"sim: held objects dropped: {what}; expected object_dropped: "
                   f"{str(ex.object_dropped).lower()}")
    for name, (lo, hi) in (ex.object_end_z_m or {}).items():
        z = r.object_end_z_m.get(name)
        if z is None or not (lo - 1e-9 <= z <= hi + 1e-9):
            out.append(f"sim: {name} ends at height {z if z is None else round(z, 3)} m, expected "
                       f"within [{lo:g}, {hi:g}] m")
    if ex.route is not None and r.route != ex.route:
        out.append(f"sim: the safe-pose planner took route {r.route!r}, expected {ex.route!r}")
    return out
