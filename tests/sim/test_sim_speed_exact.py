"""The speed-ups of ``check --sim`` (issue 32) change no number: each shortcut gives, bit for bit,
what the code it replaced gave (the whole-run proof is ``python -m bench.sim.sim_check diff``)."""

from __future__ import annotations

import numpy as np
import pytest

pytestmark = [pytest.mark.sim]


def test_cross3_is_np_cross_bit_for_bit():
    from ethimon.sim._cell import _cross3
    rng = np.random.default_rng(7)
    for _ in range(100):
        a, b = rng.normal(size=3) * 10.0 ** rng.integers(-6, 6), rng.normal(size=3)
        assert _cross3(tuple(a), b).tobytes() == np.cross(a, b).tobytes()


def test_hermite_refs_equal_the_step_by_step_formula():
    from ethimon.sim._arm import ArmSim
    rng = np.random.default_rng(3)
    q0, v0, q1, v1 = (rng.normal(size=7) for _ in range(4))
    n, T = 4, 1 / 60
    refs = ArmSim._hermite_refs(type("S", (), {"_hermite_coef": {}})(), n, T, q0, v0, q1, v1)
    for k in range(1, n + 1):  # the expression ArmSim.step used per physics step before
        s = k / n
        s2, s3 = s * s, s * s * s
        q_ref = ((2 * s3 - 3 * s2 + 1) * q0 + (s3 - 2 * s2 + s) * T * v0
                 + (-2 * s3 + 3 * s2) * q1 + (s3 - s2) * T * v1)
        qd_ref = ((6 * s2 - 6 * s) * q0 / T + (3 * s2 - 4 * s + 1) * v0
                  + (-6 * s2 + 6 * s) * q1 / T + (3 * s2 - 2 * s) * v1)
        assert refs[0][k - 1].tobytes() == q_ref.tobytes()
        assert refs[1][k - 1].tobytes() == qd_ref.tobytes()


@pytest.mark.slow  # builds an ArmSim (~0.3 s on the shared cores)
def test_one_multidof_reset_is_seven_joint_resets_and_the_floor_query_is_per_link():
    pytest.importorskip("pybullet")
    from ethimon.sim._arm import ArmSim
    from ethimon.sim._cell import ARM_JOINTS
    rng = np.random.default_rng(1)
    with ArmSim(visuals=False) as sim:
        p, cid, r = sim._p, sim.cid, sim.robot
        for _ in range(10):
            q = sim.lower + (sim.upper - sim.lower) * rng.random(7)
            qd = rng.normal(size=7)
            for j, v, w in zip(ARM_JOINTS, q, qd):
                p.resetJointState(r, j, float(v), float(w), physicsClientId=cid)
            one = (p.getJointStates(r, ARM_JOINTS, physicsClientId=cid),
                   p.getLinkStates(r, list(range(12)), computeForwardKinematics=1, physicsClientId=cid))
            sim._set_arm(np.zeros(7))
            sim._set_arm(q, qd)
            assert (p.getJointStates(r, ARM_JOINTS, physicsClientId=cid),
                    p.getLinkStates(r, list(range(12)), computeForwardKinematics=1,
                                    physicsClientId=cid)) == one
            for ob0 in (1.0, 0.1):  # probe's floor clearance: one query filtered = ten per link
                ob = ob0
                for link in range(2, 12):
                    pts = p.getClosestPoints(r, sim.plane, ob, linkIndexA=link, physicsClientId=cid)
                    if pts:
                        ob = min(ob, max(0.0, min(pt[8] for pt in pts)))
                d = [pt[8] for pt in p.getClosestPoints(r, sim.plane, ob0, physicsClientId=cid) if pt[3] >= 2]
                assert (min(ob0, max(0.0, min(d))) if d else ob0) == ob


# ---- the servo and the brakes on plain floats (third cut): the numpy code they replaced, verbatim

