"""The world a robot works in, as plain immutable values in SI units (no MuJoCo).

A :class:`Scene` holds any number of named obstacles (:class:`Cylinder`,
:class:`Box`, :class:`Sphere`), the :class:`Table` and, optionally, the
:class:`Cube` the arm picks. Every frame is the arm's base frame: z up, the
base plane at z = 0; the table top lies half a cube below it so that a tool
point at z = 0 is the centre of a cube resting on the table.

Task files describe their scene in the report's units (``[[obstacles]]``,
see :mod:`lynxsim.tasks`); :mod:`lynxsim.sim` builds the MuJoCo scene from it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from lynxsim.bounds import MAX_ANGLE_RAD, MAX_COORDINATE_M
from lynxsim.errors import InvalidInputError

__all__ = [
    "MAX_CUBE_MASS_KG",
    "MAX_FRICTION",
    "MIN_CUBE_MASS_KG",
    "MIN_SIZE_M",
    "REPORT_CUBE",
    "REPORT_CYLINDER",
    "REPORT_SCENE",
    "TABLE",
    "Box",
    "Cube",
    "Cylinder",
    "Obstacle",
    "Scene",
    "Sphere",
    "Table",
]


MIN_SIZE_M = 1e-4
"""Smallest size of anything in a scene (radius, height, edge) [m]; the largest is
:data:`lynxsim.bounds.MAX_COORDINATE_M`, which also bounds every coordinate."""
MIN_CUBE_MASS_KG = 1e-4
"""Lightest cube [kg] (MuJoCo refuses a body of almost no mass or inertia)."""
MAX_CUBE_MASS_KG = 100.0
"""Heaviest cube [kg]."""
MAX_FRICTION = 10.0
"""Largest sliding friction coefficient of the cube [-]."""


def _finite(owner: str, **values: float) -> None:
    for key, value in values.items():
        if not isinstance(value, int | float) or isinstance(value, bool):
            raise InvalidInputError(f"{owner}: {key} must be a number, got {value!r}")
        try:
            finite = math.isfinite(value)
        except OverflowError:  # an int too large for a float
            finite = False
        if not finite:
            raise InvalidInputError(f"{owner}: {key} must be finite, got {value!r}")


def _positive(owner: str, unit: str, **values: float) -> None:
    _finite(owner, **values)
    for key, value in values.items():
        if value <= 0.0:
            raise InvalidInputError(f"{owner}: {key} must be positive, got {value!r}{unit}")


def _within(owner: str, low: float, high: float, unit: str, **values: float) -> None:
    _finite(owner, **values)
    for key, value in values.items():
        if not low <= value <= high:
            raise InvalidInputError(
                f"{owner}: {key} must lie within {low:g}..{high:g}{unit}, got {value!r}{unit}"
            )


def _sizes(owner: str, **values: float) -> None:
    _within(owner, MIN_SIZE_M, MAX_COORDINATE_M, " m", **values)


def _vector(owner: str, key: str, value: tuple[float, ...], n: int) -> None:
    """A tuple of n coordinates [m], each within +-:data:`~lynxsim.bounds.MAX_COORDINATE_M`."""
    if not isinstance(value, tuple) or len(value) != n:
        raise InvalidInputError(f"{owner}: {key} must be a tuple of {n} numbers, got {value!r}")
    values = {f"{key}[{i}]": v for i, v in enumerate(value)}
    _within(owner, -MAX_COORDINATE_M, MAX_COORDINATE_M, " m", **values)


def _angle(owner: str, **values: float) -> None:
    _within(owner, -MAX_ANGLE_RAD, MAX_ANGLE_RAD, " rad", **values)


def _check_name(kind: str, name: str) -> None:
    if not isinstance(name, str) or not name or not name.isprintable():
        raise InvalidInputError(f"{kind} name must be a non-empty printable string, got {name!r}")


@dataclass(frozen=True)
class Cylinder:
    """A vertical cylinder standing on its bottom face.

    Attributes:
        name: Unique name in its scene.
        position: Centre of the bottom face (x, y, z) [m].
        radius: Radius [m], within :data:`MIN_SIZE_M` .. 10 m.
        height: Height [m], within :data:`MIN_SIZE_M` .. 10 m.
    """

    name: str
    position: tuple[float, float, float]
    radius: float
    height: float

    def __post_init__(self) -> None:
        _check_name("cylinder", self.name)
        owner = f"cylinder {self.name!r}"
        _vector(owner, "position", self.position, 3)
        _sizes(owner, radius=self.radius, height=self.height)

    @property
    def bottom_z(self) -> float:
        """Height of its bottom face [m]."""
        return self.position[2]

    @property
    def shape(self) -> str:
        """``"cylinder"``."""
        return "cylinder"

    def contains(self, point: tuple[float, float, float]) -> bool:
        """Whether a point [m] lies inside (or on) the cylinder."""
        return self.distance(point) == 0.0

    def distance(self, point: tuple[float, float, float]) -> float:
        """Distance from a point to the cylinder [m]; 0 inside or on it."""
        x, y, z = (point[i] - self.position[i] for i in range(3))
        radial = max(math.hypot(x, y) - self.radius, 0.0)
        return math.hypot(radial, max(-z, z - self.height, 0.0))


@dataclass(frozen=True)
class Box:
    """A box standing on its bottom face, turned about the vertical.

    Attributes:
        name: Unique name in its scene.
        position: Centre of the bottom face (x, y, z) [m].
        size: Full extents along its own x, y, z [m], each within
            :data:`MIN_SIZE_M` .. 10 m.
        yaw: Rotation about the vertical axis, counter-clockwise seen from +z [rad].
    """

    name: str
    position: tuple[float, float, float]
    size: tuple[float, float, float]
    yaw: float = 0.0

    def __post_init__(self) -> None:
        _check_name("box", self.name)
        owner = f"box {self.name!r}"
        _vector(owner, "position", self.position, 3)
        _vector(owner, "size", self.size, 3)
        _sizes(owner, **{f"size[{i}]": v for i, v in enumerate(self.size)})
        _angle(owner, yaw=self.yaw)

    @property
    def bottom_z(self) -> float:
        """Height of its bottom face [m]."""
        return self.position[2]

    @property
    def shape(self) -> str:
        """``"box"``."""
        return "box"

    def contains(self, point: tuple[float, float, float]) -> bool:
        """Whether a point [m] lies inside (or on) the box."""
        return self.distance(point) == 0.0

    def distance(self, point: tuple[float, float, float]) -> float:
        """Distance from a point to the box [m]; 0 inside or on it."""
        dx, dy, dz = (point[i] - self.position[i] for i in range(3))
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        u, v = c * dx + s * dy, -s * dx + c * dy
        return math.sqrt(
            max(abs(u) - 0.5 * self.size[0], 0.0) ** 2
            + max(abs(v) - 0.5 * self.size[1], 0.0) ** 2
            + max(-dz, dz - self.size[2], 0.0) ** 2
        )


@dataclass(frozen=True)
class Sphere:
    """A sphere.

    Attributes:
        name: Unique name in its scene.
        position: Its centre (x, y, z) [m].
        radius: Radius [m], within :data:`MIN_SIZE_M` .. 10 m.
    """

    name: str
    position: tuple[float, float, float]
    radius: float

    def __post_init__(self) -> None:
        _check_name("sphere", self.name)
        owner = f"sphere {self.name!r}"
        _vector(owner, "position", self.position, 3)
        _sizes(owner, radius=self.radius)

    @property
    def bottom_z(self) -> float:
        """Height of its lowest point [m]."""
        return self.position[2] - self.radius

    @property
    def shape(self) -> str:
        """``"sphere"``."""
        return "sphere"

    def contains(self, point: tuple[float, float, float]) -> bool:
        """Whether a point [m] lies inside (or on) the sphere."""
        return self.distance(point) == 0.0

    def distance(self, point: tuple[float, float, float]) -> float:
        """Distance from a point to the sphere [m]; 0 inside or on it."""
        return max(math.dist(point, self.position) - self.radius, 0.0)


Obstacle = Cylinder | Box | Sphere
"""An obstacle of a scene."""


@dataclass(frozen=True)
class Table:
    """The table the arm stands on (a box; the arm's riser stands on its top).

    Attributes:
        top_z: Height of the table top in the base frame [m] (below the base plane).
        center: (x, y) of the table's centre [m].
        size: Full extents of the table top (x, y) [m].
        thickness: Thickness of the top [m].
    """

    top_z: float = -0.0125
    center: tuple[float, float] = (0.1, 0.0)
    size: tuple[float, float] = (0.7, 1.0)
    thickness: float = 0.04

    def __post_init__(self) -> None:
        _within("table", -MAX_COORDINATE_M, MAX_COORDINATE_M, " m", top_z=self.top_z)
        _vector("table", "center", self.center, 2)
        _vector("table", "size", self.size, 2)
        _sizes("table", size_x=self.size[0], size_y=self.size[1], thickness=self.thickness)


@dataclass(frozen=True)
class Cube:
    """The cube the arm picks: a free body resting on the table.

    Attributes:
        position: Its centre (x, y, z) at the start [m].
        size: Edge length [m], within :data:`MIN_SIZE_M` .. 10 m.
        yaw: Rotation about the vertical at the start [rad].
        mass: Mass [kg], within :data:`MIN_CUBE_MASS_KG` .. :data:`MAX_CUBE_MASS_KG`.
        friction: Sliding friction coefficient [-], > 0 and at most :data:`MAX_FRICTION`.
    """

    position: tuple[float, float, float] = (0.0, 0.3, 0.0)
    size: float = 0.025
    yaw: float = 0.0
    mass: float = 0.01
    friction: float = 1.0

    def __post_init__(self) -> None:
        _vector("cube", "position", self.position, 3)
        _sizes("cube", size=self.size)
        _within("cube", MIN_CUBE_MASS_KG, MAX_CUBE_MASS_KG, " kg", mass=self.mass)
        _positive("cube", "", friction=self.friction)
        _within("cube", 0.0, MAX_FRICTION, "", friction=self.friction)
        _angle("cube", yaw=self.yaw)

    @property
    def bottom_z(self) -> float:
        """Height of its bottom face at the start [m]."""
        return self.position[2] - self.size / 2


TABLE = Table()
"""The table of the shipped scene: its top 12.5 mm below the base plane."""

REPORT_CUBE = Cube()
"""A 25 mm, 10 g cube at the report's P1 (0, 300, 0) mm."""

REPORT_CYLINDER = Cylinder(
    name="cylinder", position=(0.15, 0.15, TABLE.top_z), radius=0.04, height=0.4 - TABLE.top_z
)
"""The report's obstacle: radius 40 mm, axis at (150, 150) mm, standing on the
table and reaching 400 mm above the base plane."""

_BASE_POINT = (0.0, 0.0, 0.0)
"""A point inside the arm's base (the base frame's origin) [m]."""


@dataclass(frozen=True)
class Scene:
    """Obstacles, table and cube.

    Attributes:
        obstacles: The obstacles, each with a unique name (any number, none included).
        table: The table.
        cube: The cube, or None for a scene without one.

    Raises:
        InvalidInputError: Obstacles, table or cube of the wrong type, duplicate
            obstacle names, an obstacle or the cube reaching into the table, or
            an obstacle that encloses the robot's base (the origin) or the
            cube's start (its centre).
    """

    obstacles: tuple[Obstacle, ...] = ()
    table: Table = field(default=TABLE)
    cube: Cube | None = field(default=REPORT_CUBE)

    def __post_init__(self) -> None:
        if not isinstance(self.table, Table):
            raise InvalidInputError(f"table must be a Table, got {self.table!r}")
        if self.cube is not None and not isinstance(self.cube, Cube):
            raise InvalidInputError(f"cube must be a Cube or None, got {self.cube!r}")
        if not isinstance(self.obstacles, tuple) or not all(
            isinstance(o, Cylinder | Box | Sphere) for o in self.obstacles
        ):
            raise InvalidInputError(
                f"obstacles must be a tuple of Cylinder, Box or Sphere, got {self.obstacles!r}"
            )
        names = [o.name for o in self.obstacles]
        for name in names:
            if names.count(name) > 1:
                raise InvalidInputError(f"two obstacles are named {name!r}; names must be unique")
        top = self.table.top_z
        for o in self.obstacles:
            if o.bottom_z < top:
                raise InvalidInputError(
                    f"obstacle {o.name!r} reaches into the table: its bottom at z = "
                    f"{o.bottom_z * 1e3:g} mm, the table top at {top * 1e3:g} mm"
                )
        if self.cube is not None and self.cube.bottom_z < top:
            raise InvalidInputError(
                f"the cube reaches into the table: its bottom at z = "
                f"{self.cube.bottom_z * 1e3:g} mm, the table top at {top * 1e3:g} mm"
            )
        for o in self.obstacles:
            if o.contains(_BASE_POINT):
                raise InvalidInputError(f"obstacle {o.name!r} encloses the robot's base")
            if self.cube is not None and o.contains(self.cube.position):
                raise InvalidInputError(f"obstacle {o.name!r} encloses the cube's start")

    def obstacle(self, name: str) -> Obstacle:
        """The obstacle of that name.

        Raises:
            InvalidInputError: No such obstacle (lists the names).
        """
        for o in self.obstacles:
            if o.name == name:
                return o
        names = ", ".join(o.name for o in self.obstacles) or "none"
        raise InvalidInputError(f"the scene has no obstacle {name!r}; obstacles: {names}")

    def without_obstacles(self) -> Scene:
        """The same table and cube, no obstacle."""
        return Scene((), self.table, self.cube)

    def without_cube(self) -> Scene:
        """The same obstacles and table, no cube."""
        return Scene(self.obstacles, self.table, None)


REPORT_SCENE = Scene(obstacles=(REPORT_CYLINDER,))
"""The report's pick-and-place scene: its cylinder and a cube at P1."""
