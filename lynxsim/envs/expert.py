"""Scripted experts: pick-and-place and reach from the observation alone.

The experts drive the default tool-space action. They move the commanded tool
point (which the observation reports) along a path that keeps the arm clear of
the obstacle without knowing where it stands: the base turns only while the
tool is tucked in near the base axis (:data:`~lynxsim.envs.workspace.TUCK_RADIUS_M`,
inside the obstacle's near face) at the carry height, and reaches out again along
the radius of the destination; the envs draw cubes and goals whose radius is
clear of the obstacle (:mod:`lynxsim.envs.workspace`). The analytic IK picks the
tool pitch of each destination: pointing down where that is reachable, else the
nearest pitch that is.

Usage::

    env = gym.make("LynxPickAndPlace-v0")
    expert = PickAndPlaceExpert(env)
    obs, _ = env.reset(seed=0)
    expert.reset()
    obs, reward, terminated, truncated, info = env.step(expert(obs))
"""

from __future__ import annotations

import enum
import math
from typing import Any

import gymnasium as gym
import numpy as np
import numpy.typing as npt

from lynxsim.arm import ik_nearest
from lynxsim.envs.base import LynxArmEnv
from lynxsim.envs.control import ToolSpaceController
from lynxsim.envs.pick_and_place import CUBE_HALF_SIZE_M, PickAndPlaceEnv
from lynxsim.envs.reach import ReachEnv
from lynxsim.envs.workspace import (
    CARRY_HEIGHT_M,
    GRIP_ROLL_RAD,
    TOP_DOWN_PITCH_RAD,
    TUCK_RADIUS_M,
)
from lynxsim.errors import InvalidInputError

__all__ = ["PickAndPlaceExpert", "ReachExpert"]

FloatArray = npt.NDArray[np.float64]
Point = tuple[float, float, float]

_AT_TARGET_M = 1e-4
"""The commanded point counts as at its destination within this [m]."""
_TURN_TOL_RAD = 0.02
"""Azimuth changes above this go through the tuck [rad]."""
_SETTLED_M = 0.002
"""The arm counts as settled when the tool point is this close to its command [m] ..."""
_SETTLED_SPEED = 0.02
"""... and moves slower than this [m/s]."""
_SLOW = 0.4
"""Fraction of the full speed for the moves down to the table."""
_CREEP = 0.1
"""Fraction of the full speed for the last centimetres around the cube."""
_PRE_GRASP_M = 0.022
"""Tool height above the cube centre where the descent pauses [m] (fingertips 1.5 mm
above the cube's top)."""
_PRE_GRASP_WAIT = 30
"""Steps the descent may take to reach and settle at the pre-grasp point."""
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
_GRIPPED_MAX_M = 2 * CUBE_HALF_SIZE_M + 0.002
"""Largest finger opening that means the cube is held [m]."""
_GRIPPED_MIN_M = 2 * CUBE_HALF_SIZE_M - 0.004
"""Smallest finger opening that still means the cube is between the fingers [m]."""
_IN_HAND_M = 0.02
"""Largest cube-to-tool distance of a held cube [m]."""
_RELEASE_STEPS = 5
"""Steps the gripper gets to open before the arm backs off."""
_PLACE_ABOVE_M = 0.002
"""The cube is let go this high above its resting height [m]."""


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


class _Router:
    """Actions that move the commanded tool point towards a destination, safely.

    Args:
        controller: The env's tool-space controller (for its step sizes).
        tuck_radius: Radius at which the base turns [m].
        carry_height: Height at which the base turns [m].
    """

    def __init__(
        self, controller: ToolSpaceController, tuck_radius: float, carry_height: float
    ) -> None:
        self.step = controller.position_step
        self.pitch_step = controller.pitch_step
        self.tuck = tuck_radius
        self.carry = carry_height

    def waypoint(self, cmd: Point, dest: Point) -> Point:
        """The next point to head for: the destination, or a tuck point on the way."""
        r0, a0 = math.hypot(cmd[0], cmd[1]), math.atan2(cmd[1], cmd[0])
        a1 = math.atan2(dest[1], dest[0])
        turn = math.remainder(a1 - a0, 2 * math.pi)
        if abs(turn) <= _TURN_TOL_RAD:
            return dest
        tucked = abs(r0 - self.tuck) < _AT_TARGET_M and abs(cmd[2] - self.carry) < _AT_TARGET_M
        if not tucked:
            return (self.tuck * math.cos(a0), self.tuck * math.sin(a0), self.carry)
        da = math.copysign(min(abs(turn), self.step / self.tuck), turn)
        a = a1 if abs(turn) <= self.step / self.tuck else a0 + da
        return (self.tuck * math.cos(a), self.tuck * math.sin(a), self.carry)

    def action(
        self, cmd: Point, cmd_pitch: float, dest: Point, pitch: float, speed: float = 1.0
    ) -> tuple[list[float], bool]:
        """Arm action (4 values) towards ``dest`` and whether the command is there already.

        ``speed`` in (0, 1] scales the largest move per step.
        """
        way = self.waypoint(cmd, dest)
        if way is dest:  # brake on the final approach: the servos overshoot sudden stops
            speed = min(speed, max(_MIN_SPEED, math.dist(cmd, dest) / _BRAKE_M))
        delta = [(way[i] - cmd[i]) / self.step for i in range(3)]
        biggest = max(abs(v) for v in delta)
        if biggest > speed:
            delta = [v * (speed / biggest) for v in delta]
        d_pitch = max(-1.0, min(1.0, (pitch - cmd_pitch) / self.pitch_step))
        at = (
            max(abs(dest[i] - cmd[i]) for i in range(3)) < _AT_TARGET_M
            and abs(pitch - cmd_pitch) < 1e-4
        )
        return [*delta, d_pitch], at


