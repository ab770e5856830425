"""``--record``: the events, the frames with their overlay, the plot and summary.json."""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

import ethimon

pytest.importorskip("matplotlib")


def _rec(cycle, *, controller="task", override=False, response="none", violations=(), faults=(),
         dist=2.0, force=0.0, qd=0.5, sp_err=1.0, risk=0.1, ee=0.2, powered=True):
    from ethimon.sim._runner import CycleRecord

    kw = dict(cycle=cycle, monitor_cycle=cycle, t_s=cycle / 60, override=override, response=response,
              signals={"human_distance": dist, "ee_speed": ee, "contact_force": force,
                       "joint_speed_max": qd, "hazard_distance": 10.0},
              violations=tuple(violations), risk=risk, faults=tuple(faults), latched=False,
              controller=controller, task_step="reach", joint_speed_max_rad_s=qd,
              safe_pose_error_rad=sp_err, human_distance_true_m=dist, contact_force_true_n=force,
              powered=powered)
    names = {f.name for f in dataclasses.fields(CycleRecord)}
    return CycleRecord(**{k: v for k, v in kw.items() if k in names})


def _stop_trace():
    """task → separation fires → stop 2 → escalates to stop 0 → standstill → released."""
    return [
        _rec(0, dist=1.2, qd=0.8),
        _rec(1, dist=0.7, qd=0.8, override=True, response="stop_2", violations=("separation",),
             controller="stop_2"),
        _rec(2, dist=0.55, qd=0.5, override=True, response="stop_2", violations=("separation",),
             controller="stop_2", force=30.0),
        _rec(3, dist=0.6, qd=0.2, override=True, response="stop_0", violations=("transient_contact",),
             controller="stop_0", force=150.0, powered=False),
        _rec(4, dist=0.8, qd=0.005, override=True, response="stop_0", controller="stop_0", powered=False),
        _rec(5, dist=1.1, qd=0.0, override=False, controller="stop_0", powered=False),
    ]


def test_events_of_a_stop_that_escalates():
    from ethimon.sim._record import trace_events

    ev = trace_events(_stop_trace(), safe_tol=0.02)
    got = [(e["event"], e["cycle"]) for e in ev]
    assert ("first_violation", 1) in got and ("override", 1) in got
    assert ("escalation", 3) in got
    assert next(e for e in ev if e["event"] == "escalation")["detail"] == "stop_2 → stop_0"
    assert ("closest_approach", 2) in got and next(e for e in ev if e["event"] == "closest_approach")["value"] == 0.55
    assert ("peak_contact_force", 3) in got
    assert ("power_off", 3) in got
    assert ("standstill", 4) in got          # first cycle under 0.01 rad/s after the first stop
    assert ("release", 5) in got
    assert "safe_pose" not in {n for n, _ in got} and "first_fault" not in {n for n, _ in got}
    assert [e["cycle"] for e in ev] == sorted(e["cycle"] for e in ev)
    assert all(math.isclose(e["t_s"], e["cycle"] / 60, abs_tol=1e-6) for e in ev)


def test_safe_pose_event_needs_an_override_and_the_tolerance():
    from ethimon.sim._record import trace_events

    tr = [_rec(0, sp_err=0.01),                                   # at the pose, but no override yet
          _rec(1, override=True, response="safe_pose", violations=("risk",), controller="safe_pose",
               sp_err=0.3, faults=("nan input: human_distance",)),
          _rec(2, override=True, response="safe_pose", controller="safe_pose", sp_err=0.021),
          _rec(3, override=True, response="safe_pose", controller="safe_pose", sp_err=0.019),
          _rec(4, override=True, response="safe_pose", controller="safe_pose", sp_err=0.001)]
    ev = trace_events(tr, safe_tol=0.02)
    assert [(e["event"], e["cycle"]) for e in ev if e["event"] == "safe_pose"] == [("safe_pose", 3)]
    assert next(e for e in ev if e["event"] == "first_fault")["cycle"] == 1
    assert not any(e["event"] in ("standstill", "escalation", "release", "peak_contact_force") for e in ev)
    # no people in the scene: no closest approach
    assert not any(e["event"] == "closest_approach" for e in trace_events(tr, has_humans=False))


def test_an_override_after_a_release_is_an_event_again():
    from ethimon.sim._record import trace_events

    tr = [_rec(0),
          _rec(1, override=True, response="safe_pose", violations=("slow_near_human",), controller="safe_pose"),
          _rec(2, controller="task"),                                               # released
          _rec(3, controller="task"),
          _rec(4, override=True, response="stop_2", violations=("separation",), controller="stop_2"),
          _rec(5, override=True, response="stop_2", violations=("separation",), controller="stop_2")]
    ev = [(e["event"], e["cycle"], e["detail"]) for e in trace_events(tr)]
    assert [x for x in ev if x[0] in ("override", "release", "escalation", "first_violation")] == [
        ("first_violation", 1, "slow_near_human"), ("override", 1, "safe_pose"), ("release", 2, ""),
        ("override", 4, "stop_2 (again, after a release)"),
        ("escalation", 4, "safe_pose → stop_2 (after a release)")]


