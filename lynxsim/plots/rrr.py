"""Figures of the 3-RRR robot: workspace maps, platform paths, robot poses (PNG, mm)."""

from __future__ import annotations

import math
import os
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection
from matplotlib.colors import ListedColormap
from matplotlib.lines import Line2D
from matplotlib.patches import Circle, Patch

from lynxsim.errors import InvalidInputError
from lynxsim.plots.style import new_figure, plain_text, save_figure
from lynxsim.rrr.geometry import RRR_ROBOT, RRRGeometry, as_pose_array
from lynxsim.rrr.ik import ik, leg_points
from lynxsim.rrr.jacobian import singularity_measures
from lynxsim.rrr.modes import N_MODES, mode_label
from lynxsim.rrr.workspace import (
    WorkspaceMap,
    grid_extent,
    leg_annuli,
    parallel_singularity_loci,
    workspace_map,
)

__all__ = [
    "LEG_COLOURS",
    "draw_robot",
    "plot_rrr_path",
    "plot_rrr_poses",
    "plot_rrr_workspace",
    "view_extent",
]

_MM = 1e3
LEG_COLOURS = ("tab:red", "tab:green", "tab:blue")
"""Colour of legs 1, 2, 3 in every figure."""
_MODE_COLOURS = (
    "tab:orange",
    "tab:purple",
    "tab:brown",
    "tab:pink",
    "tab:olive",
    "tab:cyan",
    "k",
    "gold",
)


def _draw_base(ax: Axes, geometry: RRRGeometry) -> None:
    b = geometry.base * _MM
    tri = np.vstack([b, b[:1]])
    ax.plot(tri[:, 0], tri[:, 1], color="0.35", lw=1.0, ls=":", zorder=2)
    for i, (px, py) in enumerate(b):
        ax.plot(px, py, marker="s", ms=6, color=LEG_COLOURS[i], mec="k", zorder=5)
        ax.annotate(f"B{i + 1}", (px, py), xytext=(4, -11), textcoords="offset points", fontsize=8)
    cx, cy = np.asarray(geometry.base_centre) * _MM
    ax.plot(cx, cy, marker="+", ms=8, color="0.3", zorder=5)


def draw_robot(
    ax: Axes,
    pose: npt.ArrayLike,
    mode: int,
    geometry: RRRGeometry = RRR_ROBOT,
    *,
    alpha: float = 1.0,
    annotate: bool = False,
) -> bool:
    """Draw the legs and platform of one pose in one working mode (mm).

    Args:
        ax: Target axes.
        pose: Platform pose (x, y, alpha), shape (3,) [m, m, rad].
        mode: Working mode 0..7.
        geometry: The robot description.
        alpha: Opacity of the drawing.
        annotate: Write each actuated angle [deg] beside its base joint.

    Returns:
        Whether the pose is reachable (an unreachable pose draws only its platform).
    """
    p = as_pose_array(pose)
    pts = leg_points(p, mode, geometry) * _MM  # (3, 3, 2)
    plat = pts[:, 2, :]
    tri = np.vstack([plat, plat[:1]])
    ok = bool(np.isfinite(pts).all())
    ax.fill(tri[:, 0], tri[:, 1], color="0.6" if ok else "tab:red", alpha=0.35 * alpha, zorder=3)
    ax.plot(tri[:, 0], tri[:, 1], color="k", lw=1.2, alpha=alpha, zorder=4)
    ax.plot(p[0] * _MM, p[1] * _MM, marker="x", color="k", ms=5, alpha=alpha, zorder=4)
    if not ok:
        return False
    for i in range(3):
        ax.plot(
            pts[i, :, 0],
            pts[i, :, 1],
            color=LEG_COLOURS[i],
            lw=2.0,
            alpha=alpha,
            marker="o",
            ms=3.5,
            zorder=4,
        )
        if annotate:
            theta = math.degrees(
                math.atan2(pts[i, 1, 1] - pts[i, 0, 1], pts[i, 1, 0] - pts[i, 0, 0])
            )
            ax.annotate(
                f"θ{i + 1} = {theta:.1f}°",
                pts[i, 0],
                xytext=(6, 6),
                textcoords="offset points",
                fontsize=8,
                color=LEG_COLOURS[i],
            )
    return True


