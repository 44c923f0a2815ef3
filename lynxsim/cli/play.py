"""``lynxsim play``: a task through MuJoCo, with its run report, its replay data and an MP4."""

from __future__ import annotations

import argparse
import json
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from lynxsim.cli.context import about_task
from lynxsim.cli.flags import add_quality_flag, quality_of
from lynxsim.errors import InvalidInputError
from lynxsim.fileio import check_destination, output_path
from lynxsim.sim.report import RunReport
from lynxsim.web.page import page_from_file
from lynxsim.web.replay_file import REPLAY_SUFFIX

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
        lines.append("obstacles: none in the scene")
    elif verdict.collided and verdict.first_pair is not None:
        lines.append(
            f"obstacles: COLLISION with {verdict.first_obstacle} first, at "
            f"{verdict.first_time_s:.3f} s ({verdict.first_pair[0]} with "
            f"{verdict.first_pair[1]}), deepest {verdict.max_penetration_m * 1e3:.1f} mm, "
            f"{verdict.steps_in_contact} steps in contact"
        )
    else:
        lines.append("obstacles: clear")
    for o in report.obstacles:
        hit = "hit" if o.first_contact_s is None else f"hit at {o.first_contact_s:.3f} s"
        lines.append(
            f"  {o.name}: {hit if o.collided else 'clear'}, minimum clearance "
            f"{o.min_clearance_m * 1e3:.1f} mm at {o.min_clearance_time_s:.3f} s"
        )
    for label, pairs in (
        ("self-collisions", report.self_collisions),
        ("table/floor contacts", report.floor_contacts),
    ):
        names = ", ".join(f"{p.geom1}/{p.geom2}" for p in pairs) or "none"
        lines.append(f"{label}: {names}")
    if report.metrics is not None:
        lines.extend(report.metrics.lines())
    health = "healthy" if report.healthy else "NOT healthy"
    if report.diverged_at_s is not None:
        health += f": diverged at {report.diverged_at_s:.3f} s"
    if report.warnings:
        health += f", MuJoCo warnings {report.warnings}"
    lines.append(f"simulation: {health}")
    return "\n".join(lines)


def progress_bar(label: str, disable: bool) -> tuple[Callable[[float], None], Callable[[], None]]:
    """A tqdm bar driven by fractions; returns (update, close)."""
    from tqdm import tqdm

    bar = tqdm(total=100, desc=label, unit="%", disable=disable, leave=False)

    def update(fraction: float) -> None:
        bar.update(round(fraction * 100) - bar.n)

    return update, bar.close


_RUN_OPTIONS = ("mode", "no_obstacle")
"""Flags of ``play`` that are options of one robot's runs (``SimAdapter.options``)."""


def _check_flags(args: argparse.Namespace, task: Task) -> None:
    """Refuse, before any work, the flags of ``play`` that do not apply to the task's robot.

    Raises:
        InvalidInputError: A run option of another robot (``--mode``, ``--no-obstacle``) or a
            ``--camera`` the robot's model lacks; the message names the flag and the robot.
    """
    from lynxsim.registry import info, names
    from lynxsim.resources import model_path
    from lynxsim.robots import robot, sim_adapter

    entry = info(task.robot)
    accepted = sim_adapter(entry.name).options
    task_is = f"{args.task} is a task of the {entry.title} (robot {entry.name!r})"
    for option in _RUN_OPTIONS:
        if getattr(args, option) is None or option in accepted:
            continue
        owners = " or ".join(
            f"the {r.title} (robot {r.name!r})"
            for r in map(info, names())
            if option in sim_adapter(r.name).options
        )
        flag = "--" + option.replace("_", "-")
        raise InvalidInputError(f"{flag} applies only to tasks of {owners}; {task_is}")
    if args.camera is not None:
        from lynxsim.sim.render import model_cameras

        cameras = model_cameras(model_path(robot(entry.name).model))
        if args.camera not in cameras:
            raise InvalidInputError(
                f"--camera {args.camera!r}: the {entry.title} model has no such camera; "
                f"available: {', '.join(cameras)}"
            )


