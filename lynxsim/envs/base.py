"""The machinery the arm envs share: options, scene, timing, control, the step loop.

:class:`LynxArmEnv` checks its options into an :class:`~lynxsim.envs.config.EnvConfig`
and owns an arm scene (:class:`lynxsim.sim.arm.env_scene.EnvScene`: the one
``MjModel``/``MjData`` pair, reached only through :mod:`lynxsim.sim`). A task
subclass says whether the scene holds the cube and the gripper is commanded,
draws the task at reset (:meth:`LynxArmEnv._sample_task`,
:mod:`lynxsim.envs.episodes`) and assembles the observation
(:meth:`LynxArmEnv._observation`). Controllers live in :mod:`lynxsim.envs.control`,
rewards in :mod:`lynxsim.envs.reward`, rendering in :mod:`lynxsim.sim.env_render`.
The step loop resolves nothing by name and allocates only the arrays it returns:
ids are resolved once, physics runs as ``mj_step(model, data, nstep=frame_skip)``,
and the observation is built from one ``tolist()`` of ``qpos`` and ``qvel``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from typing import Any, ClassVar, Literal

import gymnasium as gym
import numpy as np
import numpy.typing as npt

from lynxsim.arm import LYNX_ARM, ik_nearest, tool_pose_of
from lynxsim.envs.commanding import READY_TOOL_POSE, make_controller
from lynxsim.envs.config import (
    CollisionCheck,
    EnvConfig,
    check_control_dt,
    check_randomization,
    reset_options,
)
from lynxsim.envs.control import (
    ControlMode,
    JointSpaceController,
    TargetFallback,
    TargetStatus,
    ToolSpaceController,
)
from lynxsim.envs.episodes import WORK_CLEARANCE_M, WorkColumn
from lynxsim.envs.randomization import Domain, Randomization
from lynxsim.envs.reward import GoalRewards, RewardType, goal_distance, goal_reward
from lynxsim.envs.scene_draw import SceneDrawing
from lynxsim.envs.tool_action import ToolRollController
from lynxsim.envs.workspace import GRIP_ROLL_RAD
from lynxsim.errors import (
    InvalidInputError,
    LynxsimError,
    NonFiniteInputError,
)
from lynxsim.inputs import real_array
from lynxsim.scene import REPORT_CUBE, Obstacle, Scene
from lynxsim.sim.arm.env_scene import EnvScene
from lynxsim.sim.arm.randomizer import ModelRandomizer
from lynxsim.sim.arm.task import GRIPPER_OPEN_M
from lynxsim.sim.collision import CollisionChecker
from lynxsim.sim.env_render import RENDER_MODES, EnvRenderer, PixelRenderer, check_frame

__all__ = [
    "READY_TOOL_POSE",
    "WORK_CLEARANCE_M",
    "CollisionCheck",
    "Domain",
    "LynxArmEnv",
    "Randomization",
    "WorkColumn",
    "check_control_dt",
]

FloatArray = npt.NDArray[np.float64]
Obs = dict[str, npt.NDArray[Any]]
"""An observation: float64 arrays, and a uint8 ``"pixels"`` array with image observations."""


def clipped_actions(actions: FloatArray) -> list[list[float]]:
    """Rows of actions (N, A) clipped to [-1, 1], as lists: the single env's (N = 1), the batch's.

    Raises:
        NonFiniteInputError: A row holds NaN or infinity (the message shows it).
    """
    finite = np.isfinite(actions).all(axis=1)
    if not finite.all():
        row = actions[int(np.argmin(finite))].tolist()
        raise NonFiniteInputError(f"action must be finite, got {row}")
    rows: list[list[float]] = np.clip(actions, -1.0, 1.0).tolist()
    return rows


class LynxArmEnv(SceneDrawing, GoalRewards, gym.Env[Obs, npt.NDArray[np.float32]]):
    """Base of the arm envs (see :class:`~lynxsim.envs.PickAndPlaceEnv` for the manual).

    Args are keyword-only, ``gym.make``'s kwargs, with the defaults of the
    signature: those of :meth:`EnvConfig.of <lynxsim.envs.config.EnvConfig.of>`
    (documented there), checked into the env's :attr:`config`. A reset's
    ``options={"randomize": ...}`` overrides ``randomize`` for that episode.

    Raises:
        InvalidInputError: A bad argument (the message names it and the valid choices).
        InfeasibleSceneError: Options that can never produce an episode (fixed
            obstacles that block a task region, a success radius no goal lies
            outside of).
    """

    metadata: dict[str, Any] = {  # noqa: RUF012  (Gymnasium's convention; copied per instance)
        "render_modes": list(RENDER_MODES),
        "render_fps": 25,
    }

    _HAS_CUBE: ClassVar[bool] = False
    _GRIPPER_ACTION: ClassVar[bool] = False
    _OBS_SIZE: ClassVar[int] = 0

    def __init__(
        self,
        *,
        render_mode: str | None = None,
        control: Literal["tool", "tool_roll", "joint"] | ControlMode = "tool",
        target_fallback: Literal["nearest", "hold"] | TargetFallback = "nearest",
        reward_type: Literal["sparse", "dense"] | RewardType = "sparse",
        distance_threshold: float = 0.025,
        obstacles: Sequence[Obstacle] | None = None,
        random_obstacles: int | tuple[int, int] | None = None,
        collision_penalty: float = 0.0,
        terminate_on_collision: bool = False,
        collision_check: Literal["control_step", "physics_step"] | CollisionCheck = "control_step",
        control_dt: float = 0.04,
        position_step: float = 0.015,
        pitch_step: float = 0.1,
        roll_step: float = 0.1,
        joint_step: float = 0.05,
        width: int = 640,
        height: int = 480,
        camera: str = "front",
        render_quality: Literal["lean", "fast", "medium", "default"] = "fast",
        pixels: str | Sequence[str] = (),
        pixel_width: int = 84,
        pixel_height: int = 84,
        randomize: Randomization | None = None,
    ) -> None:
        config = EnvConfig.of(
            render_mode=render_mode,
            control=control,
            target_fallback=target_fallback,
            reward_type=reward_type,
            distance_threshold=distance_threshold,
            obstacles=obstacles,
            random_obstacles=random_obstacles,
            collision_penalty=collision_penalty,
            terminate_on_collision=terminate_on_collision,
            collision_check=collision_check,
            control_dt=control_dt,
            position_step=position_step,
            pitch_step=pitch_step,
            roll_step=roll_step,
            joint_step=joint_step,
            width=width,
            height=height,
            camera=camera,
            render_quality=render_quality,
            pixels=pixels,
            pixel_width=pixel_width,
            pixel_height=pixel_height,
            randomize=randomize,
        )
        self.config = config
        """The env's options, checked (an :class:`~lynxsim.envs.config.EnvConfig`)."""
        self.control = config.control
        self.reward_type = config.reward_type
        self.collision_check = config.collision_check
        self.distance_threshold = config.distance_threshold
        self.collision_penalty = config.collision_penalty
        self.terminate_on_collision = config.terminate_on_collision
        self.render_mode = config.render_mode
        self.random_obstacles = config.random_obstacles
        self._cube_spec = REPORT_CUBE if self._HAS_CUBE else None
        self._obstacles: tuple[Obstacle, ...] = config.obstacles
        spare = None if self.random_obstacles is None else self.random_obstacles[1]
        scene = self._scene = EnvScene(self._obstacles, self._cube_spec, spare)
        self.table_top_z = scene.table_top_z
        self.model = scene.model
        self.data = scene.data
        self._slots = scene.slots
        self.frame_skip = config.frame_skip(scene.timestep)
        for frame in (config.frames, *config.pixels):
            check_frame(self.model, frame)
        fps = self._control_rate = 1.0 / self.dt
        self.metadata = {
            **self.metadata,
            "render_fps": round(fps) if abs(fps - round(fps)) < 1e-9 else fps,
        }
        self._renderer = EnvRenderer(self.model, config.render_mode, config.frames)
        self._pixels = PixelRenderer(self.model, config.pixels) if config.pixels else None
        self._resolve_ids()
        self.randomize = self._check_randomization(config.randomize, "randomize")
        self._randomizer = ModelRandomizer(
            self.model, self.data, self._arm_act, self._arm_dof, self.ids.cube_geom, REPORT_CUBE
        )
        self._controller = make_controller(config)
        n_act = (4 if self.control is ControlMode.TOOL else 5) + int(self._GRIPPER_ACTION)
        self._n_act = n_act
        self.action_space = gym.spaces.Box(-1.0, 1.0, shape=(n_act,), dtype=np.float32)
        box = gym.spaces.Box(-np.inf, np.inf, shape=(3,), dtype=np.float64)
        spaces: dict[str, gym.Space[Any]] = {
            "observation": gym.spaces.Box(
                -np.inf, np.inf, shape=(self._OBS_SIZE,), dtype=np.float64
            ),
            "achieved_goal": box,
            "desired_goal": box,
        }
        if config.pixels:
            first = config.pixels[0]
            shape = (first.height, first.width, 3 * len(config.pixels))
            spaces["pixels"] = gym.spaces.Box(0, 255, shape=shape, dtype=np.uint8)
        self.observation_space = gym.spaces.Dict(spaces)  # type: ignore[assignment]
        status, q_ready = ik_nearest(*READY_TOOL_POSE, GRIP_ROLL_RAD, LYNX_ARM.q_min)
        if q_ready is None:  # pragma: no cover - a property of the arm, tested at reset
            raise LynxsimError(f"the ready pose is unreachable ({status.name})")
        self._q_ready = q_ready
        base = self.model.qpos0.copy()
        base[self._finger_qpos] = 0.5 * GRIPPER_OPEN_M
        self._checker = scene.checker(base)
        self._set_goal(np.zeros(3))
        self._tool_now: tuple[float, float, float] = (0.0, 0.0, 0.0)
        self._check_feasible()

    # ----------------------------------------------------------------- setup

    def _resolve_ids(self) -> None:
        scene = self._scene
        self.ids = scene.ids
        self._arm_qpos = scene.arm_qpos
        self._arm_dof = scene.arm_dofs
        self._arm_act = scene.arm_actuators
        self._grip_act = scene.gripper_actuator
        self._finger_qpos = scene.finger_qpos
        self._finger_dof = scene.finger_dofs
        self._goal_mark = scene.goal_mark

    def _check_randomization(self, value: object, name: str) -> Randomization | None:
        """``value`` if None or a :class:`Randomization` this env can apply, else raise."""
        return check_randomization(value, name, has_cube=self._HAS_CUBE, env=type(self).__name__)

    def _randomize_model(self, r: Randomization | None) -> None:
        """Draw the episode's physical parameters into the model (None: the nominal ones)."""
        cube = self._randomizer.apply(r, self.np_random)
        if self._cube_spec is not None:
            self._cube_spec = cube

    @property
    def domain(self) -> Domain:
        """The episode's physical parameters: drawn at reset with randomisation, else nominal."""
        return self._randomizer.domain

    @property
    def scene(self) -> Scene:
        """The scene now: the episode's obstacles, and the cube where it is."""
        cube, pose = self._cube_spec, self._scene.cube_pose()
        if cube is not None and pose is not None:
            cube = replace(cube, position=pose[:3], yaw=pose[3])
        return Scene(self._obstacles, cube=cube)

    @property
    def collision_checker(self) -> CollisionChecker:
        """Collision verdicts and clearances of arm configurations in this env's scene.

        Kinematics only, on a private ``MjData``; the gripper open, the cube held at
        the tool point with ``grasped=True``. It sees the episode's obstacles.
        """
        return self._checker

    @property
    def q_ready(self) -> tuple[float, ...]:
        """Joints of the ready pose (:data:`READY_TOOL_POSE`), 5 values [rad]."""
        return tuple(self._q_ready)

    @property
    def controller(self) -> ToolSpaceController | JointSpaceController:
        """What turns actions into servo targets (its ``q_cmd`` and ``target``: the command)."""
        return self._controller

    # -------------------------------------------------------------- timing

    @property
    def dt(self) -> float:
        """Control period [s]: ``frame_skip`` physics steps."""
        return float(self.model.opt.timestep) * self.frame_skip

    # -------------------------------------------------------------- reset

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[Obs, dict[str, Any]]:
        """Start an episode: the whole simulation state is set, nothing carries over.

        Args:
            seed: Seeds ``np_random`` (None continues its stream).
            options: None, or a dict whose only key may be ``"randomize"``: a
                :class:`Randomization` (or None: none) that replaces the
                constructor's ``randomize`` for this episode.

        Returns:
            The observation and an info dict with the keys of :meth:`step`'s
            (``is_success`` False, no collision, target ACCEPTED).

        Raises:
            InvalidInputError: ``seed`` is not None or a non-negative integer, or
                ``options`` not None or a dict of the keys above, or its
                ``"randomize"`` not a :class:`Randomization` this env can apply.
        """
        seed, randomize = reset_options(seed, options, self.randomize)
        randomize = self._check_randomization(randomize, "options['randomize']")
        super().reset(seed=seed)
        self._randomize_model(randomize)
        q = self._q_ready
        self._scene.rest(q, 0.5 * GRIPPER_OPEN_M, GRIPPER_OPEN_M)
        self._controller.reset(q)
        if self._slots is None:
            self._sample_task()
        else:
            self._sample_scene(self._slots)
        self._scene.forward()
        x, y, z, _ = tool_pose_of(q)
        self._tool_now = (x, y, z)
        obs = self._observation()
        if self._pixels is not None:
            obs["pixels"] = self._pixels.render(self.data)
        if self.render_mode == "human":
            self.render()
        return obs, self._info(obs, False, TargetStatus.ACCEPTED, held=False)

    # --------------------------------------------------------------- step

    def step(self, action: npt.ArrayLike) -> tuple[Obs, float, bool, bool, dict[str, Any]]:
        """Advance one control period.

        Args:
            action: Shape ``action_space.shape``, values clipped to [-1, 1].

        Returns:
            ``(observation, reward, terminated, truncated, info)``; ``truncated`` is
            always False here (the time limit is a wrapper). ``info`` holds
            ``is_success``, ``collision``, ``distance`` [m], ``reward_goal``,
            ``reward_collision``, ``target_status`` (a :class:`TargetStatus` value)
            and ``target_held``.

        Raises:
            InvalidInputError: The action is not real numbers (strings, None,
                booleans, complex numbers, object arrays...) or has the wrong shape.
            NonFiniteInputError: The action holds NaN or infinity.
        """
        command = self._command(action)
        return self._outcome(command, self._simulate())

    def _command(self, action: npt.ArrayLike) -> tuple[TargetStatus, bool]:
        """Check an action and write its servo targets into ``data.ctrl`` (a step's first part).

        Returns:
            What became of the tool target, and whether it was held.

        Raises:
            InvalidInputError: As :meth:`step`.
            NonFiniteInputError: As :meth:`step`.
        """
        return self._command_values(self._action_values(action))

    def _command_values(self, values: list[float]) -> tuple[TargetStatus, bool]:
        """:meth:`_command` of an action already checked and clipped (:func:`clipped_actions`)."""
        before = self._controller.target
        return self._commanded(values, self._controller.apply(values), before)

    def _action_values(self, action: npt.ArrayLike) -> list[float]:
        """The action checked (as :meth:`step` says), its values clipped to [-1, 1]."""
        a = real_array(action, "action")
        if a.shape != (self._n_act,):
            raise InvalidInputError(f"action must have shape ({self._n_act},), got {a.shape}")
        return clipped_actions(a[None, :])[0]

    def _commanded(
        self, values: list[float], status: TargetStatus, before: tuple[float, ...]
    ) -> tuple[TargetStatus, bool]:
        """Write the controller's command (moved by ``values``) into ``data.ctrl``.

        Args:
            values: The action (:meth:`_action_values`).
            status: What the controller made of it.
            before: The controller's target before it.
        """
        ctrl = self.data.ctrl
        ctrl[self._arm_act] = self._controller.q_cmd
        if self._GRIPPER_ACTION:
            ctrl[self._grip_act] = (values[-1] + 1.0) * (0.5 * GRIPPER_OPEN_M)
        return status, self._controller.target == before

    def _outcome(
        self, command: tuple[TargetStatus, bool], collision: bool
    ) -> tuple[Obs, float, bool, bool, dict[str, Any]]:
        """A step's result once its physics ran (its last part; :meth:`step` returns it).

        Args:
            command: What :meth:`_command` returned.
            collision: Whether the arm or the cube touched an obstacle.
        """
        status, held = command
        obs = self._observation()
        if self._pixels is not None:
            obs["pixels"] = self._pixels.render(self.data)
        info = self._info(obs, collision, status, held=held)
        terminated = collision and self.terminate_on_collision
        if self.render_mode == "human":
            self.render()
        return obs, info["reward_goal"] + info["reward_collision"], terminated, False, info

    def _info(
        self, obs: Obs, collision: bool, status: TargetStatus, *, held: bool
    ) -> dict[str, Any]:
        """The info dict of a step (and, with no collision and status ACCEPTED, of a reset)."""
        d = goal_distance(obs["achieved_goal"], self._goal)
        distance = float(d)
        reward_goal = float(goal_reward(d, self.distance_threshold, self.reward_type))
        info: dict[str, Any] = {
            "is_success": distance <= self.distance_threshold,
            "collision": collision,
            "distance": distance,
            "reward_goal": reward_goal,
            "reward_collision": -self.collision_penalty if collision else 0.0,
            "target_status": int(status),
            "target_held": status is not TargetStatus.ACCEPTED and held,
            "target_shortfall_m": self._controller.shortfall_m,
            "target_shortfall_rad": self._controller.shortfall_rad,
        }
        if isinstance(self._controller, ToolRollController):
            info["target_correction"] = np.array(self._controller.correction)
        return info

    def _simulate(self) -> bool:
        """Run the control period's physics steps; True on arm–obstacle contact."""
        return self._scene.simulate(self.frame_skip, every_step=self._physics_step_contacts)

    @property
    def _physics_step_contacts(self) -> bool:
        """Whether the contacts are tested after every physics step (else after the last)."""
        return self.collision_check is CollisionCheck.PHYSICS_STEP

    def _touching_obstacle(self) -> bool:
        """Whether the arm or the cube touches an obstacle in the current contacts."""
        return self._scene.touching_obstacle()

    # -------------------------------------------------------- observation

    def _observation(self) -> Obs:
        """The observation dict; every array is new (never a view of the simulation)."""
        raise NotImplementedError

    def _tool_state(self, q: list[float]) -> tuple[float, float, float, float, float, float, float]:
        """Tool point, pitch and tool-point velocity from the measured joints.

        The velocity is the change of the tool point over the last control period
        divided by it (zero right after reset) [m/s].
        """
        x, y, z, pitch = tool_pose_of(q)
        px, py, pz = self._tool_now
        rate = self._control_rate
        self._tool_now = (x, y, z)
        return x, y, z, pitch, (x - px) * rate, (y - py) * rate, (z - pz) * rate

    def _set_goal(self, goal: npt.ArrayLike) -> None:
        """Set the episode's goal, shape (3,) [m], and move the table mark below it."""
        self._goal = np.array(goal, dtype=np.float64).reshape(3)
        self.model.site_pos[self._goal_mark, :2] = self._goal[:2]

    @property
    def goal(self) -> FloatArray:
        """The desired goal of the episode, shape (3,) [m] (a copy)."""
        return self._goal.copy()

    # ---------------------------------------------------------- rendering

    def render(self) -> npt.NDArray[np.uint8] | None:
        """An RGB frame (``rgb_array``: shape (height, width, 3), uint8), or None.

        The goal is marked by an orange sphere. The renderer (and its GL context)
        is created on the first call, in the process that calls it.
        """
        frame: npt.NDArray[np.uint8] | None = self._renderer.render(self.data, self._goal)
        return frame

    @property
    def pixel_cameras(self) -> tuple[str, ...]:
        """Cameras of the image observation, in channel order (empty without one)."""
        return () if self._pixels is None else tuple(s.camera for s in self._pixels.settings)

    def close(self) -> None:
        """Free the renderers and close the viewer window, if any."""
        self._renderer.close()
        if self._pixels is not None:
            self._pixels.close()
