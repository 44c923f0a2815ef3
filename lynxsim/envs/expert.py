"""Scripted experts: pick-and-place and reach, planning around the obstacles.

The experts drive the default tool-space action. Every move between places
(from the start to above the cube, from above the cube to above the goal,
to a reach goal) is a collision-free joint path planned with
:func:`lynxsim.plan.plan_segment` in the env's own scene
(:attr:`~lynxsim.envs.base.LynxArmEnv.collision_checker`, the cube held on the
carry), with the wrist roll held as the env holds it and the tool pitch
within the env's range. The path becomes a dense list of tool poses (the FK of
its joints) that the expert follows, each one reachable within one action;
a dry run through a copy of the env's controller checks beforehand that the
IK it answers with is the planned joints (the same branch, no clipping).
The moves at the cube and the goal (down, grasp, up; down, release, up) are
straight vertical lines, kept clear by the env
(:func:`~lynxsim.envs.workspace.work_column`). The analytic IK picks the tool
pitch of each place: pointing down where that is reachable, else the nearest
pitch that is.

Usage::

    env = gym.make("LynxPickAndPlace-v1", random_obstacles=(1, 3))
    expert = PickAndPlaceExpert(env)
    obs, _ = env.reset(seed=0)
    expert.reset()
    obs, reward, terminated, truncated, info = env.step(expert(obs))
"""

from __future__ import annotations

import copy
import enum
import itertools
import math
from typing import Any, NamedTuple

import gymnasium as gym
import numpy as np
import numpy.typing as npt

from lynxsim.arm import LYNX_ARM, ik_nearest, tool_pose_of
from lynxsim.arm.motion import arm_lipschitz
from lynxsim.envs.base import LynxArmEnv
from lynxsim.envs.control import TargetStatus, ToolSpaceController
from lynxsim.envs.pick_and_place import CUBE_HALF_SIZE_M, PickAndPlaceEnv
from lynxsim.envs.reach import ReachEnv
from lynxsim.envs.workspace import CARRY_HEIGHT_M, GRIP_ROLL_RAD, TOP_DOWN_PITCH_RAD
from lynxsim.errors import InvalidInputError
from lynxsim.plan import PlanningError, plan_segment
from lynxsim.plan.subspace import JointSubspace
from lynxsim.sim.arm.planning import DEFAULT_MARGIN_M, CheckerOracle

__all__ = ["PickAndPlaceExpert", "ReachExpert"]

FloatArray = npt.NDArray[np.float64]
Point = tuple[float, float, float]
Pose = tuple[float, float, float, float]
"""Tool point and pitch (x, y, z, pitch) [m, rad]."""