def _play(args: argparse.Namespace) -> int:
    from lynxsim.robots import sim_adapter
    from lynxsim.sim.render import RenderSettings
    from lynxsim.tasks import load_task

    task = load_task(args.task)
    _check_flags(args, task)
    if args.controller == "ssc32":
        from lynxsim.cli.real import play_through_ssc32

        return play_through_ssc32(args, task)
    adapter = sim_adapter(task.robot)
    options = {
        name: getattr(args, name) for name in _RUN_OPTIONS if getattr(args, name) is not None
    }
    with about_task(args.task):
        prepared = adapter.prepare(task, args.type)
    out = args.out or output_path("videos", task.name, prepared.label, suffix=".mp4")
    if out.suffix.lower() != ".mp4":
        raise InvalidInputError(f"--out must name an .mp4 file, got {out}")
    check_destination(out.with_suffix(".json"))
    replay = check_destination(out.with_suffix(REPLAY_SUFFIX))
    page = check_destination(out.with_suffix(".html")) if args.html else None
    if not args.no_video:
        check_destination(out)
    update, close = progress_bar(f"{task.name} {prepared.label}", args.json or args.quiet)
    try:
        with about_task(args.task):
            playback = prepared.run(
                video=None if args.no_video else out,
                render=RenderSettings(
                    camera=args.camera or adapter.default_camera,
                    quality=quality_of(args),
                    fps=args.fps,
                ),
                progress=update,
                replay=replay,
                **options,
            )
    finally:
        close()
    if page is not None:
        page_from_file(replay, page)
    return _print_run(args, playback.report, None if args.no_video else out, out, page)


def _print_run(
    args: argparse.Namespace, report: RunReport, video: Path | None, out: Path, page: Path | None
) -> int:
    report.write_json(out.with_suffix(".json"))
    if args.json:
        print(json.dumps(report.to_dict(), indent=2))
    else:
        print(format_report(report))
        if video is not None:
            print(f"video: {video} (report {Path(video).with_suffix('.json')})")
        if page is not None:
            print(f"replay: {page} (open it in a browser; 'lynxsim view REPORT.json' remakes it)")
    return 0


def register(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add the ``play`` sub-command."""
    from lynxsim.bounds import MAX_FPS, MIN_FPS
    from lynxsim.cli.real import add_controller_flags
    from lynxsim.cli.units import bounded_float

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
    p.add_argument(
        "--out",
        type=Path,
        default=None,
        metavar="FILE",
        help="MP4 path (default videos/TASK_TYPE.mp4)",
    )
    p.add_argument("--no-video", action="store_true", help="simulate only")
    p.add_argument(
        "--html",
        action="store_true",
        help="also write the run's replay page FILE.html beside the report (the replay data "
        "FILE.replay.npz is always saved, for 'lynxsim view')",
    )
    p.add_argument(
        "--no-obstacle",
        action="store_const",
        const=True,
        default=None,
        help="arm tasks: the scene without the task's obstacles",
    )
    p.add_argument(
        "--camera",
        default=None,
        help="camera of the robot's model: front, top (default front; top for rrr tasks)",
    )
    p.add_argument(
        "--mode",
        type=int,
        choices=range(8),
        default=None,
        metavar="0..7",
        help="rrr tasks: working mode of the inverse kinematics (default 7, the report's)",
    )
    add_quality_flag(p)
    p.add_argument(
        "--fps",
        type=bounded_float(MIN_FPS, MAX_FPS, "frames/s"),
        default=30.0,
        help=f"video frame rate, {MIN_FPS:g} to {MAX_FPS:g} frames/s (default 30)",
    )
    p.add_argument("--json", action="store_true", help="print the report as JSON (SI units)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    add_controller_flags(p)
    p.set_defaults(handler=_play)
