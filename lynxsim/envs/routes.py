"""Planned moves of the scripted experts: collision-free joint paths followed as tool poses.

A move between places is a joint path planned with :func:`lynxsim.plan.plan_segment`
in the env's own scene (:attr:`~lynxsim.envs.base.LynxArmEnv.collision_checker`),
first with the gripper pointing down all the way, then in the four joints the
tool-space controller moves, the wrist roll held where the command has it
(:class:`Planner`); the path becomes a dense list of tool poses, each reachable
within one action, dry-run through a copy of the
controller (:class:`Route`); :class:`Mover` re-plans when the command strays or
the destination moves. The experts (:mod:`lynxsim.envs.expert`) drive it.
"""

from __future__ import annotations

import copy
import itertools
import math
from typing import Literal, NamedTuple

import numpy as np
import numpy.typing as npt

from lynxsim.arm import LYNX_ARM, ik_nearest, tool_pose_of
from lynxsim.arm.motion import arm_lipschitz
from lynxsim.envs.base import LynxArmEnv
from lynxsim.envs.control import TargetStatus, ToolSpaceController
from lynxsim.envs.workspace import TOP_DOWN_PITCH_RAD
from lynxsim.errors import InvalidInputError
from lynxsim.plan import PlanningError, plan_segment
from lynxsim.plan.oracle import ClearanceOracle
from lynxsim.plan.subspace import JointSubspace
from lynxsim.sim.planning import DEFAULT_MARGIN_M, CheckerOracle, cover_oracle

__all__ = [
    "ARRIVED_M",
    "ARRIVED_RAD",
    "Mover",
    "Planner",
    "Point",
    "Pose",
    "Route",
    "SearchWorld",
    "arrived",
    "braking",
    "toward",
]

FloatArray = npt.NDArray[np.float64]
Point = tuple[float, float, float]
Pose = tuple[float, float, float, float]
"""Tool point and pitch (x, y, z, pitch) [m, rad]."""
SearchWorld = Literal["cover", "exact"]
"""Where the experts' moves are searched: the robot's sphere cover, else the exact checker."""

ARRIVED_M = 0.003
"""The commanded point counts as at its destination within this [m] (per axis) ..."""
ARRIVED_RAD = 0.03
"""... and the commanded pitch within this [rad]: loose enough for noisy actions."""
_MAX_LAG_M = 0.008
"""A planned route is not followed further while the tool lags its command by more [m]."""
_OFF_ROUTE_M = 0.025
"""A command this far from the route's next pose [m] is re-planned from where it is."""
_SNAP_RAD = 0.05
"""A start this close to the pointing-down subspace [rad] is planned from its projection."""
_BRAKE_M = 0.05
"""Within this distance of a destination the expert slows down, in proportion [m]."""
_MIN_SPEED = 0.1
"""Slowest fraction of full speed while braking."""
_ROLL_JOINT = 4
"""Index of the wrist roll, held by the tool-space controller."""
_WAYPOINT_STEP_RAD = 0.02
"""Largest joint change between the tool poses a planned path is followed through [rad]."""
_FOLLOW_TOL_RAD = 1e-6
"""The dry run accepts a path when the controller's joints match it within this [rad]."""
_PITCH_TOL_RAD = 1e-9
"""Rounding allowed beyond the controller's pitch range (which it clips) [rad]."""
_PLAN_TIME_S = 10.0
"""Time limit of one planning attempt [s]: generous (a search takes ~0.1 s), because a
search cut by the clock would make the expert's actions depend on the machine's load."""
_PLAN_ATTEMPTS = 3
"""Attempts (new seeds) before a move is given up for this step."""