def _pitch_for(point: Point, q_ref: FloatArray) -> float:
    """Pitch for a tool point: straight down if the IK reaches it so, else the nearest that does."""
    for pitch in _PITCH_SEARCH_RAD:
        status, _ = ik_nearest(*point, float(pitch), GRIP_ROLL_RAD, q_ref.tolist())
        if status == 0:
            return float(pitch)
    return TOP_DOWN_PITCH_RAD


class _Phase(enum.Enum):
    APPROACH = "approach"
    DESCEND = "descend"
    GRASP = "grasp"
    LIFT = "lift"
    CARRY = "carry"
    PLACE = "place"
    RELEASE = "release"
    RETREAT = "retreat"
    HOLD = "hold"


class PickAndPlaceExpert:
    """Scripted pick-and-place: approach, descend, grasp, lift, carry around the obstacle, place.

    A goal above the table's resting height is held in the air (the cube stays
    gripped); a goal on the table is placed and released, and the arm backs off
    upwards. A grasp that misses or a cube that slips out starts over.

    Args:
        env: A ``LynxPickAndPlace`` env (wrapped or not) with ``control="tool"``.
        tuck_radius: Tool distance from the base axis while the base turns [m].
        carry_height: Tool height while the base turns [m].

    Raises:
        InvalidInputError: Another env or control mode.
    """

    def __init__(
        self,
        env: gym.Env[Any, Any],
        *,
        tuck_radius: float = TUCK_RADIUS_M,
        carry_height: float = CARRY_HEIGHT_M,
    ) -> None:
        u, controller = _tool_env(env, PickAndPlaceEnv)
        self._router = _Router(controller, tuck_radius, carry_height)
        self._idx = PickAndPlaceEnv.OBS_INDEX
        self._rest_z = u.table_top_z + CUBE_HALF_SIZE_M
        self.reset()

    def reset(self) -> None:
        """Forget the episode (call after every ``env.reset``)."""
        self.phase = _Phase.APPROACH
        self._count = 0
        self._offset: Point = (0.0, 0.0, 0.0)

    def _enter(self, phase: _Phase) -> None:
        self.phase = phase
        self._count = 0

    def __call__(self, observation: dict[str, FloatArray]) -> npt.NDArray[np.float32]:
        """The action for an observation, shape (5,), float32 in [-1, 1]."""
        o = observation["observation"]
        ix = self._idx
        cmd: Point = tuple(o[ix["commanded_tool_position"]].tolist())
        cmd_pitch = float(o[ix["commanded_tool_pitch"]][0])
        tool: Point = tuple(o[ix["tool_position"]].tolist())
        tool_speed = math.hypot(*o[ix["tool_velocity"]].tolist())
        q_cmd = o[ix["commanded_joint_angles"]]
        opening = float(o[ix["gripper_opening"]][0])
        cube: Point = tuple(observation["achieved_goal"].tolist())
        goal: Point = tuple(observation["desired_goal"].tolist())
        settled = (
            max(abs(tool[i] - cmd[i]) for i in range(3)) < _SETTLED_M
            and tool_speed < _SETTLED_SPEED
        )
        in_hand = math.dist(cube, tool) < _IN_HAND_M
        route = self._router
        self._count += 1
        phase = self.phase
        grip = 1.0

        if phase is _Phase.APPROACH:
            dest = (cube[0], cube[1], cube[2] + _HOVER_M)
            arm, at = route.action(cmd, cmd_pitch, dest, _pitch_for(dest, q_cmd))
            if at and (settled or self._count > _MAX_WAIT_STEPS):
                self._enter(_Phase.DESCEND)
        elif phase is _Phase.DESCEND:
            # First to just above the cube (fingertips clear of its top); once settled
            # there, slowly down until the cube is between the fingers.
            final = self._count > _PRE_GRASP_WAIT
            height = 0.0 if final else _PRE_GRASP_M
            dest = (cube[0], cube[1], cube[2] + height)
            speed = _CREEP if final else _SLOW
            arm, at = route.action(cmd, cmd_pitch, dest, _pitch_for(dest, q_cmd), speed)
            if not final and at and (settled or self._count == _PRE_GRASP_WAIT):
                self._count = _PRE_GRASP_WAIT + 1
            elif final and at and (settled or self._count > 2 * _PRE_GRASP_WAIT):
                self._enter(_Phase.GRASP)
            elif self._count > 3 * _PRE_GRASP_WAIT:  # stuck on the cube
                self._enter(_Phase.APPROACH)
        elif phase is _Phase.GRASP:
            arm, grip = [0.0, 0.0, 0.0, 0.0], -1.0
            if self._count >= _GRIP_CLOSE_STEPS:
                if _GRIPPED_MIN_M <= opening <= _GRIPPED_MAX_M:
                    self._enter(_Phase.LIFT)
                elif self._count > _MAX_WAIT_STEPS:
                    self._enter(_Phase.APPROACH)
        elif phase is _Phase.LIFT:
            dest = (cmd[0], cmd[1], route.carry)
            arm, at = route.action(cmd, cmd_pitch, dest, cmd_pitch)
            grip = -1.0
            if at and (settled or self._count > _MAX_WAIT_STEPS):
                if in_hand:
                    self._offset = (cube[0] - tool[0], cube[1] - tool[1], cube[2] - tool[2])
                    self._enter(_Phase.CARRY)
                else:
                    self._enter(_Phase.APPROACH)
        elif phase in (_Phase.CARRY, _Phase.PLACE, _Phase.HOLD):
            arm, grip = self._carry(phase, cmd, cmd_pitch, tool, cube, goal, q_cmd, settled)
            if not in_hand:
                self._enter(_Phase.APPROACH)
        elif phase is _Phase.RELEASE:
            arm = [0.0, 0.0, 0.0, 0.0]
            if self._count >= _RELEASE_STEPS:
                self._enter(_Phase.RETREAT)
        else:  # RETREAT, then stay
            dest = (cmd[0], cmd[1], goal[2] + _HOVER_M)
            arm, _ = route.action(cmd, cmd_pitch, dest, cmd_pitch)
        return np.array([*arm, grip], dtype=np.float32)

    def _carry(
        self,
        phase: _Phase,
        cmd: Point,
        cmd_pitch: float,
        tool: Point,
        cube: Point,
        goal: Point,
        q_cmd: FloatArray,
        settled: bool,
    ) -> tuple[list[float], float]:
        """Carry to the goal, then place (table goal) or hold (goal in the air)."""
        route = self._router
        if settled:  # where the cube sits in the hand, measured at rest
            self._offset = (cube[0] - tool[0], cube[1] - tool[1], cube[2] - tool[2])
        off = self._offset
        on_table = goal[2] <= self._rest_z + 1e-3
        speed = 1.0
        if phase is _Phase.PLACE:
            dest = (goal[0] - off[0], goal[1] - off[1], goal[2] + _PLACE_ABOVE_M - off[2])
            speed = _SLOW
        elif on_table:
            dest = (goal[0] - off[0], goal[1] - off[1], route.carry)
        else:
            dest = (goal[0] - off[0], goal[1] - off[1], goal[2] - off[2])
        arm, at = route.action(cmd, cmd_pitch, dest, _pitch_for(dest, q_cmd), speed)
        if at and phase is _Phase.CARRY:
            self._enter(_Phase.PLACE if on_table else _Phase.HOLD)
        elif at and phase is _Phase.PLACE and (settled or self._count > _MAX_WAIT_STEPS):
            self._enter(_Phase.RELEASE)
            return [0.0, 0.0, 0.0, 0.0], 1.0
        return arm, -1.0