def test_limits_are_read_from_the_spec(root):
    from ethimon.sim._plot import spec_limits, spec_constants

    spec = ethimon.load_spec(str(root / "specs/cobot_cell.yaml"))
    limits, skipped = spec_limits(spec)
    const = {(lim.rule, lim.signal): (lim.constant, lim.value) for lim in limits if lim.value is not None}
    assert const[("slow_near_human", "human_distance")] == ("d_slow", 1.5)
    assert const[("slow_near_human", "ee_speed")] == ("v_slow", 0.25)
    assert const[("transient_contact", "contact_force")] == ("f_transient", 140.0)
    assert const[("clamping", "contact_force")] == ("f_quasi", 65.0)   # inside held(...)
    assert const[("joint_speed", "joint_speed_max")] == ("w_max", 2.0)
    sep = next(lim for lim in limits if lim.rule == "separation")
    assert sep.value is None and sep.op == ">=" and sep.signals_used == {"ee_speed"}
    v = np.array([0.0, 1.0])
    got = sep.values({"ee_speed": v}, spec_constants(spec), 2)
    want = 1.6 * (0.1 + 0.3) + v * 0.1 + v * v / (2 * 2.5) + 0.1 + 0.05  # S_p of the spec's own text
    assert np.allclose(got, want)
    assert skipped == []


def test_limits_not_drawable_are_listed_not_guessed():
    from ethimon.sim._plot import spec_limits
    from ethimon.language import parse_spec_text

    spec = parse_spec_text("""
ethimon: 1
name: odd
signals: {ee_speed: {}, human_distance: {}, contact_force: {}}
constants: {k: 2.0}
obligations:
  - {id: rate, require: "ee_speed <= prev(ee_speed, 0) + 0.1", response: stop_2}
  - {id: rel, require: "human_distance >= ee_speed", response: stop_2}
  - {id: lin, require: "k * 10 > contact_force", response: stop_0}
""")
    limits, skipped = spec_limits(spec)
    assert [(x.rule, x.signal, x.op, x.value) for x in limits] == [("lin", "contact_force", "<", 20.0)]
    assert len(skipped) == 2 and any(s.startswith("rate.require") for s in skipped) \
        and any(s.startswith("rel.require") for s in skipped)


@pytest.mark.slow
def test_plot_has_tau_limits_event_markers_and_a_controller_lane(root):
    from ethimon.sim._plot import build_figure
    from ethimon.sim._record import trace_events

    spec = ethimon.load_spec(str(root / "specs/cobot_cell.yaml"))
    tr = _stop_trace()
    events = trace_events(tr)
    fig, meta = build_figure(tr, spec=spec, events=events, title="t", dt=1 / 60)
    axes = fig.axes
    assert meta["panels"] == ["risk", "human_distance", "ee_speed", "joint_speed", "joint_accel",
                              "contact_force", "hazard_distance", "controller"] and len(axes) == 8
    # one unit per axis; the acceleration panel carries the rated limit (issue 23)
    assert [a.get_ylabel() for a in axes[2:5]] == ["ee speed (m/s)", "joint speed (rad/s)",
                                                  "joint accel.\n(× rated)"]
    rated = [ln for ln in axes[4].get_lines() if ln.get_gid() == "rated_accel"]
    assert len(rated) == 1 and set(rated[0].get_ydata()) == {1.0}
    for a in axes[:-1]:  # legends beside the panels, not over the data
        leg = a.get_legend()
        assert leg is None or leg.get_bbox_to_anchor().x0 > a.get_window_extent().x1 - 1
    tau = [ln for ln in axes[0].get_lines() if ln.get_gid() == "tau"]
    assert len(tau) == 1 and set(tau[0].get_ydata()) == {spec.risk.threshold} and meta["tau"] == spec.risk.threshold
    times = sorted({e["t_s"] for e in events})
    for ax in axes:  # one marker per distinct event time, on every panel
        marks = [ln for ln in ax.get_lines() if (ln.get_gid() or "").startswith("event:")]
        assert sorted(float(ln.get_xdata()[0]) for ln in marks) == pytest.approx(times)
    gids = {ln.get_gid() for ax in axes for ln in ax.get_lines()}
    assert {"limit:slow_near_human:require:ee_speed", "limit:transient_contact:require:contact_force",
            "limit:separation:require:human_distance", "limit:slow_near_human:when:human_distance"} <= gids
    lanes = {c.get_gid() for c in axes[7].collections}
    assert {"lane:task", "lane:stop_2", "lane:stop_0", "rules:response"} <= lanes  # rules during a response marked
    assert fig._suptitle.get_text() == "t"
    assert {m["letter"] for m in meta["event_marks"]} == {"A", "B", "C", "D", "E"}


