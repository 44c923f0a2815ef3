"""Loading task files: the top-level keys, the trajectory table, the poses, the scene."""

from __future__ import annotations

import os
import tomllib
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from lynxsim.errors import InvalidInputError, TaskFileError
from lynxsim.registry import discover, info, names
from lynxsim.scene import Scene
from lynxsim.tasks.pose_readers import POSE_READERS
from lynxsim.tasks.reader import MAX_DESCRIPTION_CHARS, MAX_NAME_CHARS, FieldReader, is_text, show
from lynxsim.tasks.scene_reader import read_scene
from lynxsim.tasks.task import Task, TaskPose
from lynxsim.traj.kinds import TrajectoryKind

__all__ = ["find_tasks", "load_task"]

_TOP_KEYS = ("name", "description", "robot", "trajectory", "poses", "obstacles", "cube")
_TRAJECTORY_KEYS = ("type", "segment_duration_s", "stretch", "pass_through")


def _parse(data: Mapping[str, Any], path: str, default_name: str) -> Task:
    r = FieldReader(path)
    top = r.table(data, "", _TOP_KEYS)
    robot = r.string(r.required(top, "robot", "robot"), "robot")
    if robot not in names():  # an installed package may offer it (an entry point)
        try:
            discover(robot)
        except InvalidInputError as exc:
            raise r.fail("robot", str(exc)) from None
    if robot not in names():
        raise r.fail("robot", f"unknown robot {show(robot)}; expected one of: {', '.join(names())}")
    entry = info(robot)
    if "name" in top:
        name = r.name(top["name"], "name")
    elif is_text(default_name, MAX_NAME_CHARS) and default_name.strip():
        name = default_name
    else:
        raise r.fail(
            "name",
            f"missing, and the file's stem {show(default_name)} is no name (1 to "
            f'{MAX_NAME_CHARS} printable characters); give one with name = "..."',
        )
    description = r.text(
        top.get("description", ""), "description", MAX_DESCRIPTION_CHARS, empty=True
    )

    traj = r.table(r.required(top, "trajectory", "trajectory"), "trajectory", _TRAJECTORY_KEYS)
    kind_name = r.string(r.required(traj, "type", "trajectory.type"), "trajectory.type")
    kinds = [k.value for k in TrajectoryKind]
    if kind_name not in kinds:
        raise r.fail(
            "trajectory.type",
            f"unknown type {show(kind_name)}; expected one of: {', '.join(kinds)}",
        )
    stretch = r.boolean(traj.get("stretch", False), "trajectory.stretch")
    pass_through = r.boolean(traj.get("pass_through", False), "trajectory.pass_through")

    raw_poses = r.required(top, "poses", "poses")
    if not isinstance(raw_poses, list) or len(raw_poses) < 2:
        raise r.fail("poses", "must be an array of at least two [[poses]] tables")
    pose_keys, read_pose = POSE_READERS[entry.poses]
    poses: list[TaskPose] = []
    for i, item in enumerate(raw_poses):
        field = f"poses[{i}]"
        raw = r.table(item, field, pose_keys)
        pose_name = r.name(raw.get("name", f"P{i + 1}"), f"{field}.name")
        if any(p.name == pose_name for p in poses):
            raise r.fail(f"{field}.name", f"duplicate pose name {show(pose_name)}")
        poses.append(read_pose(r, raw, field, pose_name, entry.joints))

    durations: tuple[float, ...] | None = None
    if "segment_duration_s" in traj:
        field = "trajectory.segment_duration_s"
        raw_d = traj["segment_duration_s"]
        n = len(poses) - 1
        if isinstance(raw_d, list):
            if len(raw_d) != n:
                raise r.fail(field, f"needs {n} durations (one per segment), got {len(raw_d)}")
            durations = tuple(r.duration_s(v, f"{field}[{i}]") for i, v in enumerate(raw_d))
        else:
            durations = (r.duration_s(raw_d, field),) * n

    if entry.scene:
        scene = read_scene(r, top)
    else:
        for key in ("obstacles", "cube"):
            if key in top:
                raise r.fail(key, f"the {entry.title} has no obstacles or cube yet; remove it")
        scene = Scene(obstacles=(), cube=None)

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
        scene=scene,
    )


def find_tasks(folder: str | os.PathLike[str], robot: str) -> list[Task]:
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
    if path.exists() and not path.is_file():  # a folder, or a FIFO that would block the read
        raise TaskFileError(str(path), None, "not a regular file")
    raw = path.read_bytes()
    try:
        data = tomllib.loads(raw.decode("utf-8"))
    except UnicodeDecodeError as exc:
        raise TaskFileError(str(path), None, f"not UTF-8 text ({exc.reason})") from None
    except tomllib.TOMLDecodeError as exc:
        raise TaskFileError(str(path), None, f"not valid TOML: {exc}") from None
    except (ValueError, RecursionError) as exc:  # an integer too long, arrays nested too deep
        raise TaskFileError(str(path), None, f"not valid TOML: {exc}") from None
    return _parse(data, str(path), path.stem)
