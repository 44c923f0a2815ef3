"""A robot's record: everything the commands ask of a robot, as typed fields.

A :class:`Robot` ties a robot's row (:class:`lynxsim.registry.RobotInfo`: name,
title, pose schema, table scene) to its parts: the trajectory types it builds,
its pure task -> motion builder, where its simulation side lives, its cameras,
the options of its runs, its joint kinematics (if its motions are joint
trajectories), its planning request (if it plans) and its real backend (if it
has one). Commands read these fields and never a robot's name.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass

from lynxsim.errors import InvalidInputError
from lynxsim.inputs import instance
from lynxsim.plan.request import PlanRequest
from lynxsim.registry import RobotInfo
from lynxsim.run_options import RunOption
from lynxsim.tasks import Task
from lynxsim.traj.kinds import TrajectoryKind
from lynxsim.traj.kinematics import Kinematics
from lynxsim.traj.motion import Motion

__all__ = ["MotionBuilder", "PlanningBuilder", "Robot"]

MotionBuilder = Callable[[Task, TrajectoryKind], Motion]
"""A task and a trajectory type in, the robot's motion out (pure: no MuJoCo)."""
PlanningBuilder = Callable[[Task], PlanRequest]
"""A task in, its planning problem out (pure: no MuJoCo)."""

_ENTRY = re.compile(r"^[A-Za-z_][\w.]*:[A-Za-z_]\w*$")


def _entry(value: object, what: str) -> None:
    if not (isinstance(value, str) and _ENTRY.match(value)):
        raise InvalidInputError(f"{what} must be 'module:attribute', got {value!r}")


@dataclass(frozen=True)
class Robot:
    """A robot's record.

    Attributes:
        info: Its row (name, title, pose schema, table scene, the entry of this record).
        kinds: The trajectory types it builds, in the order the demo plays them;
            :attr:`~lynxsim.traj.TrajectoryKind.PLANNED` among them exactly when
            it plans (``planning``).
        motion: Builds a task into its motion of a type, ``(task, kind) -> Motion``,
            for every type but ``planned`` (pure: no MuJoCo). It raises
            :class:`~lynxsim.errors.InvalidInputError` for a type it does not
            build or a task that is not its own.
        sim: ``"module:attribute"`` of its :class:`~lynxsim.sim.adapter.SimAdapter`,
            imported only when a command simulates.
        cameras: The cameras of its model, the first the default of its videos.
        run_options: The options its runs take (``lynxsim play``'s flags).
        kinematics: Its joints, limits and tool, for robots whose motions are joint
            trajectories (``lynxsim traj``, the joint plots), or None.
        planning: Turns a task into its :class:`~lynxsim.plan.PlanRequest` (pure),
            for robots that plan (they have ``kinematics``), or None.
        real: ``"module:attribute"`` of its :class:`~lynxsim.sim.adapter.RealBackend`
            (the real robot and the twin of its controller), or None.

    Every callable must be a module-level function, so that a record (or a job
    holding one) pickles to worker processes.

    Raises:
        InvalidInputError: A malformed field, or ``planned`` among the kinds
            exactly when there is no planning.
    """

    info: RobotInfo
    kinds: tuple[TrajectoryKind, ...]
    motion: MotionBuilder
    sim: str
    cameras: tuple[str, ...]
    run_options: tuple[RunOption, ...] = ()
    kinematics: Kinematics | None = None
    planning: PlanningBuilder | None = None
    real: str | None = None

    def __post_init__(self) -> None:
        instance(self.info, RobotInfo, "info")
        name = self.info.name
        kinds = self.kinds
        if not (
            isinstance(kinds, tuple) and kinds and all(isinstance(k, TrajectoryKind) for k in kinds)
        ):
            raise InvalidInputError(f"robot {name!r}: kinds must be a non-empty tuple of types")
        if len(set(kinds)) != len(kinds):
            raise InvalidInputError(f"robot {name!r}: kinds must be distinct, got {kinds!r}")
        if (TrajectoryKind.PLANNED in kinds) != (self.planning is not None):
            raise InvalidInputError(
                f"robot {name!r}: 'planned' is among its kinds exactly when it has planning"
            )
        if not callable(self.motion):
            raise InvalidInputError(f"robot {name!r}: motion must be callable")
        if self.planning is not None and not callable(self.planning):
            raise InvalidInputError(f"robot {name!r}: planning must be callable or None")
        if self.planning is not None and self.kinematics is None:
            raise InvalidInputError(
                f"robot {name!r}: a robot that plans needs kinematics (its plans are joint "
                "trajectories)"
            )
        _entry(self.sim, f"robot {name!r}: sim")
        if self.real is not None:
            _entry(self.real, f"robot {name!r}: real")
        cameras = self.cameras
        named = isinstance(cameras, tuple) and all(isinstance(c, str) and c for c in cameras)
        if not (named and cameras and len(set(cameras)) == len(cameras)):
            raise InvalidInputError(
                f"robot {name!r}: cameras must be a non-empty tuple of distinct names"
            )
        options = self.run_options
        if not (isinstance(options, tuple) and all(isinstance(o, RunOption) for o in options)):
            raise InvalidInputError(f"robot {name!r}: run_options must be a tuple of RunOption")
        if len({o.name for o in options}) != len(options):
            raise InvalidInputError(f"robot {name!r}: run options must have distinct names")
        if self.kinematics is not None:
            instance(self.kinematics, Kinematics, "kinematics")

    @property
    def name(self) -> str:
        """Its name (a task file's ``robot``)."""
        return self.info.name

    @property
    def title(self) -> str:
        """Its human name, for messages."""
        return self.info.title

    @property
    def described(self) -> str:
        """``the TITLE (robot 'NAME')``, for messages."""
        return f"the {self.info.title} (robot {self.info.name!r})"
