"""Tasks: named sequences of poses read from small TOML files.

A task file is declarative and in the report's units, each key naming its
unit; the loader validates it and converts to SI. Example::

    name = "pick_and_place"
    description = "Report Table 4"
    robot = "arm"                    # "arm" (5-DOF arm) or "rrr" (planar 3-RRR)

    [trajectory]
    type = "quintic"                 # default type: free, cubic, quintic, lspb, line, ruckig
    segment_duration_s = 1.0         # one number, or one per segment; leave out for the shortest
    stretch = true                   # lengthen segments the joint limits cannot fit (default false)
    pass_through = false             # ruckig: pass intermediate poses without stopping

    [[poses]]                        # an arm pose: tool point and pitch (roll optional) ...
    name = "P1"
    position_mm = [0.0, 300.0, 0.0]
    pitch_deg = -90.0
    roll_deg = 0.0

    [[poses]]                        # ... or joints directly
    name = "home"
    q_deg = [0.0, 90.0, -90.0, 0.0, 0.0]

Poses of the 3-RRR robot are platform poses: ``x_mm``, ``y_mm``, ``alpha_deg``.
Every problem is reported as a :class:`~lynxsim.errors.TaskFileError` naming
the file and the field (``poses[2].pitch_deg``, pose indices from 0).
"""

from __future__ import annotations

import math
import os
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal, get_args

from lynxsim.errors import TaskFileError
from lynxsim.traj.kinds import TrajectoryKind
from lynxsim.traj.waypoints import ArmPose, JointPose

__all__ = ["PlanarPose", "Robot", "Task", "TaskPose", "find_tasks", "load_task"]

Robot = Literal["arm", "rrr"]
"""The robots a task can name."""

_MM = 1e-3


@dataclass(frozen=True)
class PlanarPose:
    """A platform pose of the planar 3-RRR robot.

    Attributes:
        x: Platform centre x in the base frame [m].
        y: Platform centre y in the base frame [m].
        alpha: Platform orientation, counter-clockwise seen from +z [rad].
        name: Label used in messages and plots.
    """

    x: float
    y: float
    alpha: float
    name: str = ""


TaskPose = ArmPose | JointPose | PlanarPose
"""A pose of a task: :class:`ArmPose` or :class:`JointPose` (arm), :class:`PlanarPose` (rrr)."""


@dataclass(frozen=True)
class Task:
    """A task: a robot, its poses and how to move through them.

    Attributes:
        name: Task name.
        robot: ``"arm"`` or ``"rrr"``.
        poses: The poses in order, SI units (at least two).
        trajectory: The default trajectory type.
        durations: Duration of every segment [s], or ``None`` for the shortest
            within the joint limits.
        stretch: Lengthen given durations that are too short for the limits.
        pass_through: Ruckig: pass intermediate poses without stopping.
        description: Free text.
        source: The file the task was read from, if any.
    """

    name: str
    robot: Robot
    poses: tuple[TaskPose, ...]
    trajectory: TrajectoryKind
    durations: tuple[float, ...] | None = None
    stretch: bool = False
    pass_through: bool = False
    description: str = ""
    source: Path | None = None


_TOP_KEYS = ("name", "description", "robot", "trajectory", "poses")
_TRAJECTORY_KEYS = ("type", "segment_duration_s", "stretch", "pass_through")
_ARM_POSE_KEYS = ("name", "position_mm", "pitch_deg", "roll_deg", "q_deg")
_RRR_POSE_KEYS = ("name", "x_mm", "y_mm", "alpha_deg")


class _Reader:
    """Validating accessors that report the file and the field on failure."""

    def __init__(self, path: str) -> None:
        self.path = path

    def fail(self, field: str | None, problem: str) -> TaskFileError:
        return TaskFileError(self.path, field, problem)

    def table(self, value: object, field: str, keys: tuple[str, ...]) -> Mapping[str, Any]:
        if not isinstance(value, Mapping):
            raise self.fail(field, f"must be a table, got {type(value).__name__}")
        unknown = sorted(set(value) - set(keys))
        if unknown:
            prefix = f"{field}." if field else ""
            raise self.fail(
                f"{prefix}{unknown[0]}", f"unknown key; expected one of: {', '.join(keys)}"
            )
        return value

    def number(self, value: object, field: str) -> float:
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise self.fail(field, f"must be a number, got {value!r}")
        if not math.isfinite(value):
            raise self.fail(field, f"must be finite, got {value!r}")
        return float(value)

    def positive(self, value: object, field: str) -> float:
        number = self.number(value, field)
        if number <= 0.0:
            raise self.fail(field, f"must be positive, got {value!r}")
        return number

    def vector(self, value: object, n: int, field: str) -> tuple[float, ...]:
        if not isinstance(value, list) or len(value) != n:
            raise self.fail(field, f"must be a list of {n} numbers, got {value!r}")
        return tuple(self.number(v, f"{field}[{i}]") for i, v in enumerate(value))

    def string(self, value: object, field: str) -> str:
        if not isinstance(value, str):
            raise self.fail(field, f"must be a string, got {value!r}")
        return value

    def boolean(self, value: object, field: str) -> bool:
        if not isinstance(value, bool):
            raise self.fail(field, f"must be true or false, got {value!r}")
        return value

    def required(self, table: Mapping[str, Any], key: str, field: str) -> Any:
        if key not in table:
            raise self.fail(field, "missing")
        return table[key]


