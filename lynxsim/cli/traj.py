"""``lynxsim traj``: trajectories of a task file, written as samples and plots.

Samples are in degrees and millimetres unless ``--si`` (rad, m); every column
or array name carries its unit. Any robot with joint kinematics
(:attr:`lynxsim.robots.Robot.kinematics`) is written: its joints, its tool
point and the tool angles its kinematics names (the arm's pitch).
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np

from lynxsim.bounds import MAX_RATE_HZ, MAX_SEGMENT_S, MIN_RATE_HZ, MIN_SEGMENT_S
from lynxsim.cli.context import about_task
from lynxsim.cli.units import bounded_float
from lynxsim.errors import InvalidInputError, LynxsimError
from lynxsim.fileio import atomic_path, check_destination, output_path
from lynxsim.robots import Robot
from lynxsim.tasks import Task, load_task
from lynxsim.traj import Kinematics, Trajectory, TrajectoryKind

__all__ = ["register", "write_samples"]

_ORDERS = (("q", ""), ("qd", "_s"), ("qdd", "_s2"), ("qddd", "_s3"))


class _Samples(NamedTuple):
    """One sampled quantity: its NPZ key, values and CSV column names (units in all)."""

    key: str
    values: np.ndarray
    columns: tuple[str, ...]


def _samples(traj: Trajectory, t: np.ndarray, si: bool, kinematics: Kinematics) -> list[_Samples]:
    angle, length, scale = ("rad", "m", 1.0) if si else ("deg", "mm", 1e3)
    to_angle = (lambda v: v) if si else np.degrees
    states = traj.sample(t)
    tool = kinematics.tool(states.q)
    joints = range(1, traj.n_joints + 1)
    out = [_Samples("t_s", t, ("t_s",))]
    for (name, per), values in zip(_ORDERS, states):
        unit = f"{angle}{per}"
        out.append(
            _Samples(f"{name}_{unit}", to_angle(values), tuple(f"{name}{j}_{unit}" for j in joints))
        )
    out.append(
        _Samples(
            f"tool_position_{length}",
            tool.position * scale,
            tuple(f"{axis}_{length}" for axis in "xyz"),
        )
    )
    for name, values in tool.angles:
        out.append(_Samples(f"{name}_{angle}", to_angle(values), (f"{name}_{angle}",)))
    return out


def _write_csv(path: Path, samples: list[_Samples]) -> None:
    table = np.column_stack([s.values for s in samples])
    header = ",".join(c for s in samples for c in s.columns)
    with atomic_path(path) as tmp:
        np.savetxt(tmp, table, delimiter=",", header=header, comments="", fmt="%.9g")


def _write_npz(path: Path, samples: list[_Samples], traj: Trajectory) -> None:
    arrays: dict[str, Any] = {s.key: s.values for s in samples}
    arrays["waypoint_times_s"] = traj.waypoint_times
    arrays["waypoint_names"] = np.array(traj.waypoints.names)
    arrays["kind"] = np.array(traj.kind.value)
    with atomic_path(path) as tmp:
        np.savez(tmp, **arrays)


def write_samples(
    traj: Trajectory, t: np.ndarray, dest: Path, *, si: bool, kinematics: Kinematics
) -> None:
    """Write a trajectory's samples at times ``t`` [s] as CSV or NPZ (by ``dest``'s suffix).

    Columns: time, the joints and their derivatives, the tool point and the tool
    angles of ``kinematics`` (the robot's).
    """
    data = _samples(traj, t, si, kinematics)
    if dest.suffix == ".csv":
        _write_csv(dest, data)
    else:
        _write_npz(dest, data, traj)


def _apply_overrides(task: Task, args: argparse.Namespace) -> Task:
    if args.shortest:
        task = dataclasses.replace(task, durations=None)
    elif args.segment_duration_s is not None:
        n = len(task.poses) - 1
        task = dataclasses.replace(task, durations=(args.segment_duration_s,) * n)
    if args.stretch is not None:
        task = dataclasses.replace(task, stretch=args.stretch)
    if args.pass_through:
        task = dataclasses.replace(task, pass_through=True)
    return task


def _comparison(robot: Robot, kinematics: Kinematics, task: Task, dest: Path) -> None:
    from lynxsim.plots.trajectory import plot_tool_paths
    from lynxsim.robots import motion

    trajectories = {}
    for kind in robot.kinds:
        try:
            trajectories[kind.value] = joint_trajectory(robot, motion(robot, task, kind))
        except LynxsimError as exc:
            print(f"lynxsim: note: no {kind.value} path in the comparison: {exc}", file=sys.stderr)
    plot_tool_paths(
        trajectories,
        dest,
        tool=kinematics.tool_points,
        obstacles=task.scene.obstacles,
        title=f"{task.name}: tool paths of every trajectory type",
    )


def joint_kinematics(robot: Robot, command: str, source: object) -> Kinematics:
    """The robot's joint kinematics, or one clear error naming the robots that have some.

    Raises:
        CapabilityError: The robot's motions are not joint trajectories.
    """
    from lynxsim.errors import CapabilityError
    from lynxsim.robots import with_capability

    if robot.kinematics is None:
        owners = ", ".join(r.name for r in with_capability("kinematics")) or "none"
        raise CapabilityError(
            f"{command} writes joint trajectories; {source} is a task of {robot.described}, "
            f"whose motions are not (robots with joint kinematics: {owners})"
        )
    return robot.kinematics


def joint_trajectory(robot: Robot, built: object) -> Trajectory:
    """A robot's motion as the joint trajectory its kinematics promise.

    Raises:
        InvalidInputError: The robot built something else.
    """
    if not isinstance(built, Trajectory):
        raise InvalidInputError(
            f"{robot.described} has joint kinematics but built a {type(built).__name__}"
        )
    return built


def _list() -> int:
    width = max(len(k.value) for k in TrajectoryKind)
    for kind in TrajectoryKind:
        print(f"{kind.value:{width}s}  {kind.description}")
    return 0


def _traj(args: argparse.Namespace) -> int:
    if args.list:
        return _list()
    if args.task is None:
        raise InvalidInputError("give a task file (e.g. tasks/pick_and_place.toml), or --list")
    from lynxsim.plots.trajectory import plot_joint_profiles
    from lynxsim.robots import get, motion

    task = _apply_overrides(load_task(args.task), args)
    robot = get(task.robot)
    kinematics = joint_kinematics(robot, "lynxsim traj", args.task)
    with about_task(args.task):
        traj = joint_trajectory(robot, motion(robot, task, args.type))
        t = traj.times_at_rate(args.rate_hz)
    out: Path = args.out_dir
    samples = output_path(out, task.name, traj.kind.value, suffix=f".{args.format}")
    joints = output_path(out, task.name, traj.kind.value, "joints", suffix=".png")
    paths = output_path(out, task.name, "paths", suffix=".png")
    for dest in (samples, joints, *(() if args.no_compare else (paths,))):
        check_destination(dest)
    write_samples(traj, t, samples, si=args.si, kinematics=kinematics)
    plot_joint_profiles(
        traj, joints, title=f"{task.name}: {traj.kind.value} trajectory, {traj.duration:.3f} s"
    )
    written = [samples, joints]
    if not args.no_compare:
        _comparison(robot, kinematics, task, paths)
        written.append(paths)
    durations = ", ".join(f"{d:.3f}" for d in traj.segment_durations)
    print(
        f"{task.name}: {traj.kind.value} trajectory through {', '.join(traj.waypoints.names)}, "
        f"{traj.duration:.3f} s (segments {durations} s), {t.size} samples at {args.rate_hz:g} Hz"
    )
    for path in written:
        print(f"wrote {path}")
    return 0


def register(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add the ``traj`` sub-command."""
    types = [k.value for k in TrajectoryKind]
    p = sub.add_parser(
        "traj",
        help="trajectories of a task file: samples (CSV/NPZ) and plots (PNG)",
        description="Build a trajectory through a task's poses and write its samples, its "
        "joint profiles and a comparison of the tool paths of every type. Samples in deg and "
        "mm unless --si.",
    )
    p.add_argument(
        "task", type=Path, nargs="?", help="task file (TOML), e.g. tasks/pick_and_place.toml"
    )
    p.add_argument("--list", action="store_true", help="list the trajectory types and exit")
    p.add_argument(
        "--type", choices=types, default=None, help="trajectory type (default: the task's)"
    )
    p.add_argument(
        "--out-dir",
        type=Path,
        default=Path("out"),
        metavar="DIR",
        help="output folder (default out/)",
    )
    p.add_argument(
        "--rate-hz",
        type=bounded_float(MIN_RATE_HZ, MAX_RATE_HZ, "Hz"),
        default=500.0,
        help=f"sampling rate of the written samples, {MIN_RATE_HZ:g} to {MAX_RATE_HZ:g} "
        "(default 500)",
    )
    p.add_argument("--format", choices=("csv", "npz"), default="csv", help="samples file format")
    p.add_argument("--si", action="store_true", help="samples in rad and m instead of deg and mm")
    timing = p.add_mutually_exclusive_group()
    timing.add_argument(
        "--segment-duration-s",
        type=bounded_float(MIN_SEGMENT_S, MAX_SEGMENT_S, "s"),
        default=None,
        help="duration of every segment, overriding the task's",
    )
    timing.add_argument(
        "--shortest",
        action="store_true",
        help="shortest segments within the joint limits, ignoring the task's durations",
    )
    p.add_argument(
        "--stretch",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="lengthen segments the joint limits cannot fit in the given duration, or not "
        "(default: as the task says)",
    )
    p.add_argument(
        "--pass-through",
        action="store_true",
        help="ruckig: pass intermediate poses without stopping",
    )
    p.add_argument(
        "--no-compare", action="store_true", help="skip the tool-path comparison of every type"
    )
    p.set_defaults(handler=_traj)