def toward(
    cmd: Pose, dest: Pose, controller: ToolSpaceController, speed: float
) -> tuple[list[float], bool]:
    """Arm action (4 values) straight towards ``dest`` and whether the command is there.

    ``speed`` in (0, 1] scales the largest move per step.
    """
    step = controller.position_step
    delta = [(dest[i] - cmd[i]) / step for i in range(3)]
    biggest = max(abs(v) for v in delta)
    if biggest > speed:
        delta = [v * (speed / biggest) for v in delta]
    d_pitch = max(-1.0, min(1.0, (dest[3] - cmd[3]) / controller.pitch_step))
    return [*delta, d_pitch], arrived(cmd, dest)


def arrived(cmd: Pose, dest: Pose) -> bool:
    """Whether the command is at a pose (within :data:`ARRIVED_M` and :data:`ARRIVED_RAD`)."""
    return (
        max(abs(dest[i] - cmd[i]) for i in range(3)) < ARRIVED_M
        and abs(dest[3] - cmd[3]) < ARRIVED_RAD
    )


def braking(distance: float, speed: float = 1.0) -> float:
    """Speed within :data:`_BRAKE_M` of a destination: the servos overshoot sudden stops."""
    return min(speed, max(_MIN_SPEED, distance / _BRAKE_M))


class Route:
    """A planned path as tool poses, followed as fast as one action per pose allows.

    Args:
        poses: Tool poses from the start to the destination, each within one
            action of the one before.
        controller: The env's controller (its step sizes).
    """

    def __init__(self, poses: list[Pose], controller: ToolSpaceController) -> None:
        self._poses = poses
        self._controller = controller
        self._index = 0
        lengths = [math.dist(a[:3], b[:3]) for a, b in itertools.pairwise(poses)]
        self._left = [*itertools.accumulate(reversed(lengths), initial=0.0)][::-1]

    @property
    def end(self) -> Pose:
        """The destination."""
        return self._poses[-1]

    def _reachable(self, cmd: Pose, pose: Pose, speed: float) -> bool:
        c = self._controller
        reach = speed * c.position_step
        return (
            max(abs(pose[0] - cmd[0]), abs(pose[1] - cmd[1]), abs(pose[2] - cmd[2])) <= reach
            and abs(pose[3] - cmd[3]) <= c.pitch_step
        )

    def off(self, cmd: Pose) -> bool:
        """Whether the command strayed from the route (perturbed actions): re-plan."""
        return math.dist(cmd[:3], self._poses[self._index][:3]) > _OFF_ROUTE_M

    def action(self, cmd: Pose, tool: Point) -> tuple[list[float], bool]:
        """Arm action towards the farthest pose within reach, and whether the end is reached.

        The command does not run ahead while the tool lags it by more than
        :data:`_MAX_LAG_M`: the arm stays on the planned path instead of cutting
        its corners (towards the obstacles it goes around).
        """
        last = len(self._poses) - 1
        i = self._index
        speed = braking(self._left[i] + math.dist(cmd[:3], self._poses[i][:3]))
        behind = max(abs(tool[k] - cmd[k]) for k in range(3)) > _MAX_LAG_M
        while (
            not behind
            and i < last
            and (self._reachable(cmd, self._poses[i + 1], speed) or arrived(cmd, self._poses[i]))
        ):
            i += 1
        self._index = i
        arm, at = toward(cmd, self._poses[i], self._controller, speed)
        return arm, at and i == last


class _Subspace(NamedTuple):
    """Where a move is planned: the joints' subspace and its bounds."""

    space: JointSubspace
    lower: FloatArray
    upper: FloatArray


