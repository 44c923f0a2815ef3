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

    [[obstacles]]                    # any number (none: no obstacle); names unique
    name = "cylinder"
    shape = "cylinder"               # cylinder, box or sphere
    position_mm = [150.0, 150.0, 0.0]  # cylinder, box: centre of the bottom face; sphere: centre
    radius_mm = 40.0                 # cylinder, sphere
    height_mm = 400.0                # cylinder

    [[obstacles]]
    name = "box"
    shape = "box"
    position_mm = [150.0, -150.0, 0.0]
    size_mm = [100.0, 60.0, 350.0]   # full extents along the box's own x, y, z
    yaw_deg = -45.0                  # about the vertical, optional (default 0)

    [[obstacles]]
    name = "ball"
    shape = "sphere"
    position_mm = [200.0, 60.0, 300.0]
    radius_mm = 30.0

    [cube]                           # optional, every key too: lynxsim.scene.REPORT_CUBE's
    position_mm = [0.0, 300.0, 0.0]  # its centre at the start
    size_mm = 25.0                   # edge length
    yaw_deg = 0.0                    # about the vertical
    mass_kg = 0.01
    friction = 1.0                   # sliding friction

Poses of the 3-RRR robot are platform poses: ``x_mm``, ``y_mm``, ``alpha_deg``.

The scene (:class:`~lynxsim.scene.Scene`, ``Task.scene``) is in the arm's base
frame, like the poses. The table top lies at ``TABLE.top_z`` = -12.5 mm, half a
cube below the base plane, so a tool point at z = 0 is the centre of a resting
cube. A cylinder or box whose bottom face lies between the table top and the
base plane (-12.5 mm <= z <= 0) stands on the table: its bottom moves down to
the table top, its top stays at z + height (the report's cylinder above spans
-12.5 to 400 mm and equals :data:`~lynxsim.scene.REPORT_CYLINDER`). A bottom
face higher than 0 is kept (a raised obstacle); one lower than the table top,
a sphere or cube reaching below it, is refused. An obstacle may not enclose
the robot's base (the origin) or the cube's start (its centre). Arm tasks
without ``[cube]`` get the report's cube; 3-RRR tasks have neither obstacles
nor cube (both keys are refused).

Sanity bounds. Most come from :mod:`lynxsim.bounds`, the one place they are
set: every coordinate (pose ``position_mm``, ``x_mm``, ``y_mm``, obstacle and
cube positions) within +-``MAX_COORDINATE_M`` (10 m, 10000 mm), every segment
duration within ``MIN_SEGMENT_S`` .. ``MAX_SEGMENT_S`` (1 ms to 1 h), every angle
(``pitch_deg``, ``roll_deg``, ``q_deg``, ``alpha_deg``, ``yaw_deg``) within
+-``MAX_ANGLE_RAD`` (two turns, +-720 deg; larger ones only make the arithmetic
lose precision). Those of every scene (:mod:`lynxsim.scene`): sizes (radius,
height, edge) 0.1 mm up to the coordinate bound, the cube's mass 0.1 g to 100 kg
and its friction at most 10.