class ReachExpert:
    """Scripted reach: the tool point to the goal, turning the base only when tucked in.

    Args:
        env: A ``LynxReach`` env (wrapped or not) with ``control="tool"``.
        tuck_radius: Tool distance from the base axis while the base turns [m].
        carry_height: Tool height while the base turns [m].

    Raises:
        InvalidInputError: Another env or control mode.
    """

    def __init__(
        self,
        env: gym.Env[Any, Any],
        *,
        tuck_radius: float = TUCK_RADIUS_M,
        carry_height: float = CARRY_HEIGHT_M,
    ) -> None:
        _, controller = _tool_env(env, ReachEnv)
        self._router = _Router(controller, tuck_radius, carry_height)
        self._idx = ReachEnv.OBS_INDEX

    def reset(self) -> None:
        """Forget the episode (nothing to forget: the reach expert is stateless)."""

    def __call__(self, observation: dict[str, FloatArray]) -> npt.NDArray[np.float32]:
        """The action for an observation, shape (4,), float32 in [-1, 1]."""
        o = observation["observation"]
        ix = self._idx
        cmd: Point = tuple(o[ix["commanded_tool_position"]].tolist())
        cmd_pitch = float(o[ix["commanded_tool_pitch"]][0])
        goal: Point = tuple(observation["desired_goal"].tolist())
        pitch = _pitch_for(goal, o[ix["commanded_joint_angles"]])
        arm, _ = self._router.action(cmd, cmd_pitch, goal, pitch)
        return np.array(arm, dtype=np.float32)
