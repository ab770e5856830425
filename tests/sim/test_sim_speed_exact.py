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
