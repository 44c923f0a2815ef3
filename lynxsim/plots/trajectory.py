"""Trajectory figures: joint profiles and tool paths with the obstacle.

Joint position, velocity, acceleration and jerk against time are the report's
Figures 10–18; the tool paths of several trajectory types over one task with
the cylinder obstacle are its Figure 19. Axes in the report's units: degrees, millimetres, seconds.
Any robot's joint trajectories are drawn: the joints are named by the trajectory's
bounds, the tool points come from the robot's forward kinematics (``tool=``).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping, Sequence

import numpy as np
import numpy.typing as npt
from matplotlib.axes import Axes

from lynxsim.plots.obstacles import (
    draw_obstacles_3d,
    draw_obstacles_top,
    inside_any,
    obstacle_extent_mm,
)
from lynxsim.plots.style import new_figure, plain_text, save_figure
from lynxsim.scene import REPORT_CYLINDER, Obstacle
from lynxsim.traj import Trajectory

__all__ = ["ToolPoints", "plot_joint_profiles", "plot_tool_paths"]

FloatArray = npt.NDArray[np.float64]
ToolPoints = Callable[[FloatArray], FloatArray]
"""A robot's tool points of joint vectors, (T, n) [rad] -> (T, 3) [m]."""

REPORT_STEPS = 10
"""Samples per segment of the report's trajectories, drawn as markers [-]."""

_PANELS = (
    ("position", "q [deg]"),
    ("velocity", "q' [deg/s]"),
    ("acceleration", "q'' [deg/s²]"),
    ("jerk", "q''' [deg/s³]"),
)
_COLORS = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple")


def _mark_waypoints(ax: Axes, traj: Trajectory, label: bool) -> None:
    for t, name in zip(traj.waypoint_times, traj.waypoints.names):
        ax.axvline(t, color="0.6", lw=0.8, ls=":")
        if label:
            ax.annotate(
                name,
                (t, 1.0),
                xycoords=("data", "axes fraction"),
                ha="center",
                va="bottom",
                fontsize=8,
                color="0.3",
            )


MAX_PLOT_POINTS = 20_000
"""Most samples of one curve: more cannot be told apart in a figure, and take long to draw."""


def _plot_rate(traj: Trajectory, rate_hz: float) -> float:
    """``rate_hz`` [Hz], lowered so that a curve has at most :data:`MAX_PLOT_POINTS` samples."""
    return min(rate_hz, MAX_PLOT_POINTS / max(traj.duration, 1e-9))


@plain_text
def plot_joint_profiles(
    traj: Trajectory,
    dest: str | os.PathLike[str],
    *,
    rate_hz: float = 500.0,
    title: str | None = None,
) -> None:
    """Write joint position, velocity, acceleration and jerk against time as PNG.

    Dashed lines show the velocity, acceleration and jerk limits the trajectory
    type is held to; dotted verticals mark the waypoints.

    Args:
        traj: The trajectory.
        dest: PNG path (written atomically).
        rate_hz: Sampling rate of the curves [Hz], lowered for long trajectories to
            :data:`MAX_PLOT_POINTS` samples; the end point is always drawn.
        title: Figure title; default names the type and the duration.
    """
    t = np.append(traj.times_at_rate(_plot_rate(traj, rate_hz)), traj.duration)
    states = traj.sample(t)
    fig = new_figure(11.0, 11.0)
    axes = fig.subplots(4, 1, sharex=True)
    limited = traj.kind.limited_orders
    names = traj.bounds.names
    for order, (ax, (quantity, ylabel), values) in enumerate(zip(axes, _PANELS, states)):
        for j in range(traj.n_joints):
            color = _COLORS[j % len(_COLORS)]
            ax.plot(
                t,
                np.degrees(values[:, j]),
                color=color,
                lw=1.3,
                label=f"q{j + 1} {names[j]}",
            )
            if order in limited:
                bound = np.degrees(traj.limits.of_order(order)[j])
                ax.axhline(bound, color=color, lw=0.7, ls="--", alpha=0.5)
                ax.axhline(-bound, color=color, lw=0.7, ls="--", alpha=0.5)
        _mark_waypoints(ax, traj, label=order == 0)
        if order and order not in limited:
            ax.text(
                0.995,
                0.97,
                "unbounded: impulses at the waypoints not drawn",
                transform=ax.transAxes,
                ha="right",
                va="top",
                fontsize=8,
                color="0.3",
            )
        ax.set_ylabel(f"{quantity}\n{ylabel}")
        ax.grid(alpha=0.3)
    axes[0].legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=8)
    axes[-1].set_xlabel("t [s]")
    fig.suptitle(
        title
        or f"{traj.kind.value} trajectory, {traj.duration:.3f} s "
        f"({traj.kind.description.split(':')[0]})"
    )
    save_figure(fig, dest)


