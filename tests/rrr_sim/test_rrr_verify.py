"""Verification by simulation: commanded poses settle on the IK's target; Figure 20 judged."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from lynxsim.errors import UnreachablePlatformPoseError
from lynxsim.reproduce.figure20 import figure20_simulation, format_figure20_simulation
from lynxsim.reproduce.rrr_formulas import FIGURE20_POSES, REPORT_MODE
from lynxsim.rrr import RRR_ROBOT
from lynxsim.sim.rrr.verify import check_pose, pull_toward
from tests.rrr_sim.conftest import FIGURE20_A, FIGURE20_E, FIGURE20_F, well_conditioned_poses

SETTLE_POSITION_TOL_M = 0.5e-3
"""Acceptance: settled platform centre within 0.5 mm of the IK's target [m]."""
SETTLE_ORIENTATION_TOL_RAD = math.radians(0.1)
"""Acceptance: settled orientation within 0.1 deg [rad]."""
REST_LOOP_TOL_M = 1e-4
"""Acceptance: loop closure at rest, 0.1 mm [m]; a settling approach stays within it."""
N_RANDOM_POSES = 60
"""Random (pose, working mode) pairs settled; the acceptance asks for at least 50."""
SPAN_TOL_M = 0.5e-3
"""A pulled leg counts as stretched within this of s_a + L [m]."""


def test_random_poses_settle_on_the_ik_target(rrr_scene, rrr_ids):
    data = mujoco.MjData(rrr_scene)
    cases = well_conditioned_poses(np.random.default_rng(20241122), N_RANDOM_POSES)
    checks = [check_pose(rrr_scene, data, pose, mode, ids=rrr_ids) for pose, mode in cases]
    assert len(checks) >= 50
    for c in checks:
        label = f"pose {np.round(c.pose, 4).tolist()} mode {c.mode}"
        assert c.healthy, label
        assert c.settled_mode == c.mode, label
        assert c.position_error_m <= SETTLE_POSITION_TOL_M, label
        assert c.orientation_error_rad <= SETTLE_ORIENTATION_TOL_RAD, label
        assert c.loop_closure_max_m <= REST_LOOP_TOL_M, label
    # The poses cover the workspace and every working mode; some of them with crossing links.
    xy = np.array([c.pose[:2] for c in checks])
    assert np.ptp(xy, axis=0).min() > 0.2
    assert {c.mode for c in checks} == set(range(8))
    assert any(c.interference for c in checks)
    assert any(not c.interference for c in checks)


def test_unreachable_pose_is_a_clear_error(rrr_scene, rrr_ids):
    data = mujoco.MjData(rrr_scene)
    with pytest.raises(
        UnreachablePlatformPoseError,
        match=r"unreachable: leg 1 cannot stretch to it \(\|P1-B1\| = 322\.\d\d mm > s_a \+ L",
    ):
        check_pose(rrr_scene, data, FIGURE20_E, REPORT_MODE, ids=rrr_ids)


def test_pulled_platform_stops_on_the_boundary_short_of_an_unreachable_pose(rrr_scene, rrr_ids):
    data = mujoco.MjData(rrr_scene)
    pull = pull_toward(rrr_scene, data, FIGURE20_E, ids=rrr_ids)
    assert not pull.reached
    assert pull.position_gap_m > 0.005
    assert pull.leg_span_m[0] == pytest.approx(RRR_ROBOT.reach_max, abs=SPAN_TOL_M)
    assert max(pull.leg_span_m[1:]) < RRR_ROBOT.reach_max - 0.05
    assert pull.loop_closure_max_m < 1e-3


def test_pulled_platform_reaches_a_reachable_pose(rrr_scene, rrr_ids):
    pull = pull_toward(rrr_scene, mujoco.MjData(rrr_scene), FIGURE20_A, ids=rrr_ids)
    assert pull.reached


def test_links_that_cross_are_reported_and_settled_without_contacts(rrr_scene, rrr_ids):
    data = mujoco.MjData(rrr_scene)
    crossing = check_pose(rrr_scene, data, FIGURE20_F, 7, ids=rrr_ids)
    assert crossing.interference
    assert not crossing.contacts
    assert crossing.reached
    clear = check_pose(rrr_scene, data, FIGURE20_F, 0, ids=rrr_ids)
    assert not clear.interference
    assert clear.contacts
    assert clear.reached


@pytest.fixture(scope="module")
def figure20():
    return {row.pose.label: row for row in figure20_simulation()}


def test_figure20_verdicts_come_from_the_simulation(figure20):
    assert set(figure20) == {p.label for p in FIGURE20_POSES}
    assert {label for label, row in figure20.items() if not row.reachable} == {"e"}
    # e: no IK solution and the pulled platform stops short with leg 1 stretched.
    e = figure20["e"]
    assert not e.ik_reachable
    assert e.failing_legs == (1,)
    assert not e.pull.reached
    # The pose the report's text calls unreachable is reached, in most working modes.
    assert figure20["text"].reachable
    assert figure20["text"].pull.reached
    for label in ("a", "b", "c", "d", "f", "text"):
        row = figure20[label]
        assert REPORT_MODE in row.reached_modes, label
        assert max(c.loop_closure_max_m for c in row.checks) < REST_LOOP_TOL_M, label


def test_figure20_link_interference_by_working_mode(figure20):
    assert figure20["a"].clear_modes == tuple(range(8))
    assert figure20["d"].clear_modes == (4, 5, 6, 7)
    assert figure20["f"].clear_modes == (0, 1, 2, 3)
    assert figure20["text"].clear_modes == (0, 1, 2, 3)


def test_figure20_text_names_every_pose_and_verdict(figure20):
    text = format_figure20_simulation(list(figure20.values()))
    assert (
        "e (300 mm, 250 mm, -40 deg): simulation says UNREACHABLE (the report: reachable)" in text
    )
    assert "text (300 mm, 250 mm, 40 deg): simulation says REACHABLE (the report: unreachable)" in (
        text
    )
    assert "leg3_proximal_collision/platform_collision23" in text
