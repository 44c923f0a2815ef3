"""``lynxsim rrr ik | fk | workspace | poses``: the 3-RRR robot at the command line.

Lengths in mm and angles in degrees unless ``--si`` is given (m, rad).
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path

import numpy as np

from lynxsim.bounds import MAX_ANGLE_RAD, check_range
from lynxsim.cli.units import Units, add_unit_flags, bounded_float, finite_float, json_list
from lynxsim.errors import InvalidInputError
from lynxsim.fileio import check_destination
from lynxsim.reproduce.rrr_formulas import FIGURE20_POSES, REPORT_MODE, format_figure20_table
from lynxsim.rrr import (
    N_MODES,
    RRR_ROBOT,
    fk_all,
    ik,
    mode_label,
    orientation_range,
    orientation_range_in_mode,
    singularity_measures,
)

__all__ = ["register"]

NEAR_SINGULAR = 0.05
"""|measure| below which a working mode is flagged as near a singularity [-]."""

DEFAULT_ALPHAS_DEG = (0.0, 20.0, -20.0, 50.0, -50.0)
"""The orientations of the report's Figure 21 [deg]."""


def _ik(args: argparse.Namespace) -> int:
    u = Units(args.si)
    pose = np.array(
        [u.length_in(args.x, "X"), u.length_in(args.y, "Y"), u.angle_in(args.alpha, "ALPHA")]
    )
    result = ik(pose)
    result.raise_for_status()
    meas = singularity_measures(pose, result.theta)
    theta = u.angle_out(result.theta)
    spans = u.length_out(result.leg_span)
    serial = float(meas.serial[0])
    if args.json:
        print(
            json.dumps(
                {
                    "units": {"length": u.length, "angle": u.angle},
                    "pose": {"x": args.x, "y": args.y, "alpha": args.alpha},
                    "leg_span": json_list(spans),
                    "serial_measure": round(serial, 9),
                    "modes": [
                        {
                            "mode": m,
                            "elbow_signs": mode_label(m),
                            "theta": json_list(theta[m]),
                            "parallel_measure": round(float(meas.parallel[m]), 9),
                        }
                        for m in range(N_MODES)
                    ],
                },
                indent=2,
            )
        )
        return 0
    near = "  (near a leg singularity)" if serial < NEAR_SINGULAR else ""
    print(
        f"leg spans |P_i - B_i| [{u.length}]: "
        + "  ".join(u.fmt_length(v) for v in spans)
        + f"   leg-singularity measure {serial:.3f}{near}"
    )
    print(
        f"mode  elbows {'theta1':>10s} {'theta2':>10s} {'theta3':>10s} [{u.angle}]"
        "  parallel measure"
    )
    for m in range(N_MODES):
        par = float(meas.parallel[m])
        flag = "  near a parallel singularity" if abs(par) < NEAR_SINGULAR else ""
        angles = " ".join(f"{u.fmt_angle(v):>10s}" for v in theta[m])
        print(f"{m:<5d} {mode_label(m):6s} {angles}        {par:+.3f}{flag}")
    return 0


def _fk(args: argparse.Namespace) -> int:
    u = Units(args.si)
    typed = [args.theta1, args.theta2, args.theta3]
    theta = np.array([u.angle_in(v, f"THETA{i}") for i, v in enumerate(typed, 1)])
    sol = fk_all(theta)
    count = int(sol.num_solutions)
    poses = sol.pose[:count]
    if args.json:
        print(
            json.dumps(
                {
                    "units": {"length": u.length, "angle": u.angle},
                    "theta": typed,
                    "assembly_modes": [
                        {
                            "x": float(u.length_out(p[0])),
                            "y": float(u.length_out(p[1])),
                            "alpha": float(u.angle_out(p[2])),
                            "working_mode": int(m),
                        }
                        for p, m in zip(poses, sol.mode[:count], strict=True)
                    ],
                },
                indent=2,
            )
        )
        return 0
    if count == 0:
        print("no platform pose closes the three loops for these angles")
        return 0
    print(f"{count} assembly mode{'s' if count > 1 else ''}:")
    print(f"{'x':>10s} {'y':>10s} [{u.length}] {'alpha':>10s} [{u.angle}]  working mode")
    for p, m in zip(poses, sol.mode[:count], strict=True):
        print(
            f"{u.fmt_length(float(u.length_out(p[0]))):>10s} "
            f"{u.fmt_length(float(u.length_out(p[1]))):>10s}      "
            f"{u.fmt_angle(float(u.angle_out(p[2]))):>10s}        {m} ({mode_label(int(m))})"
        )
    return 0


MAX_ALPHAS = 12
"""Most orientations of one workspace figure (one panel each)."""


def _workspace(args: argparse.Namespace) -> int:
    from lynxsim.plots.rrr import plot_rrr_workspace, view_extent
    from lynxsim.plots.style import check_png
    from lynxsim.rrr.workspace import workspace_maps

    if len(args.alpha_deg) > MAX_ALPHAS:
        raise InvalidInputError(
            f"--alpha-deg takes 1 to {MAX_ALPHAS} orientations, got {len(args.alpha_deg)}"
        )
    limit = math.degrees(MAX_ANGLE_RAD)
    check_destination(check_png(args.out, "--out"))
    alphas = [
        math.radians(check_range(a, "--alpha-deg", -limit, limit, "deg")) for a in args.alpha_deg
    ]
    maps = workspace_maps(alphas, view_extent(alphas), args.resolution_mm * 1e-3)
    plot_rrr_workspace(maps, args.out, mode=args.mode)
    for wmap in maps:
        alpha_deg = math.degrees(wmap.alpha)
        line = f"alpha {alpha_deg:+7.2f} deg: reachable area {wmap.area * 1e6:9,.0f} mm²"
        if args.mode is not None:
            free = wmap.singularity_free(args.mode, NEAR_SINGULAR).sum() * wmap.cell_area
            line += (
                f", {free * 1e6:9,.0f} mm² of it >= {NEAR_SINGULAR} from singularities "
                f"in mode {args.mode}"
            )
        print(line)
    print(f"wrote {args.out}")
    return 0