def _draw_annuli(ax: Axes, alpha: float, geometry: RRRGeometry) -> None:
    ann = leg_annuli(alpha, geometry)
    for i, centre in enumerate(ann.centres * _MM):
        for radius, style in ((ann.r_max, "-"), (ann.r_min, "--")):
            ax.add_patch(
                Circle(
                    tuple(centre),
                    radius * _MM,
                    fill=False,
                    ec=LEG_COLOURS[i],
                    lw=0.8,
                    ls=style,
                    alpha=0.55,
                    zorder=2,
                )
            )


def _square_axes(ax: Axes, extent: tuple[float, float, float, float]) -> None:
    x0, x1, y0, y1 = (v * _MM for v in extent)
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.grid(alpha=0.25)


def _map_extent(wmap: WorkspaceMap) -> tuple[float, float, float, float]:
    return float(wmap.x[0]), float(wmap.x[-1]), float(wmap.y[0]), float(wmap.y[-1])


def view_extent(
    alphas: Sequence[float], geometry: RRRGeometry = RRR_ROBOT, margin: float = 0.03
) -> tuple[float, float, float, float]:
    """A rectangle around the base joints and the workspaces of ``alphas`` [m].

    Args:
        alphas: Platform orientations [rad].
        geometry: The robot description.
        margin: Added on every side [m].

    Returns:
        ``(x_min, x_max, y_min, y_max)`` [m].
    """
    x0, x1, y0, y1 = grid_extent(alphas, geometry, margin=0.0)
    b = geometry.base
    return (
        min(x0, float(b[:, 0].min())) - margin,
        max(x1, float(b[:, 0].max())) + margin,
        min(y0, float(b[:, 1].min())) - margin,
        max(y1, float(b[:, 1].max())) + margin,
    )


