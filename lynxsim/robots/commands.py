"""What every command does with a robot: its motion of a task, its plan, its simulation side.

:func:`motion` builds any type a robot builds (``planned`` through
:func:`plan`), :func:`plan` puts a robot's planning request and its checker
together, :func:`simulation` and :func:`real_backend` import a robot's
simulation side and real backend on demand (MuJoCo only then). Each checks the
record's fields and raises :class:`~lynxsim.errors.CapabilityError` naming the
robot where it lacks what is asked.
"""

from __future__ import annotations

import functools
from typing import TYPE_CHECKING

from lynxsim.errors import CapabilityError, InvalidInputError
from lynxsim.inputs import instance
from lynxsim.plan.request import DEFAULT_MARGIN_M
from lynxsim.robots.catalog import attribute, get, names
from lynxsim.robots.robot import Robot
from lynxsim.tasks import Task
from lynxsim.traj.build import parse_kind
from lynxsim.traj.kinds import TrajectoryKind
from lynxsim.traj.motion import Motion

if TYPE_CHECKING:
    from lynxsim.plan import PlannedMotion, PlannerName, ProgressCallback
    from lynxsim.sim.adapter import RealBackend, SimAdapter
    from lynxsim.sim.planning import SearchWorld

__all__ = ["motion", "plan", "real_backend", "simulation", "with_capability"]


def with_capability(field: str) -> tuple[Robot, ...]:
    """The registered robots whose record's ``field`` is set (planning, kinematics, real)."""
    return tuple(r for r in map(get, names()) if getattr(r, field) is not None)


def _owners(field: str) -> str:
    return ", ".join(r.name for r in with_capability(field)) or "none"


def _own_task(robot: Robot, task: Task) -> Task:
    robot = instance(robot, Robot, "robot")
    task = instance(task, Task, "task")
    if task.robot != robot.name:
        raise InvalidInputError(
            f"task {task.name!r} is for robot {task.robot!r}, not {robot.described}"
        )
    return task


def motion(robot: Robot, task: Task, kind: TrajectoryKind | str | None = None) -> Motion:
    """A task's motion of a type its robot builds (``planned``: seed 0, default planner).

    Args:
        robot: The task's robot.
        task: The task.
        kind: Trajectory type overriding the task's; None keeps it.

    Raises:
        InvalidInputError: The task is another robot's, or the type is unknown or
            not built by the robot (the robot's own message, or one listing its types).
        LynxsimError: Whatever the robot's builder or the planner raises.
    """
    task = _own_task(robot, task)
    chosen = task.trajectory if kind is None else parse_kind(kind)
    if chosen is TrajectoryKind.PLANNED and robot.planning is not None:
        return plan(robot, task).trajectory
    built = robot.motion(task, chosen)
    if chosen not in robot.kinds or not isinstance(built, Motion):
        raise InvalidInputError(
            f"trajectory type {chosen.value!r} is not built for {robot.described}; expected "
            f"one of: {', '.join(k.value for k in robot.kinds)}"
        )
    return built


def plan(
    robot: Robot,
    task: Task,
    *,
    planner: PlannerName = "compiled",
    search_world: SearchWorld = "cover",
    margin_m: float = DEFAULT_MARGIN_M,
    seed: int = 0,
    time_limit_s: float = 5.0,
    progress: ProgressCallback | None = None,
) -> PlannedMotion:
    """Plan a task around its scene: the robot's request, its checker, the generic planner.

    Args:
        robot: The task's robot (it plans: :attr:`Robot.planning`).
        task: The task (its scene gives the obstacles).
        planner: ``compiled`` (RRT-Connect compiled on the robot's sphere cover,
            the default) or an OMPL planner (:data:`lynxsim.plan.PLANNERS`).
        search_world: Where the search runs: ``cover`` (default) or ``exact``
            (the MuJoCo checker); the timed motion is checked exactly either way.
        margin_m: Clearance to keep from every obstacle [m].
        seed: Same task and seed give the same trajectory, bit for bit.
        time_limit_s: Search time per segment [s].
        progress: Called as each segment's stages begin.

    Returns:
        The :class:`~lynxsim.plan.PlannedMotion` (kind ``planned``).

    Raises:
        CapabilityError: The robot does not plan (the message names those that do).
        PlanningError: No clear path (names the segment and why).
    """
    task = _own_task(robot, task)
    if robot.planning is None:
        raise CapabilityError(
            f"task {task.name!r} is for {robot.described}, which does not plan; robots "
            f"that plan: {_owners('planning')}"
        )
    request = robot.planning(task)
    from lynxsim.sim.planning import plan_request

    return plan_request(
        request,
        simulation(robot).checker(task.scene),
        planner=planner,
        search_world=search_world,
        margin_m=margin_m,
        seed=seed,
        time_limit_s=time_limit_s,
        progress=progress,
    )


@functools.cache
def _imported(entry: str, what: str) -> object:
    """The object of an entry, imported once per process."""
    return attribute(entry, what)


def simulation(robot: Robot) -> SimAdapter:
    """A robot's simulation side (imported on first use: imports MuJoCo).

    Raises:
        InvalidInputError: Its ``sim`` entry does not import or is no
            :class:`~lynxsim.sim.adapter.SimAdapter`.
    """
    from lynxsim.sim.adapter import SimAdapter

    robot = instance(robot, Robot, "robot")
    adapter = _imported(robot.sim, f"robot {robot.name!r}: its simulation side")
    if not isinstance(adapter, SimAdapter):
        raise InvalidInputError(f"robot {robot.name!r}: {robot.sim} is no SimAdapter")
    return adapter


def real_backend(robot: Robot, what: str, source: object) -> RealBackend:
    """A robot's real backend, for a command ``what`` on a task file ``source``.

    Raises:
        CapabilityError: The robot has none (``WHAT applies only to NAME tasks; ...``,
            naming the robots that have one).
    """
    from lynxsim.sim.adapter import RealBackend

    robot = instance(robot, Robot, "robot")
    if robot.real is None:
        owners = " or ".join(r.name for r in with_capability("real")) or "no"
        raise CapabilityError(
            f"{what} applies only to {owners} tasks; {source} is a task of robot {robot.name!r}"
        )
    backend = _imported(robot.real, f"robot {robot.name!r}: its real backend")
    if not isinstance(backend, RealBackend):
        raise InvalidInputError(f"robot {robot.name!r}: {robot.real} is no RealBackend")
    return backend
