"""The report's Figure 20 poses judged by simulation (settling in every mode, and a pull).

:func:`lynxsim.sim.rrr.judge.judge_poses` on the poses of
:data:`lynxsim.reproduce.rrr_formulas.FIGURE20_POSES`, and the verdicts as text.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from lynxsim.reproduce.rrr_formulas import FIGURE20_POSES, REPORT_MODE, Figure20Pose
from lynxsim.rrr import N_MODES
from lynxsim.sim.rrr.judge import PoseJudgement, judge_poses
from lynxsim.sim.rrr.verify import ORIENTATION_TOL_RAD, POSITION_TOL_M

__all__ = ["Figure20Sim", "figure20_simulation", "format_figure20_simulation"]

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True)
class Figure20Sim(PoseJudgement):
    """One of the report's Figure 20 poses judged by simulation (:func:`judge_poses`).

    Attributes:
        pose: The report's pose (mm, deg) and what the report says.
    """

    pose: Figure20Pose


def _radians(p: Figure20Pose) -> FloatArray:
    return np.array([p.x_mm * 1e-3, p.y_mm * 1e-3, math.radians(p.alpha_deg)])


def figure20_simulation(
    poses: Sequence[Figure20Pose] = FIGURE20_POSES,
    *,
    modes: Sequence[int] = tuple(range(N_MODES)),
) -> list[Figure20Sim]:
    """Judge the report's Figure 20 poses by simulation.

    Args:
        poses: The poses (default: Figure 20's six and the one its text calls unreachable).
        modes: Working modes to settle each reachable pose in.

    Returns:
        One :class:`Figure20Sim` per pose.
    """
    judged = judge_poses([_radians(p) for p in poses], modes=modes)
    return [
        Figure20Sim(
            ik_reachable=j.ik_reachable,
            failing_legs=j.failing_legs,
            checks=j.checks,
            pull=j.pull,
            pose=p,
        )
        for p, j in zip(poses, judged, strict=True)
    ]


def _mm_deg(position_m: float, angle_rad: float) -> str:
    return f"{position_m * 1e3:.3f} mm, {math.degrees(angle_rad):.3f} deg"


def format_figure20_simulation(rows: Sequence[Figure20Sim]) -> str:
    """The simulation verdicts as text (mm, deg), a few lines per pose."""
    lines = [
        "3-RRR poses of the report's Figure 20 judged in MuJoCo. Settle: the IK's actuated "
        "angles commanded in each working mode; reached within "
        f"{POSITION_TOL_M * 1e3:g} mm and {math.degrees(ORIENTATION_TOL_RAD):g} deg. "
        "Pull: actuators off, platform pulled from home by a spring.",
    ]
    for row in rows:
        p = row.pose
        said = "reachable" if p.report_reachable else "unreachable"
        verdict = "REACHABLE" if row.reachable else "UNREACHABLE"
        lines.append(
            f"{p.label} ({p.x_mm:g} mm, {p.y_mm:g} mm, {p.alpha_deg:g} deg): simulation says "
            f"{verdict} (the report: {said})"
        )
        pull = row.pull
        spans = ", ".join(f"{v * 1e3:.1f}" for v in pull.leg_span_m)
        lines.append(
            f"    pull: {'reached' if pull.reached else 'stops short'}, gap "
            f"{_mm_deg(pull.position_gap_m, pull.orientation_gap_rad)}, leg spans {spans} mm, "
            f"loop closure max {pull.loop_closure_max_m * 1e3:.4f} mm"
        )
        if not row.checks:
            legs = ", ".join(str(leg) for leg in row.failing_legs)
            lines.append(f"    IK: no solution, leg {legs} cannot reach (nothing to command)")
            continue
        reached = ",".join(str(m) for m in row.reached_modes) or "none"
        clear = ",".join(str(m) for m in row.clear_modes) or "none"
        loop = max(c.loop_closure_max_m for c in row.checks) * 1e3
        lines.append(
            f"    settle: reached in modes {reached}; links clear in modes {clear}; "
            f"loop closure max {loop:.4f} mm"
        )
        for c in row.checks:
            if c.reached and not c.interference and c.mode != REPORT_MODE:
                continue
            notes = []
            if not c.reached:
                near = abs(c.parallel_measure) < 0.3
                notes.append(
                    "not reached"
                    + (f", settled in mode {c.settled_mode}" if c.settled_mode != c.mode else "")
                    + f" (|parallel measure| {abs(c.parallel_measure):.2f}"
                    + (": near a parallel singularity)" if near else ")")
                )
            if c.interference:
                worst = max(c.interference, key=lambda pair: pair.max_penetration_m)
                notes.append(
                    f"links overlap: {worst.geom1}/{worst.geom2} by "
                    f"{worst.max_penetration_m * 1e3:.1f} mm (settled with contacts off)"
                )
            lines.append(
                f"    mode {c.mode}: error {_mm_deg(c.position_error_m, c.orientation_error_rad)}"
                + (f"; {'; '.join(notes)}" if notes else "")
            )
    return "\n".join(lines)