@plain_text
def plot_rrr_workspace(
    maps: Sequence[WorkspaceMap],
    dest: str | os.PathLike[str],
    *,
    mode: int | None = None,
    title: str | None = None,
) -> None:
    """Write constant-orientation workspace maps as PNG, one panel per map.

    Every panel shows the reachable platform centres (shaded), the three leg
    annuli (solid: stretched-leg circle, dashed: folded-leg circle; these are
    the leg-singularity loci), the base, and parallel-singularity loci. With
    ``mode=None`` the loci of all 8 working modes are drawn in 8 colours; with
    a mode, the shading is that mode's signed parallel measure (white at a
    singularity, the two colours on its two sides) and its loci are black.

    Args:
        maps: Results of :func:`~lynxsim.rrr.workspace.workspace_map` (one per alpha).
        dest: PNG path (written atomically).
        mode: Working mode to detail, or None for the loci of all modes.
        title: Figure title; a default names the robot's numbers.

    Raises:
        InvalidInputError: If ``maps`` is empty.
    """
    if not maps:
        raise InvalidInputError("no workspace maps to plot")
    n = len(maps)
    cols = min(n, 3)
    rows = math.ceil(n / cols)
    spare = rows * cols > n  # an empty panel holds the legend
    fig = new_figure(
        5.0 * cols + (1.0 if mode is not None else 0.0), 4.9 * rows + (0.0 if spare else 0.9)
    )
    axes = fig.subplots(rows, cols, squeeze=False)
    g = maps[0].geometry
    view = view_extent([m.alpha for m in maps], g)
    image = None
    for k, wmap in enumerate(maps):
        ax = axes.ravel()[k]
        x0, x1, y0, y1 = _map_extent(wmap)
        ext = (x0 * _MM, x1 * _MM, y0 * _MM, y1 * _MM)
        if mode is None:
            ax.imshow(
                wmap.reachable,
                origin="lower",
                extent=ext,
                interpolation="nearest",
                cmap=ListedColormap(["white", "#cfe3f5"]),
                vmin=0,
                vmax=1,
                zorder=1,
            )
        else:
            shade = np.ma.masked_invalid(wmap.parallel[..., mode])
            image = ax.imshow(
                shade,
                origin="lower",
                extent=ext,
                interpolation="nearest",
                cmap="PuOr",
                vmin=-2.0,
                vmax=2.0,
                zorder=1,
            )
        _draw_annuli(ax, wmap.alpha, wmap.geometry)
        _draw_base(ax, wmap.geometry)
        for m in range(N_MODES) if mode is None else (mode,):
            colour = _MODE_COLOURS[m] if mode is None else "k"
            for line in parallel_singularity_loci(wmap, m):
                ax.plot(line[:, 0] * _MM, line[:, 1] * _MM, color=colour, lw=1.0, zorder=3)
        mx = _map_extent(wmap)
        _square_axes(
            ax, (min(view[0], mx[0]), max(view[1], mx[1]), min(view[2], mx[2]), max(view[3], mx[3]))
        )
        ax.set_title(
            f"alpha = {math.degrees(wmap.alpha):+.0f}°,  area {wmap.area * 1e6:,.0f} mm²",
            fontsize=10,
        )
    handles: list[Line2D | Patch] = []
    if mode is None:
        handles.append(Patch(color="#cfe3f5", label="reachable (all 8 modes)"))
    handles += [
        Line2D([], [], color=LEG_COLOURS[i], lw=1.2, label=f"leg {i + 1} annulus (B{i + 1} ■)")
        for i in range(3)
    ]
    handles.append(Line2D([], [], color="0.3", ls="--", lw=1.0, label="folded-leg circle"))
    handles.append(Line2D([], [], color="0.3", marker="+", ls="", ms=8, label="base centre C_b"))
    if mode is None:
        handles += [
            Line2D(
                [],
                [],
                color=_MODE_COLOURS[m],
                lw=1.5,
                label=f"parallel singularity, mode {m} ({mode_label(m)})",
            )
            for m in range(N_MODES)
        ]
    else:
        handles.append(Line2D([], [], color="k", lw=1.5, label="parallel singularity"))
    for ax in axes.ravel()[n:]:
        ax.set_axis_off()
    if spare:
        axes.ravel()[-1].legend(
            handles=handles, loc="center", fontsize=9, frameon=False, title="legend (lengths in mm)"
        )
    else:
        fig.legend(handles=handles, loc="outside lower center", ncol=4, fontsize=8, frameon=False)
    if image is not None and mode is not None:
        fig.colorbar(
            image,
            ax=axes.ravel()[:n].tolist(),
            shrink=0.6,
            pad=0.02,
            label=f"parallel measure, mode {mode} ({mode_label(mode)}) [-]",
        )
    fig.suptitle(
        title
        or (
            "3-RRR constant-orientation workspace of the platform centre: "
            f"s_a = {g.proximal * _MM:.0f} mm, L = {g.distal * _MM:.0f} mm, "
            f"r_p = {g.platform_radius * _MM:.0f} mm"
        )
    )
    save_figure(fig, dest)


