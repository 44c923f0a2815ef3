"""``lynxsim plan``: a collision-free motion through a task's poses around its obstacles.

Any robot that plans (:attr:`lynxsim.robots.Robot.planning`) is planned by
:func:`lynxsim.robots.plan`; another robot's task is one line on stderr.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any

from lynxsim.bounds import MAX_RATE_HZ, MIN_RATE_HZ
from lynxsim.cli.context import about_task
from lynxsim.cli.units import bounded_float, seed_int
from lynxsim.fileio import check_destination, output_path

__all__ = ["register"]


def _plan(args: argparse.Namespace) -> int:
    from lynxsim.cli.traj import joint_kinematics, write_samples
    from lynxsim.errors import InvalidInputError
    from lynxsim.plan import PlanProgress, UnknownPlannerError
    from lynxsim.plan.ompl_planners import check_planner
    from lynxsim.plots.trajectory import plot_tool_paths
    from lynxsim.robots import get, plan
    from lynxsim.tasks import load_task

    try:
        check_planner(args.planner)  # a flag, not a field of the task: named as one
    except UnknownPlannerError as exc:
        raise InvalidInputError(f"--planner: {exc}") from None
    task = load_task(args.task)
    robot = get(task.robot)
    out: Path = args.out_dir
    samples = output_path(out, task.name, "planned", suffix=f".{args.format}")
    plot = output_path(out, task.name, "planned_path", suffix=".png")
    for dest in (samples, plot):
        check_destination(dest)

    show = sys.stderr.isatty() and not (args.quiet or args.json)

    def progress(p: PlanProgress) -> None:
        if show:
            print(f"\rsegment {p.label}: {p.stage}...{' ' * 20}", end="", file=sys.stderr)

    with about_task(args.task):
        motion = plan(
            robot,
            task,
            planner=args.planner,
            search_world=args.search_world,
            margin_m=args.margin_mm * 1e-3,
            seed=args.seed,
            time_limit_s=args.time_limit_s,
            progress=progress,
        )
    if show:
        print("\r" + " " * 60 + "\r", end="", file=sys.stderr)
    traj = motion.trajectory
    kinematics = joint_kinematics(robot, "lynxsim plan", args.task)
    write_samples(
        traj, traj.times_at_rate(args.rate_hz), samples, si=args.si, kinematics=kinematics
    )
    plot_tool_paths(
        {"planned": traj},
        plot,
        tool=kinematics.tool_points,
        obstacles=task.scene.obstacles,
        title=f"{task.name}: planned tool path ({args.planner}, margin {args.margin_mm:g} mm)",
    )
    rows: list[dict[str, Any]] = [
        {
            "segment": s.label,
            "planner": s.planner,
            "planning_time_s": round(s.planning_time_s, 6),
            "path_length_rad": round(s.length_rad, 6),
            "min_clearance_m": round(s.min_clearance_m, 6),
            "timed_min_clearance_m": round(t.min_clearance_m, 6),
            "duration_s": round(t.end_s - t.start_s, 6),
        }
        for s, t in zip(motion.segments, motion.timing)
    ]
    if args.json:
        report = {
            "task": task.name,
            "planner": args.planner,
            "margin_m": args.margin_mm * 1e-3,
            "seed": args.seed,
            "duration_s": traj.duration,
            "planning_time_s": motion.planning_time_s,
            "segments": rows,
            "samples": str(samples),
            "plot": str(plot),
        }
        print(json.dumps(report, indent=2))
        return 0
    print(
        f"{task.name}: planned with {args.planner}, margin {args.margin_mm:g} mm, seed "
        f"{args.seed}: {traj.duration:.2f} s of motion, planned in {motion.planning_time_s:.2f} s"
    )
    print(f"{'segment':24s} {'found by':11s} {'time [s]':>9s} {'length [rad]':>13s} "
          f"{'clearance [mm]':>15s} {'timed [mm]':>11s}")  # fmt: skip
    for r in rows:
        print(
            f"{r['segment']:24.24s} {r['planner']:11s} {r['planning_time_s']:9.3f} "
            f"{r['path_length_rad']:13.2f} {r['min_clearance_m'] * 1e3:15.1f} "
            f"{r['timed_min_clearance_m'] * 1e3:11.1f}"
        )
    print(f"wrote {samples}\nwrote {plot}")
    return 0


def register(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add the ``plan`` sub-command."""
    p = sub.add_parser(
        "plan",
        help="plan a collision-free motion through a task's poses",
        description="Plan the task's poses in order around its obstacles (joint space, "
        "compiled RRT-Connect on a sphere cover or OMPL, "
        "clearance margin kept by every configuration), shorten, time within the servo limits "
        "(Ruckig) and check the timed motion clear; write its samples and a plot of the tool "
        "path among the obstacles.",
    )
    p.add_argument("task", type=Path, help="arm task file (TOML), e.g. tasks/three_obstacles.toml")
    p.add_argument(
        "--planner",
        default="compiled",
        metavar="NAME",
        help="compiled (default: RRT-Connect and shortcutting compiled on the robot's sphere "
        "cover) or an OMPL planner: RRTConnect, RRT, RRTstar, BITstar, ... "
        "(a wrong name lists them all)",
    )
    p.add_argument(
        "--search-world",
        choices=("cover", "exact"),
        default="cover",
        help="where the search checks configurations: the robot's sphere cover (default; "
        "never more optimistic than the exact checker) or MuJoCo's exact checker; the timed "
        "motion is checked exactly either way",
    )
    p.add_argument(
        "--margin-mm",
        type=bounded_float(1.0, 100.0, "mm"),
        default=10.0,
        help="clearance every configuration keeps from every obstacle, 1 to 100 (default 10)",
    )
    p.add_argument("--seed", type=seed_int, default=0, help="random seed (default 0)")
    p.add_argument(
        "--time-limit-s",
        type=bounded_float(0.1, 600.0, "s"),
        default=5.0,
        help="search time per segment, 0.1 to 600 s (default 5)",
    )
    p.add_argument(
        "--out-dir",
        type=Path,
        default=Path("out"),
        metavar="DIR",
        help="output folder (default out/)",
    )
    p.add_argument("--format", choices=("csv", "npz"), default="csv", help="samples file format")
    p.add_argument(
        "--rate-hz",
        type=bounded_float(MIN_RATE_HZ, MAX_RATE_HZ, "Hz"),
        default=500.0,
        help="sampling rate of the written samples (default 500)",
    )
    p.add_argument("--si", action="store_true", help="samples in rad and m instead of deg and mm")
    p.add_argument("--json", action="store_true", help="print the plan as JSON (SI units)")
    p.add_argument("--quiet", action="store_true", help="no progress line")
    p.set_defaults(handler=_plan)
