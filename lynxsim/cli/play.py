"""``lynxsim play``: a task through MuJoCo, with its run report and an MP4."""

from __future__ import annotations

import argparse
import json
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from lynxsim.sim.report import RunReport

if TYPE_CHECKING:
    from lynxsim.tasks import Task

__all__ = ["SUMMARY_HEADER", "format_report", "progress_bar", "register", "summary_row"]

SUMMARY_HEADER = (
    f"{'task':20s} {'type':14s} {'duration':>9s} {'max err':>8s} {'final':>7s} "
    f"{'collision':>9s} {'clearance':>10s} {'healthy':>7s}"
)


def summary_row(report: RunReport) -> str:
    """One line of the summary table (mm, s)."""
    clearance = "-" if report.min_clearance_m is None else f"{report.min_clearance_m * 1e3:.1f} mm"
    collided = "-" if report.obstacle is None else ("YES" if report.collided else "no")
    return (
        f"{report.task:20s} {report.trajectory:14s} {report.duration_s:7.2f} s "
        f"{report.tool_max_error_m * 1e3:5.1f} mm {report.tool_final_error_m * 1e3:4.1f} mm "
        f"{collided:>9s} {clearance:>10s} {'yes' if report.healthy else 'NO':>7s}"
    )


def format_report(report: RunReport) -> str:
    """The run report as a readable block (mm, degrees, s)."""
    deg = np.degrees
    lines = [
        f"task {report.task}, trajectory {report.trajectory}: {report.duration_s:.2f} s "
        f"+ {report.settle_s:.2f} s settling at dt = {report.physics_dt_s * 1e3:.1f} ms",
        f"tool tracking error: max {report.tool_max_error_m * 1e3:.2f} mm, RMS "
        f"{report.tool_rms_error_m * 1e3:.2f} mm, final {report.tool_final_error_m * 1e3:.2f} mm",
        "joint error max [deg]: " + " ".join(f"{v:.2f}" for v in deg(report.joint_max_error_rad)),
        "joint error RMS [deg]: " + " ".join(f"{v:.2f}" for v in deg(report.joint_rms_error_rad)),
        "peak torque / stall:   " + " ".join(f"{v:.2f}" for v in report.max_torque_ratio),
    ]
    verdict = report.obstacle
    if verdict is None:
        lines.append("obstacle: none in the scene")
    elif verdict.collided and verdict.first_pair is not None:
        lines.append(
            f"obstacle: COLLISION at {verdict.first_time_s:.3f} s ({verdict.first_pair[0]} with "
            f"{verdict.first_pair[1]}), deepest {verdict.max_penetration_m * 1e3:.1f} mm, "
            f"{verdict.steps_in_contact} steps in contact"
        )
    else:
        lines.append("obstacle: clear")
    if report.min_clearance_m is not None:
        lines.append(
            f"minimum clearance to the obstacle: {report.min_clearance_m * 1e3:.1f} mm "
            f"at {report.min_clearance_time_s:.3f} s"
        )
    for label, pairs in (
        ("self-collisions", report.self_collisions),
        ("table/floor contacts", report.floor_contacts),
    ):
        names = ", ".join(f"{p.geom1}/{p.geom2}" for p in pairs) or "none"
        lines.append(f"{label}: {names}")
    lines.extend(_format_extra(report.extra))
    health = "healthy" if report.healthy else "NOT healthy"
    if report.diverged_at_s is not None:
        health += f": diverged at {report.diverged_at_s:.3f} s"
    if report.warnings:
        health += f", MuJoCo warnings {report.warnings}"
    lines.append(f"simulation: {health}")
    return "\n".join(lines)


def _format_extra(extra: dict[str, float]) -> list[str]:
    """Robot-specific figures, one per line, in mm and degrees where the name says m or rad."""
    lines = []
    for key, value in extra.items():
        for suffix, unit, scale in (
            ("_rad_s", "deg/s", float(np.degrees(1.0))),
            ("_rad", "deg", float(np.degrees(1.0))),
            ("_m", "mm", 1e3),
        ):
            if key.endswith(suffix):
                lines.append(f"{key.removesuffix(suffix)}: {value * scale:.4g} {unit}")
                break
        else:
            lines.append(f"{key}: {value:g}")
    return lines