@plain_text
def plot_rrr_path(
    poses: npt.ArrayLike,
    dest: str | os.PathLike[str],
    *,
    mode: int = 0,
    geometry: RRRGeometry = RRR_ROBOT,
    snapshots: int = 3,
    resolution: float = 0.002,
    title: str | None = None,
) -> None:
    """Write a platform path over its workspace as PNG.

    Left: the centres reachable at every orientation the path takes (dark) and
    at some of them (light), evaluated at up to 13 orientations spanning the
    path's; the path coloured by alpha, its unreachable samples as red crosses,
    and the robot in working mode ``mode`` at a few samples. Right: alpha and
    the singularity measures of ``mode`` along the path.

    Args:
        poses: Platform poses (x, y, alpha), shape (T, 3) [m, m, rad].
        dest: PNG path (written atomically).
        mode: Working mode drawn and measured.
        geometry: The robot description.
        snapshots: Number of robot drawings along the path.
        resolution: Grid step of the workspace shading [m].
        title: Figure title.

    Raises:
        InvalidInputError: If ``poses`` is not a (T, 3) array with T >= 2.
    """
    p = as_pose_array(poses)
    if p.ndim != 2 or len(p) < 2:
        raise InvalidInputError(f"poses must have shape (T, 3) with T >= 2, got {p.shape}")
    result = ik(p, geometry)
    ok = result.ok
    alphas = np.unique(np.linspace(np.nanmin(p[:, 2]), np.nanmax(p[:, 2]), 13))
    extent = view_extent(alphas.tolist(), geometry)
    xs = np.arange(extent[0], extent[1] + resolution / 2, resolution)
    ys = np.arange(extent[2], extent[3] + resolution / 2, resolution)
    count = np.zeros((len(ys), len(xs)), dtype=int)
    for a in alphas:
        count += workspace_map(xs, ys, float(a), geometry).reachable
    level = np.where(count == len(alphas), 2, np.where(count > 0, 1, 0))

    fig = new_figure(13.0, 6.4)
    grid = fig.add_gridspec(2, 2, width_ratios=(1.35, 1.0))
    ax = fig.add_subplot(grid[:, 0])
    ext = (xs[0] * _MM, xs[-1] * _MM, ys[0] * _MM, ys[-1] * _MM)
    ax.imshow(
        level,
        origin="lower",
        extent=ext,
        interpolation="nearest",
        cmap=ListedColormap(["white", "#e3eef8", "#a9cbe8"]),
        vmin=0,
        vmax=2,
        zorder=1,
    )
    _draw_base(ax, geometry)
    xy = p[:, :2] * _MM
    seg = np.stack([xy[:-1], xy[1:]], axis=1)
    lc = LineCollection(list(seg), cmap="coolwarm", lw=2.5, zorder=6)
    lc.set_array(np.degrees(0.5 * (p[:-1, 2] + p[1:, 2])))
    ax.add_collection(lc)
    fig.colorbar(
        lc,
        ax=ax,
        location="bottom",
        shrink=0.5,
        pad=0.01,
        label="platform alpha along the path [deg]",
    )
    if (~ok).any():
        ax.plot(xy[~ok, 0], xy[~ok, 1], "x", color="tab:red", ms=6, zorder=7)
    ax.annotate("start", xy[0], xytext=(-10, -14), textcoords="offset points", fontsize=8)
    ax.annotate("end", xy[-1], xytext=(4, -14), textcoords="offset points", fontsize=8)
    shown = np.unique(np.linspace(0, len(p) - 1, max(snapshots, 0)).round().astype(int))
    for t in shown:
        draw_robot(ax, p[t], mode, geometry, alpha=0.45)
    pts = leg_points(p[shown], mode, geometry).reshape(-1, 2)
    pts = pts[np.isfinite(pts).all(axis=-1)]
    if pts.size:
        lo, hi = pts.min(axis=0) - 0.02, pts.max(axis=0) + 0.02
        extent = (
            min(extent[0], lo[0]),
            max(extent[1], hi[0]),
            min(extent[2], lo[1]),
            max(extent[3], hi[1]),
        )
    _square_axes(ax, extent)
    handles: list[Patch | Line2D] = [
        Patch(color="#a9cbe8", label="reachable at every path alpha"),
        Patch(color="#e3eef8", label="reachable at some path alpha"),
    ]
    if (~ok).any():
        handles.append(
            Line2D(
                [],
                [],
                marker="x",
                color="tab:red",
                ls="",
                label=f"unreachable ({int((~ok).sum())} of {len(p)})",
            )
        )
    ax.legend(handles=handles, loc="upper right", fontsize=8)
    ax.set_title(
        f"platform centre path; robot in mode {mode} ({mode_label(mode)}) at {len(shown)} samples",
        fontsize=10,
    )

    idx = np.arange(len(p))
    ax_a = fig.add_subplot(grid[0, 1])
    ax_a.plot(idx, np.degrees(p[:, 2]), color="k")
    ax_a.set_ylabel("alpha [deg]")
    ax_a.grid(alpha=0.3)
    ax_m = fig.add_subplot(grid[1, 1], sharex=ax_a)
    meas = singularity_measures(p, result.theta[:, mode, :], geometry)
    ax_m.plot(idx, meas.serial, label="leg (serial): min |sin bend|")
    ax_m.plot(idx, np.abs(meas.parallel), label="|parallel measure|")
    ax_m.axhline(0.0, color="k", lw=0.8)
    if (~ok).any():
        for t in idx[~ok]:
            ax_m.axvspan(t - 0.5, t + 0.5, color="tab:red", alpha=0.15, lw=0)
    ax_m.set_xlabel("sample")
    ax_m.set_ylabel(f"measure, mode {mode} [-]")
    ax_m.legend(fontsize=8)
    ax_m.grid(alpha=0.3)
    fig.suptitle(title or f"3-RRR platform path: {int(ok.sum())} of {len(p)} poses reachable")
    save_figure(fig, dest)


