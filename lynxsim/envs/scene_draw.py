"""How an arm env draws its episodes: the task, obstacles that leave room to work, refusals.

:class:`SceneDrawing` is a mixin of :class:`~lynxsim.envs.base.LynxArmEnv`: a task subclass
implements :meth:`SceneDrawing._sample_task` and :meth:`SceneDrawing._check_feasible` with
the helpers here; the drawing itself is :mod:`lynxsim.envs.episodes`'s.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from lynxsim.envs.commanding import READY_TOOL_POSE, TARGET_BOX_LOWER
from lynxsim.envs.episodes import WorkColumn, draw_point, draw_scene, workable
from lynxsim.envs.workspace import PolarRegion
from lynxsim.errors import InfeasibleSceneError
from lynxsim.scene import Obstacle
from lynxsim.sim.arm.slots import ObstacleSlots
from lynxsim.sim.collision import CollisionChecker

__all__ = ["SceneDrawing"]

FloatArray = npt.NDArray[np.float64]


class SceneDrawing:
    """The episode-drawing half of an arm env (the env provides the attributes below)."""

    np_random: np.random.Generator
    distance_threshold: float
    random_obstacles: tuple[int, int] | None
    _obstacles: tuple[Obstacle, ...]
    _goal: FloatArray
    _checker: CollisionChecker
    _q_ready: tuple[float, ...]

    @property
    def obstacles(self) -> tuple[Obstacle, ...]:
        """The obstacles of the episode (drawn at reset with ``random_obstacles``)."""
        return self._obstacles

    def _check_feasible(self) -> None:
        """Refuse options that can never produce an episode.

        Raises:
            InfeasibleSceneError: The fixed obstacles block a region the task draws
                from, or no goal there lies outside ``distance_threshold``.
        """
        raise NotImplementedError

    def _refuse(self, what: str) -> None:
        raise InfeasibleSceneError(
            f"{type(self).__name__} with obstacles={self._obstacles!r} and distance_threshold="
            f"{self.distance_threshold} m can never draw an episode: {what}"
        )

    def _sample_task(self) -> None:
        """Place the cube (in ``data.qpos``) and set the goal, drawing from ``np_random``."""
        raise NotImplementedError

    def _work_columns(self) -> list[WorkColumn]:
        """Where the arm works in the episode drawn (default: at the goal, empty-handed)."""
        return [WorkColumn(self._goal.copy(), float(self._goal[2]), False)]

    def _sample_scene(self, slots: ObstacleSlots) -> None:
        """Draw the task, then obstacles that leave the arm room to work (:func:`draw_scene`)."""
        assert self.random_obstacles is not None

        def place(obstacles: Sequence[Obstacle]) -> None:
            slots.place(obstacles)
            self._obstacles = tuple(obstacles)

        def task() -> list[WorkColumn]:
            self._sample_task()
            return self._work_columns()

        ready = READY_TOOL_POSE[:3]
        draw_scene(self.np_random, self.random_obstacles, ready, task, place, self._workable)

    def _workable(self, columns: list[WorkColumn]) -> bool:
        """Whether the ready pose and every work column keep :data:`WORK_CLEARANCE_M`.

        A column starts no lower than the tool target box's floor: a small cube's
        centre lies below it, and the tool goes no lower than the floor (which
        keeps the fingertips above the table) to grasp it or put it down.
        """
        floor = TARGET_BOX_LOWER[2]
        raised = [
            c._replace(point=np.array([c.point[0], c.point[1], max(float(c.point[2]), floor)]))
            for c in columns
        ]
        return workable(self._checker, self._q_ready, raised)

    def _draw_point(
        self, region: PolarRegion, away_from: npt.ArrayLike | None = None
    ) -> FloatArray:
        """A point of ``region`` reachable top-down, clear of the obstacles (:func:`draw_point`).

        ``away_from``: a point, shape (3,) [m], that the drawn one must be more
        than ``distance_threshold`` away from.
        """
        return draw_point(
            self.np_random, region, self.obstacles, away_from, self.distance_threshold
        )