@pytest.mark.slow
def test_overlay_is_burned_into_the_render():
    from ethimon.sim._overlay import compose_frame

    rng = np.random.default_rng(0)
    main = rng.integers(0, 255, (420, 560, 3), dtype=np.uint8)
    side = rng.integers(0, 255, (210, 280, 3), dtype=np.uint8)
    img = compose_frame(main, side, side, lines=["t 1.000 s   cycle 60", "controller: stop_2"],
                        banner="override: stop_2", marks=[{"xy": (400.0, 100.0), "text": "knife (sharp)",
                                                           "ring": 14, "color": "red"}])
    assert img.shape == (420, 840, 3)
    same = np.all(img[:, :560] == main, axis=2)
    assert same.mean() > 0.85                      # the render itself, unscaled
    box = ~same[340:412, 8:150]                   # the text box (bottom left)
    assert box.mean() > 0.5
    assert not same[100, 386:414].all()           # the hazard ring around (400, 100)
    assert np.all(img[:, 560:][150:200, 100:200] == side[150:200, 100:200])


@pytest.mark.slow
@pytest.mark.sim
def test_a_recording_has_its_events_frames_and_files(tmp_path, root):
    pytest.importorskip("pybullet")
    from matplotlib import image as mpimg

    from ethimon.sim import SimBlock, run_sim
    from ethimon.sim._overlay import MAIN_WH, render_view
    from ethimon.sim._record import trace_events

    spec = ethimon.load_spec(str(root / "specs/cobot_cell.yaml"))
    block = SimBlock.model_validate({
        "duration_s": 1.0,
        "start_xyz_m": [0.5, 0.2, 0.35], "start_holding": "knife",
        "objects": [{"name": "knife", "shape": "box", "xyz_m": [0.5, 0.2, 0.32],
                     "half_extents_m": [0.1, 0.012, 0.004], "hazard": "sharp", "mass_kg": 0.15}],
        "humans": [{"name": "child", "radius_m": 0.14, "height_m": 1.1,
                    "waypoints": [{"t_s": 0, "xy_m": [1.8, 0.9]}, {"t_s": 0.5, "xy_m": [1.2, 0.7]},
                                  {"t_s": 1.0, "xy_m": [1.8, 0.9]}]}],
        "inputs_at": [{"t_s": 0.3, "inputs": {"p_unsafe": 0.0}}],
    })
    out = tmp_path / "rec"
    res = run_sim(block, ethimon.Monitor(spec), p_unsafe=0.95, record_dir=str(out))
    summary = json.loads((out / "summary.json").read_text())
    # every file written is listed, and every listed file exists
    assert sorted(summary["files"]) == sorted(str(p) for p in out.iterdir())
    assert summary["wall_time_s"] > 0
    ev = summary["events"]
    names = [e["event"] for e in ev]
    rising = [r.cycle for i, r in enumerate(res.trace) if r.override and (i == 0 or not res.trace[i - 1].override)]
    assert [e["cycle"] for e in ev if e["event"] == "override"] == rising
    assert rising[0] == res.first_override_cycle == 0
    assert ("release" in names) == res.released is True
    closest = next(e for e in ev if e["event"] == "closest_approach")
    assert closest["value"] == pytest.approx(min(r.human_distance_true_m for r in res.trace))
    # the child is nearest mid-run, at no other event: that frame is rendered after the run from
    # the snapshot of that cycle (not the end state)
    assert 20 < closest["cycle"] < 40 and closest["frame"].endswith(f"frame_{closest['cycle']:05d}_closest_approach.png")
    assert (out / closest["frame"].rsplit("/", 1)[-1]).read_bytes() != \
        next(out.glob("frame_*_end.png")).read_bytes()
    # the same events from the trace alone (deterministic, one definition)
    again = trace_events(res.trace, safe_tol=spec.safe_pose.tolerance_rad)
    assert [(e["event"], e["cycle"]) for e in again] == [(e["event"], e["cycle"]) for e in ev]
    for e in ev:  # a frame for every event, written and listed
        assert e["frame"] in summary["files"]
    assert summary["plot"]["tau"] == spec.risk.threshold and summary["plot"]["event_marks"]
    # the start frame: the raw render with the overlay burned in
    img = mpimg.imread(str(next(out.glob("frame_00000_start.png"))))
    img = (img[:, :, :3] * 255).round().astype(np.uint8) if img.dtype != np.uint8 else img[:, :, :3]
    assert img.shape[:2] == (MAIN_WH[1], MAIN_WH[0] + MAIN_WH[0] // 2)
    from ethimon.sim._arm import ArmSim
    from ethimon.sim._overlay import frame_cameras
    from ethimon.sim._record import _restore, _snapshot
    with ArmSim.from_block(block) as sim:
        cam = frame_cameras(sim)[0]
        raw, _, _ = render_view(sim, cam, MAIN_WH)
        same = np.all(img[:, :MAIN_WH[0]] == raw, axis=2)
        assert same.mean() > 0.8 and not same[-60:, 10:200].all()
        # a snapshot brings back what a frame shows (arm, held knife, person), after the run moved on
        snap = _snapshot(sim)
        q, _ = sim.joint_state()
        for _ in range(20):
            sim.command_joints(q + 0.4)
            sim.step()
        moved, _, _ = render_view(sim, cam, MAIN_WH)
        _restore(sim, snap)
        back, _, _ = render_view(sim, cam, MAIN_WH)
        assert not np.array_equal(moved, raw) and np.array_equal(back, raw)
