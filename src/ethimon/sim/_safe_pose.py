"""The safe-pose controller: plans a route to the spec's safe pose that keeps away from people
(and turns a held hazard away from them), moves at or under the spec's joint speed limit within
the rated limits, replans when people move, and holds with a category-2 stop when no route is
clear."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ._arm import ArmSim
from ._control import _DDDQ, _DDQ, _DQ, _LIMIT_SHARE, _Q_MAX, _Q_MIN, StopController, _Decel, _Move

__all__ = ["SafePoseController"]

#: a held hazard-tagged object (sharp, hot) within this of a person is never carried nearer
#: (by more than 0.05 m) by the safe-pose retreat, whatever the spec's near-human zone
_HAZARD_KEEP_M = 1.5
#: a held object's declared hazard_axis (blade tip, spout) ends the retreat at least this far
#: (deg) from the direction to the nearest person (90 = side-on; the margin allows for people moving)
_HAZARD_AWAY_DEG = 135.0
#: a hazard axis may turn this much (deg) toward a person along a route (sampling, the
#: wrist's own swing) before the route counts as sweeping it through them; also the
#: hysteresis before a moving person makes the retreat re-orient it
_AXIS_SLACK_DEG = 10.0
#: at rest (holding, or turned in place), a full trial plan (a retreat clear now) is tried at most
#: this often (s); while holding, a wrist turn away from the people whenever someone moves 0.1 m
_RECHECK_S = 1.0


class SafePoseController:
    """Takes the arm to the safe pose, around people and obstacles, or holds if it cannot.

    At its first command it reads the measured joint state and (1) decelerates from the
    current velocity (:class:`_Decel`, rated-limited, never adding speed) when the arm
    moves; (2) plans the route from where that leaves the arm: the straight joint-space
    line, else a fold-first, a lift-first or an away-from-the-person waypoint, each
    sampled every ``sample_rad`` in the PyBullet scene (:meth:`ArmSim.probe`) and kept
    only if it stays 0.02 m clear of every obstacle, table and the floor and never brings
    the arm (or a held hazardous object) more than 0.1 m (0.05 m) nearer any person than
    it is now, or than ``near_human[0]`` (1.5 m at least for a hazard), nor within 0.3 m;
    the fastest route of those
    that pass is taken; (3) when none passes it holds the pose
    like a stop 2 (``name`` becomes ``"stop_2"``).

    Every joint keeps ``margin × max_joint_speed_rad_s`` and the rated speed,
    ``accel_rad_s2`` and the rated acceleration and jerk shares; with ``near_human =
    (distance_m, speed_m_s)`` (the spec's near-human speed rule) a route that passes
    within ``distance_m`` (+ 0.5 m, people move) of a person is slowed so that no link
    frame or held object exceeds 0.8 × ``speed_m_s``.

    Attributes (after the first command):
        route: ``"direct"``, ``"fold"``, ``"lift"``, ``"away"``, ``"hold"`` or ``"none"`` (at rest there).
        planned_closest_m: closest planned approach of the arm to a person on the route.
        speed_cap_m_s: the Cartesian cap applied (``None``: none).
        plan_s: planned time from the first command to the safe pose.
        q_safe: the pose the retreat goes to: the spec's, with joint 7 turned by
            ``wrist_turn_rad`` when a held object's ``hazard_axis`` would otherwise point
            toward a person (``hazard_axis_angle_deg``: its planned angle from them there).
    """

    name = "safe_pose"

    def __init__(self, q_now: np.ndarray, q_safe: Sequence[float], max_joint_speed_rad_s: float,
                 *, margin: float = 0.98, accel_rad_s2: float = 8.0,
                 near_human: tuple[float, float] | None = None, plan: bool = True,
                 sample_rad: float = 0.05, path_back: Sequence[np.ndarray] = ()) -> None:
        self.q0 = np.asarray(q_now, dtype=float)
        self.q_safe = np.asarray(q_safe, dtype=float)
        self._q_spec = self.q_safe.copy()
        self._alt_safe: list[tuple[np.ndarray, float, float]] = []
        self.v_limit = float(max_joint_speed_rad_s)
        self.v_joint = np.minimum(margin * self.v_limit, 0.98 * _DQ)
        self.a_joint = np.minimum(accel_rad_s2, _LIMIT_SHARE * _DDQ)
        self.j_joint = _LIMIT_SHARE * _DDDQ
        self.near_human = near_human
        self.plan = plan
        self.sample_rad = sample_rad
        #: the way the arm came in (most recent first): route ``back`` retraces it
        self.path_back = [np.asarray(q, dtype=float) for q in path_back]
        self.route = ""
        self.planned_closest_m: float | None = None
        self.speed_cap_m_s: float | None = None
        self.plan_s = 0.0
        self.wrist_turn_rad = 0.0
        self.hazard_axis_angle_deg: float | None = None
        self.t = 0.0
        self._decel: _Decel | None = None
        self._moves: list[_Move] = []
        self._gains: list[float] = []   # per move: link metres per rad of path (fastest joint)
        self._hold: StopController | None = None
        self._started = False
        #: path time along the planned moves and its rate (1 = as planned; lowered when a
        #: person comes into range, 0 = paused on the path before a re-plan)
        self.tau = 0.0
        self.rate = 1.0
        self.min_rate = 1.0
        #: every change of plan after the first: ``(t_s, why)`` (controller time)
        self.replans: list[tuple[float, str]] = []
        self._need: tuple[float, float] = (0.0, 0.0)   # (human, hazard) clearance the route keeps
        self._checked_xy: dict[str, np.ndarray] = {}
        self._blocked = False
        self._arrival_checked = False
        self._last_trial_s = -math.inf  # sim time of the last trial plan (_try_plan)

    @property
    def holding(self) -> StopController | None:
        """The stop 2 that holds the arm when no route was clear (``None`` otherwise)."""
        return self._hold

    @property
    def decelerating(self) -> bool:
        """Still slowing down from the task's velocity (before the planned route starts)."""
        return (self._started and self._hold is None and self._decel is not None
                and self.t < self._decel.T)

    @property
    def done(self) -> bool:
        """The reference has arrived (the measured pose may still be settling) or it holds."""
        if not self._started:
            return False
        if self._hold is not None:
            return True
        t_dec = self._decel.T if self._decel else 0.0
        return self.t >= t_dec and self.tau >= sum(m.T for m in self._moves) - 1e-12

    # -- planning

    def _moves_for(self, waypoints: list[np.ndarray]) -> list[_Move]:
        return [_Move(a, b, self.v_joint, self.a_joint, self.j_joint)
                for a, b in zip(waypoints, waypoints[1:]) if np.max(np.abs(b - a)) > 1e-9]

    def _samples(self, waypoints: list[np.ndarray]) -> list[np.ndarray]:
        out = [waypoints[0]]
        for a, b in zip(waypoints, waypoints[1:]):
            n = max(1, int(math.ceil(float(np.max(np.abs(b - a))) / self.sample_rad)))
            out += [a + (k / n) * (b - a) for k in range(1, n + 1)]
        return out

    def _candidates(self, sim: ArmSim, q_start: np.ndarray) -> list[tuple[str, list[np.ndarray]]]:
        qs = self.q_safe
        out = [("direct", [q_start, qs])]
        fold = q_start.copy()
        fold[[1, 3, 5]] = qs[[1, 3, 5]]  # shoulder, elbow and wrist pitch to the safe pose first
        out.append(("fold", [q_start, fold, qs]))
        key = tuple(np.round(q_start, 9)) + tuple(np.round(np.concatenate(
            list(sim.human_xy().values()) or [np.zeros(2)]), 6))
        if getattr(self, "_via_key", None) != key:  # the lift/away waypoints (IK) once per start
            self._via_key, self._via = key, []
            try:
                ee = sim.fk(q_start)
                lift = np.clip(sim.solve_ik((ee[0], ee[1], ee[2] + 0.2), seed=q_start), _Q_MIN, _Q_MAX)
                if np.linalg.norm(sim.fk(lift) - (ee + (0, 0, 0.2))) < 0.03:
                    self._via.append(("lift", lift))
                away = sim.away_from_humans(ee, 0.25)
                if away is not None:
                    q_away = np.clip(sim.solve_ik(away, seed=q_start), _Q_MIN, _Q_MAX)
                    if np.linalg.norm(sim.fk(q_away) - away) < 0.03:
                        self._via.append(("away", q_away))
            except Exception:  # noqa: BLE001 - IK trouble only removes candidates
                pass
        out += [(name, [q_start, via, qs]) for name, via in self._via]
        if abs(float(qs[6] - q_start[6])) > 0.05:
            # a held hazard turned away in place first (joint 7 alone), then direct or folding:
            # the blade is not carried round through someone while the wrist still turns
            wrist = q_start.copy()
            wrist[6] = qs[6]
            fold_w = wrist.copy()
            fold_w[[1, 3, 5]] = qs[[1, 3, 5]]
            out += [("direct", [q_start, wrist, qs]), ("fold", [q_start, wrist, fold_w, qs])]
        # back out the way the arm came in (its task's joint-space path, reversed), then go
        back, prev = [q_start], q_start
        for p in self.path_back:
            if float(np.max(np.abs(p - prev))) > 0.05:
                back.append(p)
                prev = p
                out.append(("back", back + [qs]))
        return out

    def _orient_hazard(self, sim: ArmSim, q_start: np.ndarray | None = None) -> None:
        """With a held object whose ``hazard_axis`` is declared, turn the safe pose's wrist
        (joint 7, within its rated range) so that the axis points away from the nearest person
        (where people are now): the spec's angle when it leaves the axis at least
        ``_HAZARD_AWAY_DEG`` from the direction to them, else the nearest angle that does, else
        the one that points it furthest away. The routes are then planned (and collision-
        checked) to that pose. Other angles that point it away (nearest the wrist's angle at
        ``q_start`` first, at most 2) are kept in ``_alt_safe``: a route to the first pose may
        sweep the axis through someone, one to another may not."""
        spec = self._q_spec
        self._alt_safe = []
        base = sim.hazard_axis_angles_deg([spec])
        if base is None or base[0] >= _HAZARD_AWAY_DEG:
            self.q_safe = spec.copy()
            self.wrist_turn_rad = 0.0
            self.hazard_axis_angle_deg = base[0] if base else None
            return
        q7 = np.linspace(_Q_MIN[6] + 0.02, _Q_MAX[6] - 0.02, 121)
        poses = []
        for v in q7:
            q = spec.copy()
            q[6] = v
            poses.append(q)
        angles = np.asarray(sim.hazard_axis_angles_deg(poses))
        ok = np.flatnonzero(angles >= _HAZARD_AWAY_DEG)
        i = (int(ok[np.argmin(np.abs(q7[ok] - spec[6]))]) if ok.size
             else int(np.argmax(angles)))
        if angles[i] > base[0]:
            self.wrist_turn_rad = float(q7[i] - spec[6])
            self.q_safe = poses[i]
            self.hazard_axis_angle_deg = float(angles[i])
        else:
            self.q_safe = spec.copy()
            self.wrist_turn_rad = 0.0
            self.hazard_axis_angle_deg = base[0]
        if ok.size and q_start is not None:
            picked = [q7[i]]
            for k in ok[np.argsort(np.abs(q7[ok] - q_start[6]))]:
                if all(abs(q7[k] - v) > 0.3 for v in picked):
                    picked.append(q7[k])
                    self._alt_safe.append((poses[k], float(q7[k] - spec[6]), float(angles[k])))
                if len(self._alt_safe) >= 2:
                    break

    def _plan(self, sim: ArmSim, q_start: np.ndarray) -> None:
        self._alt_safe = []
        if self.plan:
            self._orient_hazard(sim, q_start)
        if float(np.max(np.abs(self.q_safe - q_start))) <= 1e-6:
            self.route, self._moves = "none", []
            return
        if not self.plan:
            self.route, self._moves = "direct", self._moves_for([q_start, self.q_safe])
            return
        now = sim.probe([q_start])[0]
        need_h, need_z = self._needs(now)
        self._need = (need_h, need_z)
        self._checked_xy = sim.human_xy()
        first = (self.q_safe, self.wrist_turn_rad, self.hazard_axis_angle_deg)
        for target in [first] + list(self._alt_safe):
            self.q_safe, self.wrist_turn_rad, self.hazard_axis_angle_deg = target
            best = self._best_route(sim, q_start, need_h, need_z)
            if best is not None:
                break
        if best is None and self.hazard_axis_angle_deg is not None:
            # no wrist angle that points the axis away (from everyone) is reachable without
            # sweeping it through someone: the best angle that is (the largest end angle among
            # up to 3 tried)
            for target in self._reachable_wrist(sim, q_start):
                self.q_safe, self.wrist_turn_rad, self.hazard_axis_angle_deg = target
                best = self._best_route(sim, q_start, need_h, need_z)
                if best is not None:
                    break
        if best is None:
            turn = self._turn_away(sim, q_start, need_h, need_z)
            if turn is not None:  # stay, but turn the held hazard away from the people
                self.q_safe, self.hazard_axis_angle_deg, self._moves = turn
                self.wrist_turn_rad = float(self.q_safe[6] - self._q_spec[6])
                self.route, self.planned_closest_m = "turn", now["human"]
                self._gains = [self._gain(sim, m.qa, m.qb) for m in self._moves]
                return
            self.q_safe, self.wrist_turn_rad, self.hazard_axis_angle_deg = first
            self.route = "hold"
            self.planned_closest_m = now["human"]
            self._moves, self._gains = [], []
            return
        _, self.route, self._moves, self.planned_closest_m, self.speed_cap_m_s = best
        self._gains = [self._gain(sim, m.qa, m.qb) for m in self._moves]

    def _reachable_wrist(self, sim: ArmSim, q_start: np.ndarray) -> list[tuple[np.ndarray, float, float]]:
        """Safe poses with joint 7 turned less far (from the wrist's angle now toward either
        end of its range, every 0.25 rad), best end angle first, at most 3."""
        spec = self._q_spec
        vals = np.concatenate([np.arange(q_start[6], _Q_MAX[6] - 0.02, 0.25),
                               np.arange(q_start[6], _Q_MIN[6] + 0.02, -0.25)])
        poses = []
        for v in vals:
            q = spec.copy()
            q[6] = v
            poses.append(q)
        angles = sim.hazard_axis_angles_deg(poses) or []
        order = np.argsort(-np.asarray(angles))[:3]
        return [(poses[k], float(vals[k] - spec[6]), float(angles[k])) for k in order]

    def _turn_away(self, sim: ArmSim, q_start: np.ndarray, need_h: float, need_z: float):
        """When no retreat passes: joint 7 alone, from where it is, turned in the direction that
        points the held hazard's axis further from the people, as far as the angle keeps rising
        (never through anyone's direction) and the range allows. ``(pose, angle, moves)``, or
        ``None`` without an axis or when no turn gains 5 deg."""
        per0 = sim.hazard_axis_angles_deg([q_start], each=True)
        if per0 is None:
            return None
        now = [min(per0[0].values())]
        floor = {n: min(a, _HAZARD_AWAY_DEG) - _AXIS_SLACK_DEG for n, a in per0[0].items()}
        best = None
        for sign in (1.0, -1.0):
            vals = np.arange(q_start[6], (_Q_MAX[6] if sign > 0 else _Q_MIN[6]) - sign * 0.02,
                             sign * 0.1)[1:]
            if vals.size == 0:
                continue
            poses = []
            for v in vals:
                q = q_start.copy()
                q[6] = v
                poses.append(q)
            per = sim.hazard_axis_angles_deg(poses, each=True)
            k, top = -1, now[0]
            for i, pa in enumerate(per):  # climb while the worst angle rises (never back toward them)
                a = min(pa.values())
                if a < top - 1.0 or any(pa[n] < f - 1e-6 for n, f in floor.items()):
                    break  # nor more than the slack toward anyone (each person on their own)
                if a > top:
                    k, top = i, a
            if k >= 0 and top >= now[0] + 5.0 and (best is None or top > best[1]):
                best = (poses[k], float(top))
        if best is None or best[1] <= 90.0:  # still in someone's half-space: tilt the wrist too
            tilt = self._tilt_away(sim, q_start if best is None else best[0], q_start, need_h, need_z, floor)
            if tilt is not None:
                best = tilt
        if best is None:
            return None
        pts = sim.probe(self._samples([q_start, best[0]]))
        if (min(p["obstacle"] for p in pts) < 0.02 or min(p["human"] for p in pts) < need_h - 1e-3
                or min(p["hazard"] for p in pts) < need_z - 1e-3):
            return None
        moves = self._moves_for([q_start, best[0]])
        if self.near_human is not None:
            moves = self._capped(sim, [q_start, best[0]], 0.8 * self.near_human[1])
        return best[0], best[1], moves

    def _tilt_away(self, sim: ArmSim, q_from: np.ndarray, q_start: np.ndarray, need_h: float,
                   need_z: float, floor: dict[str, float]):
        """Joint 7 alone leaves the held hazard's axis within 90 deg of someone (its range ends):
        the elbow and the wrist moved too (joint 4 by up to 0.6 rad, 5 by up to 1.5, 6 by up to
        1.2, every 0.3 rad), the pose that points it furthest from everyone, beyond 90 deg, on a
        straight joint-space line from ``q_start`` that never turns it more than the slack toward
        anyone, keeps the clearances and never comes nearer anyone than the arm is now (issue 32:
        the showcase ended 75.6 deg from the child; now 137.6). ``(pose, angle)`` or ``None``."""
        poses = []
        for d4 in np.arange(-0.6, 0.61, 0.3):
            for d5 in np.arange(-1.5, 1.51, 0.3):
                for d6 in np.arange(-1.2, 1.21, 0.3):
                    q = q_from.copy()
                    q[3] += d4
                    q[4] += d5
                    q[5] += d6
                    if np.all(q >= _Q_MIN + 0.02) and np.all(q <= _Q_MAX - 0.02):
                        poses.append(q)
        per = sim.hazard_axis_angles_deg(poses) or []
        h_now = sim.probe([q_start])[0]["human"]
        for k in np.argsort(-np.asarray(per), kind="stable")[:40]:  # the 40 best-pointed, best first
            if per[k] <= 90.0:
                break
            samples = self._samples([q_start, poses[k]])
            angles = sim.hazard_axis_angles_deg(samples, each=True)
            if any(a[n] < f - 1e-6 for a in angles for n, f in floor.items()):
                continue
            pts = sim.probe(samples)
            if (min(p["obstacle"] for p in pts) < 0.02 or min(p["human"] for p in pts) < max(need_h, h_now - 1e-3)
                    or min(p["hazard"] for p in pts) < need_z - 1e-3):
                continue
            return poses[k], float(per[k])
        return None

    def _best_route(self, sim: ArmSim, q_start: np.ndarray, need_h: float, need_z: float):
        """The fastest candidate route to ``q_safe`` that keeps the clearances and the hazard
        axis, as ``(time, name, moves, closest, cap)``; ``None`` when none does."""
        best = None
        for name, wps in self._candidates(sim, q_start):
            smp = self._samples(wps)
            if not self._axis_ok(sim, smp):  # the cheaper check first
                continue
            pts = sim.probe(smp, until=lambda c: (c["obstacle"] < 0.02 or c["human"] < need_h - 1e-3
                                                  or c["hazard"] < need_z - 1e-3))  # stop at the first miss
            h = min(p["human"] for p in pts)
            if min(p["obstacle"] for p in pts) < 0.02 or h < need_h - 1e-3:
                continue
            if min(p["hazard"] for p in pts) < need_z - 1e-3:
                continue
            moves = self._moves_for(wps)
            cap = None
            if self.near_human is not None and h < self.near_human[0] + 0.5:
                cap = 0.8 * self.near_human[1]
                moves = self._capped(sim, wps, cap)
            total = sum(m.T for m in moves)
            if best is None or total < best[0]:
                best = (total, name, moves, h, cap)
        return best

    def _axis_ok(self, sim: ArmSim, samples: list[np.ndarray]) -> bool:
        """A held object's declared hazard axis never turns more toward any person along the
        samples than it points at that person now (or than ``_HAZARD_AWAY_DEG``), less
        ``_AXIS_SLACK_DEG``: a blade or spout is never swept through anyone's direction (each
        person judged on their own, issue 32). True without an axis."""
        floors: dict[str, float] = {}
        turned = []

        def toward(per: dict[str, float]) -> bool:  # the samples stop at the first that fails
            if not floors:  # every person, each against where it points at them now
                floors.update((name, min(a0, _HAZARD_AWAY_DEG) - _AXIS_SLACK_DEG) for name, a0 in per.items())
            if any(per[name] < floor - 1e-6 for name, floor in floors.items()):
                turned.append(True)
            return bool(turned)

        per = sim.hazard_axis_angles_deg(samples, each=True, until=toward)
        return not per or not turned

    def _needs(self, now: dict[str, float]) -> tuple[float, float]:
        """The clearances a route from a pose with clearances ``now`` must keep: never nearer
        a person than now (or than the near-human zone), less 0.1 m of slack for the sampling
        and the arm's swing, never within 0.3 m; a held hazard never more than 0.05 m nearer."""
        keep = self.near_human[0] if self.near_human else 0.3
        need_h = max(min(now["human"], keep) - 0.1, min(now["human"], 0.3))
        keep_z = max(keep, _HAZARD_KEEP_M)
        need_z = max(min(now["hazard"], keep_z) - 0.05, min(now["hazard"], 0.3))
        return need_h, need_z

    def _gain(self, sim: ArmSim, a: np.ndarray, b: np.ndarray) -> float:
        """Largest link-frame (or held object) displacement per rad of path (of the fastest
        joint) along the straight line ``a → b``, from 11 samples."""
        L = float(np.max(np.abs(b - a)))
        if L <= 1e-9:
            return 0.0
        pts = sim.link_points_at([a + (k / 10) * (b - a) for k in range(11)])
        return max(float(np.max(np.linalg.norm(q2 - q1, axis=1))) / (L / 10)
                   for q1, q2 in zip(pts, pts[1:]))

    def _capped(self, sim: ArmSim, wps: list[np.ndarray], cap: float) -> list[_Move]:
        """Moves whose joint speeds keep every link frame at or under ``cap`` m/s."""
        moves = []
        for a, b in zip(wps, wps[1:]):
            L = float(np.max(np.abs(b - a)))
            if L <= 1e-9:
                continue
            gain = self._gain(sim, a, b)  # m per rad of path
            scale = 1.0
            if gain > 0:
                d = np.abs(b - a) / L
                v_path = float(np.min(self.v_joint[d > 1e-12] / d[d > 1e-12]))
                scale = min(1.0, cap / (1.3 * gain * v_path))  # 1.3: chord vs arc, sampling
            moves.append(_Move(a, b, self.v_joint * scale, self.a_joint, self.j_joint))
        return moves

    # -- execution

    def _at(self, tau: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
        """Reference on the planned moves at path time ``tau``: position, velocity and
        acceleration per unit path time, and the move's index (``len`` past the end)."""
        for i, m in enumerate(self._moves):
            if tau <= m.T:
                q, qd = m.at(tau)
                h = 1e-3
                q2, qd2 = m.at(min(tau + h, m.T)) if tau + h <= m.T else m.at(tau)
                qdd = (qd2 - qd) / h if tau + h <= m.T else np.zeros(7)
                return q, qd, qdd, i
            tau -= m.T
        return self.q_safe.copy(), np.zeros(7), np.zeros(7), len(self._moves)

    def _rate_target(self, sim: ArmSim, i: int) -> float:
        """The path-time rate this cycle: 1 as planned; lower when a person is in range now
        (the near-human cap: no link frame or held object above 0.8 V); 0 when the rest of the
        route is no longer clear of the people where they are now (pause, then re-plan)."""
        if self._blocked:
            return 0.0
        r = 1.0
        if self.near_human is not None and i < len(self._moves):
            d = sim.human_distance()
            if d < self.near_human[0] + 0.5:
                cap = 0.8 * self.near_human[1]
                m, g = self._moves[i], self._gains[i]
                if g > 0 and m.v > 0:
                    r = min(r, cap / (1.3 * g * m.v))  # 1.3: chord vs arc, sampling (as planned)
        return r

    def _people_moved(self, sim: ArmSim) -> bool:
        """Someone within 3 m of the arm moved more than 0.1 m since the route was last checked."""
        if not sim.humans:
            return False
        xy = sim.human_xy()
        moved = [n for n, v in xy.items()
                 if n not in self._checked_xy or float(np.linalg.norm(v - self._checked_xy[n])) > 0.1]
        return bool(moved) and sim.human_distance() < 3.0

    def _rest_clear(self, sim: ArmSim) -> bool:
        """The rest of the route (from path time ``tau``) still keeps the clearances, from the
        people where they stand now (checked as at planning, every ``sample_rad``)."""
        self._checked_xy = sim.human_xy()
        q_now = self._at(self.tau)[0]
        rest = [q_now]
        tau = self.tau
        for m in self._moves:
            if tau < m.T:
                rest.append(m.qb)
            tau = max(tau - m.T, 0.0) if tau >= m.T else -1.0
        if len(rest) < 2:
            return True
        pts = sim.probe(self._samples(rest))
        need_h, need_z = self._needs(pts[0])
        need_h = min(need_h, self._need[0]) if pts[0]["human"] >= self._need[0] else need_h
        if min(p["obstacle"] for p in pts) < 0.02:
            return False
        if not (min(p["human"] for p in pts) >= need_h - 1e-3
                and min(p["hazard"] for p in pts) >= need_z - 1e-3):
            return False
        return True

    def _replan(self, sim: ArmSim, q: np.ndarray, why: str) -> None:
        """Plan again from ``q`` (the arm paused on its route) with the people where they are."""
        self.replans.append((round(self.t, 6), why))
        self._plan(sim, q)
        self._blocked = False
        self.tau, self.rate = 0.0, 1.0
        if self.route == "hold":
            q_m, qd_m = sim.joint_state()
            self._hold = StopController(2, q_m, qd_m, 0.0)
            self.name = "stop_2"

    def _try_plan(self, sim: ArmSim, q: np.ndarray, why: str, accept: tuple[str, ...]) -> bool:
        """Plan from ``q`` (the arm at rest there) as a trial: a route named in ``accept`` is
        taken (and counted a re-plan); anything else leaves the current plan as it was. The
        people's positions are noted either way, so the next trial waits until someone moves."""
        if sim.time_s - self._last_trial_s < _RECHECK_S - 1e-9:
            return False
        self._last_trial_s = sim.time_s
        saved = (self.q_safe.copy(), self.wrist_turn_rad, self.hazard_axis_angle_deg, self.route,
                 self._moves, self._gains, self.planned_closest_m, self.speed_cap_m_s, self._need)
        self._plan(sim, q)
        self._checked_xy = sim.human_xy()
        if self.route in accept and self._moves:
            self.replans.append((round(self.t, 6), why))
            self.tau, self.rate, self._blocked = 0.0, 1.0, False
            return True
        (self.q_safe, self.wrist_turn_rad, self.hazard_axis_angle_deg, self.route, self._moves,
         self._gains, self.planned_closest_m, self.speed_cap_m_s, self._need) = saved
        return False

    def _recheck_hold(self, sim: ArmSim) -> bool:
        """While holding (no route was clear, a stop 2 with power on), someone moved: plan again
        from the held pose with the people where they are now. A route that keeps every clearance
        and the hazard axis (a retreat, or a wrist turn away from the people) ends the hold."""
        hold = self._hold
        if (not self.plan or hold is None or hold.category != 2 or hold.t < hold.decel.T
                or not self._people_moved(sim)):
            return False
        q, _ = sim.joint_state()
        self._checked_xy = sim.human_xy()
        now = sim.probe([q])[0]
        need_h, need_z = self._needs(now)
        turn = self._turn_away(sim, q, need_h, need_z)  # cheap: joint 7 alone, checked as routes are
        if turn is not None:
            self.replans.append((round(self.t, 6), "re-checked while holding: the held hazard turns away"))
            self.q_safe, self.hazard_axis_angle_deg, self._moves = turn
            self.wrist_turn_rad = float(self.q_safe[6] - self._q_spec[6])
            self.route, self.planned_closest_m = "turn", now["human"]
            self._gains = [self._gain(sim, m.qa, m.qb) for m in self._moves]
            self.tau, self.rate, self._blocked = 0.0, 1.0, False
        elif not self._try_plan(sim, q, "re-checked while holding: a way is clear now",
                                ("direct", "fold", "lift", "away", "back")):
            return False
        sim.rebase_reference()
        self._hold, self.name, self._decel = None, "safe_pose", None
        self._arrival_checked = False
        return True

    def command(self, sim: ArmSim) -> None:
        if not self._started:
            self._started = True
            q, qd = sim.joint_state()
            sim.rebase_reference()
            self._decel = _Decel(q, qd) if float(np.max(np.abs(qd))) > 1e-3 else None
            q_start = self._decel.q_end if self._decel else q
            self._plan(sim, q_start)
            if self.route == "hold":
                self._hold = StopController(2, q, qd, 0.0)
                self.name = "stop_2"
            t_dec = self._decel.T if self._decel else 0.0
            self.plan_s = t_dec + sum(m.T for m in self._moves)
        if self._hold is not None and not self._recheck_hold(sim):
            self._hold.command(sim)
            self.name = self._hold.name
            return
        self.t += sim.dt
        t = self.t
        t_dec = self._decel.T if self._decel else 0.0
        if self._decel is not None and t < t_dec:
            # the deceleration starts at the task's speed (possibly above the safe-pose limit)
            # and only falls; clipping it at the limit would brake harder than rated
            q, qd = self._decel.at(t)
            sim.command_joints(q, qd, speed_cap=np.abs(self._decel.qd0) + 1e-3)
            return
        # the route, re-planned every cycle: its speed follows the people in range now, and
        # a route that someone now blocks pauses on the path and is planned again
        q, dq, ddq, i = self._at(self.tau)
        arrived_now = i >= len(self._moves) and not self._arrival_checked
        if self.plan and not self._blocked and (arrived_now or self._people_moved(sim)):
            self._arrival_checked = self._arrival_checked or i >= len(self._moves)
            if i < len(self._moves):
                if not self._rest_clear(sim):
                    self._blocked = True
            else:  # arrived: a held hazard's axis still pointed away from the people where they are?
                self._checked_xy = sim.human_xy()
                now = sim.hazard_axis_angles_deg()
                want = _HAZARD_AWAY_DEG if self.route != "turn" else min(
                    _HAZARD_AWAY_DEG, (self.hazard_axis_angle_deg or 0.0) + _AXIS_SLACK_DEG)
                if self.route == "turn" and self._try_plan(
                        sim, q, "turned away in place: the retreat is clear from here",
                        ("direct", "fold", "lift", "away", "back")):
                    self._arrival_checked = False
                    q, dq, ddq, i = self._at(0.0)
                elif now is not None and now[0] < want - _AXIS_SLACK_DEG:
                    self._blocked = True  # plan again from here (a wrist turn, as it can)
        target = self._rate_target(sim, i)
        # change the rate no faster than the rated acceleration allows on top of the planned one
        avail = np.maximum(_LIMIT_SHARE * _DDQ - np.abs(ddq) * self.rate ** 2, 0.05 * _DDQ)
        nz = np.abs(dq) > 1e-9
        rdot = float(np.min(avail[nz] / np.abs(dq[nz]))) if nz.any() else math.inf
        step = rdot * sim.dt
        rate_before = self.rate
        self.rate = (max(target, self.rate - step) if target < self.rate
                     else min(target, self.rate + step))
        self.min_rate = min(self.min_rate, self.rate)
        if self._blocked and self.rate <= 1e-9:
            self._replan(sim, q, "route or hazard axis no longer clear of the people where they are")
            if self._hold is not None:
                self._hold.command(sim)
                self.name = self._hold.name
                return
            q, dq, ddq, i = self._at(0.0)
            rate_before = self.rate
            # at rest with nothing better to do (no move planned), nothing moves and nothing is
            # planned again until someone moves (issue 32: 363 re-plans after arrival)
            self._arrival_checked = bool(self._moves) is False
        # the path time advances by the mean rate over the cycle: the position the servo is given
        # then matches a linear change of the rate (its cubic interpolation keeps a constant
        # acceleration; the end rate alone made it peak at 4x the mean, over the rating)
        self.tau += 0.5 * (rate_before + self.rate) * sim.dt
        q, dq, _, _ = self._at(self.tau)
        sim.command_joints(q, dq * self.rate, max_velocity=self.v_limit)
