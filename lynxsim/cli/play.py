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
from lynxsim.errors import InvalidInputError, OutputPathError
from lynxsim.fileio import check_destination, output_path
from lynxsim.sim.report import RunReport, is_run_report
from lynxsim.web.page import page_from_file
from lynxsim.web.replay_file import REPLAY_SUFFIX

if TYPE_CHECKING:
    from lynxsim.robots import Robot
    from lynxsim.run_options import RunOption

__all__ = [
    "SUMMARY_HEADER",
    "add_run_option_flags",
    "format_report",
    "progress_bar",
    "register",
    "summary_row",
]

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


def _check_flags(args: argparse.Namespace, robot: Robot) -> None:
    """Refuse, before any work, the flags of ``play`` that do not apply to the task's robot.

    Raises:
        InvalidInputError: A run option of another robot (``--mode``, ``--no-obstacle``) or a
            ``--camera`` the robot's model lacks; the message names the flag and the robot.
    """
    from lynxsim.robots import every

    accepted = {o.name for o in robot.run_options}
    task_is = f"{args.task} is a task of {robot.described}"
    robots = every()
    for option in dict.fromkeys(o for r in robots for o in r.run_options):
        if getattr(args, option.name, None) is None or option.name in accepted:
            continue
        owners = " or ".join(
            r.described for r in robots if option.name in {o.name for o in r.run_options}
        )
        raise InvalidInputError(f"{option.flag} applies only to tasks of {owners}; {task_is}")
    if args.camera is not None and args.camera not in robot.cameras:
        raise InvalidInputError(
            f"--camera {args.camera!r}: the {robot.title} model has no such camera; "
            f"available: {', '.join(robot.cameras)}"
        )


def _play(args: argparse.Namespace) -> int:
    from lynxsim.robots import get, motion, simulation
    from lynxsim.run_options import RunValues
    from lynxsim.sim.render import RenderSettings
    from lynxsim.tasks import load_task

    task = load_task(args.task)
    robot = get(task.robot)
    _check_flags(args, robot)
    if args.controller != "ideal":
        from lynxsim.cli.real import play_through_controller

        return play_through_controller(args, task, robot)
    values = RunValues.of(
        robot.run_options, {o.name: getattr(args, o.name) for o in robot.run_options}
    )
    with about_task(args.task):
        built = motion(robot, task, args.type)
    out = args.out or output_path("videos", task.name, built.label, suffix=".mp4")
    if out.suffix.lower() != ".mp4":
        raise InvalidInputError(f"--out must name an .mp4 file, got {out}")
    report_file = check_destination(out.with_suffix(".json"))
    if report_file.exists() and not is_run_report(report_file):
        raise OutputPathError(
            f"will not replace {report_file}: it is not a lynxsim run report (the report of {out} "
            "goes there; move it or choose another --out)"
        )
    replay = check_destination(out.with_suffix(REPLAY_SUFFIX))
    page = check_destination(out.with_suffix(".html")) if args.html else None
    if not args.no_video:
        check_destination(out)
    update, close = progress_bar(f"{task.name} {built.label}", args.json or args.quiet)
    try:
        with about_task(args.task):
            playback = simulation(robot).play(
                task,
                built,
                options=values,
                video=None if args.no_video else out,
                render=RenderSettings(
                    camera=args.camera or robot.cameras[0],
                    quality=quality_of(args),
                    fps=args.fps,
                ),
                progress=update,
                replay=replay,
            )
    finally:
        close()
    if page is not None:
        page_from_file(replay, page)
    return _print_run(args, playback.report, None if args.no_video else out, out, page)


def add_run_option_flags(p: argparse.ArgumentParser) -> None:
    """One flag per run option of every registered robot (:attr:`Robot.run_options`)."""
    from lynxsim.robots import every

    owners: dict[RunOption, list[str]] = {}
    for robot in every():
        for option in robot.run_options:
            owners.setdefault(option, []).append(robot.name)
    for option, names in owners.items():
        text = f"{' or '.join(names)} tasks: {option.help}"
        if option.type is bool:
            p.add_argument(option.flag, action="store_const", const=True, default=None, help=text)
        else:
            p.add_argument(
                option.flag,
                type=int,
                choices=option.choices,
                default=None,
                metavar=option.metavar,
                help=text,
            )


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
    from lynxsim.robots import every

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
    add_run_option_flags(p)
    p.add_argument(
        "--camera",
        default=None,
        help="camera of the robot's model (default the robot's first: "
        + "; ".join(f"{r.name} {', '.join(r.cameras)}" for r in every())
        + ")",
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
