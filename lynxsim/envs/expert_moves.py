"""The small moves the scripted experts share: straight lines, per-axis steps, grasp roll, pitch.

Pure functions of tool poses and the env's controller (:mod:`lynxsim.envs.expert`).
"""

from __future__ import annotations

import math
from typing import Any

import gymnasium as gym
import numpy as np
import numpy.typing as npt

from lynxsim.arm import ik_nearest
from lynxsim.envs.base import LynxArmEnv
from lynxsim.envs.control import ToolSpaceController
from lynxsim.envs.routes import Point, Pose, braking, toward
from lynxsim.envs.workspace import GRIP_ROLL_RAD, TOP_DOWN_PITCH_RAD
from lynxsim.errors import InvalidInputError

__all__ = [
    "QUARTER_RAD",
    "across_along",
    "grasp_roll",
    "per_axis",
    "pitch_for",
    "straight",
    "tool_env",
]

FloatArray = npt.NDArray[np.float64]

SNAP_M = 0.005
"""Short moves correct an error up to this [m] in one step, braking or not: noisy
actions push the command a few millimetres every step."""
QUARTER_RAD = 0.5 * math.pi
"""A cube looks the same turned by a quarter turn about the vertical [rad]."""
PITCH_SEARCH_RAD = np.linspace(TOP_DOWN_PITCH_RAD, math.pi / 2, 61)
"""Pitches tried, in order, when the gripper cannot point straight down at a point [rad]."""


def tool_env(
    env: gym.Env[Any, Any], kind: type[LynxArmEnv]
) -> tuple[LynxArmEnv, ToolSpaceController]:
    """The unwrapped env of ``kind`` under ``env`` and its tool-space controller.

    Raises:
        InvalidInputError: ``env`` is another env, or not driven by tool actions.
    """
    u = env.unwrapped
    if not isinstance(u, kind):
        raise InvalidInputError(f"this expert drives a {kind.__name__}, got {type(u).__name__}")
    if not isinstance(u.controller, ToolSpaceController):
        raise InvalidInputError(
            f"the expert needs control='tool', the env has control={u.control.value!r}"
        )
    return u, u.controller


def straight(
    cmd: Pose, dest: Pose, controller: ToolSpaceController, speed: float = 1.0
) -> tuple[list[float], bool]:
    """:func:`toward` with braking: for the short straight moves at the cube and the goal.

    The last :data:`SNAP_M` are taken in one step.
    """
    distance = math.dist(cmd[:3], dest[:3])
    snap = min(distance, SNAP_M) / controller.position_step
    return toward(cmd, dest, controller, max(braking(distance, speed), snap))


def per_axis(cmd: Pose, dest: Pose, controller: ToolSpaceController) -> list[float]:
    """Arm action (4 values) towards ``dest``, each axis as far as one step allows."""
    steps = (*(controller.position_step,) * 3, controller.pitch_step)
    return [max(-1.0, min(1.0, (dest[i] - cmd[i]) / steps[i])) for i in range(4)]


def across_along(dx: float, dy: float, azimuth: float) -> tuple[float, float]:
    """A horizontal offset (dx, dy) [m] along the fingers' closing axis and across it.

    The gripper, pointing down, closes along the arm's vertical plane (azimuth
    ``azimuth`` [rad], the base joint's angle).
    """
    c, s = math.cos(azimuth), math.sin(azimuth)
    return dx * c + dy * s, dy * c - dx * s


def grasp_roll(base: float, yaw: float, roll: float) -> float:
    """The wrist roll that closes the fingers (pointing down) across faces of a cube [rad].

    The fingers close along the azimuth ``base - (roll - GRIP_ROLL_RAD)``; the roll
    chosen puts it on a face normal (``yaw`` plus a multiple of a quarter turn),
    the nearest the roll ``roll`` now unless that is more than 3/16 of a turn from
    :data:`GRIP_ROLL_RAD` (then a quarter turn back): a cube turned by about an
    eighth of a turn does not make the choice flip from step to step.
    """
    closing = base - (roll - GRIP_ROLL_RAD)
    turn = (closing - yaw + 0.5 * QUARTER_RAD) % QUARTER_RAD - 0.5 * QUARTER_RAD
    new = roll + turn
    if new - GRIP_ROLL_RAD > 0.75 * QUARTER_RAD:
        new -= QUARTER_RAD
    elif GRIP_ROLL_RAD - new > 0.75 * QUARTER_RAD:
        new += QUARTER_RAD
    return new


def pitch_for(point: Point, q_ref: FloatArray) -> float:
    """Pitch for a tool point: straight down if the IK reaches it so, else the nearest that does."""
    for pitch in PITCH_SEARCH_RAD:
        status, _ = ik_nearest(*point, float(pitch), GRIP_ROLL_RAD, q_ref.tolist())
        if status == 0:
            return float(pitch)
    return TOP_DOWN_PITCH_RAD
