"""The report's Figure 20 poses judged with the correct geometry."""

from __future__ import annotations

import math

import numpy as np

from lynxsim.reproduce.rrr_formulas import (
    FIGURE20_POSES,
    REPORT_MODE,
    figure20_table,
    format_figure20_table,
    report_leg_spans,
)
from lynxsim.rrr import RRR_ROBOT, ik
from tests.helpers import assert_close


def test_correct_geometry_verdicts():
    rows = {r.pose.label: r for r in figure20_table()}
    assert [label for label, r in rows.items() if r.reachable] == ["a", "b", "c", "d", "f", "text"]
    assert rows["e"].failing_legs == (1,)
    assert rows["e"].leg_span_mm[0] == __import__("pytest").approx(322.29, abs=0.01)


def test_report_geometry_reproduces_the_reports_verdicts():
    # arm.m's computation says (e) is reachable and (300, 250, +40) is not, as the report does.
    for row in figure20_table():
        assert row.report_geometry_reachable == row.pose.report_reachable, row.pose


def test_report_spans_equal_true_spans_at_zero_orientation():
    rng = np.random.default_rng(3)
    poses = np.column_stack([rng.uniform(0.1, 0.4, (50, 2)), np.zeros(50)])
    assert_close(report_leg_spans(poses), ik(poses).leg_span, atol=1e-12)
    turned = poses + [0.0, 0.0, math.radians(30.0)]
    assert np.abs(report_leg_spans(turned) - ik(turned).leg_span).max() > 0.01


def test_report_mode_is_the_reports_half_angle_root():
    # arm.m: theta = 2 atan(t_1), t_1 = (-e1 + sqrt(e1^2 + e2^2 - e3^2)) / (e3 - e2).
    pose = np.array([0.2, 0.15, 0.0])
    d = ik(pose).platform_joints - RRR_ROBOT.base
    s_a, ell = RRR_ROBOT.proximal, RRR_ROBOT.distal
    e1, e2 = -2 * d[:, 1] * s_a, -2 * d[:, 0] * s_a
    e3 = (d**2).sum(-1) + s_a**2 - ell**2
    t1 = (-e1 + np.sqrt(e1**2 + e2**2 - e3**2)) / (e3 - e2)
    assert_close(2 * np.arctan(t1), ik(pose).theta[REPORT_MODE], atol=1e-12)


def test_table_text_has_one_line_per_pose():
    text = format_figure20_table()
    assert len(text.splitlines()) == 2 + len(FIGURE20_POSES)
    assert "leg 1 fails" in text
