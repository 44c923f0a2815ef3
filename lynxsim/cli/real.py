"""``lynxsim real``: drive the real arm through an SSC-32U, emulate the board, compare a run.

``lynxsim real play`` checks a task's motion in simulation (the ideal playback
and the digital twin through the board must both be clear, unless
``--force``), prints the controller's deviation, then streams the lines to the
board with a log; ``--dry-run`` prints the stream instead. ``lynxsim real
emulate`` serves an emulated board on a pseudo-terminal and prints its path.
``lynxsim real compare`` compares measured joint angles with a log's simulated
run. ``lynxsim play --controller ssc32`` (:func:`play_through_controller`) plays a
task through the digital twin. The task's robot is looked up through the robot
interface; a robot without a real backend (:attr:`lynxsim.robots.Robot.real`)
is refused.
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime
import json
import sys
import time
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from lynxsim.cli.context import about_task
from lynxsim.errors import CollisionRefusedError, InvalidInputError
from lynxsim.fileio import check_destination, output_path, write_json

if TYPE_CHECKING:
    from lynxsim.real.calibration import Calibration
    from lynxsim.real.stream import StreamOptions
    from lynxsim.robots import Robot
    from lynxsim.sim.adapter import RealBackend
    from lynxsim.sim.twin import TwinRun
    from lynxsim.tasks import Task

__all__ = ["add_controller_flags", "play_through_controller", "register"]

_TWIN_EVERY = 10
"""The log keeps every this-th physics step of the twin's simulated joints (20 ms at 2 ms)."""


def _backend(robot: Robot, what: str, source: object, controller: str) -> RealBackend:
    """The real backend of a task's robot, refused by capability (the robots that have one)."""
    from lynxsim.errors import CapabilityError
    from lynxsim.robots import real_backend

    backend = real_backend(robot, what, source)
    if backend.controller != controller:
        raise CapabilityError(
            f"{what}: {robot.described} is driven through {backend.controller!r}, "
            f"not {controller!r}"
        )
    return backend


def _real_task(path: Path) -> tuple[Task, Robot, RealBackend]:
    from lynxsim.robots import get
    from lynxsim.tasks import load_task

    task = load_task(path)
    robot = get(task.robot)
    return task, robot, _backend(robot, "lynxsim real", task.source, "ssc32")


def _calibration(backend: RealBackend, value: str) -> Calibration:
    return backend.calibration(None if value == "default" else value)


def _options(args: argparse.Namespace) -> StreamOptions:
    from lynxsim.real.stream import StreamOptions

    return StreamOptions(mode=args.mode, period_ms=args.period_ms)


def _verdict(twin: TwinRun) -> str | None:
    """Why the motion is refused (it collides in a simulation), or None."""
    for label, report in (
        ("ideal playback", twin.ideal.report),
        ("digital twin", twin.twin.report),
    ):
        v = report.obstacle
        if v is not None and v.collided:
            return (
                f"the motion collides in simulation ({label}: {v.first_obstacle} at "
                f"{v.first_time_s:.3f} s); --force sends it anyway"
            )
    return None


def _header(task: Task, twin: TwinRun, calibration: Calibration, version: str) -> dict[str, Any]:
    t, q = twin.simulated_joints()
    stream = twin.stream
    return {
        "lynxsim": __import__("lynxsim").__version__,
        "started_utc": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        "task": task.name,
        "task_file": str(task.source),
        "trajectory": twin.ideal.report.trajectory,
        "mode": stream.options.mode,
        "period_ms": stream.options.period_ms,
        "baud": stream.baud,
        "board": version,
        "channels": list(stream.channels),
        "joint_names": list(calibration.names),
        "calibration": calibration.to_dict(),
        "lines": len(stream.lines),
        "commanded_final_us": list(stream.final_us),
        "twin": {
            "time_s": [round(float(v), 4) for v in t[::_TWIN_EVERY]],
            "q_deg": np.round(np.degrees(q[::_TWIN_EVERY]), 4).tolist(),
        },
    }


