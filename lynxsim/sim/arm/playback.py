"""Playing arm trajectories in the arm scene: binding, collision checker, playback."""

from __future__ import annotations

from collections.abc import Callable

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.arm import tool_pose
from lynxsim.sim.arm.model import SceneIds
from lynxsim.sim.binding import RobotBinding
from lynxsim.sim.collision import CollisionChecker
from lynxsim.sim.joint_playback import play_joints
from lynxsim.sim.stepping.log import ProgressFn, StepHook
from lynxsim.sim.summary import Playback
from lynxsim.traj import Trajectory

__all__ = ["arm_binding", "arm_checker", "arm_tool_points", "play_arm"]


def arm_binding(model: mujoco.MjModel) -> RobotBinding:
    """What the playback drives and watches in an arm scene (or the robot alone)."""
    return SceneIds.from_model(model).binding(model)


def arm_tool_points(q: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    """Tool points of joint vectors, (T, 5) [rad] -> (T, 3) [m] (the analytic FK)."""
    points: npt.NDArray[np.float64] = tool_pose(q).position
    return points


def arm_checker(model: mujoco.MjModel, base_qpos: npt.ArrayLike | None = None) -> CollisionChecker:
    """A :class:`~lynxsim.sim.collision.CollisionChecker` of the arm's five joints.

    The fingers and the cube stay as in ``base_qpos`` (default the model's
    ``qpos0``: the cube at its start) unless ``check(..., grasped=True)`` puts
    the cube at the tool point.
    """
    ids = SceneIds.from_model(model)
    attach = None if ids.cube_qpos is None else (ids.cube_qpos, ids.tool_site)
    return CollisionChecker(
        model, ids.collision_groups(model), ids.arm_qpos, base_qpos=base_qpos, attach=attach
    )


def play_arm(
    model: mujoco.MjModel,
    trajectory: Trajectory,
    *,
    task: str,
    data: mujoco.MjData | None = None,
    settle_s: float = 0.5,
    gripper_cmd: Callable[[float], float] | None = None,
    on_step: StepHook | None = None,
    progress: ProgressFn | None = None,
) -> Playback:
    """Play an arm trajectory through the position actuators, targets updated every step.

    The commanded tool point is the analytic FK of the commanded joints
    (:func:`lynxsim.sim.joint_playback.play_joints` with the arm's binding).

    Args:
        model: An arm scene (see :func:`lynxsim.sim.arm.model.load_arm_scene`).
        trajectory: The joint trajectory.
        task: Task name for the report.
        data: Data to use (a new one if None).
        settle_s: Hold time after the trajectory [s].
        gripper_cmd: Gripper opening [m] over trajectory time [s].
        on_step: Called after every physics step (a monitor; the run then
            steps in a Python loop).
        progress: Called with the fraction of the stepping done, now and then.

    Returns:
        The :class:`~lynxsim.sim.summary.Playback` (report and log).
    """
    return play_joints(
        model,
        arm_binding(model),
        trajectory,
        arm_tool_points,
        task=task,
        data=data,
        settle_s=settle_s,
        gripper_cmd=gripper_cmd,
        on_step=on_step,
        progress=progress,
    )
