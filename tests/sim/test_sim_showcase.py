"""The shipped showcase (issue 32, row "every person counts"): a child walks round the arm while it
retreats with a knife; the blade must end out of every person's half-space (more than 90 deg from
the direction to each of them), and the turn that gets it there never brings the arm nearer anyone."""

from __future__ import annotations

import pytest

from tests.sim._scenarios import run_scenario

pytestmark = [pytest.mark.sim, pytest.mark.slow]


def test_knife_ends_out_of_every_persons_half_space():
    pytest.importorskip("pybullet")
    block, res = run_scenario("knife_child_walks_around")
    assert res.hazard_axis_angles_end_deg, "a held knife and a person at the end"
    worst = min(res.hazard_axis_angles_end_deg.values())
    assert worst > 90.0, res.hazard_axis_angles_end_deg  # was 75.6 deg: still in her half-space
    # never swept toward her on the way (more than the 10 deg slack), never nearer than it was
    assert all(v <= 10.0 + 1e-6 for v in res.hazard_axis_min_swing_deg.values()), res.hazard_axis_min_swing_deg
    end = res.trace[-1].human_distance_true_m
    assert end >= 0.95, end
