"""The run report of a playback: tracking, collisions, clearance, health.

A plain frozen dataclass (JSON on disk through :meth:`RunReport.write_json`).
Lengths in metres and angles in radians, as everywhere inside lynxsim; the
field names carry the unit.
"""

from __future__ import annotations

import dataclasses
import json
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from lynxsim.fileio import write_json

__all__ = [
    "CollisionVerdict",
    "ContactPair",
    "ObstacleClearance",
    "RobotMetrics",
    "RunReport",
    "is_run_report",
]


@dataclass(frozen=True)
class ContactPair:
    """A pair of geoms that touched, with the worst moment.

    Attributes:
        geom1: Name of the first geom (the robot's, where one is).
        geom2: Name of the second geom.
        first_time_s: Simulated time of the first contact [s].
        max_penetration_m: Deepest penetration over the run [m] (>= 0).
    """

    geom1: str
    geom2: str
    first_time_s: float
    max_penetration_m: float


@dataclass(frozen=True)
class CollisionVerdict:
    """Did any robot geom, or what it carries, touch the obstacle, and how badly.

    Attributes:
        collided: True if any robot or payload geom touched the obstacle at any physics step.
        first_time_s: Time of the first contact [s], or None.
        first_pair: The (robot or payload geom, obstacle geom) names of that contact, or None.
        first_obstacle: Name of the obstacle hit first (the scene's name), or None.
        max_penetration_m: Deepest penetration [m] (0 when clear).
        steps_in_contact: Number of physics steps with such a contact.
        pairs: Every geom pair that touched.
    """

    collided: bool
    first_time_s: float | None
    first_pair: tuple[str, str] | None
    first_obstacle: str | None
    max_penetration_m: float
    steps_in_contact: int
    pairs: tuple[ContactPair, ...] = ()


@dataclass(frozen=True)
class ObstacleClearance:
    """One obstacle over a run.

    Attributes:
        name: The obstacle's name in the scene.
        collided: Whether the robot or its payload touched it.
        first_contact_s: Time of the first contact [s], or None.
        min_clearance_m: Smallest signed distance to the robot or payload [m]
            (negative: penetration).
        min_clearance_time_s: When it occurred [s].
    """

    name: str
    collided: bool
    first_contact_s: float | None
    min_clearance_m: float
    min_clearance_time_s: float


@dataclass(frozen=True)
class RobotMetrics:
    """Base class of the figures one robot adds to a run report (see its ``sim`` adapter)."""

    def lines(self) -> list[str]:
        """The figures as readable lines (mm, degrees)."""
        return []


@dataclass(frozen=True)
class RunReport:
    """What a playback did.

    Attributes:
        task: Task name.
        trajectory: Trajectory type name.
        duration_s: Trajectory duration [s].
        settle_s: Time simulated after the trajectory with the final command held [s].
        physics_dt_s: Physics time step [s].
        joint_max_error_rad: Largest |commanded - actual| per joint during the trajectory, (5,).
        joint_rms_error_rad: RMS of the same per joint, (5,).
        tool_max_error_m: Largest distance between the commanded tool point (FK of the
            commanded joints) and the simulated tool site during the trajectory [m].
        tool_rms_error_m: RMS of the same [m].
        tool_final_error_m: Distance to the final target after settling [m].
        max_torque_ratio: Largest |actuator force| / force limit per joint, (5,)
            (1.0 means the servo saturated at its datasheet stall torque).
        obstacle: The obstacle-collision verdict (None if the scene has no obstacle).
        obstacles: Per obstacle of the scene: hit or not, first contact, clearance.
        min_clearance_m: Smallest distance between any robot or payload geom and any
            obstacle [m] (negative: penetration; None without obstacle).
        min_clearance_time_s: When it occurred [s].
        self_collisions: Robot-robot geom pairs that touched.
        floor_contacts: Robot geoms that touched the table or floor.
        healthy: No MuJoCo warning and no NaN during the run.
        warnings: MuJoCo warning counts by name (only those that fired).
        diverged_at_s: End of the step in which the state diverged (not finite, or
            so bad that MuJoCo reset it) [s]; the log ends before it. None if it did not.
        metrics: Robot-specific figures (e.g. the 3-RRR's loop closure), or None.
    """

    task: str
    trajectory: str
    duration_s: float
    settle_s: float
    physics_dt_s: float
    joint_max_error_rad: tuple[float, ...]
    joint_rms_error_rad: tuple[float, ...]
    tool_max_error_m: float
    tool_rms_error_m: float
    tool_final_error_m: float
    max_torque_ratio: tuple[float, ...]
    obstacle: CollisionVerdict | None
    obstacles: tuple[ObstacleClearance, ...]
    min_clearance_m: float | None
    min_clearance_time_s: float | None
    self_collisions: tuple[ContactPair, ...]
    floor_contacts: tuple[ContactPair, ...]
    healthy: bool
    warnings: dict[str, int] = field(default_factory=dict)
    diverged_at_s: float | None = None
    metrics: RobotMetrics | None = None

    @property
    def collided(self) -> bool:
        """True if the robot touched the obstacle."""
        return self.obstacle is not None and self.obstacle.collided

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready dictionary (tuples become lists)."""
        out: dict[str, Any] = dataclasses.asdict(self)
        out["collided"] = self.collided
        return out

    def write_json(self, dest: str | os.PathLike[str]) -> Path:
        """Write the report as JSON, atomically."""
        return write_json(dest, self.to_dict())


def is_run_report(path: str | os.PathLike[str]) -> bool:
    """Whether ``path`` holds a :class:`RunReport` as :meth:`RunReport.write_json` wrote it.

    A command may replace its own report from an earlier run, never another
    file that happens to have the name.
    """
    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return False
    return isinstance(data, dict) and {f.name for f in dataclasses.fields(RunReport)} <= set(data)