@plain_text
def plot_rrr_poses(
    poses: npt.ArrayLike,
    dest: str | os.PathLike[str],
    *,
    mode: int = 0,
    labels: Sequence[str] | None = None,
    geometry: RRRGeometry = RRR_ROBOT,
) -> None:
    """Write one panel per pose with the robot in ``mode`` (like the report's Figure 20).

    Args:
        poses: Platform poses, shape (N, 3) [m, m, rad].
        dest: PNG path (written atomically).
        mode: Working mode drawn.
        labels: Panel captions (default: the pose in mm and degrees).
        geometry: The robot description.
    """
    p = as_pose_array(poses).reshape(-1, 3)
    result = ik(p, geometry)
    cols = min(len(p), 3)
    rows = math.ceil(len(p) / cols)
    fig = new_figure(4.6 * cols, 4.4 * rows)
    axes = fig.subplots(rows, cols, squeeze=False)
    extent = view_extent([float(a) for a in p[:, 2]], geometry)
    pts = leg_points(p, mode, geometry)[result.ok].reshape(-1, 2)  # include every elbow
    if pts.size:
        lo, hi = pts.min(axis=0) - 0.03, pts.max(axis=0) + 0.03
        extent = (
            min(extent[0], lo[0]),
            max(extent[1], hi[0]),
            min(extent[2], lo[1]),
            max(extent[3], hi[1]),
        )
    for k, ax in enumerate(axes.ravel()):
        if k >= len(p):
            ax.set_axis_off()
            continue
        _draw_base(ax, geometry)
        _draw_annuli(ax, float(p[k, 2]), geometry)
        draw_robot(ax, p[k], mode, geometry, annotate=True)
        _square_axes(ax, extent)
        caption = (
            labels[k]
            if labels is not None
            else (f"({p[k, 0] * _MM:g}, {p[k, 1] * _MM:g}) mm, alpha {math.degrees(p[k, 2]):g}°")
        )
        verdict = (
            "reachable"
            if result.ok[k]
            else "unreachable: leg " + ", ".join(map(str, result.failing_legs(k)))
        )
        ax.set_title(f"{caption}\n{verdict}", fontsize=9, color="k" if result.ok[k] else "tab:red")
    fig.suptitle(
        f"3-RRR poses, working mode {mode} ({mode_label(mode)}); "
        "circles: the platform centre's leg annuli"
    )
    save_figure(fig, dest)