_ARRIVED_M = 0.003
"""The commanded point counts as at its destination within this [m] (per axis) ..."""
_ARRIVED_RAD = 0.03
"""... and the commanded pitch within this [rad]: loose enough for noisy actions."""
_MAX_LAG_M = 0.008
"""A planned route is not followed further while the tool lags its command by more [m]."""
_OFF_ROUTE_M = 0.025
"""A command this far from the route's next pose [m] is re-planned from where it is."""
_SNAP_RAD = 0.05
"""A start this close to the pointing-down subspace [rad] is planned from its projection."""
_SETTLED_M = 0.004
"""The arm counts as settled when the tool point is this close to its command [m] ..."""
_SETTLED_SPEED = 0.04
"""... and moves slower than this [m/s]."""
_NEAR_M = 0.008
"""A tool point this close to its command [m] may go on to the next phase unsettled."""
_SLOW = 0.4
"""Fraction of the full speed for the moves down to the table."""
_FINGERTIP_M = 0.008
"""How far the fingertips reach below the tool point [m]."""
_ALIGN_ABOVE_TOP_M = 0.002
"""Fingertip height above the cube's top while centring over it [m]: one full step
down takes them past it."""
_ON_TOP_SLACK_M = 0.0025
"""A plunging tool point higher above the cube's centre than half the cube plus the
fingertip reach, less this [m], has its fingertips on the cube's top: the plunge is
given up at once."""
_GRASP_ABOVE_M = 0.003
"""Tool height above the cube's centre at the grasp [m]: the pads cover its faces, the
palm stays off its top."""
_CENTRED_ACROSS_M = 0.0015
"""The plunge starts when the tool point is this close to the cube's centre along the
fingers' closing axis [m] (a 30 mm opening leaves 2.5 mm each side of a 25 mm cube) ..."""
_CENTRED_ALONG_M = 0.005
"""... and this close along the pads' width (18 mm wide pads) [m]."""
_PRESS_M = 0.006
"""A plunging command goes at most this far below the tool point [m]: a finger that
lands on the cube presses it no harder (hard presses tip it over)."""
_SNAP_M = 0.005
"""Short moves correct an error up to this [m] in one step, braking or not: noisy
actions push the command a few millimetres every step."""
_PRE_GRASP_WAIT = 20
"""Steps the centring may take before the expert plunges anyway."""
_PLUNGE_STEPS = 6
"""Steps a plunge may take to bring the cube between the fingers."""
_AROUND_M = 0.004
"""The cube counts as between the fingers when the tool point is this close to its
centre horizontally and this little above it [m]."""
_BRAKE_M = 0.05
"""Within this distance of a destination the expert slows down, in proportion [m]."""
_MIN_SPEED = 0.1
"""Slowest fraction of full speed while braking."""
_MAX_WAIT_STEPS = 15
"""Steps to wait at most for the arm to settle."""
_HOVER_M = 0.05
"""Height of the tool above the cube before it descends [m]."""
_PITCH_SEARCH_RAD = np.linspace(TOP_DOWN_PITCH_RAD, math.pi / 2, 61)
"""Pitches tried, in order, when the gripper cannot point straight down at a point [rad]."""
_GRIP_CLOSE_STEPS = 6
"""Steps the gripper gets to close before the lift."""
_IN_HAND_M = 0.02
"""Largest cube-to-tool distance of a held cube [m]."""
_RELEASE_STEPS = 3
"""Steps the gripper gets at least to open before the arm backs off ..."""
"""... until the fingers stand 2.5 mm wider than the cube."""
_REOPEN_STEPS = 5
"""Steps the gripper gets to open after a missed grasp."""
_ON_GOAL_M = 0.006
"""A cube put down this close to the goal horizontally [m] is let go at once."""
_DOWN_M = 0.004
"""A cube within this of its resting height [m] may be let go."""
_PLACE_ABOVE_M = 0.002
"""The cube is let go this high above its resting height [m]."""
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


def _tool_env(
    env: gym.Env[Any, Any], kind: type[LynxArmEnv]
) -> tuple[LynxArmEnv, ToolSpaceController]:
    u = env.unwrapped
    if not isinstance(u, kind):
        raise InvalidInputError(f"this expert drives a {kind.__name__}, got {type(u).__name__}")
    if not isinstance(u.controller, ToolSpaceController):
        raise InvalidInputError(
            f"the expert needs control='tool', the env has control={u.control.value!r}"
        )
    return u, u.controller


