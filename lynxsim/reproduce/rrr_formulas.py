"""The report's 3-RRR poses (its Figure 20) judged with the correct geometry.

The report's inverse kinematics (appendix ``arm.m``) turns the base-joint
vector by the platform rotation alpha and turns the platform-joint vector by
alpha twice (SPEC section 3.1). :func:`report_leg_spans` reproduces that
computation, only so that :func:`figure20_table` can show where the report's
verdicts come from; nothing else in lynxsim uses it.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from lynxsim.rrr.geometry import RRR_ROBOT, RRRGeometry, as_pose_array, rotation
from lynxsim.rrr.ik import ik
from lynxsim.rrr.jacobian import singularity_measures
from lynxsim.rrr.modes import HOME_MODE

__all__ = [
    "FIGURE20_POSES",
    "REPORT_MODE",
    "Figure20Pose",
    "Figure20Row",
    "figure20_table",
    "format_figure20_table",
    "report_leg_spans",
]

FloatArray = npt.NDArray[np.float64]


class Figure20Pose(NamedTuple):
    """A platform pose the report discusses, in its units.

    Attributes:
        label: The report's sub-figure letter (or ``"text"``).
        x_mm: Platform centre x [mm].
        y_mm: Platform centre y [mm].
        alpha_deg: Platform orientation [deg].
        report_reachable: Whether the report draws it (True) or says it lies
            outside the workspace (False).
    """

    label: str
    x_mm: float
    y_mm: float
    alpha_deg: float
    report_reachable: bool


FIGURE20_POSES = (
    Figure20Pose("a", 200.0, 150.0, 0.0, True),
    Figure20Pose("b", 200.0, 150.0, 30.0, True),
    Figure20Pose("c", 200.0, 150.0, -30.0, True),
    Figure20Pose("d", 300.0, 250.0, 0.0, True),
    Figure20Pose("e", 300.0, 250.0, -40.0, True),
    Figure20Pose("f", 200.0, 210.0, 40.0, True),
    Figure20Pose("text", 300.0, 250.0, 40.0, False),
)
"""Figure 20's six poses, and the pose its text says "lies outside of the workspace"."""


REPORT_MODE = HOME_MODE
"""Working mode the report draws: ``arm.m`` takes ``theta = 2 atan(t_1)`` with the
``+`` root of its half-angle quadratic, which is elbow sign -1 on every leg (the
model's home mode, :data:`lynxsim.rrr.modes.HOME_MODE`)."""


def report_leg_spans(pose: npt.ArrayLike, geometry: RRRGeometry = RRR_ROBOT) -> FloatArray:
    """Leg spans ``|P_i - B_i|`` as the report's ``arm.m`` computes them (wrong for alpha != 0).

    ``arm.m`` builds ``PBPP = R(alpha) CPP + BC - BPB`` with both ``BPB`` and
    ``CPP`` taken along the angle ``alpha + 30° + 120° (i - 1)``: the base joint
    turns with the platform, and the platform joint turns by ``2 alpha``.

    Args:
        pose: Platform poses (x, y, alpha), shape (..., 3) [m, m, rad].
        geometry: The robot description.

    Returns:
        Shape (..., 3) [m]; equal to the true spans at ``alpha = 0``.
    """
    p = as_pose_array(pose)
    centre_offset = p[..., None, :2] - np.asarray(geometry.base_centre)  # BC
    base_offset = geometry.base - np.asarray(geometry.base_centre)  # B_i - C_b
    rot1 = rotation(p[..., 2])[..., None, :, :]
    rot2 = rotation(2.0 * p[..., 2])[..., None, :, :]
    d = (
        centre_offset
        + (rot2 @ geometry.platform[..., None])[..., 0]
        - (rot1 @ base_offset[..., None])[..., 0]
    )
    out: FloatArray = np.hypot(d[..., 0], d[..., 1])
    return out


