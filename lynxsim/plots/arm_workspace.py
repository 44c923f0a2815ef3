"""Reachable-workspace figure of the arm: three views and a 3-D cloud (report Fig. 5)."""

from __future__ import annotations

import os

import numpy as np

from lynxsim.arm.workspace import WorkspaceSamples
from lynxsim.plots.style import new_figure, plain_text, save_figure

__all__ = ["plot_arm_workspace"]

_MAX_POINTS_3D = 20_000


@plain_text
def plot_arm_workspace(
    samples: WorkspaceSamples, dest: str | os.PathLike[str], title: str | None = None
) -> None:
    """Write the workspace figure as PNG.

    Top (x–y), side (x–z) and front (y–z) views as 2-D density maps, and a 3-D
    scatter of a subsample coloured by tool pitch. Axes in mm.

    Args:
        samples: Output of :func:`~lynxsim.arm.workspace.sample_workspace`.
        dest: PNG path (written atomically).
        title: Figure title; default states the sample count.
    """
    p_mm = samples.position * 1e3
    fig = new_figure(12.0, 10.0)
    views = [
        (0, 1, "top view", "x [mm]", "y [mm]"),
        (0, 2, "side view", "x [mm]", "z [mm]"),
        (1, 2, "front view", "y [mm]", "z [mm]"),
    ]
    for k, (i, j, name, xl, yl) in enumerate(views):
        ax = fig.add_subplot(2, 2, k + 1)
        ax.hexbin(p_mm[:, i], p_mm[:, j], gridsize=120, bins="log", cmap="viridis", mincnt=1)
        ax.set_title(name)
        ax.set_xlabel(xl)
        ax.set_ylabel(yl)
        ax.set_aspect("equal")
        ax.grid(alpha=0.3)
        if j == 2:
            ax.axhline(0.0, color="k", lw=0.8)
    ax3 = fig.add_subplot(2, 2, 4, projection="3d")
    step = max(1, len(p_mm) // _MAX_POINTS_3D)
    sub = p_mm[::step]
    sc = ax3.scatter(
        sub[:, 0],
        sub[:, 1],
        sub[:, 2],
        c=np.degrees(samples.pitch[::step]),
        s=1,
        cmap="twilight",
        alpha=0.6,
    )
    fig.colorbar(sc, ax=ax3, shrink=0.6, label="tool pitch [deg]")
    ax3.set_xlabel("x [mm]")
    ax3.set_ylabel("y [mm]")
    ax3.set_zlabel("z [mm]")
    ax3.set_title("3-D (subsample)")
    fig.suptitle(title or f"Reachable workspace of the tool point ({len(p_mm):,} joint samples)")
    save_figure(fig, dest)
