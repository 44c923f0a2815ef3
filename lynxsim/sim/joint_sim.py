"""The simulation side of any joint robot in the table scene, from its names and kinematics.

:class:`JointRobotSim` implements :class:`~lynxsim.sim.adapter.SimAdapter` for a
robot whose motions are joint trajectories, from what its MJCF scene names
(:class:`~lynxsim.sim.joint_robot.JointRobotNames`), its
:class:`~lynxsim.traj.Kinematics` and, if it grips the scene's cube, its
gripper's schedule. Its model is the robot's scene with the task's scene built
in (:func:`~lynxsim.sim.joint_robot.load_joint_scene`); its checker the batch
:class:`~lynxsim.sim.collision.CollisionChecker` of its joints (the cube held at
the tool site when it grips); its play and its recorded runs those of
:mod:`lynxsim.sim.joint_playback`. It takes the run option
:data:`~lynxsim.run_options.NO_OBSTACLE` if its record declares it.

A new robot's adapter is one instance::

    ADAPTER: SimAdapter = JointRobotSim(
        name="planar_arm", scene_xml=HERE / "scene.xml", names=NAMES, kinematics=KINEMATICS
    )
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError
from lynxsim.inputs import instance
from lynxsim.run_options import NO_OBSTACLE, RunValues
from lynxsim.scene import Scene
from lynxsim.sim.collision import CollisionChecker, CollisionGroups
from lynxsim.sim.joint_playback import Gripper, record_joints, run_joints
from lynxsim.sim.joint_robot import JointRobotIds, JointRobotNames, load_joint_scene
from lynxsim.sim.recorded import RecordedRun
from lynxsim.sim.recording import ProgressFn
from lynxsim.sim.render import RenderSettings
from lynxsim.sim.summary import Playback
from lynxsim.tasks import Task
from lynxsim.traj import Kinematics, Trajectory
from lynxsim.traj.motion import Motion

__all__ = ["GripperSchedule", "JointRobotSim", "Targets"]

FloatArray = npt.NDArray[np.float64]

GripperSchedule = Callable[[float], Gripper]
"""A motion's duration [s] in, the gripper's opening [m] over its time [s] out."""
Targets = Callable[[Trajectory], FloatArray]
"""A trajectory in, the points its video and replay mark out, (M, 3) [m]."""
_DEFAULT_RENDER = RenderSettings()


@dataclass(frozen=True)
class JointRobotSim:
    """A joint robot's simulation side (:class:`~lynxsim.sim.adapter.SimAdapter`).

    Attributes:
        name: The robot's name (its trajectories' joints are its kinematics').
        scene_xml: Its MJCF scene (robot, table, obstacle class, optional cube,
            lights, cameras), named as :mod:`lynxsim.sim.scene_build` says.
        names: What the scene names of the robot.
        kinematics: Its joints and tool.
        gripper: Its gripper's schedule when the scene has a cube, or None
            (no gripper: the cube stays where it lies).
        targets: The points a trajectory's video and replay mark (None: the
            tool points of its waypoints).
        owner: Names the robot in messages about its scene (default its name).
        render: Video settings when none are given (its default camera first).
        settle_s: Hold after the motion [s].
    """

    name: str
    scene_xml: str | os.PathLike[str]
    names: JointRobotNames
    kinematics: Kinematics
    gripper: GripperSchedule | None = None
    targets: Targets | None = None
    owner: str | None = None
    render: RenderSettings = _DEFAULT_RENDER
    settle_s: float = 0.5

    def _owner(self) -> str:
        return self.name if self.owner is None else self.owner

    def _trajectory(self, motion: Motion) -> Trajectory:
        trajectory = instance(motion, Trajectory, "motion")
        if trajectory.n_joints != self.kinematics.n_joints:
            raise InvalidInputError(
                f"robot {self.name!r} moves {self.kinematics.n_joints} joints, the trajectory "
                f"{trajectory.n_joints}"
            )
        return trajectory

    def _schedule(self, scene: Scene, trajectory: Trajectory) -> Gripper | None:
        if self.gripper is None or scene.cube is None:
            return None
        return self.gripper(trajectory.duration)

    def _targets(self, trajectory: Trajectory) -> FloatArray:
        if self.targets is not None:
            return self.targets(trajectory)
        return self.kinematics.tool_points(trajectory.waypoints.q)

    def model(self, scene: Scene) -> mujoco.MjModel:
        """The robot's scene with ``scene`` built in, compiled with its recording sensors."""
        return load_joint_scene(Path(self.scene_xml), self.names, scene, owner=self._owner())

    def ids(self, model: mujoco.MjModel) -> JointRobotIds:
        """The robot's ids in a compiled scene."""
        return JointRobotIds.from_model(model, self.names)

    def checker(self, scene: Scene) -> CollisionChecker:
        """The batch checker of the robot's joints in ``scene`` (the cube held when it grips)."""
        model = self.model(scene)
        ids = self.ids(model)
        cube = ids.table.cube_qpos
        attach = None if cube is None or self.gripper is None else (cube, ids.tool_site)
        return CollisionChecker(model, ids.collision_groups(model), ids.qpos, attach=attach)

    def scene_model(self, scene: Scene) -> tuple[mujoco.MjModel, CollisionGroups]:
        """The scene compiled, and its collision groups (the sweep's placement judge)."""
        model = self.model(scene)
        return model, self.ids(model).collision_groups(model)

    def _scene(self, task: Task, options: RunValues | None) -> Scene:
        if options is not None and NO_OBSTACLE.name in options and options.flag(NO_OBSTACLE.name):
            return task.scene.without_obstacles()
        return task.scene

    def play(
        self,
        task: Task,
        motion: Motion,
        *,
        options: RunValues | None = None,
        video: str | os.PathLike[str] | None = None,
        render: RenderSettings | None = None,
        progress: ProgressFn | None = None,
        replay: str | os.PathLike[str] | None = None,
    ) -> Playback:
        """Play a task's trajectory in its scene (``no_obstacle``: without its obstacles)."""
        trajectory = self._trajectory(motion)
        scene = self._scene(task, options)
        model = self.model(scene)
        return run_joints(
            model,
            self.ids(model).binding(model),
            trajectory,
            self.kinematics.tool_points,
            task=task.name,
            targets=self._targets(trajectory),
            render=self.render if render is None else render,
            video=video,
            settle_s=self.settle_s,
            gripper_cmd=self._schedule(scene, trajectory),
            progress=progress,
            replay=replay,
        )

    def record(self, task: Task, motion: Motion, scene: Scene) -> RecordedRun:
        """Play a task's trajectory in ``scene`` as :meth:`play` does, keeping every state."""
        trajectory = self._trajectory(motion)
        playback = self.play(dataclasses.replace(task, scene=scene), trajectory)
        model = self.model(scene)
        return record_joints(
            playback,
            model,
            self.ids(model).binding(model),
            trajectory,
            self.kinematics.tool_points,
            task=task.name,
            scene=scene,
            gripper=self._schedule(scene, trajectory),
        )