Text. Names (the task's ``name``, pose and obstacle names) are 1 to 100
characters; the ``description`` at most 1000. Both are printable text, one
line: letters, digits, marks, punctuation, symbols and the space of any script;
no control character (NUL, tab, newline, escape sequences), no other
whitespace or invisible format character (``str.isprintable``). A task without
``name`` takes the file's stem, which must pass the same check.

Every problem is reported as a :class:`~lynxsim.errors.TaskFileError` naming
the file and the field (``poses[2].pitch_deg``, ``obstacles[1].radius_mm``,
indices from 0).
"""

from __future__ import annotations

import dataclasses
import math
import os
import reprlib
import tomllib
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from lynxsim.bounds import MAX_ANGLE_RAD, MAX_COORDINATE_M, MAX_SEGMENT_S, MIN_SEGMENT_S
from lynxsim.errors import InvalidInputError, TaskFileError
from lynxsim.poses import ArmPose, JointPose, PlanarPose
from lynxsim.robots import ROBOTS, PoseSchema
from lynxsim.scene import (
    MAX_CUBE_MASS_KG,
    MAX_FRICTION,
    MIN_CUBE_MASS_KG,
    MIN_SIZE_M,
    REPORT_CUBE,
    TABLE,
    Box,
    Cube,
    Cylinder,
    Obstacle,
    Scene,
    Sphere,
)
from lynxsim.traj.kinds import TrajectoryKind

__all__ = ["PlanarPose", "Task", "TaskPose", "find_tasks", "load_task"]

_MM = 1e-3


TaskPose = ArmPose | JointPose | PlanarPose
"""A pose of a task: :class:`ArmPose` or :class:`JointPose` (arm), :class:`PlanarPose` (rrr)."""


@dataclass(frozen=True)
class Task:
    """A task: a robot, its poses and how to move through them.

    Attributes:
        name: Task name.
        robot: A row of the robot table (:data:`lynxsim.robots.ROBOTS`): ``"arm"`` or ``"rrr"``.
        poses: The poses in order, SI units (at least two).
        trajectory: The default trajectory type.
        durations: Duration of every segment [s], or ``None`` for the shortest
            within the joint limits.
        stretch: Lengthen given durations that are too short for the limits.
        pass_through: Ruckig: pass intermediate poses without stopping.
        description: Free text.
        source: The file the task was read from, if any.
        scene: Obstacles, table and cube (:class:`~lynxsim.scene.Scene`, SI units,
            the arm's base frame; default: no obstacle, the report's cube).
    """

    name: str
    robot: str
    poses: tuple[TaskPose, ...]
    trajectory: TrajectoryKind
    durations: tuple[float, ...] | None = None
    stretch: bool = False
    pass_through: bool = False
    description: str = ""
    source: Path | None = None
    scene: Scene = dataclasses.field(default_factory=Scene)


_TOP_KEYS = ("name", "description", "robot", "trajectory", "poses", "obstacles", "cube")
_TRAJECTORY_KEYS = ("type", "segment_duration_s", "stretch", "pass_through")
_TOOL_POSE_KEYS = ("name", "position_mm", "pitch_deg", "roll_deg", "q_deg")
_PLATFORM_POSE_KEYS = ("name", "x_mm", "y_mm", "alpha_deg")
_SHAPE_KEYS: dict[str, tuple[str, ...]] = {
    "cylinder": ("name", "shape", "position_mm", "radius_mm", "height_mm"),
    "box": ("name", "shape", "position_mm", "size_mm", "yaw_deg"),
    "sphere": ("name", "shape", "position_mm", "radius_mm"),
}
_OBSTACLE_KEYS = tuple(dict.fromkeys(k for keys in _SHAPE_KEYS.values() for k in keys))
_CUBE_KEYS = ("position_mm", "size_mm", "yaw_deg", "mass_kg", "friction")

_LIMIT_MM = MAX_COORDINATE_M * 1e3
"""Bound on every coordinate and scene size [mm]: :data:`lynxsim.bounds.MAX_COORDINATE_M`."""
_MAX_ANGLE_DEG = math.degrees(MAX_ANGLE_RAD)
"""Bound on every angle [deg]: :data:`lynxsim.bounds.MAX_ANGLE_RAD`, two turns either way."""
_MAX_NAME_CHARS = 100
"""Longest name (task, pose, obstacle) [characters]."""
_MAX_DESCRIPTION_CHARS = 1000
"""Longest description [characters]."""
_MIN_SIZE_MM = MIN_SIZE_M * 1e3
"""Smallest scene size (radius, height, edge) [mm]: :data:`lynxsim.scene.MIN_SIZE_M`."""


_SHOW = reprlib.Repr()
_SHOW.maxstring = 60
_SHOW.maxother = 60
_SHOW.maxlong = 40
_SHOW.maxlevel = 3


def _show(value: object) -> str:
    """``value`` for a message: its repr, shortened (long strings, lists, integers, nesting)."""
    return _SHOW.repr(value)


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
            key = unknown[0] if _is_text(unknown[0], _MAX_NAME_CHARS) else _show(unknown[0])
            raise self.fail(f"{prefix}{key}", f"unknown key; expected one of: {', '.join(keys)}")
        return value

    def number(self, value: object, field: str) -> float:
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise self.fail(field, f"must be a number, got {_show(value)}")
        try:
            number = float(value)
        except OverflowError:  # an integer beyond the float range
            raise self.fail(field, "must be finite, got an integer beyond 1e308") from None
        if not math.isfinite(number):
            raise self.fail(field, f"must be finite, got {_show(value)}")
        return number

    def positive(self, value: object, field: str) -> float:
        number = self.number(value, field)
        if number <= 0.0:
            raise self.fail(field, f"must be positive, got {_show(value)}")
        return number

    def bounded(self, value: object, field: str, low: float, high: float, unit: str) -> float:
        """A number in [low, high], ``unit`` naming its unit in the message."""
        number = self.number(value, field)
        if not low <= number <= high:
            raise self.fail(field, f"must lie within {low:g}..{high:g} {unit}, got {_show(value)}")
        return number

    def angle_deg(self, value: object, field: str) -> float:
        """An angle [deg] within +-720 deg, as radians."""
        bound = _MAX_ANGLE_DEG
        return math.radians(self.bounded(value, field, -bound, bound, "deg (two turns)"))

    def duration_s(self, value: object, field: str) -> float:
        """A segment duration [s] within the bounds of :mod:`lynxsim.bounds`."""
        self.positive(value, field)
        return self.bounded(value, field, MIN_SEGMENT_S, MAX_SEGMENT_S, "s")

    def size_mm(self, value: object, field: str, high: float = _LIMIT_MM) -> float:
        """A positive size [mm], at least 0.1 mm and at most ``high``."""
        number = self.positive(value, field)
        if not _MIN_SIZE_MM <= number <= high:
            raise self.fail(
                field, f"must lie within {_MIN_SIZE_MM:g}..{high:g} mm, got {_show(value)}"
            )
        return number

    def coordinate_mm(self, value: object, field: str) -> float:
        """A coordinate [mm] within +-10000 mm (:data:`lynxsim.bounds.MAX_COORDINATE_M`)."""
        unit = f"mm (+-{MAX_COORDINATE_M:g} m)"
        return self.bounded(value, field, -_LIMIT_MM, _LIMIT_MM, unit)

    def position_mm(self, value: object, field: str) -> tuple[float, float, float]:
        """A point (x, y, z) [mm], each coordinate within +-10000 mm (10 m)."""
        if not isinstance(value, list) or len(value) != 3:
            raise self.fail(field, f"must be a list of 3 numbers, got {_show(value)}")
        x, y, z = (self.coordinate_mm(v, f"{field}[{i}]") for i, v in enumerate(value))
        return x, y, z

    def string(self, value: object, field: str) -> str:
        if not isinstance(value, str):
            raise self.fail(field, f"must be a string, got {_show(value)}")
        return value

    def text(self, value: object, field: str, max_chars: int, *, empty: bool) -> str:
        """Printable one-line text of at most ``max_chars`` characters (empty if ``empty``)."""
        text = self.string(value, field)
        what = "printable text" if empty else "a non-empty printable string"
        if not empty and not text.strip():
            raise self.fail(field, f"must be {what}, got {_show(text)}")
        bad = next((i for i, c in enumerate(text) if not c.isprintable()), None)
        if bad is not None:
            raise self.fail(
                field,
                f"must be {what}, got {_show(text)} "
                f"(character U+{ord(text[bad]):04X} at index {bad} is a control, "
                "format or whitespace character)",
            )
        if len(text) > max_chars:
            raise self.fail(
                field, f"must be at most {max_chars} characters, got {len(text)}: {_show(text)}"
            )
        return text

    def name(self, value: object, field: str) -> str:
        """A name: 1 to 100 printable characters."""
        return self.text(value, field, _MAX_NAME_CHARS, empty=False)

    def boolean(self, value: object, field: str) -> bool:
        if not isinstance(value, bool):
            raise self.fail(field, f"must be true or false, got {_show(value)}")
        return value

    def required(self, table: Mapping[str, Any], key: str, field: str) -> Any:
        if key not in table:
            raise self.fail(field, "missing")
        return table[key]


def _is_text(value: str, max_chars: int) -> bool:
    """Whether ``value`` is printable, one line and at most ``max_chars`` long."""
    return len(value) <= max_chars and value.isprintable()


def _tool_pose(r: _Reader, raw: Mapping[str, Any], field: str, name: str) -> ArmPose | JointPose:
    if "q_deg" in raw:
        extra = sorted(set(raw) & {"position_mm", "pitch_deg", "roll_deg"})
        if extra:
            raise r.fail(
                f"{field}.{extra[0]}", "a pose gives either q_deg or a tool pose, not both"
            )
        raw_q = raw["q_deg"]
        if not isinstance(raw_q, list) or len(raw_q) != 5:
            raise r.fail(f"{field}.q_deg", f"must be a list of 5 numbers, got {_show(raw_q)}")
        q = tuple(r.angle_deg(v, f"{field}.q_deg[{i}]") for i, v in enumerate(raw_q))
        return JointPose(q, name)
    position = r.position_mm(
        r.required(raw, "position_mm", f"{field}.position_mm"), f"{field}.position_mm"
    )
    pitch = r.angle_deg(r.required(raw, "pitch_deg", f"{field}.pitch_deg"), f"{field}.pitch_deg")
    roll = None
    if "roll_deg" in raw:
        roll = r.angle_deg(raw["roll_deg"], f"{field}.roll_deg")
    x, y, z = (v * _MM for v in position)
    return ArmPose((x, y, z), pitch, roll, name)


def _platform_pose(r: _Reader, raw: Mapping[str, Any], field: str, name: str) -> PlanarPose:
    x, y = (
        r.coordinate_mm(r.required(raw, key, f"{field}.{key}"), f"{field}.{key}")
        for key in ("x_mm", "y_mm")
    )
    alpha = r.angle_deg(r.required(raw, "alpha_deg", f"{field}.alpha_deg"), f"{field}.alpha_deg")
    return PlanarPose(x * _MM, y * _MM, alpha, name)


_PoseReader = Callable[["_Reader", Mapping[str, Any], str, str], TaskPose]
_POSE_SCHEMAS: dict[PoseSchema, tuple[tuple[str, ...], _PoseReader]] = {
    "tool": (_TOOL_POSE_KEYS, _tool_pose),
    "platform": (_PLATFORM_POSE_KEYS, _platform_pose),
}
"""Each pose schema of the robot table: its keys and its reader."""


def _m(mm: float) -> float:
    """Millimetres to metres, correctly rounded (150 mm is 0.15 m exactly as a float)."""
    return mm / 1000.0


def _standing(
    r: _Reader, field: str, position_mm: tuple[float, float, float], height_mm: float
) -> tuple[tuple[float, float, float], float]:
    """Bottom-face centre [m] and height [m] of a cylinder or box, put on the table.

    A bottom face between the table top and the base plane moves down to the
    table top; the top stays where the file puts it.
    """
    x, y, z = (_m(v) for v in position_mm)
    height = _m(height_mm)
    if z < TABLE.top_z:
        raise r.fail(
            f"{field}.position_mm[2]",
            f"the bottom face at z = {position_mm[2]:g} mm would sink into the table "
            f"(its top is at z = {TABLE.top_z * 1e3:g} mm)",
        )
    if z <= 0.0 and z != TABLE.top_z:
        height = (z + height) - TABLE.top_z
        z = TABLE.top_z
    return (x, y, z), height


def _obstacle(r: _Reader, item: object, field: str) -> Obstacle:
    raw = r.table(item, field, _OBSTACLE_KEYS)
    shape = r.string(r.required(raw, "shape", f"{field}.shape"), f"{field}.shape")
    if shape not in _SHAPE_KEYS:
        raise r.fail(
            f"{field}.shape",
            f"unknown shape {_show(shape)}; expected one of: {', '.join(_SHAPE_KEYS)}",
        )
    keys = _SHAPE_KEYS[shape]
    foreign = [k for k in raw if k not in keys]
    if foreign:
        raise r.fail(
            f"{field}.{foreign[0]}", f"not a key of a {shape}; a {shape} takes: {', '.join(keys)}"
        )
    name = r.name(r.required(raw, "name", f"{field}.name"), f"{field}.name")
    position_mm = r.position_mm(
        r.required(raw, "position_mm", f"{field}.position_mm"), f"{field}.position_mm"
    )

    def size(key: str) -> float:
        return r.size_mm(r.required(raw, key, f"{field}.{key}"), f"{field}.{key}")

    try:
        if shape == "cylinder":
            radius, height_mm = size("radius_mm"), size("height_mm")
            position, height = _standing(r, field, position_mm, height_mm)
            return Cylinder(name, position, _m(radius), height)
        if shape == "box":
            raw_size = r.required(raw, "size_mm", f"{field}.size_mm")
            if not isinstance(raw_size, list) or len(raw_size) != 3:
                raise r.fail(
                    f"{field}.size_mm", f"must be a list of 3 numbers, got {_show(raw_size)}"
                )
            sx, sy, sz = (r.size_mm(v, f"{field}.size_mm[{i}]") for i, v in enumerate(raw_size))
            yaw = r.angle_deg(raw.get("yaw_deg", 0.0), f"{field}.yaw_deg")
            position, height = _standing(r, field, position_mm, sz)
            return Box(name, position, (_m(sx), _m(sy), height), yaw)
        radius = size("radius_mm")
        x, y, z = (_m(v) for v in position_mm)
        if z - _m(radius) < TABLE.top_z:
            raise r.fail(
                f"{field}.position_mm[2]",
                f"a sphere of radius {radius:g} mm centred at z = {position_mm[2]:g} mm "
                f"would reach into the table (its top is at z = {TABLE.top_z * 1e3:g} mm)",
            )
        return Sphere(name, (x, y, z), _m(radius))
    except InvalidInputError as exc:  # a value the checks above let through
        raise r.fail(field, str(exc)) from None


def _cube(r: _Reader, item: object) -> Cube:
    """The ``[cube]`` table; a key left out keeps the report's cube's value."""
    raw = r.table(item, "cube", _CUBE_KEYS)
    position = REPORT_CUBE.position
    if "position_mm" in raw:
        x, y, z = r.position_mm(raw["position_mm"], "cube.position_mm")
        position = (_m(x), _m(y), _m(z))
    size = REPORT_CUBE.size
    if "size_mm" in raw:
        size = _m(r.size_mm(raw["size_mm"], "cube.size_mm"))
    yaw = REPORT_CUBE.yaw
    if "yaw_deg" in raw:
        yaw = r.angle_deg(raw["yaw_deg"], "cube.yaw_deg")
    mass = r.positive(raw.get("mass_kg", REPORT_CUBE.mass), "cube.mass_kg")
    if not MIN_CUBE_MASS_KG <= mass <= MAX_CUBE_MASS_KG:
        raise r.fail(
            "cube.mass_kg",
            f"must lie within {MIN_CUBE_MASS_KG:g}..{MAX_CUBE_MASS_KG:g} kg, got {mass!r}",
        )
    friction = r.positive(raw.get("friction", REPORT_CUBE.friction), "cube.friction")
    if friction > MAX_FRICTION:
        raise r.fail("cube.friction", f"must be at most {MAX_FRICTION:g}, got {friction!r}")
    if position[2] - size / 2 < TABLE.top_z:
        raise r.fail(
            "cube.position_mm[2]" if "position_mm" in raw else "cube.size_mm",
            f"a {size * 1e3:g} mm cube centred at z = {position[2] * 1e3:g} mm would reach "
            f"into the table (its top is at z = {TABLE.top_z * 1e3:g} mm)",
        )
    try:
        return Cube(position, size, yaw, mass, friction)
    except InvalidInputError as exc:  # a value the checks above let through
        raise r.fail("cube", str(exc)) from None


def _scene(r: _Reader, top: Mapping[str, Any]) -> Scene:
    """The scene of an arm task: its obstacles and cube."""
    cube = _cube(r, top["cube"]) if "cube" in top else REPORT_CUBE
    raw = top.get("obstacles", [])
    if not isinstance(raw, list):
        raise r.fail("obstacles", "must be an array of [[obstacles]] tables")
    obstacles: list[Obstacle] = []
    for i, item in enumerate(raw):
        field = f"obstacles[{i}]"
        obstacle = _obstacle(r, item, field)
        if any(o.name == obstacle.name for o in obstacles):
            raise r.fail(f"{field}.name", f"duplicate obstacle name {_show(obstacle.name)}")
        try:  # does it enclose the base or the cube's start?
            Scene((obstacle,), TABLE, cube)
        except InvalidInputError as exc:
            raise r.fail(field, str(exc)) from None
        obstacles.append(obstacle)
    try:
        return Scene(tuple(obstacles), TABLE, cube)
    except InvalidInputError as exc:  # checked obstacle by obstacle above
        raise r.fail("obstacles", str(exc)) from None


def _parse(data: Mapping[str, Any], path: str, default_name: str) -> Task:
    r = _Reader(path)
    top = r.table(data, "", _TOP_KEYS)
    robot = r.string(r.required(top, "robot", "robot"), "robot")
    entry = ROBOTS.get(robot)
    if entry is None:
        raise r.fail("robot", f"unknown robot {_show(robot)}; expected one of: {', '.join(ROBOTS)}")
    if "name" in top:
        name = r.name(top["name"], "name")
    elif _is_text(default_name, _MAX_NAME_CHARS) and default_name.strip():
        name = default_name
    else:
        raise r.fail(
            "name",
            f"missing, and the file's stem {_show(default_name)} is no name (1 to "
            f'{_MAX_NAME_CHARS} printable characters); give one with name = "..."',
        )
    description = r.text(
        top.get("description", ""), "description", _MAX_DESCRIPTION_CHARS, empty=True
    )

    traj = r.table(r.required(top, "trajectory", "trajectory"), "trajectory", _TRAJECTORY_KEYS)
    kind_name = r.string(r.required(traj, "type", "trajectory.type"), "trajectory.type")
    kinds = [k.value for k in TrajectoryKind]
    if kind_name not in kinds:
        raise r.fail(
            "trajectory.type",
            f"unknown type {_show(kind_name)}; expected one of: {', '.join(kinds)}",
        )
    stretch = r.boolean(traj.get("stretch", False), "trajectory.stretch")
    pass_through = r.boolean(traj.get("pass_through", False), "trajectory.pass_through")

    raw_poses = r.required(top, "poses", "poses")
    if not isinstance(raw_poses, list) or len(raw_poses) < 2:
        raise r.fail("poses", "must be an array of at least two [[poses]] tables")
    pose_keys, read_pose = _POSE_SCHEMAS[entry.poses]
    poses: list[TaskPose] = []
    for i, item in enumerate(raw_poses):
        field = f"poses[{i}]"
        raw = r.table(item, field, pose_keys)
        pose_name = r.name(raw.get("name", f"P{i + 1}"), f"{field}.name")
        if any(p.name == pose_name for p in poses):
            raise r.fail(f"{field}.name", f"duplicate pose name {_show(pose_name)}")
        poses.append(read_pose(r, raw, field, pose_name))

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
        scene = _scene(r, top)
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
