"""Trajectory figures are written as PNG."""

from __future__ import annotations

import numpy as np

from lynxsim.arm.motion import ARM_KINEMATICS, cubic, free_motion, quintic
from lynxsim.plots.obstacles import inside_any
from lynxsim.plots.trajectory import plot_joint_profiles, plot_tool_paths
from lynxsim.scene import REPORT_CYLINDER

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
Q = np.radians(
    [
        [90.0, 15.89, -18.47, -87.42, 0.0],
        [90.0, 80.38, -46.11, -34.27, 0.0],
        [0.0, 80.38, -46.11, -34.27, 0.0],
    ]
)


def test_joint_profiles_png(tmp_path):
    dest = tmp_path / "nested" / "joints.png"
    plot_joint_profiles(free_motion(Q, durations=1.0), dest, rate_hz=100.0)
    assert dest.read_bytes().startswith(PNG_MAGIC)
    assert not list(dest.parent.glob(".*tmp*"))  # written atomically, nothing left over


def test_tool_paths_png(tmp_path):
    dest = tmp_path / "paths.png"
    plot_tool_paths(
        {"cubic": cubic(Q, 1.0), "quintic": quintic(Q, 1.0)},
        dest,
        tool=ARM_KINEMATICS.tool_points,
        rate_hz=50.0,
    )
    assert dest.read_bytes().startswith(PNG_MAGIC)


def test_inside_any_is_the_cylinder_of_the_report_standing_on_the_table():
    p = np.array([[0.15, 0.15, 0.2], [0.15, 0.185, 0.2], [0.15, 0.15, 0.41], [0.15, 0.15, -0.02]])
    assert inside_any(p, (REPORT_CYLINDER,)).tolist() == [True, True, False, False]