class Planner:
    """Collision-free moves in an env's scene, as :class:`Route` objects.

    A move is planned first with the gripper pointing down all the way (three
    free joints: the wrist pitch follows the shoulder and elbow), where start and
    goal point down, then, if that fails, in the four joints the tool-space
    controller moves; the roll is held where the start has it
    (:data:`GRIP_ROLL_RAD` unless a ``-v2`` action turned it) and the tool pitch
    kept within the controller's range. The result is dry-run through a
    copy of the controller.

    With ``search="cover"`` the moves are searched on the episode's sphere cover
    of the arm (:func:`lynxsim.sim.planning.cover_oracle`, built once per episode
    at :meth:`reset`: one compiled call per batch of checks instead of MuJoCo's
    distances); the cover never reads more clearance than the exact checker, so a
    path certified on it is certified in the scene. Where the cover is too
    pessimistic (no path on it), the exact checker plans the move.

    Args:
        env: The env whose scene the moves avoid.
        controller: Its tool-space controller.
        search: ``"cover"`` (default) or ``"exact"`` (every check on MuJoCo).
    """

    def __init__(
        self, env: LynxArmEnv, controller: ToolSpaceController, search: SearchWorld = "cover"
    ) -> None:
        if search not in ("cover", "exact"):
            raise InvalidInputError(f"search must be 'cover' or 'exact', got {search!r}")
        self._controller = controller
        self._checker = env.collision_checker
        self._search = search
        self._exact = CheckerOracle(self._checker)
        self._worlds: list[ClearanceOracle] = [self._exact]
        self._lipschitz = arm_lipschitz()
        self.reset()

    def _subspaces(self, world: ClearanceOracle, roll: float) -> tuple[_Subspace, _Subspace]:
        """The two subspaces of the moves in ``world``, the wrist roll held at ``roll`` [rad]."""
        lower, upper = np.asarray(LYNX_ARM.q_min), np.asarray(LYNX_ARM.q_max)
        top_down = JointSubspace(
            world,
            [[1, 0, 0], [0, 1, 0], [0, 0, 1], [0, -1, -1], [0, 0, 0]],
            [0.0, 0.0, 0.0, TOP_DOWN_PITCH_RAD, roll],
            lower,
            upper,
        )
        roll_held = JointSubspace.holding(world, [_ROLL_JOINT], [roll], lower, upper)
        return (
            _Subspace(top_down, lower[:3], upper[:3]),
            _Subspace(roll_held, lower[:4], upper[:4]),
        )

    def reset(self) -> None:
        """Restart the seeds and read the episode's scene (call at every episode start)."""
        self._plans = 0
        cover = cover_oracle(self._checker) if self._search == "cover" else None
        self._worlds = [self._exact] if cover is None else [cover, self._exact]
        self._spaces: dict[tuple[int, float], tuple[_Subspace, _Subspace]] = {}

    def route(
        self, start: tuple[float, ...], goal: tuple[float, ...], *, grasped: bool
    ) -> Route | None:
        """A route from the commanded joints ``start`` to the joints ``goal`` (5 values [rad]).

        The roll is held at the start's (:data:`GRIP_ROLL_RAD` unless the env's
        action turns it); ``goal`` must have that roll.

        Returns None when no attempt gave a path the controller follows exactly.
        """
        ends = np.array([start, goal], dtype=float)
        for i, world in enumerate(self._worlds):
            key = (i, start[_ROLL_JOINT])
            if key not in self._spaces:
                self._spaces[key] = self._subspaces(world, start[_ROLL_JOINT])
            found = self._route(self._spaces[key], ends, start, grasped)
            if found is not None:
                return found
        return None

    def _route(
        self,
        spaces: tuple[_Subspace, _Subspace],
        ends: FloatArray,
        start: tuple[float, ...],
        grasped: bool,
    ) -> Route | None:
        """:meth:`route` in one world's subspaces; ``ends`` (2, 5): start and goal [rad]."""
        for sub in spaces:
            # Into the joint box: the controller's commands may stand a rounding error
            # beyond a limit (a pitch clipped to -pi/2 leaves the wrist 4e-8 rad past it).
            p = np.clip(sub.space.project(ends), sub.lower, sub.upper)
            miss = np.abs(sub.space.full(p) - ends).max(axis=1)
            if miss[0] > _SNAP_RAD or miss[1] > _FOLLOW_TOL_RAD:
                continue  # start or goal outside this subspace (a start near it snaps to it)
            world = _PitchInRange(sub.space)
            for _ in range(_PLAN_ATTEMPTS):
                seed = self._plans
                self._plans += 1
                try:
                    plan = plan_segment(
                        p[0], p[1:], world, sub.lower, sub.upper,
                        lipschitz=self._lipschitz * sub.space.stretch, margin_m=DEFAULT_MARGIN_M,
                        time_limit_s=_PLAN_TIME_S, seed=seed, grasped=grasped,
                    )  # fmt: skip
                except PlanningError:
                    continue
                path = np.vstack([ends[:1], sub.space.full(plan.path)])  # from the start itself
                poses = self._poses(path, start)
                if poses is not None:
                    return Route(poses, self._controller)
        return None

    def _poses(self, path: FloatArray, start: tuple[float, ...]) -> list[Pose] | None:
        """Tool poses along a joint path, or None if the controller would not follow it."""
        dry = copy.deepcopy(self._controller)
        dry.reset(start)
        poses: list[Pose] = [dry.target]
        for a, b in itertools.pairwise(path):
            n = max(1, math.ceil(float(np.abs(b - a).max()) / _WAYPOINT_STEP_RAD))
            for q in (a + (b - a) * (k / n) for k in range(1, n + 1)):
                pose = tool_pose_of(q.tolist())
                x, y, z, pitch = dry.target
                c = dry.position_step
                action = ((pose[0] - x) / c, (pose[1] - y) / c, (pose[2] - z) / c,
                          (pose[3] - pitch) / dry.pitch_step)  # fmt: skip
                if max(abs(v) for v in action) > 1.0 or dry.apply(action) != TargetStatus.ACCEPTED:
                    return None
                if max(abs(u - v) for u, v in zip(dry.q_cmd, q.tolist())) > _FOLLOW_TOL_RAD:
                    return None
                poses.append(pose)
        return poses


