"""``LynxReach-v1``/``-v2``: bring the tool point to a goal, around the obstacles."""

from __future__ import annotations

import math
from typing import ClassVar

import numpy as np

from lynxsim.envs.base import READY_TOOL_POSE, LynxArmEnv, Obs
from lynxsim.envs.episodes import farthest_apart, task_points
from lynxsim.envs.pick_and_place import _fields
from lynxsim.envs.workspace import PolarRegion

__all__ = ["ReachEnv"]


class ReachEnv(LynxArmEnv):
    """Reach a point with the tool of the report's 5-DOF arm (the easy sibling of pick-and-place).

    The scene is pick-and-place's without the cube: the arm, the table and (unless
    ``obstacles`` removes or moves it, or ``random_obstacles`` draws new ones at
    every reset, clear of the goal and of the arm pointing down at it, as in
    :class:`~lynxsim.envs.PickAndPlaceEnv`) the report's cylinder obstacle. The gripper
    stays open and is not part of the action. SI units, arm base frame.

    **Action space** ``Box(-1, 1, (4,), float32)`` with ``control="tool"`` (default):
    moves of the commanded tool point x, y, z (+1 = + ``position_step`` [m], 0.015)
    and pitch (+1 = + ``pitch_step`` [rad], 0.1), turned into servo targets by the
    analytic IK exactly as in :class:`~lynxsim.envs.PickAndPlaceEnv` (an infeasible
    request moves the target as far as is feasible in ``-v1``, holds it in ``-v0``;
    ``info`` reports it). With
    ``control="joint"``: ``Box(-1, 1, (5,), float32)``, deltas of q1..q5
    (+1 = + ``joint_step`` [rad], 0.05). ``-v2`` (``control="tool_roll"``):
    ``Box(-1, 1, (5,), float32)``, the tool action with the wrist roll at index 4
    (+1 = + ``roll_step`` [rad], 0.1); an infeasible request goes to the nearest
    feasible target, as in :class:`~lynxsim.envs.PickAndPlaceEnv`.

    **Observation** (a dict, float64, freshly allocated; with ``pixels`` also the
    uint8 ``"pixels"``): ``achieved_goal`` is the
    tool point, ``desired_goal`` the goal, both shape (3,) [m]; ``observation`` has
    shape (26,):

    =====  ====================================================  =======
    idx    observation                                           unit
    =====  ====================================================  =======
    0-2    tool point x, y, z                                    m
    3      tool pitch (q2 + q3 + q4)                             rad
    4-6    tool-point velocity (difference over one step)        m/s
    7-11   joint angles q1..q5                                   rad
    12-16  joint velocities                                      rad/s
    17-21  commanded joint angles (servo targets)                rad
    22-24  commanded tool point                                  m
    25     commanded tool pitch                                  rad
    =====  ====================================================  =======

    **Rewards**, with ``d`` the distance from the tool point to the goal [m]:
    ``reward_goal`` sparse (default) -1 if ``d > distance_threshold`` (0.025 m) else
    0, dense ``-d``; ``reward_collision`` ``-collision_penalty`` (default 0) on a step
    with arm–obstacle contact. ``compute_reward`` reproduces their sum, vectorised.

    **Starting state**: the ready pose of pick-and-place (tool point (0.18, 0, 0.08) m
    pointing down, gripper open, velocities zero, servo targets equal to the joints).
    The goal is drawn with ``np_random`` uniformly from 0.10..0.25 m from the base
    axis, azimuth -80..80 deg, z 0.0..0.10 m, among points reachable with the
    gripper pointing down whose arm plane keeps 2 cm from the obstacle, and farther
    than ``distance_threshold`` from the starting tool point.

    **Episode end**: as pick-and-place (no termination on success; optional on
    collision); truncation at ``max_episode_steps`` (100 steps = 4 s as registered).

    **Info**, **arguments**, **rendering** and **image observations** (``pixels``: a
    uint8 ``obs["pixels"]`` of shape (``pixel_height``, ``pixel_width``, 3 x cameras),
    the goal not drawn), **domain randomisation** (``randomize``: servo gains,
    joint damping and cameras; a :class:`~lynxsim.envs.Randomization` that
    touches the cube is refused) and **for RL users**: as
    :class:`~lynxsim.envs.PickAndPlaceEnv`, without ``goal_in_air_prob``.

    **Version history**: v2: the wrist roll in the tool action (5-D), and an
    infeasible request goes to the nearest feasible target, sliding along the reach
    boundary (was: it stops dead at the edge of the reach), with
    ``info["target_correction"]`` (``control="tool_roll"``; v1 still registered).
    v1: an infeasible tool request moves the target as far as is feasible (was:
    held); ``random_obstacles`` and ``pixels`` (off by default). v0: first release
    (still registered, with ``target_fallback="hold"``).
    """

    OBS_INDEX: ClassVar[dict[str, slice]] = _fields(
        ("tool_position", 3),
        ("tool_pitch", 1),
        ("tool_velocity", 3),
        ("joint_angles", 5),
        ("joint_velocities", 5),
        ("commanded_joint_angles", 5),
        ("commanded_tool_position", 3),
        ("commanded_tool_pitch", 1),
    )
    """Slices of ``observation`` by name."""
    _OBS_SIZE: ClassVar[int] = 26

    GOAL_REGION = PolarRegion(
        radius=(0.10, 0.25), azimuth=(-math.radians(80), math.radians(80)), height=(0.0, 0.10)
    )
    """Where goals are drawn."""

    def _check_feasible(self) -> None:
        goals = task_points(self.GOAL_REGION, self._obstacles)
        if not goals.size:
            self._refuse(f"the obstacles block every goal of {self.GOAL_REGION}")
        if farthest_apart(goals, np.array([READY_TOOL_POSE[:3]])) <= self.distance_threshold:
            self._refuse("no goal lies farther than distance_threshold from the start")

    def _sample_task(self) -> None:
        self._set_goal(self._draw_point(self.GOAL_REGION, READY_TOOL_POSE[:3]))

    def _observation(self) -> Obs:
        d = self.data
        qp = d.qpos.tolist()
        qv = d.qvel.tolist()
        q = [qp[i] for i in self._arm_qpos]
        x, y, z, pitch, vx, vy, vz = self._tool_state(q)
        cmd = self._controller
        o = [
            x, y, z, pitch, vx, vy, vz,
            *q,
            *(qv[i] for i in self._arm_dof),
            *cmd.q_cmd,
            *cmd.target,
        ]  # fmt: skip
        return {
            "observation": np.array(o),
            "achieved_goal": np.array((x, y, z)),
            "desired_goal": self._goal.copy(),
        }
