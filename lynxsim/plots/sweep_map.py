"""Where may an obstacle stand? A sweep's verdicts drawn over the table, seen from above."""

from __future__ import annotations

import os
from collections.abc import Mapping

import numpy as np
import numpy.typing as npt
from matplotlib.cm import ScalarMappable
from matplotlib.colors import ListedColormap
from matplotlib.patches import Circle, Patch, Rectangle

from lynxsim.errors import InvalidInputError
from lynxsim.plots.obstacles import draw_obstacles_top
from lynxsim.plots.style import new_figure, plain_text, save_figure
from lynxsim.poses import ArmPose
from lynxsim.scene import Obstacle, Table
from lynxsim.verdicts import Verdict

__all__ = ["VERDICT_COLOURS", "plot_obstacle_map"]

VERDICT_COLOURS = {
    Verdict.COLLIDED.label: "#d62728",
    Verdict.START_OVERLAP.label: "#6b0d0d",
    Verdict.INVALID.label: "#bdbdbd",
    Verdict.NO_MOTION.label: "#ffffff",
}
"""Colour of each verdict but ``clear`` (clear cells are coloured by their clearance)."""
CLEAR = Verdict.CLEAR.label

_CLEARANCE_CMAP = "viridis"
_CLEARANCE_TOP_MM = 100.0
"""Clearances from this up share the top colour [mm]."""


def _grid(x: npt.NDArray[np.float64], y: npt.NDArray[np.float64]) -> tuple[np.ndarray, ...] | None:
    """Column and row of each point of a full regular grid, or None if they are not one."""
    xs, ys = np.unique(x), np.unique(y)
    if len(xs) * len(ys) != len(x):
        return None
    return xs, ys, np.searchsorted(xs, x), np.searchsorted(ys, y)


@plain_text
def plot_obstacle_map(
    rows: Mapping[str, npt.NDArray[np.generic]],
    dest: str | os.PathLike[str],
    *,
    obstacle: Obstacle,
    table: Table,
    poses: tuple[object, ...] = (),
    title: str = "",
) -> None:
    """Write one map of placements of an obstacle as PNG (mm, seen from above).

    Each placement of the obstacle's centre is a cell: red where the arm (or the
    cube it carries) touches it during the run, dark red where it overlaps the
    arm or cube before the motion starts, grey where no scene allows it (it
    would enclose the arm's base or the cube), else coloured by the smallest
    clearance over the run. The obstacle's own placement (the task's) is drawn
    as its outline, the task's tool poses as crosses.

    Args:
        rows: Rows of one (task, type, ...) of a sweep table (:mod:`lynxsim.sweep.table`).
        dest: PNG path (written atomically).
        obstacle: The obstacle at its task placement.
        table: The table (its outline is drawn).
        poses: The task's poses (tool poses are marked).
        title: Figure title.

    Raises:
        InvalidInputError: No rows, or rows without obstacle placements.
    """
    x = np.asarray(rows["obstacle_x_m"], dtype=float) * 1e3
    y = np.asarray(rows["obstacle_y_m"], dtype=float) * 1e3
    if len(x) == 0 or not np.isfinite(x).all():
        raise InvalidInputError("a map needs rows with obstacle placements")
    verdict = np.asarray(rows["verdict"]).astype(str)
    clearance = np.asarray(rows["min_clearance_m"], dtype=float) * 1e3
    clear = verdict == CLEAR
    top = _CLEARANCE_TOP_MM
    fig = new_figure(8.0, 9.0)
    ax = fig.add_subplot(1, 1, 1)
    grid = _grid(x, y)
    image: ScalarMappable
    if grid is not None:
        xs, ys, col, row = grid
        step_x = float(np.diff(xs).min()) if len(xs) > 1 else 1.0
        step_y = float(np.diff(ys).min()) if len(ys) > 1 else 1.0
        extent = (
            xs[0] - step_x / 2,
            xs[-1] + step_x / 2,
            ys[0] - step_y / 2,
            ys[-1] + step_y / 2,
        )
        values = np.full((len(ys), len(xs)), np.nan)
        values[row[clear], col[clear]] = clearance[clear]
        image = ax.imshow(
            values,
            origin="lower",
            extent=extent,
            cmap=_CLEARANCE_CMAP,
            vmin=0.0,
            vmax=top,
            interpolation="nearest",
        )
        names = list(VERDICT_COLOURS)
        codes = np.full((len(ys), len(xs)), np.nan)
        for k, name in enumerate(names):
            mask = verdict == name
            codes[row[mask], col[mask]] = k
        ax.imshow(
            codes,
            origin="lower",
            extent=extent,
            cmap=ListedColormap([VERDICT_COLOURS[n] for n in names]),
            vmin=-0.5,
            vmax=len(names) - 0.5,
            interpolation="nearest",
        )
    else:
        image = ax.scatter(
            x[clear], y[clear], c=clearance[clear], s=6, cmap=_CLEARANCE_CMAP, vmin=0.0, vmax=top
        )
        for name, colour in VERDICT_COLOURS.items():
            mask = verdict == name
            ax.scatter(x[mask], y[mask], c=colour, s=6)
    fig.colorbar(
        image, ax=ax, shrink=0.7, extend="max", label="minimum clearance over the run [mm]"
    )
    (cx, cy), (sx, sy) = table.center, table.size
    ax.add_patch(
        Rectangle(
            ((cx - sx / 2) * 1e3, (cy - sy / 2) * 1e3),
            sx * 1e3,
            sy * 1e3,
            fill=False,
            edgecolor="k",
            linewidth=0.8,
        )
    )
    draw_obstacles_top(ax, (obstacle,))
    ox, oy = obstacle.position[0] * 1e3, obstacle.position[1] * 1e3
    if hasattr(obstacle, "radius"):
        ax.add_patch(
            Circle((ox, oy), obstacle.radius * 1e3, fill=False, edgecolor="k", linestyle="--")
        )
    ax.plot([ox], [oy], marker="+", color="k", markersize=12, mew=2)
    ax.plot([0.0], [0.0], marker="s", color="k", markersize=6)
    for pose in poses:
        if isinstance(pose, ArmPose):
            px, py = pose.position[0] * 1e3, pose.position[1] * 1e3
            ax.plot([px], [py], marker="x", color="w", markersize=7, mew=2)
            ax.annotate(pose.name, (px, py), textcoords="offset points", xytext=(4, 4), color="w")
    counts = {name: int((verdict == name).sum()) for name in (CLEAR, *VERDICT_COLOURS)}
    handles = [Patch(color=VERDICT_COLOURS[n], label=f"{n} ({counts[n]})") for n in VERDICT_COLOURS]
    handles.insert(0, Patch(color="#21918c", label=f"{CLEAR} ({counts[CLEAR]}): clearance"))
    handles.append(
        Patch(facecolor="none", edgecolor="k", linestyle="--", label="the task's placement (+)")
    )
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(0.0, -0.06), ncol=3, fontsize=8)
    ax.set_xlabel("obstacle centre x [mm]")
    ax.set_ylabel("obstacle centre y [mm]")
    ax.set_aspect("equal")
    own = np.flatnonzero((x == ox) & (y == oy))
    if len(own):
        k = int(own[0])
        shown = verdict[k]
        if shown == CLEAR:
            shown += f", clearance {clearance[k]:.1f} mm"
        elif np.isfinite(float(rows["first_contact_s"][k])):
            shown += f" at {float(rows['first_contact_s'][k]):.3f} s"
        title = f"{title}\nthe task's placement (+): {shown}"
    ax.set_title(title or "where may the obstacle stand?")
    save_figure(fig, dest)