def _toward(
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
    return [*delta, d_pitch], _arrived(cmd, dest)


def _arrived(cmd: Pose, dest: Pose) -> bool:
    """Whether the command is at a pose (within :data:`_ARRIVED_M` and :data:`_ARRIVED_RAD`)."""
    return (
        max(abs(dest[i] - cmd[i]) for i in range(3)) < _ARRIVED_M
        and abs(dest[3] - cmd[3]) < _ARRIVED_RAD
    )


def _braking(distance: float, speed: float = 1.0) -> float:
    """Speed within :data:`_BRAKE_M` of a destination: the servos overshoot sudden stops."""
    return min(speed, max(_MIN_SPEED, distance / _BRAKE_M))


def _straight(
    cmd: Pose, dest: Pose, controller: ToolSpaceController, speed: float = 1.0
) -> tuple[list[float], bool]:
    """:func:`_toward` with braking: for the short straight moves at the cube and the goal.

    The last :data:`_SNAP_M` are taken in one step.
    """
    distance = math.dist(cmd[:3], dest[:3])
    snap = min(distance, _SNAP_M) / controller.position_step
    return _toward(cmd, dest, controller, max(_braking(distance, speed), snap))


def _per_axis(cmd: Pose, dest: Pose, controller: ToolSpaceController) -> list[float]:
    """Arm action (4 values) towards ``dest``, each axis as far as one step allows."""
    steps = (*(controller.position_step,) * 3, controller.pitch_step)
    return [max(-1.0, min(1.0, (dest[i] - cmd[i]) / steps[i])) for i in range(4)]


def _across_along(dx: float, dy: float, azimuth: float) -> tuple[float, float]:
    """A horizontal offset (dx, dy) [m] along the fingers' closing axis and across it.

    The gripper, pointing down, closes along the arm's vertical plane (azimuth
    ``azimuth`` [rad], the base joint's angle).
    """
    c, s = math.cos(azimuth), math.sin(azimuth)
    return dx * c + dy * s, dy * c - dx * s


class _Route:
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
        speed = _braking(self._left[i] + math.dist(cmd[:3], self._poses[i][:3]))
        behind = max(abs(tool[k] - cmd[k]) for k in range(3)) > _MAX_LAG_M
        while (
            not behind
            and i < last
            and (self._reachable(cmd, self._poses[i + 1], speed) or _arrived(cmd, self._poses[i]))
        ):
            i += 1
        self._index = i
        arm, at = _toward(cmd, self._poses[i], self._controller, speed)
        return arm, at and i == last


class _Subspace(NamedTuple):
    """Where a move is planned: the joints' subspace and its bounds."""

    space: JointSubspace
    lower: FloatArray
    upper: FloatArray


class _Planner:
    """Collision-free moves in an env's scene, as :class:`_Route` objects.

    A move is planned first with the gripper pointing down all the way (three
    free joints: the wrist pitch follows the shoulder and elbow), where start and
    goal point down, then, if that fails, in the four joints the tool-space
    controller moves; the roll is held at :data:`GRIP_ROLL_RAD` and the tool
    pitch kept within the controller's range. The result is dry-run through a
    copy of the controller.
    """

    def __init__(self, env: LynxArmEnv, controller: ToolSpaceController) -> None:
        self._controller = controller
        world = CheckerOracle(env.collision_checker)
        lower, upper = np.asarray(LYNX_ARM.q_min), np.asarray(LYNX_ARM.q_max)
        top_down = JointSubspace(
            world,
            [[1, 0, 0], [0, 1, 0], [0, 0, 1], [0, -1, -1], [0, 0, 0]],
            [0.0, 0.0, 0.0, TOP_DOWN_PITCH_RAD, GRIP_ROLL_RAD],
            lower,
            upper,
        )
        roll_held = JointSubspace.holding(world, [_ROLL_JOINT], [GRIP_ROLL_RAD], lower, upper)
        self._spaces = (
            _Subspace(top_down, lower[:3], upper[:3]),
            _Subspace(roll_held, lower[:4], upper[:4]),
        )
        self._lipschitz = arm_lipschitz()
        self.reset()

    def reset(self) -> None:
        """Restart the seeds (call at every episode start)."""
        self._plans = 0

    def route(
        self, start: tuple[float, ...], goal: tuple[float, ...], *, grasped: bool
    ) -> _Route | None:
        """A route from the commanded joints ``start`` to the joints ``goal`` (5 values [rad]).

        Returns None when no attempt gave a path the controller follows exactly.
        """
        ends = np.array([start, goal], dtype=float)
        for sub in self._spaces:
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
                    return _Route(poses, self._controller)
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


class _Mover:
    """Planned moves to a destination: planned once, followed, re-planned when needed.

    A route is planned again from where the command is when the command strays
    from it (perturbed actions) or the destination moves (the cube was pushed,
    the hold in the hand changed); when no route is found the arm holds still
    for a step and the next step tries new seeds.
    """

    def __init__(self, planner: _Planner, q_ready: tuple[float, ...]) -> None:
        self._planner = planner
        self._q_ready = q_ready
        self.route: _Route | None = None

    def step(
        self, cmd: Pose, tool: Point, q_cmd: FloatArray, dest: Pose, *, grasped: bool
    ) -> tuple[list[float], bool]:
        """Arm action towards ``dest`` (a tool pose) and whether the command is there."""
        route = self.route
        if route is not None and (
            route.off(cmd)
            or math.dist(route.end[:3], dest[:3]) > _ARRIVED_M
            or abs(route.end[3] - dest[3]) > _ARRIVED_RAD
        ):
            route = None
        if route is None:
            _, goal = ik_nearest(*dest, GRIP_ROLL_RAD, self._q_ready)
            if goal is not None:
                route = self._planner.route(tuple(q_cmd.tolist()), goal, grasped=grasped)
        self.route = route
        if route is None:
            return [0.0, 0.0, 0.0, 0.0], False
        return route.action(cmd, tool)


def _pitch_for(point: Point, q_ref: FloatArray) -> float:
    """Pitch for a tool point: straight down if the IK reaches it so, else the nearest that does."""
    for pitch in _PITCH_SEARCH_RAD:
        status, _ = ik_nearest(*point, float(pitch), GRIP_ROLL_RAD, q_ref.tolist())
        if status == 0:
            return float(pitch)
    return TOP_DOWN_PITCH_RAD


class _Phase(enum.Enum):
    APPROACH = "approach"
    ALIGN = "align"
    PLUNGE = "plunge"
    GRASP = "grasp"
    REOPEN = "reopen"
    LIFT = "lift"
    CARRY = "carry"
    PLACE = "place"
    RELEASE = "release"
    RETREAT = "retreat"
    HOLD = "hold"


class PickAndPlaceExpert:
    """Scripted pick-and-place: approach, descend, grasp, lift, carry around the obstacles, place.

    The approach and the carry are planned (module docstring); a goal above the
    table's resting height is held in the air (the cube stays gripped); a goal
    on the table is placed and released, and the arm backs off straight up.
    Closed loop: every step decides from the observation; a grasp that misses is
    opened and tried again, a cube that slips out or is knocked off the goal is
    picked up again, a command pushed off a planned route is re-planned.

    Args:
        env: A ``LynxPickAndPlace`` env (wrapped or not) with ``control="tool"``.

    Raises:
        InvalidInputError: Another env or control mode.
    """

    def __init__(self, env: gym.Env[Any, Any]) -> None:
        u, controller = _tool_env(env, PickAndPlaceEnv)
        self._controller = controller
        self._planner = _Planner(u, controller)
        self._mover = _Mover(self._planner, u.q_ready)
        self._idx = PickAndPlaceEnv.OBS_INDEX
        self._env = u
        self._threshold = u.distance_threshold
        self.reset()

    def reset(self) -> None:
        """Forget the episode and read its cube's size (call after every ``env.reset``)."""
        size = self._env.domain.cube_size_m or 2 * CUBE_HALF_SIZE_M
        half = 0.5 * size
        self._rest_z = self._env.table_top_z + half
        self._align = half + _FINGERTIP_M + _ALIGN_ABOVE_TOP_M
        self._on_top = half + _FINGERTIP_M - _ON_TOP_SLACK_M
        self._gripped = (size - 0.004, size + 0.002)
        self._opened = size + 0.0025
        self.phase = _Phase.APPROACH
        self._count = 0
        self._offset: Point = (0.0, 0.0, 0.0)
        self._hold_at: Pose = (0.0, 0.0, 0.0, 0.0)
        self._mover.route = None
        self._planner.reset()

    def _enter(self, phase: _Phase) -> None:
        self.phase = phase
        self._count = 0
        self._mover.route = None

    def _transit(
        self, cmd: Pose, tool: Point, q_cmd: FloatArray, dest: Point, *, grasped: bool
    ) -> tuple[list[float], bool]:
        """A planned move to ``dest``, the gripper pointing down if the IK reaches it so."""
        pose = (*dest, _pitch_for(dest, q_cmd))
        return self._mover.step(cmd, tool, q_cmd, pose, grasped=grasped)

    def __call__(self, observation: dict[str, FloatArray]) -> npt.NDArray[np.float32]:
        """The action for an observation, shape (5,), float32 in [-1, 1]."""
        o = observation["observation"]
        ix = self._idx
        x, y, z = o[ix["commanded_tool_position"]].tolist()
        cmd: Pose = (x, y, z, float(o[ix["commanded_tool_pitch"]][0]))
        tool: Point = tuple(o[ix["tool_position"]].tolist())
        tool_speed = math.hypot(*o[ix["tool_velocity"]].tolist())
        q_cmd = o[ix["commanded_joint_angles"]]
        opening = float(o[ix["gripper_opening"]][0])
        cube: Point = tuple(observation["achieved_goal"].tolist())
        goal: Point = tuple(observation["desired_goal"].tolist())
        lag = max(abs(tool[i] - cmd[i]) for i in range(3))
        settled = lag < _SETTLED_M and tool_speed < _SETTLED_SPEED
        near = lag < _NEAR_M  # close enough to go on (noisy actions never settle)
        in_hand = math.dist(cube, tool) < _IN_HAND_M
        c = self._controller
        self._count += 1
        phase = self.phase
        grip = 1.0

        if phase is _Phase.APPROACH:
            hover = (cube[0], cube[1], cube[2] + _HOVER_M)
            arm, at = self._transit(cmd, tool, q_cmd, hover, grasped=False)
            if at and (settled or near or self._count > _MAX_WAIT_STEPS):
                self._enter(_Phase.ALIGN)
        elif phase is _Phase.ALIGN:
            # Above the cube, fingertips clear of its top, until centred over it.
            point = (cube[0], cube[1], cube[2] + self._align)
            arm, at = _straight(cmd, (*point, _pitch_for(point, q_cmd)), c, _SLOW)
            across, along = _across_along(tool[0] - cube[0], tool[1] - cube[1], float(q_cmd[0]))
            centred = (
                abs(across) < _CENTRED_ACROSS_M
                and abs(along) < _CENTRED_ALONG_M
                and abs(tool[2] - point[2]) < _AROUND_M
            )
            if centred or (at and self._count > _PRE_GRASP_WAIT):
                # Down at once: one more step of noisy actions would undo the centring.
                self._enter(_Phase.PLUNGE)
                phase = _Phase.PLUNGE
        if phase is _Phase.PLUNGE:
            # Down past the cube's top in as few steps as possible, then close. Heights
            # count from the resting centre: a cube pressed into the table reads lower.
            base = max(cube[2], self._rest_z)
            point = (cube[0], cube[1], max(base + _GRASP_ABOVE_M, c.box[0][2]))
            dive = (*point[:2], max(point[2], tool[2] - _PRESS_M))
            arm = _per_axis(cmd, (*dive, _pitch_for(point, q_cmd)), c)
            around = (
                math.dist(tool[:2], cube[:2]) < _AROUND_M
                and tool[2] - base < _GRASP_ABOVE_M + _AROUND_M
            )
            if around:
                self._enter(_Phase.GRASP)
                self._hold_at = point_pose = (cmd[0], cmd[1], point[2], TOP_DOWN_PITCH_RAD)
                arm, _ = _straight(cmd, point_pose, c, _SLOW)
            elif self._count > _PLUNGE_STEPS or (
                self._count >= 1 and tool[2] - base > self._on_top
            ):  # landed on the cube or beside it: up and again
                self._enter(_Phase.ALIGN)
        elif phase is _Phase.GRASP:  # close, holding the arm where the grasp began
            arm, _ = _straight(cmd, self._hold_at, c, _SLOW)
            grip = -1.0
            if self._count >= _GRIP_CLOSE_STEPS:
                if self._gripped[0] <= opening <= self._gripped[1]:
                    self._enter(_Phase.LIFT)
                elif self._count > _MAX_WAIT_STEPS:
                    self._enter(_Phase.REOPEN)
        elif phase is _Phase.REOPEN:
            point = (cmd[0], cmd[1], cube[2] + self._align)
            arm, _ = _straight(cmd, (*point, cmd[3]), c, _SLOW)
            if self._count >= _REOPEN_STEPS:
                self._enter(_Phase.ALIGN)
        elif phase is _Phase.LIFT:
            # Straight up from where the grasp began (noisy actions must not walk it off).
            arm, at = _straight(cmd, (*self._hold_at[:2], CARRY_HEIGHT_M, cmd[3]), c)
            grip = -1.0
            if at and (settled or near or self._count > _MAX_WAIT_STEPS):
                if in_hand:
                    self._offset = (cube[0] - tool[0], cube[1] - tool[1], cube[2] - tool[2])
                    self._enter(_Phase.CARRY)
                else:
                    self._enter(_Phase.APPROACH)
        elif phase in (_Phase.CARRY, _Phase.PLACE, _Phase.HOLD):
            arm, grip = self._carry(phase, cmd, q_cmd, tool, cube, goal, settled)
            if not in_hand:
                self._enter(_Phase.APPROACH)
        elif phase is _Phase.RELEASE:  # open, holding the arm where the cube was put down
            arm, _ = _straight(cmd, self._hold_at, c, _SLOW)
            opened = opening > self._opened
            if self._count >= _RELEASE_STEPS and (opened or self._count > _MAX_WAIT_STEPS):
                self._enter(_Phase.RETREAT)
        elif phase is _Phase.RETREAT:  # straight up (a jerk up drags the cube along the fingers)
            above = (*self._hold_at[:2], goal[2] + _HOVER_M, cmd[3])  # where it was let go
            arm, _ = _straight(cmd, above, c, _SLOW)
            # Knocked off the goal: again (a cube still within the success radius is
            # left alone: picking it up again would risk more than it can win).
            if math.dist(cube, goal) > self._threshold:
                self._enter(_Phase.APPROACH)
        return np.array([*arm, grip], dtype=np.float32)

    def _carry(
        self,
        phase: _Phase,
        cmd: Pose,
        q_cmd: FloatArray,
        tool: Point,
        cube: Point,
        goal: Point,
        settled: bool,
    ) -> tuple[list[float], float]:
        """Carry to the goal, then place (table goal) or hold (goal in the air)."""
        off = (cube[0] - tool[0], cube[1] - tool[1], cube[2] - tool[2])  # the cube in the hand
        if phase is _Phase.CARRY:
            # The planned destination follows the hold measured at rest (a swinging
            # cube would move it, and re-plan the route, at every step).
            if settled:
                self._offset = off
            on_table = goal[2] <= self._rest_z + 1e-3
            held = self._offset
            height = CARRY_HEIGHT_M if on_table else goal[2] - held[2]
            dest = (goal[0] - held[0], goal[1] - held[1], height)
            arm, at = self._transit(cmd, tool, q_cmd, dest, grasped=True)
            if at:
                self._enter(_Phase.PLACE if on_table else _Phase.HOLD)
            return arm, -1.0
        # At the goal the cube itself is steered, with the hold as it is now.
        over = (goal[0] - off[0], goal[1] - off[1])
        if phase is _Phase.PLACE:
            point = (*over, goal[2] + _PLACE_ABOVE_M - off[2])
            arm, at = _straight(cmd, (*point, _pitch_for(point, q_cmd)), self._controller, _SLOW)
            down = cube[2] - goal[2] < _DOWN_M  # the cube (almost) rests on the table
            on_goal = math.dist(cube[:2], goal[:2]) < _ON_GOAL_M
            if (
                (at or on_goal)
                and (down or self._count > _MAX_WAIT_STEPS)
                and (on_goal or self._count > 2 * _MAX_WAIT_STEPS)
            ):
                self._enter(_Phase.RELEASE)
                self._hold_at = cmd
                return [0.0, 0.0, 0.0, 0.0], 1.0
            return arm, -1.0
        point = (*over, goal[2] - off[2])  # HOLD: follow the cube's offset in the hand
        arm, _ = _straight(cmd, (*point, _pitch_for(point, q_cmd)), self._controller)
        return arm, -1.0


class ReachExpert:
    """Scripted reach: a planned move of the tool point to the goal.

    The goal's pitch is pointing down where the IK reaches the goal so, else the
    nearest pitch that does.

    Args:
        env: A ``LynxReach`` env (wrapped or not) with ``control="tool"``.

    Raises:
        InvalidInputError: Another env or control mode.
    """

    def __init__(self, env: gym.Env[Any, Any]) -> None:
        u, controller = _tool_env(env, ReachEnv)
        self._controller = controller
        self._planner = _Planner(u, controller)
        self._mover = _Mover(self._planner, u.q_ready)
        self._idx = ReachEnv.OBS_INDEX
        self.reset()

    def reset(self) -> None:
        """Forget the episode (call after every ``env.reset``)."""
        self._mover.route = None
        self._planner.reset()

    def __call__(self, observation: dict[str, FloatArray]) -> npt.NDArray[np.float32]:
        """The action for an observation, shape (4,), float32 in [-1, 1]."""
        o = observation["observation"]
        ix = self._idx
        x, y, z = o[ix["commanded_tool_position"]].tolist()
        cmd: Pose = (x, y, z, float(o[ix["commanded_tool_pitch"]][0]))
        q_cmd = o[ix["commanded_joint_angles"]]
        goal: Point = tuple(observation["desired_goal"].tolist())
        dest = (*goal, _pitch_for(goal, q_cmd))
        tool: Point = tuple(o[ix["tool_position"]].tolist())
        arm, _ = self._mover.step(cmd, tool, q_cmd, dest, grasped=False)
        return np.array(arm, dtype=np.float32)