def _poses(args: argparse.Namespace) -> int:
    if args.out is not None:
        check_destination(args.out)
    print(format_figure20_table())
    centre = np.asarray(RRR_ROBOT.base_centre)
    rng = orientation_range(centre)
    print()
    print(
        f"orientations reachable at the base centre C_b = ({centre[0] * 1e3:.2f}, "
        f"{centre[1] * 1e3:.2f}) mm: {math.degrees(float(rng.lower)):+.2f} to "
        f"{math.degrees(float(rng.upper)):+.2f} deg "
        f"(limited by legs {rng.limiting_leg[0]} and {rng.limiting_leg[1]})"
    )
    for m in range(N_MODES):
        lo, hi = orientation_range_in_mode(float(centre[0]), float(centre[1]), m)
        print(
            f"  without meeting a parallel singularity in mode {m} ({mode_label(m)}): "
            f"{math.degrees(lo):+.2f} to {math.degrees(hi):+.2f} deg"
        )
    if args.out is not None:
        from lynxsim.plots.rrr import plot_rrr_poses

        poses = np.array(
            [[p.x_mm * 1e-3, p.y_mm * 1e-3, math.radians(p.alpha_deg)] for p in FIGURE20_POSES]
        )
        labels = [
            f"({p.label}) {p.x_mm:g}, {p.y_mm:g} mm, {p.alpha_deg:g}°" for p in FIGURE20_POSES
        ]
        plot_rrr_poses(poses, args.out, mode=args.mode, labels=labels)
        print(f"wrote {args.out}")
    return 0


def _mode_arg(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"working mode must be an integer 0..7, got {text!r}"
        ) from None
    if not 0 <= value < N_MODES:
        raise argparse.ArgumentTypeError(f"working mode must be 0..7, got {value}")
    return value


def register(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add the ``rrr`` command group (``ik``, ``fk``, ``workspace``, ``poses``)."""
    group = sub.add_parser(
        "rrr",
        help="kinematics of the planar 3-RRR parallel robot",
        description="Kinematics of the report's planar 3-RRR robot. Working modes 0..7: "
        "bit i set when leg i+1's elbow sign is -1 (see lynxsim.rrr.modes).",
    )
    rrr_sub = group.add_subparsers(required=True, parser_class=type(group))

    p = rrr_sub.add_parser(
        "ik",
        help="actuated angles of a platform pose in all 8 working modes",
        description="Inverse kinematics of the platform pose X Y [mm] ALPHA [deg] (--si: m, "
        "rad). Prints the base angles of every working mode; an unreachable pose names the "
        "leg that fails and exits with status 1.",
    )
    p.add_argument("x", type=finite_float, metavar="X")
    p.add_argument("y", type=finite_float, metavar="Y")
    p.add_argument("alpha", type=finite_float, metavar="ALPHA")
    add_unit_flags(p)
    p.set_defaults(handler=_ik)

    p = rrr_sub.add_parser(
        "fk",
        help="every platform pose (assembly mode) of three actuated angles",
        description="Forward kinematics of the actuated angles THETA1..3 [deg] (--si: rad).",
    )
    for i in range(1, 4):
        p.add_argument(f"theta{i}", type=finite_float, metavar=f"THETA{i}")
    add_unit_flags(p)
    p.set_defaults(handler=_fk)

    p = rrr_sub.add_parser(
        "workspace",
        help="constant-orientation workspace maps (PNG)",
        description="Plot the reachable platform centres at each orientation with the leg "
        "annuli and the parallel-singularity loci of all working modes (or of --mode).",
    )
    p.add_argument(
        "--alpha-deg",
        "--alpha",
        type=finite_float,
        nargs="+",
        default=list(DEFAULT_ALPHAS_DEG),
        metavar="DEG",
        help="platform orientations [deg] (default: the report's 0 20 -20 50 -50)",
    )
    p.add_argument(
        "--out", type=Path, default=Path("rrr_workspace.png"), metavar="FILE", help="PNG file"
    )
    p.add_argument(
        "--resolution-mm",
        type=bounded_float(0.1, 100.0, "mm"),
        default=2.0,
        help="grid step, 0.1 to 100 mm (default 2)",
    )
    p.add_argument(
        "--mode",
        type=_mode_arg,
        default=None,
        help="shade this working mode's parallel-singularity measure",
    )
    p.set_defaults(handler=_workspace)

    p = rrr_sub.add_parser(
        "poses",
        help="the report's Figure 20 poses judged with the correct geometry",
        description="Print the Figure 20 verdicts (correct geometry and the report's) and "
        "the orientation range at the base centre; --out draws the poses.",
    )
    p.add_argument("--out", type=Path, default=None, metavar="FILE", help="PNG file of the poses")
    p.add_argument(
        "--mode",
        type=_mode_arg,
        default=REPORT_MODE,
        help=f"working mode drawn (default {REPORT_MODE}, the report's)",
    )
    p.set_defaults(handler=_poses)
