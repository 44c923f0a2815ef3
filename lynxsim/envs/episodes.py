"""What an arm env draws for an episode: task points, and obstacles that leave the arm room.

:func:`draw_point` draws a task point (a cube's start, a goal) where the arm
reaches it top-down, clear of the obstacles (:mod:`lynxsim.envs.workspace`);
with randomised obstacles, a scene counts only when the arm keeps
:data:`WORK_CLEARANCE_M` from them at the ready pose and along every
:class:`WorkColumn` of the task (:func:`workable`, asked of the env's
collision checker).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from lynxsim.envs.workspace import (
    PolarRegion,
    clear_of_obstacle,
    sample_points,
    top_down_reachable,
    work_column,
)
from lynxsim.errors import InvalidInputError, LynxsimError
from lynxsim.random_scenes import random_obstacles
from lynxsim.scene import Obstacle
from lynxsim.sim.collision import CollisionChecker

__all__ = [
    "MAX_SCENE_DRAWS",
    "OBSTACLE_GAP_M",
    "WORK_CLEARANCE_M",
    "WorkColumn",
    "draw_point",
    "draw_scene",
    "farthest_apart",
    "task_points",
    "workable",
]

FloatArray = npt.NDArray[np.float64]

_DRAW_BATCH = 16
_MAX_DRAWS = 100
WORK_CLEARANCE_M = 0.015
"""Clearance from every randomised obstacle that the arm keeps at the ready pose and
wherever it works at the cube and the goal (:func:`~lynxsim.envs.workspace.work_column`) [m]."""
OBSTACLE_GAP_M = 0.06
"""Least distance from a randomised obstacle to the cube, the goal and the ready tool point [m]."""
MAX_SCENE_DRAWS = 200
"""Scenes drawn at most per reset before giving up."""


class WorkColumn(NamedTuple):
    """Where the arm works at a task point: the vertical above it, gripper down.

    Attributes:
        point: The lowest tool point, shape (3,) [m].
        top_z: Height up to which the arm rises there [m].
        grasped: Whether it holds the cube there.
    """

    point: FloatArray
    top_z: float
    grasped: bool


def workable(
    checker: CollisionChecker, q_ready: Sequence[float], columns: Sequence[WorkColumn]
) -> bool:
    """Whether the ready pose ``q_ready`` and every work column keep :data:`WORK_CLEARANCE_M`.

    Args:
        checker: The env's collision checker (the episode's obstacles placed).
        q_ready: Joints of the ready pose, 5 values [rad].
        columns: Where the arm works in the episode.
    """
    groups: dict[bool, list[FloatArray]] = {False: [np.array([q_ready])], True: []}
    for column in columns:
        q = work_column(column.point, column.top_z, q_ready)
        if q is None:
            return False
        groups[column.grasped].append(q)
    for grasped, parts in groups.items():
        if parts:
            clearance = checker.min_clearance(
                np.concatenate(parts), grasped=grasped, cap=WORK_CLEARANCE_M
            )
            if clearance.min() < WORK_CLEARANCE_M:
                return False
    return True


def draw_point(
    rng: np.random.Generator,
    region: PolarRegion,
    obstacles: Sequence[Obstacle],
    away_from: npt.ArrayLike | None,
    min_distance_m: float,
) -> FloatArray:
    """A point of ``region`` reachable top-down and clear of the obstacles.

    Args:
        rng: Where to draw from (the env's ``np_random``).
        region: Where to draw.
        obstacles: The episode's obstacles.
        away_from: A point, shape (3,) [m], that the drawn one must be more
            than ``min_distance_m`` away from, or None.
        min_distance_m: That distance [m].

    Returns:
        The point, shape (3,) [m].

    Raises:
        InvalidInputError: No such point after many draws (the obstacle blocks the region).
    """
    for _ in range(_MAX_DRAWS):
        p = sample_points(rng, region, _DRAW_BATCH)
        ok = top_down_reachable(p)
        for obstacle in obstacles:
            ok &= clear_of_obstacle(p, obstacle)
        if away_from is not None:
            gap = p - np.asarray(away_from, dtype=float)
            ok &= np.sqrt(np.sum(gap * gap, axis=1)) > min_distance_m
        hits = np.flatnonzero(ok)
        if hits.size:
            point: FloatArray = p[hits[0]]
            return point
    raise InvalidInputError(
        f"found no point of {region} that the arm reaches top-down clear of {tuple(obstacles)}"
    )


def task_points(region: PolarRegion, obstacles: Sequence[Obstacle]) -> FloatArray:
    """The points of a region that :func:`draw_point` could draw, among a fixed sample.

    As many points as :func:`draw_point` tries at most, from a generator of its
    own (seed 0): an empty result means the region is blocked (no reset would
    find a point there).

    Returns:
        Shape (K, 3) [m], K >= 0.
    """
    p = sample_points(np.random.default_rng(0), region, _DRAW_BATCH * _MAX_DRAWS)
    ok = top_down_reachable(p)
    for obstacle in obstacles:
        ok &= clear_of_obstacle(p, obstacle)
    points: FloatArray = p[ok]
    return points


def farthest_apart(a: FloatArray, b: FloatArray) -> float:
    """About the largest distance between a point of ``a`` (n, 3) and one of ``b`` (m, 3) [m].

    Over at most 400 evenly spaced points of each (a lower bound of the largest).
    """
    if not (a.size and b.size):
        return 0.0
    a, b = a[:: max(1, len(a) // 400)], b[:: max(1, len(b) // 400)]  # 400 x 400 pairs at most
    d = a[:, None, :] - b[None, :, :]
    return float(np.sqrt(np.einsum("ijk,ijk->ij", d, d).max()))


def draw_scene(
    rng: np.random.Generator,
    count: tuple[int, int],
    ready_point: Sequence[float],
    task: Callable[[], list[WorkColumn]],
    place: Callable[[Sequence[Obstacle]], None],
    roomy: Callable[[list[WorkColumn]], bool],
) -> None:
    """Draw a task, then obstacles that leave the arm room to work; again until they do.

    The obstacles keep :data:`OBSTACLE_GAP_M` from the task's work points and
    the ready tool point; the scene counts when ``roomy`` says the arm keeps
    its clearance there (:func:`workable`).

    Args:
        rng: Where to draw from (the env's ``np_random``).
        count: ``(fewest, most)`` obstacles.
        ready_point: The ready tool point, (3,) [m].
        task: Draws the task (no obstacle placed) and returns its work columns.
        place: Places obstacles in the scene (none, then those drawn).
        roomy: Whether the arm has room to work along the columns.

    Raises:
        LynxsimError: No such scene in :data:`MAX_SCENE_DRAWS` draws.
    """
    fewest, most = count
    ready = np.array(ready_point)
    for _ in range(MAX_SCENE_DRAWS):
        place(())
        columns = task()
        number = int(rng.integers(fewest, most + 1))
        keep = [ready.tolist(), *(c.point.tolist() for c in columns)]
        try:
            obstacles = random_obstacles(rng, number, keep_free=keep, gap_m=OBSTACLE_GAP_M)
        except InvalidInputError:  # no room around these points: draw them again
            continue
        place(obstacles)
        if roomy(columns):
            return
    raise LynxsimError(
        f"no scene with {fewest}..{most} obstacles left the arm room to work in "
        f"{MAX_SCENE_DRAWS} draws"
    )