def _numpy_servo(q_ref, qd_ref, q_meas, v_out, a_out, max_velocity, speed_cap):
    from ethimon.sim._actuation import _HOLD_SPEED_RAD_S
    from ethimon.sim._cell import _K_POS, _LIMIT_SHARE, _Q_MAX, _Q_MIN, _RATED_DDDQ, _RATED_DDQ, _RATED_DQ
    from ethimon.sim._limits import LIMIT_MARGIN_RAD
    from ethimon.sim._model import PHYSICS_HZ
    h = 1.0 / PHYSICS_HZ
    v = qd_ref + _K_POS * (q_ref - q_meas)
    cap = _RATED_DQ
    if max_velocity is not None:
        cap = np.minimum(cap, max_velocity)
    if speed_cap is not None:
        cap = np.minimum(cap, np.maximum(speed_cap, _HOLD_SPEED_RAD_S))
    v = np.clip(v, -cap, cap)
    up = np.sqrt(2.0 * _LIMIT_SHARE * _RATED_DDQ * np.maximum(_Q_MAX - LIMIT_MARGIN_RAD - q_meas, 0.0))
    dn = np.sqrt(2.0 * _LIMIT_SHARE * _RATED_DDQ * np.maximum(q_meas - _Q_MIN - LIMIT_MARGIN_RAD, 0.0))
    v = np.clip(v, -dn, up)
    a = np.clip((v - v_out) / h, -_RATED_DDQ, _RATED_DDQ)
    a = np.clip(a, a_out - _RATED_DDDQ * h, a_out + _RATED_DDDQ * h)
    return v_out + a * h, a


def _numpy_brakes(q, qd, hold):
    from ethimon.sim._cell import _BRAKE_DECEL
    from ethimon.sim._model import PHYSICS_HZ
    step = _BRAKE_DECEL / PHYSICS_HZ
    target = np.sign(qd) * np.maximum(np.abs(qd) - step, 0.0)
    stopped = np.abs(qd) <= np.maximum(step, 0.01)
    newly = stopped & np.isnan(hold)
    hold[newly] = q[newly]
    hold[~stopped & (np.abs(q - np.nan_to_num(hold, nan=0.0)) > 0.02)] = np.nan
    return target


def _odd(rng, n, scale):
    """Random 7-vectors with the odd values mixed in: NaN, infinities, signed zeros, exact ties."""
    x = rng.normal(size=n) * scale
    mask = rng.random(n)
    x[mask < 0.04] = np.nan
    x[(mask >= 0.04) & (mask < 0.07)] = 0.0
    x[(mask >= 0.07) & (mask < 0.10)] = -0.0
    x[(mask >= 0.10) & (mask < 0.11)] = np.inf
    return x


def test_float_servo_is_the_numpy_servo_bit_for_bit():
    from ethimon.sim._actuation import _servo_step
    from ethimon.sim._cell import _Q_MAX, _Q_MIN
    rng = np.random.default_rng(11)
    for i in range(200):
        q_meas = _Q_MIN + (_Q_MAX - _Q_MIN) * rng.uniform(-0.05, 1.05, size=7)
        if i % 7 == 0:
            q_meas = _odd(rng, 7, 2.0)
        q_ref = q_meas + _odd(rng, 7, 0.05)
        qd_ref, v_out = _odd(rng, 7, 1.5), rng.normal(size=7)
        a_out = rng.normal(size=7) * 10.0
        if i % 5 == 0:  # the servo at rest, or its own last step repeated
            v_out, a_out = np.zeros(7), np.zeros(7)
        mv = (None, 0.3, float(rng.uniform(0, 3)), np.nan)[i % 4]
        cap = None if i % 3 == 0 else np.abs(_odd(rng, 7, 0.5))
        with np.errstate(invalid="ignore"):
            want_v, want_a = _numpy_servo(q_ref, qd_ref, q_meas, v_out, a_out, mv, cap)
        got_v, got_a = _servo_step(q_ref.tolist(), qd_ref.tolist(), q_meas.tolist(), v_out, a_out, mv,
                                   None if cap is None else cap.tolist())
        assert np.array(got_v).tobytes() == want_v.tobytes()
        assert np.array(got_a).tobytes() == want_a.tobytes()


def test_float_brakes_are_the_numpy_brakes_bit_for_bit():
    from ethimon.sim._actuation import _brake_step
    rng = np.random.default_rng(5)
    for i in range(200):
        q = _odd(rng, 7, 1.0)
        qd = _odd(rng, 7, 0.05) if i % 2 else _odd(rng, 7, 1.0)
        hold = np.where(rng.random(7) < 0.5, np.nan, q + rng.normal(size=7) * 0.03)
        if i % 9 == 0:
            hold[rng.integers(7)] = -np.inf
        want_hold = hold.copy()
        with np.errstate(invalid="ignore"):
            want = _numpy_brakes(q, qd, want_hold)
        got_hold = hold.tolist()
        got = _brake_step(q.tolist(), qd.tolist(), got_hold)
        assert np.array(got).tobytes() == want.tobytes()
        assert np.array(got_hold).tobytes() == want_hold.tobytes()