@plain_text
def plot_tool_paths(
    trajectories: Mapping[str, Trajectory],
    dest: str | os.PathLike[str],
    *,
    tool: ToolPoints,
    obstacles: Sequence[Obstacle] = (REPORT_CYLINDER,),
    rate_hz: float = 200.0,
    title: str | None = None,
) -> None:
    """Write the tool paths of several trajectories with the obstacle as PNG.

    A 3-D view and a top view. Lines are sampled at ``rate_hz``; markers show
    the report's sampling (10 steps per segment), so their spacing shows the
    tool's speed. Paths whose tool point enters the cylinder say so in the legend.

    Args:
        trajectories: Label to trajectory, all through the same waypoints.
        dest: PNG path (written atomically).
        tool: The robot's tool points of joint vectors (its forward kinematics).
        obstacles: The obstacles to draw (default: the report's cylinder).
        rate_hz: Sampling rate of the lines [Hz] (at most :data:`MAX_PLOT_POINTS` samples).
        title: Figure title.
    """
    fig = new_figure(13.0, 7.5)
    grid = fig.add_gridspec(1, 2, width_ratios=(1.3, 1.0))
    ax3 = fig.add_subplot(grid[0], projection="3d")
    ax2 = fig.add_subplot(grid[1])
    first = next(iter(trajectories.values()))
    extent = [obstacle_extent_mm(obstacles)]
    for label, traj in trajectories.items():
        t = np.append(traj.times_at_rate(_plot_rate(traj, rate_hz)), traj.duration)
        path = tool(traj.sample(t).q)
        marks = tool(traj.sample(traj.times_per_segment(REPORT_STEPS)).q) * 1e3
        hit = " — tool crosses the obstacle" if inside_any(path, obstacles).any() else ""
        p = path * 1e3
        extent.append(p)
        (line,) = ax3.plot(
            p[:, 0], p[:, 1], p[:, 2], lw=1.4, label=f"{label} ({traj.duration:.2f} s){hit}"
        )
        ax3.scatter(marks[:, 0], marks[:, 1], marks[:, 2], s=6, color=line.get_color())
        ax2.plot(p[:, 0], p[:, 1], lw=1.4, color=line.get_color())
        ax2.plot(marks[:, 0], marks[:, 1], ".", ms=4, color=line.get_color())
    draw_obstacles_3d(ax3, obstacles)
    names = first.waypoints.names
    targets = tool(first.waypoints.q) * 1e3
    ax3.scatter(
        targets[:, 0],
        targets[:, 1],
        targets[:, 2],
        s=40,
        marker="o",
        facecolors="none",
        edgecolors="k",
    )
    for name, xyz in zip(names, targets):
        ax3.text(xyz[0], xyz[1], xyz[2] + 15.0, name, fontsize=9)
        ax2.annotate(name, xyz[:2], textcoords="offset points", xytext=(5, 5), fontsize=9)
    ax2.plot(targets[:, 0], targets[:, 1], "ko", mfc="none", ms=7)
    draw_obstacles_top(ax2, obstacles)
    ax2.plot(0.0, 0.0, "k+", ms=10)
    ax2.set_aspect("equal")
    ax2.grid(alpha=0.3)
    ax2.set_xlabel("x [mm]")
    ax2.set_ylabel("y [mm]")
    ax2.set_title("top view (grey: obstacle, +: base axis)", fontsize=10)
    ax3.set_xlabel("x [mm]")
    ax3.set_ylabel("y [mm]")
    ax3.set_zlabel("z [mm]")
    points = np.concatenate(extent)
    lo, hi = points.min(axis=0), points.max(axis=0)
    ax3.set_box_aspect(tuple(np.maximum(hi - lo, 1.0)), zoom=1.15)
    ax3.legend(loc="upper left", fontsize=8)
    fig.suptitle(title or "Tool paths of the trajectory types")
    save_figure(fig, dest)