def _play(args: argparse.Namespace) -> int:
    from lynxsim.cli.play import progress_bar
    from lynxsim.real.driver import Ssc32Link, play_stream
    from lynxsim.real.log import RunLogWriter
    from lynxsim.robots import motion

    if args.port is None and not args.dry_run:
        raise InvalidInputError("--port DEV is needed (or --dry-run to print the stream)")
    task, robot, backend = _real_task(args.task)
    calibration = _calibration(backend, args.calibration)
    options = _options(args)
    with about_task(args.task):
        built = motion(robot, task, args.type)
    log_path = args.log or output_path("logs", task.name, built.label, suffix=".jsonl")
    check_destination(log_path)
    with about_task(args.task):
        twin = backend.twin(task, built, calibration, options)

    def say(text: str) -> None:
        if not args.quiet:
            print(text, file=sys.stderr)

    for line in twin.comparison.deviation.lines(calibration.names) + twin.comparison.lines():
        say(line)
    refusal = _verdict(twin)
    if refusal is not None and not args.force:
        raise CollisionRefusedError(refusal)
    if args.dry_run:
        for ln in twin.stream.lines:
            print(f"{ln.at_s:9.3f} s  {ln.kind:8s} {ln.text}")
        return 0
    with Ssc32Link(args.port, calibration.baud, timeout_s=args.timeout_s) as link:
        version = link.version()
        say(f"board: {version} on {args.port} at {calibration.baud} baud")
        log = RunLogWriter(log_path, _header(task, twin, calibration, version))
        update, close = progress_bar(f"{task.name} to {args.port}", args.quiet)
        try:
            result = play_stream(link, twin.stream, log, progress=update)
        finally:
            close()
    agree = "agree" if result.agrees else "DISAGREE"
    print(
        f"sent {result.lines_sent} lines, motion done at {result.end_s:.3f} s; final pulses "
        f"read back {list(result.final_pulses_us)} us, commanded {list(result.commanded_final_us)} "
        f"us ({agree} to QP's 10 us); log {result.log}"
    )
    return 0 if result.agrees else 1


def _emulate(args: argparse.Namespace) -> int:
    from lynxsim.real.pty_server import PtyEmulator

    if args.state is not None:
        check_destination(args.state)
    emulator = PtyEmulator(answers=not args.silent)
    print(emulator.path, flush=True)
    try:
        while True:
            time.sleep(0.2)
    finally:
        with emulator.lock:
            now = emulator.now_s()
            board = emulator.board
            state = {
                "pulses_us": {str(c): board.pulse_us(c, now) for c in range(32)},
                "lines": len(board.lines),
                "rejected": len(board.rejected),
                "received": [line for _, line in board.lines],
            }
        emulator.close()
        if args.state is not None:
            write_json(args.state, state)


def _compare(args: argparse.Namespace) -> int:
    from lynxsim.real.compare import compare_measured, read_measured
    from lynxsim.real.log import read_log

    log = read_log(args.log)
    t, measured = read_measured(args.measured, tuple(log.header["joint_names"]))
    rows = compare_measured(log, t, measured)
    if args.json:
        print(json.dumps([r.__dict__ for r in rows], indent=2))
        return 0
    print(f"run {log.header['task']} ({log.header['trajectory']}), ended {log.end}")
    print(f"{'joint':12s} {'samples':>7s} {'max err':>9s} {'at':>8s} {'RMS':>8s}")
    for r in rows:
        print(
            f"{r.joint:12s} {r.samples:7d} {np.degrees(r.max_error_rad):7.2f} deg "
            f"{r.max_error_time_s:7.3f}s {np.degrees(r.rms_error_rad):6.2f} deg"
        )
    return 0


def add_controller_flags(p: argparse.ArgumentParser) -> None:
    """``--controller`` and ``--calibration`` of ``lynxsim play``."""
    p.add_argument(
        "--controller",
        choices=("ideal", "ssc32"),
        default="ideal",
        help="arm tasks: ideal (targets every physics step) or ssc32 (the digital twin: the "
        "pulses an SSC-32U would send, 20 ms frames, 1 us steps, the servos' dead band)",
    )
    p.add_argument(
        "--calibration",
        default="default",
        metavar="FILE",
        help="with --controller ssc32: calibration file (default: the shipped one)",
    )