class _PitchInRange:
    """A subspace world in which tool pitches the controller would clip read -inf.

    The pitch is linear in the joints, so an edge between two accepted vectors
    keeps it in range too.
    """

    def __init__(self, space: JointSubspace) -> None:
        self._space = space
        self.n_joints = space.n_joints

    def clearance(self, p: FloatArray, *, grasped: bool) -> FloatArray:
        """Clearance of subspace vectors, (N, k) -> (N,) [m]."""
        q = self._space.full(p)
        out = self._space.clearance(p, grasped=grasped)
        out[np.abs(q[:, 1] + q[:, 2] + q[:, 3]) > 0.5 * math.pi + _PITCH_TOL_RAD] = -np.inf
        return out


class Mover:
    """Planned moves to a destination: planned once, followed, re-planned when needed.

    A route is planned again from where the command is when the command strays
    from it (perturbed actions) or the destination moves (the cube was pushed,
    the hold in the hand changed); when no route is found the arm holds still
    for a step and the next step tries new seeds.
    """

    def __init__(self, planner: Planner, q_ready: tuple[float, ...]) -> None:
        self._planner = planner
        self._q_ready = q_ready
        self.route: Route | None = None

    def step(
        self, cmd: Pose, tool: Point, q_cmd: FloatArray, dest: Pose, *, grasped: bool
    ) -> tuple[list[float], bool]:
        """Arm action towards ``dest`` (a tool pose) and whether the command is there."""
        route = self.route
        if route is not None and (
            route.off(cmd)
            or math.dist(route.end[:3], dest[:3]) > ARRIVED_M
            or abs(route.end[3] - dest[3]) > ARRIVED_RAD
        ):
            route = None
        if route is None:
            _, goal = ik_nearest(*dest, float(q_cmd[_ROLL_JOINT]), self._q_ready)
            if goal is not None:
                route = self._planner.route(tuple(q_cmd.tolist()), goal, grasped=grasped)
        self.route = route
        if route is None:
            return [0.0, 0.0, 0.0, 0.0], False
        return route.action(cmd, tool)