def _arm_pose(r: _Reader, raw: Mapping[str, Any], field: str, name: str) -> ArmPose | JointPose:
    if "q_deg" in raw:
        extra = sorted(set(raw) & {"position_mm", "pitch_deg", "roll_deg"})
        if extra:
            raise r.fail(
                f"{field}.{extra[0]}", "a pose gives either q_deg or a tool pose, not both"
            )
        q = r.vector(raw["q_deg"], 5, f"{field}.q_deg")
        return JointPose(tuple(math.radians(v) for v in q), name)
    position = r.vector(
        r.required(raw, "position_mm", f"{field}.position_mm"), 3, f"{field}.position_mm"
    )
    pitch = r.number(r.required(raw, "pitch_deg", f"{field}.pitch_deg"), f"{field}.pitch_deg")
    roll = None
    if "roll_deg" in raw:
        roll = math.radians(r.number(raw["roll_deg"], f"{field}.roll_deg"))
    x, y, z = (v * _MM for v in position)
    return ArmPose((x, y, z), math.radians(pitch), roll, name)


def _rrr_pose(r: _Reader, raw: Mapping[str, Any], field: str, name: str) -> PlanarPose:
    x, y, alpha = (
        r.number(r.required(raw, key, f"{field}.{key}"), f"{field}.{key}")
        for key in ("x_mm", "y_mm", "alpha_deg")
    )
    return PlanarPose(x * _MM, y * _MM, math.radians(alpha), name)


def _parse(data: Mapping[str, Any], path: str, default_name: str) -> Task:
    r = _Reader(path)
    top = r.table(data, "", _TOP_KEYS)
    robot_name = r.string(r.required(top, "robot", "robot"), "robot")
    robots: tuple[Robot, ...] = get_args(Robot)
    robot = next((rb for rb in robots if rb == robot_name), None)
    if robot is None:
        raise r.fail("robot", f"unknown robot {robot_name!r}; expected one of: {', '.join(robots)}")
    name = r.string(top.get("name", default_name), "name")
    description = r.string(top.get("description", ""), "description")

    traj = r.table(r.required(top, "trajectory", "trajectory"), "trajectory", _TRAJECTORY_KEYS)
    kind_name = r.string(r.required(traj, "type", "trajectory.type"), "trajectory.type")
    kinds = [k.value for k in TrajectoryKind]
    if kind_name not in kinds:
        raise r.fail(
            "trajectory.type", f"unknown type {kind_name!r}; expected one of: {', '.join(kinds)}"
        )
    stretch = r.boolean(traj.get("stretch", False), "trajectory.stretch")
    pass_through = r.boolean(traj.get("pass_through", False), "trajectory.pass_through")

    raw_poses = r.required(top, "poses", "poses")
    if not isinstance(raw_poses, list) or len(raw_poses) < 2:
        raise r.fail("poses", "must be an array of at least two [[poses]] tables")
    pose_keys = _ARM_POSE_KEYS if robot == "arm" else _RRR_POSE_KEYS
    poses: list[TaskPose] = []
    for i, item in enumerate(raw_poses):
        field = f"poses[{i}]"
        raw = r.table(item, field, pose_keys)
        pose_name = r.string(raw.get("name", f"P{i + 1}"), f"{field}.name")
        if any(p.name == pose_name for p in poses):
            raise r.fail(f"{field}.name", f"duplicate pose name {pose_name!r}")
        if robot == "arm":
            poses.append(_arm_pose(r, raw, field, pose_name))
        else:
            poses.append(_rrr_pose(r, raw, field, pose_name))

    durations: tuple[float, ...] | None = None
    if "segment_duration_s" in traj:
        field = "trajectory.segment_duration_s"
        raw_d = traj["segment_duration_s"]
        n = len(poses) - 1
        if isinstance(raw_d, list):
            if len(raw_d) != n:
                raise r.fail(field, f"needs {n} durations (one per segment), got {len(raw_d)}")
            durations = tuple(r.positive(v, f"{field}[{i}]") for i, v in enumerate(raw_d))
        else:
            durations = (r.positive(raw_d, field),) * n

    return Task(
        name=name,
        robot=robot,
        poses=tuple(poses),
        trajectory=TrajectoryKind(kind_name),
        durations=durations,
        stretch=stretch,
        pass_through=pass_through,
        description=description,
        source=Path(path),
    )


def find_tasks(folder: str | os.PathLike[str], robot: Robot) -> list[Task]:
    """Every task file (``*.toml``) of ``folder`` for ``robot``, sorted by file name.

    Raises:
        TaskFileError: A task file in the folder is malformed (names file and field).
    """
    tasks = [load_task(p) for p in sorted(Path(folder).glob("*.toml"))]
    return [t for t in tasks if t.robot == robot]


def load_task(path: str | os.PathLike[str]) -> Task:
    """Read and validate a task file.

    Args:
        path: The TOML file.

    Returns:
        The :class:`Task`, in SI units; its name defaults to the file's stem.

    Raises:
        TaskFileError: The file is not UTF-8 TOML or breaks the schema (the
            message names the file and the field).
        OSError: The file cannot be read.
    """
    path = Path(path)
    raw = path.read_bytes()
    try:
        data = tomllib.loads(raw.decode("utf-8"))
    except UnicodeDecodeError as exc:
        raise TaskFileError(str(path), None, f"not UTF-8 text ({exc.reason})") from None
    except tomllib.TOMLDecodeError as exc:
        raise TaskFileError(str(path), None, f"not valid TOML: {exc}") from None
    return _parse(data, str(path), path.stem)