def play_through_controller(args: argparse.Namespace, task: Task, robot: Robot) -> int:
    """``lynxsim play TASK --controller ssc32``: the twin's report, video, and the difference."""
    from lynxsim.cli.play import format_report, progress_bar
    from lynxsim.real.stream import StreamOptions
    from lynxsim.robots import motion
    from lynxsim.sim.render import Quality, RenderSettings

    what = f"--controller {args.controller}"
    backend = _backend(robot, what, task.source, args.controller)
    calibration = _calibration(backend, args.calibration)
    with about_task(args.task):
        built = motion(robot, task, args.type)
    label = f"{built.label}_{backend.controller}"
    out = args.out or output_path("videos", task.name, label, suffix=".mp4")
    if out.suffix.lower() != ".mp4":
        raise InvalidInputError(f"--out must name an .mp4 file, got {out}")
    check_destination(out.with_suffix(".json"))
    scene = task.scene.without_obstacles() if args.no_obstacle else task.scene
    update, close = progress_bar(f"{task.name} {label}", args.json or args.quiet)
    try:
        with about_task(args.task):
            run = backend.twin(
                dataclasses.replace(task, scene=scene),
                built,
                calibration,
                StreamOptions(),
                video=None if args.no_video else out,
                render=RenderSettings(
                    camera=args.camera or robot.cameras[0],
                    quality=Quality(args.quality),
                    fps=args.fps,
                ),
                progress=update,
            )
    finally:
        close()
    report = run.twin.report
    report.write_json(out.with_suffix(".json"))
    comparison = run.comparison
    if args.json:
        data = report.to_dict()
        data["ideal"] = run.ideal.report.to_dict()
        data["extra_tool_max_error_m"] = comparison.extra_tool_max_error_m
        data["extra_tool_rms_error_m"] = comparison.extra_tool_rms_error_m
        data["same_verdicts"] = comparison.same_verdicts
        print(json.dumps(data, indent=2))
        return 0
    print(format_report(report))
    for line in comparison.deviation.lines(calibration.names) + comparison.lines():
        print(line)
    if not args.no_video:
        print(f"video: {out} (report {out.with_suffix('.json')})")
    return 0


def register(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add the ``real`` sub-command and its ``play``, ``emulate`` and ``compare``."""
    from lynxsim.cli.units import bounded_float

    p = sub.add_parser(
        "real",
        help="the real arm: stream a task to an SSC-32U, emulate the board, compare a run",
        description="Drive the real arm through an SSC-32U servo controller (needs the extra "
        "lynxsim[real]), emulate the board on a pseudo-terminal, or compare a run's measured "
        "joint angles with its simulation.",
    )
    real = p.add_subparsers(required=True, parser_class=type(p))
    play = real.add_parser(
        "play",
        help="check a task's motion in simulation, then stream it to the board",
        description="Refuses a motion that collides in simulation (ideal playback or the digital "
        "twin through the board) unless --force, and any pulse outside the calibration or "
        "speed over its limits. On Ctrl-C or SIGTERM sends STOP to every channel.",
    )
    play.add_argument("task", type=Path, help="arm task file (TOML)")
    play.add_argument("--port", default=None, metavar="DEV", help="serial device of the board")
    play.add_argument(
        "--calibration",
        required=True,
        metavar="FILE",
        help="calibration file (TOML), or 'default' for the shipped starting point",
    )
    play.add_argument("--type", default=None, help="trajectory type overriding the task's")
    play.add_argument(
        "--mode",
        choices=("streamed", "waypoints"),
        default="streamed",
        help="streamed: a group move every --period-ms; waypoints: one timed move per segment",
    )
    play.add_argument(
        "--period-ms",
        type=int,
        default=100,
        metavar="MS",
        help="streaming period, a multiple of 20 ms within 20..1000 (default 100)",
    )
    play.add_argument("--dry-run", action="store_true", help="print the stream, send nothing")
    play.add_argument("--force", action="store_true", help="send a motion that collides")
    play.add_argument("--log", type=Path, default=None, metavar="FILE", help="log (.jsonl)")
    play.add_argument(
        "--timeout-s",
        type=bounded_float(0.05, 10.0, "s"),
        default=0.5,
        help="how long a query waits for the board's answer, 0.05 to 10 s (default 0.5)",
    )
    play.add_argument("--quiet", action="store_true", help="no checks printed")
    play.set_defaults(handler=_play)
    emulate = real.add_parser(
        "emulate",
        help="serve an emulated SSC-32U on a pseudo-terminal and print its path",
        description="Runs until Ctrl-C or SIGTERM.",
    )
    emulate.add_argument("--silent", action="store_true", help="a board that never answers")
    emulate.add_argument(
        "--state", type=Path, default=None, metavar="FILE", help="on exit, write pulses (JSON)"
    )
    emulate.set_defaults(handler=_emulate)
    compare = real.add_parser(
        "compare",
        help="compare measured joint angles (CSV) with a run's simulation",
        description="MEASURED.csv: a time_s column (seconds from the first line sent, the log's "
        "clock) and <joint>_deg columns (any of base, shoulder, elbow, wrist_pitch, wrist_roll).",
    )
    compare.add_argument("log", type=Path, help="the run's log (.jsonl)")
    compare.add_argument("measured", type=Path, help="measured joint angles (CSV)")
    compare.add_argument("--json", action="store_true", help="print JSON (rad, s)")
    compare.set_defaults(handler=_compare)