def progress_bar(label: str, disable: bool) -> tuple[Callable[[float], None], Callable[[], None]]:
    """A tqdm bar driven by fractions; returns (update, close)."""
    from tqdm import tqdm

    bar = tqdm(total=100, desc=label, unit="%", disable=disable, leave=False)

    def update(fraction: float) -> None:
        bar.update(round(fraction * 100) - bar.n)

    return update, bar.close


def _play(args: argparse.Namespace) -> int:
    from lynxsim.sim.arm_task import run_arm_trajectory
    from lynxsim.sim.render import Quality, RenderSettings
    from lynxsim.sim.scene import REPORT_OBSTACLE
    from lynxsim.tasks import load_task
    from lynxsim.traj import build_trajectory

    task = load_task(args.task)
    if task.robot == "rrr":
        return _play_rrr(args, task)
    trajectory = build_trajectory(task, args.type)
    video = (
        None
        if args.no_video
        else (args.out or Path("videos") / f"{task.name}_{trajectory.kind.value}.mp4")
    )
    update, close = progress_bar(f"{task.name} {trajectory.kind.value}", args.json or args.quiet)
    try:
        playback = run_arm_trajectory(
            trajectory,
            task=task.name,
            obstacle=None if args.no_obstacle else REPORT_OBSTACLE,
            video=video,
            render=RenderSettings(
                camera=args.camera or "front", quality=Quality(args.quality), fps=args.fps
            ),
            progress=update,
        )
    finally:
        close()
    return _print_run(args, playback.report, video)


def _play_rrr(args: argparse.Namespace, task: Task) -> int:
    from lynxsim.sim.render import Quality, RenderSettings
    from lynxsim.sim.rrr_task import path_from_task, run_rrr_path

    path = path_from_task(task, args.type)
    video = (
        None if args.no_video else (args.out or Path("videos") / f"{task.name}_{path.label}.mp4")
    )
    update, close = progress_bar(f"{task.name} {path.label}", args.json or args.quiet)
    try:
        playback = run_rrr_path(
            path,
            task=task.name,
            mode=args.mode,
            video=video,
            render=RenderSettings(
                camera=args.camera or "top", quality=Quality(args.quality), fps=args.fps
            ),
            progress=update,
        )
    finally:
        close()
    return _print_run(args, playback.report, video)


def _print_run(args: argparse.Namespace, report: RunReport, video: Path | None) -> int:
    if video is not None:
        report.write_json(Path(video).with_suffix(".json"))
    if args.json:
        print(json.dumps(report.to_dict(), indent=2))
    else:
        print(format_report(report))
        if video is not None:
            print(f"video: {video} (report {Path(video).with_suffix('.json')})")
    return 0


def register(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add the ``play`` sub-command."""
    p = sub.add_parser(
        "play",
        help="play a task in MuJoCo: run report and MP4",
        description="Play a task file's trajectory through the position actuators, print the run "
        "report (exit 0 whether or not the arm collided) and render an MP4.",
    )
    p.add_argument("task", type=Path, help="task file (TOML), e.g. tasks/pick_and_place.toml")
    p.add_argument(
        "--type",
        default=None,
        help="trajectory type overriding the task's (see 'lynxsim traj --list')",
    )
    p.add_argument("--out", type=Path, default=None, help="MP4 path (default videos/TASK_TYPE.mp4)")
    p.add_argument("--no-video", action="store_true", help="simulate only")
    p.add_argument("--no-obstacle", action="store_true", help="the scene without the cylinder")
    p.add_argument(
        "--camera", default=None, help="camera name: front, top (default front; top for rrr tasks)"
    )
    p.add_argument(
        "--mode",
        type=int,
        choices=range(8),
        default=7,
        metavar="0..7",
        help="rrr tasks: working mode of the inverse kinematics (default 7, the report's)",
    )
    p.add_argument(
        "--quality",
        choices=("fast", "default"),
        default="default",
        help="rendering preset: fast (no shadows, no multisampling) or default",
    )
    p.add_argument("--fps", type=float, default=30.0, help="video frame rate [1/s]")
    p.add_argument("--json", action="store_true", help="print the report as JSON (SI units)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(handler=_play)