class Figure20Row(NamedTuple):
    """One pose judged both ways.

    Attributes:
        pose: The report's pose.
        leg_span_mm: True ``|P_i - B_i|``, three values [mm].
        reachable: Verdict of the correct geometry.
        failing_legs: 1-based legs that cannot reach (correct geometry).
        report_leg_span_mm: Spans as the report computes them [mm].
        report_geometry_reachable: Verdict of the report's computation.
        min_parallel: Smallest ``|parallel measure|`` over the 8 working modes
            (NaN when unreachable) [-].
        max_parallel: Largest ``|parallel measure|`` over the 8 working modes [-].
        theta_report_mode_deg: Actuated angles in the report's working mode
            :data:`REPORT_MODE` [deg] (NaN when unreachable).
    """

    pose: Figure20Pose
    leg_span_mm: tuple[float, float, float]
    reachable: bool
    failing_legs: tuple[int, ...]
    report_leg_span_mm: tuple[float, float, float]
    report_geometry_reachable: bool
    min_parallel: float
    max_parallel: float
    theta_report_mode_deg: tuple[float, float, float]


def _triple(v: FloatArray) -> tuple[float, float, float]:
    return (float(v[0]), float(v[1]), float(v[2]))


def figure20_table(geometry: RRRGeometry = RRR_ROBOT) -> list[Figure20Row]:
    """Judge :data:`FIGURE20_POSES` with the correct geometry and with the report's.

    Args:
        geometry: The robot description.

    Returns:
        One :class:`Figure20Row` per pose, in order.
    """
    poses = np.array(
        [[p.x_mm * 1e-3, p.y_mm * 1e-3, math.radians(p.alpha_deg)] for p in FIGURE20_POSES]
    )
    result = ik(poses, geometry)
    report = report_leg_spans(poses, geometry)
    lo, hi = geometry.reach_min, geometry.reach_max
    rows = []
    for i, spec in enumerate(FIGURE20_POSES):
        ok = bool(result.ok[i])
        if ok:
            meas = np.abs(singularity_measures(poses[i], result.theta[i], geometry).parallel)
            min_par, max_par = float(meas.min()), float(meas.max())
        else:
            min_par = max_par = math.nan
        rows.append(
            Figure20Row(
                pose=spec,
                leg_span_mm=_triple(result.leg_span[i] * 1e3),
                reachable=ok,
                failing_legs=result.failing_legs(i),
                report_leg_span_mm=_triple(report[i] * 1e3),
                report_geometry_reachable=bool(((report[i] >= lo) & (report[i] <= hi)).all()),
                min_parallel=min_par,
                max_parallel=max_par,
                theta_report_mode_deg=_triple(np.degrees(result.theta[i, REPORT_MODE])),
            )
        )
    return rows


def format_figure20_table(geometry: RRRGeometry = RRR_ROBOT) -> str:
    """:func:`figure20_table` as fixed-width text (mm, deg), one line per pose."""
    mode_head = f"mode-{REPORT_MODE} theta [deg]"
    lines = [
        "3-RRR poses of the report's Figure 20: leg spans |P_i - B_i| must lie in "
        f"[{geometry.reach_min * 1e3:.0f}, {geometry.reach_max * 1e3:.0f}] mm",
        f"{'fig':5s} {'x, y [mm], alpha [deg]':22s} {'spans [mm]':23s} {'verdict':18s} "
        f"{'report says':12s} {'spans, report geometry':23s} {mode_head}",
    ]
    for row in figure20_table(geometry):
        p = row.pose
        target = f"{p.x_mm:g}, {p.y_mm:g}, {p.alpha_deg:g}"
        spans = ", ".join(f"{v:.1f}" for v in row.leg_span_mm)
        rspans = ", ".join(f"{v:.1f}" for v in row.report_leg_span_mm)
        if row.reachable:
            verdict = "reachable"
            theta = ", ".join(f"{v:.2f}" for v in row.theta_report_mode_deg)
        else:
            verdict = "leg " + ", ".join(str(leg) for leg in row.failing_legs) + " fails"
            theta = "-"
        said = "reachable" if p.report_reachable else "unreachable"
        lines.append(
            f"{p.label:5s} {target:22s} {spans:23s} {verdict:18s} {said:12s} {rspans:23s} {theta}"
        )
    return "\n".join(lines)
