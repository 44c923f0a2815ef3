"""The 3-RRR figures are written as PNG files."""

from __future__ import annotations

import math

import numpy as np
import pytest

from lynxsim.plots.rrr import plot_rrr_path, plot_rrr_poses, plot_rrr_workspace, view_extent
from lynxsim.rrr import workspace_map

PNG_MAGIC = b"\x89PNG"


def _is_png(path):
    data = path.read_bytes()
    return data[:4] == PNG_MAGIC and len(data) > 20_000


@pytest.fixture(scope="module")
def maps():
    alphas = [math.radians(a) for a in (0.0, 20.0, -50.0)]
    x0, x1, y0, y1 = view_extent(alphas)
    x = np.arange(x0, x1, 0.006)
    y = np.arange(y0, y1, 0.006)
    return [workspace_map(x, y, a) for a in alphas]


@pytest.mark.parametrize("mode", [None, 3], ids=["all-modes", "mode-3"])
def test_workspace_figure_is_written(tmp_path, maps, mode):
    dest = tmp_path / "ws.png"
    plot_rrr_workspace(maps, dest, mode=mode)
    assert _is_png(dest)
    assert list(tmp_path.iterdir()) == [dest]  # no temporary left behind


def test_workspace_figure_with_a_spare_panel(tmp_path, maps):
    dest = tmp_path / "ws.png"
    plot_rrr_workspace(maps[:2], dest)
    assert _is_png(dest)


def test_workspace_figure_needs_maps(tmp_path):
    with pytest.raises(ValueError, match="no workspace maps"):
        plot_rrr_workspace([], tmp_path / "x.png")


def test_path_figure_marks_unreachable_samples(tmp_path):
    s = np.linspace(0.0, 1.0, 60)
    path = np.column_stack([0.15 + 0.25 * s, 0.15 + 0.0 * s, np.radians(-30 + 60 * s)])
    dest = tmp_path / "path.png"
    plot_rrr_path(path, dest, mode=2, resolution=0.005)
    assert _is_png(dest)


def test_path_figure_needs_two_poses(tmp_path):
    with pytest.raises(ValueError, match="T >= 2"):
        plot_rrr_path(np.zeros((1, 3)), tmp_path / "p.png")


def test_poses_figure_is_written(tmp_path):
    poses = np.array([[0.2, 0.15, 0.0], [0.3, 0.25, math.radians(-40.0)]])
    dest = tmp_path / "poses.png"
    plot_rrr_poses(poses, dest, mode=7)
    assert _is_png(dest)
