"""The machinery the arm envs share: scene, timing, control, contacts, the step loop.

:class:`LynxArmEnv` owns one :class:`mujoco.MjModel`/:class:`mujoco.MjData` pair
built by :func:`lynxsim.sim.load_arm_scene`. A task subclass says whether the
scene holds the cube and the gripper is commanded, draws the task at reset
(:meth:`LynxArmEnv._sample_task`) and assembles the observation
(:meth:`LynxArmEnv._observation`). Controllers live in :mod:`lynxsim.envs.control`,
rewards in :mod:`lynxsim.envs.reward`, rendering in :mod:`lynxsim.envs.rendering`.
The step loop resolves nothing by name and allocates only the arrays it returns:
ids are resolved once, physics runs as ``mj_step(model, data, nstep=frame_skip)``,
and the observation is built from one ``tolist()`` of ``qpos`` and ``qvel``.
"""

from __future__ import annotations

import enum
import math
from collections.abc import Sequence
from dataclasses import replace
from typing import Any, ClassVar, Literal, NamedTuple

import gymnasium as gym
import numpy as np
import numpy.typing as npt

# lynxsim.sim chooses the GL backend (MUJOCO_GL), which mujoco reads when first imported.
import lynxsim.sim  # noqa: F401

# isort: split
import mujoco

from lynxsim.arm import LYNX_ARM, ik_nearest, tool_pose_of
from lynxsim.bounds import (
    MAX_CONTROL_DT_S,
    MAX_COORDINATE_M,
    MAX_RANDOM_OBSTACLES,
    check_range,
)
from lynxsim.envs.control import (
    ControlMode,
    JointSpaceController,
    TargetFallback,
    TargetStatus,
    ToolSpaceController,
)
from lynxsim.envs.randomization import Domain, ModelRandomizer, Randomization
from lynxsim.envs.rendering import RENDER_MODES, EnvRenderer, PixelRenderer
from lynxsim.envs.reward import RewardType, collision_flags, goal_distance, goal_reward
from lynxsim.envs.workspace import (
    GRIP_ROLL_RAD,
    TOP_DOWN_PITCH_RAD,
    PolarRegion,
    clear_of_obstacle,
    sample_points,
    top_down_reachable,
    work_column,
)
from lynxsim.errors import InvalidInputError, LynxsimError, NonFiniteInputError
from lynxsim.inputs import count, real_array
from lynxsim.random_scenes import random_obstacles
from lynxsim.scene import REPORT_CUBE, REPORT_CYLINDER, Box, Cylinder, Obstacle, Scene, Sphere
from lynxsim.sim.arm.model import SceneIds, load_arm_spec, table_top_z
from lynxsim.sim.arm.playback import arm_checker
from lynxsim.sim.arm.slots import ObstacleSlots, add_obstacle_slots
from lynxsim.sim.arm.task import GRIPPER_OPEN_M
from lynxsim.sim.collision import CollisionChecker
from lynxsim.sim.render import Quality, RenderSettings

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

READY_TOOL_POSE = (0.18, 0.0, 0.08, TOP_DOWN_PITCH_RAD)
"""Tool point (x, y, z) [m] and pitch [rad] of the arm at reset: 18 cm in front of
the base, 8 cm above the base plane, gripper pointing down."""

_TARGET_BOX_LOWER = (-0.30, -0.45, -0.004)
"""Lower corner of the tool-target box [m]; z keeps the fingertips (8 mm past the
tool point) above the table top (z = -12.5 mm) when the gripper points down."""
_TARGET_BOX_UPPER = (0.45, 0.45, 0.50)
_MAX_JOINT_JUMP_RAD = 0.5
_GOAL_MARK_SITE = "place_target"
"""The scene's green disc on the table; it is moved below the goal (visual only)."""
_DRAW_BATCH = 16
_MAX_DRAWS = 100
_MAX_FRAME_PX = 16_384
"""Largest frame side accepted before the model's off-screen buffer is known [px]."""
_MAX_PENALTY = 1e6
"""Largest collision penalty (rewards are -1..0 or minus metres)."""
WORK_CLEARANCE_M = 0.015
"""Clearance from every randomised obstacle that the arm keeps at the ready pose and
wherever it works at the cube and the goal (:func:`~lynxsim.envs.workspace.work_column`) [m]."""
_OBSTACLE_GAP_M = 0.06
"""Least distance from a randomised obstacle to the cube, the goal and the ready tool point [m]."""
_MAX_SCENE_DRAWS = 200
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


class CollisionCheck(enum.Enum):
    """When the arm–obstacle contact test runs.

    CONTROL_STEP: on the contacts of the last physics step of each control period
        (one test per env step; the default, cheap).
    PHYSICS_STEP: after every physics step (exact: a graze shorter than the
        control period is caught; costs a Python loop over the physics steps).
    """

    CONTROL_STEP = "control_step"
    PHYSICS_STEP = "physics_step"


def _real(value: object, name: str, low: float, high: float, unit: str = "") -> float:
    """A real number (no bool, str, complex...) in ``[low, high]`` as a float, or raise.

    Raises:
        InvalidInputError: Not a real number, or out of range (the message states it).
        NonFiniteInputError: NaN or infinity.
    """
    if isinstance(value, bool | np.bool_) or not isinstance(
        value, int | float | np.integer | np.floating
    ):
        raise InvalidInputError(f"{name} must be a number, got {value!r}")
    try:
        return check_range(value, name, low, high, unit)  # type: ignore[arg-type]
    except InvalidInputError as exc:
        if not isinstance(value, int) and math.isnan(float(value)):
            raise NonFiniteInputError(str(exc)) from None
        if not isinstance(value, int) and math.isinf(float(value)):
            raise NonFiniteInputError(str(exc)) from None
        raise


def check_control_dt(control_dt: float, timestep: float) -> int:
    """Frame skip for a control period, which must be a whole number of physics steps.

    Args:
        control_dt: Control period [s], from ``timestep`` to
            :data:`~lynxsim.bounds.MAX_CONTROL_DT_S`.
        timestep: Physics step [s].

    Returns:
        Physics steps per control step, >= 1.

    Raises:
        InvalidInputError: The period is not a number, outside
            [timestep, MAX_CONTROL_DT_S] (the message states the range), or not a
            whole multiple of the step.
        NonFiniteInputError: The period is NaN or infinite.
    """
    timestep = _real(timestep, "timestep", 1e-9, MAX_CONTROL_DT_S, "s")
    control_dt = _real(control_dt, "control_dt", timestep, MAX_CONTROL_DT_S, "s")
    ratio = control_dt / timestep
    n = round(ratio)
    if n < 1 or abs(ratio - n) > 1e-6:
        raise InvalidInputError(
            f"control_dt = {control_dt} s is not a whole multiple of the physics timestep "
            f"{timestep} s (ratio {ratio:.6g}); use e.g. {max(n, 1) * timestep:g} s"
        )
    return n


def _enum(kind: type[enum.Enum], value: object, name: str) -> Any:
    try:
        return kind(value.value if isinstance(value, kind) else value)
    except (ValueError, TypeError):
        choices = ", ".join(repr(m.value) for m in kind)
        raise InvalidInputError(f"{name} must be one of {choices}, got {value!r}") from None


class LynxArmEnv(gym.Env[Obs, npt.NDArray[np.float32]]):
    """Base of the arm envs (see :class:`~lynxsim.envs.PickAndPlaceEnv` for the manual).

    Args:
        render_mode: None, ``"rgb_array"`` (off-screen) or ``"human"`` (a passive
            :mod:`mujoco.viewer` window; needs a display).
        control: ``"tool"`` (tool-space deltas through the IK) or ``"joint"``.
        target_fallback: What a tool request the IK cannot reach does: ``"nearest"``
            (the feasible target nearest it; ``-v1``) or ``"hold"`` (the previous
            target; ``-v0``); see :class:`~lynxsim.envs.control.TargetFallback`.
        reward_type: ``"sparse"`` or ``"dense"``.
        distance_threshold: Success radius around the goal [m].
        obstacles: The obstacles (:mod:`lynxsim.scene`; default: the report's cylinder,
            or none with ``random_obstacles``; ``()`` for none).
        random_obstacles: ``(fewest, most)`` obstacles (or one number) drawn anew at
            every reset, at most :data:`~lynxsim.bounds.MAX_RANDOM_OBSTACLES`; None (default) keeps
            ``obstacles`` fixed. Exclusive with ``obstacles``.
        collision_penalty: Subtracted from the reward on a step with arm–obstacle
            contact, >= 0.
        terminate_on_collision: End the episode on arm–obstacle contact.
        collision_check: ``"control_step"`` or ``"physics_step"`` (see :class:`CollisionCheck`).
        control_dt: Control period [s], a whole multiple of the 2 ms physics step.
        position_step: Tool-point move for a tool action of 1 [m].
        pitch_step: Pitch change for a tool action of 1 [rad].
        joint_step: Joint change for a joint action of 1 [rad].
        width: Frame width [px].
        height: Frame height [px].
        camera: Camera of the scene (``"front"`` or ``"top"``).
        render_quality: ``"fast"`` (no shadows), ``"medium"`` (shadows) or ``"default"``
            (shadows and multisampling); of ``render()`` frames and image observations.
        pixels: Cameras of the image observation (``"front"``, ``"top"``), in
            channel order; a name or a sequence of distinct names; ``()`` (default):
            no ``"pixels"`` entry.
        pixel_width: Width of the image observation [px].
        pixel_height: Height of the image observation [px].
        randomize: Domain randomisation drawn at every reset (a
            :class:`Randomization`); None (default): the nominal model. A reset's
            ``options={"randomize": ...}`` overrides it for that episode.

    Raises:
        InvalidInputError: A bad argument (the message names it and the valid choices).
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
        control: Literal["tool", "joint"] | ControlMode = "tool",
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
        joint_step: float = 0.05,
        width: int = 640,
        height: int = 480,
        camera: str = "front",
        render_quality: Literal["fast", "medium", "default"] = "fast",
        pixels: str | Sequence[str] = (),
        pixel_width: int = 84,
        pixel_height: int = 84,
        randomize: Randomization | None = None,
    ) -> None:
        quality = _enum(Quality, render_quality, "render_quality")
        pixel_settings = _pixel_settings(pixels, pixel_width, pixel_height, quality)
        if not isinstance(camera, str):
            raise InvalidInputError(f"camera must be a camera name (a string), got {camera!r}")
        width = count(width, "width", 1, _MAX_FRAME_PX)
        height = count(height, "height", 1, _MAX_FRAME_PX)
        settings = RenderSettings(width=width, height=height, camera=camera, quality=quality)
        self.control = _enum(ControlMode, control, "control")
        fallback = _enum(TargetFallback, target_fallback, "target_fallback")
        self.reward_type = _enum(RewardType, reward_type, "reward_type")
        self.collision_check = _enum(CollisionCheck, collision_check, "collision_check")
        self.distance_threshold = _real(
            distance_threshold, "distance_threshold", 0.0, MAX_COORDINATE_M, "m"
        )
        if self.distance_threshold == 0.0:
            raise InvalidInputError("distance_threshold must be > 0 m, got 0")
        self.collision_penalty = _real(collision_penalty, "collision_penalty", 0.0, _MAX_PENALTY)
        if not isinstance(terminate_on_collision, bool | np.bool_):
            raise InvalidInputError(
                f"terminate_on_collision must be True or False, got {terminate_on_collision!r}"
            )
        self.terminate_on_collision = bool(terminate_on_collision)
        position_step = _real(position_step, "position_step", 0.0, MAX_COORDINATE_M, "m")
        pitch_step = _real(pitch_step, "pitch_step", 0.0, 2.0 * math.pi, "rad")
        joint_step = _real(joint_step, "joint_step", 0.0, 2.0 * math.pi, "rad")
        for name, value in (
            ("position_step", position_step),
            ("pitch_step", pitch_step),
            ("joint_step", joint_step),
        ):
            if value == 0.0:
                raise InvalidInputError(f"{name} must be a positive number, got 0")
        if render_mode is not None and not (
            isinstance(render_mode, str) and render_mode in RENDER_MODES
        ):
            raise InvalidInputError(
                f"render_mode must be None or one of {list(RENDER_MODES)}, got {render_mode!r}"
            )
        self.render_mode = render_mode
        self.random_obstacles = _obstacle_range(random_obstacles)
        if obstacles is None:
            obstacles = (REPORT_CYLINDER,) if self.random_obstacles is None else ()
        elif self.random_obstacles is not None:
            raise InvalidInputError("give obstacles or random_obstacles, not both")
        if not isinstance(obstacles, list | tuple) or not all(
            isinstance(o, Cylinder | Box | Sphere) for o in obstacles
        ):
            raise InvalidInputError(
                f"obstacles must be a sequence of Cylinder, Box or Sphere, got {obstacles!r}"
            )
        self._cube_spec = REPORT_CUBE if self._HAS_CUBE else None
        self._obstacles: tuple[Obstacle, ...] = tuple(obstacles)
        spec = load_arm_spec(Scene(self._obstacles, cube=self._cube_spec))
        if self.random_obstacles is not None:
            add_obstacle_slots(spec, self.random_obstacles[1])
        self.table_top_z = table_top_z(spec)
        self.model = spec.compile()
        self.data = mujoco.MjData(self.model)
        self._slots = (
            None if self.random_obstacles is None else ObstacleSlots.from_model(self.model)
        )
        if self._slots is not None:
            self._slots.place(())
        self.frame_skip = check_control_dt(control_dt, float(self.model.opt.timestep))
        for frame in (settings, *pixel_settings):
            _check_frame(self.model, frame)
        fps = self._control_rate = 1.0 / self.dt
        self.metadata = {
            **self.metadata,
            "render_fps": round(fps) if abs(fps - round(fps)) < 1e-9 else fps,
        }
        self._renderer = EnvRenderer(self.model, render_mode, settings)
        self._pixels = PixelRenderer(self.model, pixel_settings) if pixel_settings else None
        self._resolve_ids()
        self.randomize = self._check_randomization(randomize, "randomize")
        self._randomizer = ModelRandomizer(
            self.model, self.data, self._arm_act, self._arm_dof, self.ids.cube_geom, REPORT_CUBE
        )

        if self.control is ControlMode.TOOL:
            self._controller: ToolSpaceController | JointSpaceController = ToolSpaceController(
                position_step,
                pitch_step,
                GRIP_ROLL_RAD,
                _TARGET_BOX_LOWER,
                _TARGET_BOX_UPPER,
                max_joint_jump=_MAX_JOINT_JUMP_RAD,
                fallback=fallback,
            )
            n_arm = 4
        else:
            self._controller = JointSpaceController(joint_step)
            n_arm = 5
        n_act = n_arm + int(self._GRIPPER_ACTION)
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
        if pixel_settings:
            first = pixel_settings[0]
            shape = (first.height, first.width, 3 * len(pixel_settings))
            spaces["pixels"] = gym.spaces.Box(0, 255, shape=shape, dtype=np.uint8)
        self.observation_space = gym.spaces.Dict(spaces)  # type: ignore[assignment]
        status, q_ready = ik_nearest(*READY_TOOL_POSE, GRIP_ROLL_RAD, LYNX_ARM.q_min)
        if q_ready is None:  # pragma: no cover - a property of the arm, tested at reset
            raise LynxsimError(f"the ready pose is unreachable ({status.name})")
        self._q_ready = q_ready
        base = self.model.qpos0.copy()
        base[self._finger_qpos] = 0.5 * GRIPPER_OPEN_M
        self._checker = arm_checker(self.model, base)
        self._set_goal(np.zeros(3))
        self._tool_now: tuple[float, float, float] = (0.0, 0.0, 0.0)

    # ----------------------------------------------------------------- setup

    def _resolve_ids(self) -> None:
        m = self.model
        ids = SceneIds.from_model(m)
        self.ids = ids
        self._arm_qpos = list(ids.arm_qpos)
        self._arm_dof = list(ids.arm_dofs)
        self._arm_act = _as_index(ids.arm_actuators)
        self._grip_act = ids.gripper_actuator
        self._finger_qpos = [int(m.jnt_qposadr[j]) for j in ids.finger_joints]
        self._finger_dof = [int(m.jnt_dofadr[j]) for j in ids.finger_joints]
        groups = ids.collision_groups(m)
        self._arm_obstacle_pairs = groups.obstacle_pairs()
        self._has_obstacle = bool(len(groups.obstacle_geoms))
        self._goal_mark = m.site(_GOAL_MARK_SITE).id

    def _check_randomization(self, value: object, name: str) -> Randomization | None:
        """``value`` if None or a :class:`Randomization` this env can apply, else raise."""
        if value is None:
            return None
        if not isinstance(value, Randomization):
            raise InvalidInputError(
                f"{name} must be None or a lynxsim.envs.Randomization, got {value!r}"
            )
        if value.touches_cube and not self._HAS_CUBE:
            raise InvalidInputError(
                f"{name} randomises the cube, but {type(self).__name__} has no cube: "
                f"leave cube_size_m, cube_mass_kg and cube_friction None"
            )
        return value

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
    def obstacles(self) -> tuple[Obstacle, ...]:
        """The obstacles of the episode (drawn at reset with ``random_obstacles``)."""
        return self._obstacles

    @property
    def scene(self) -> Scene:
        """The scene now: the episode's obstacles, and the cube where it is."""
        cube = self._cube_spec
        adr = self.ids.cube_qpos
        if cube is not None and adr is not None:
            w, _, _, z = self.data.qpos[adr + 3 : adr + 7].tolist()
            x, y, h = self.data.qpos[adr : adr + 3].tolist()
            cube = replace(cube, position=(x, y, h), yaw=2.0 * math.atan2(z, w))
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

    # ------------------------------------------------------------- reward

    def compute_reward(
        self, achieved_goal: npt.ArrayLike, desired_goal: npt.ArrayLike, info: Any
    ) -> FloatArray:
        """Reward of goals, vectorised over leading axes (for hindsight relabelling).

        Equals the reward :meth:`step` returned for the same goals and info, bit for bit.

        Args:
            achieved_goal: Achieved goals, shape (..., 3) [m].
            desired_goal: Desired goals, shape (..., 3) [m].
            info: The step's info dict, a sequence (or object array) of such dicts,
                or a dict of arrays (a vector env's infos). Read only when
                ``collision_penalty > 0`` (its ``"collision"`` entries).

        Returns:
            Rewards, shape (...).
        """
        d = goal_distance(achieved_goal, desired_goal)
        reward = goal_reward(d, self.distance_threshold, self.reward_type)
        if self.collision_penalty == 0.0:
            return reward + 0.0
        flags = collision_flags(info, d.shape)
        total: FloatArray = reward + np.where(flags, -self.collision_penalty, 0.0)
        return total

    def compute_terminated(
        self, achieved_goal: npt.ArrayLike, desired_goal: npt.ArrayLike, info: Any
    ) -> npt.NDArray[np.bool_]:
        """Termination of goals and infos (vectorised like :meth:`compute_reward`).

        True only on arm–obstacle contact with ``terminate_on_collision``;
        reaching the goal does not end an episode.
        """
        shape = np.shape(np.asarray(achieved_goal))[:-1]
        if not self.terminate_on_collision:
            return np.zeros(shape, dtype=bool)
        return np.asarray(collision_flags(info, shape), dtype=bool)

    def compute_truncated(
        self, achieved_goal: npt.ArrayLike, desired_goal: npt.ArrayLike, info: Any
    ) -> npt.NDArray[np.bool_]:
        """Always False: the time limit is ``max_episode_steps`` (a wrapper)."""
        return np.zeros(np.shape(np.asarray(achieved_goal))[:-1], dtype=bool)

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
        if seed is not None:
            if isinstance(seed, bool | np.bool_) or not isinstance(seed, int | np.integer):
                raise InvalidInputError(f"seed must be None or an integer >= 0, got {seed!r}")
            seed = int(seed)
            if seed < 0:
                raise InvalidInputError(f"seed must be None or an integer >= 0, got {seed}")
        if options is not None and not isinstance(options, dict):
            raise InvalidInputError(f"options must be None or a dict, got {options!r}")
        randomize = self.randomize
        if options:
            unknown = set(options) - {"randomize"}
            if unknown:
                raise InvalidInputError(
                    f"unknown reset options {sorted(map(str, unknown))}; valid: ['randomize']"
                )
            randomize = self._check_randomization(
                options.get("randomize", randomize), "options['randomize']"
            )
        super().reset(seed=seed)
        self._randomize_model(randomize)
        m, d = self.model, self.data
        mujoco.mj_resetData(m, d)  # qvel, act, warm start, time, contacts, warnings
        q = self._q_ready
        for adr, v in zip(self._arm_qpos, q):
            d.qpos[adr] = v
        half = 0.5 * GRIPPER_OPEN_M
        for adr in self._finger_qpos:
            d.qpos[adr] = half
        self._controller.reset(q)
        d.ctrl[self._arm_act] = q
        d.ctrl[self._grip_act] = GRIPPER_OPEN_M
        if self._slots is None:
            self._sample_task()
        else:
            self._sample_scene(self._slots)
        mujoco.mj_forward(m, d)
        x, y, z, _ = tool_pose_of(q)
        self._tool_now = (x, y, z)
        obs = self._observation()
        if self._pixels is not None:
            obs["pixels"] = self._pixels.render(d)
        if self.render_mode == "human":
            self.render()
        return obs, self._info(obs, False, TargetStatus.ACCEPTED, held=False)

    def _sample_task(self) -> None:
        """Place the cube (in ``data.qpos``) and set the goal, drawing from ``np_random``."""
        raise NotImplementedError

    def _work_columns(self) -> list[WorkColumn]:
        """Where the arm works in the episode drawn (default: at the goal, empty-handed)."""
        return [WorkColumn(self._goal.copy(), float(self._goal[2]), False)]

    def _sample_scene(self, slots: ObstacleSlots) -> None:
        """Draw the task, then obstacles that leave the arm room to work (``random_obstacles``).

        The obstacles keep :data:`_OBSTACLE_GAP_M` from the cube, the goal and the
        ready tool point, and the arm keeps :data:`WORK_CLEARANCE_M` from them at the
        ready pose and along every :meth:`_work_columns`; scenes that fail are drawn
        again.

        Raises:
            LynxsimError: No such scene in :data:`_MAX_SCENE_DRAWS` draws.
        """
        assert self.random_obstacles is not None
        fewest, most = self.random_obstacles
        rng = self.np_random
        ready = np.array(READY_TOOL_POSE[:3])
        for _ in range(_MAX_SCENE_DRAWS):
            self._set_obstacles(slots, ())
            self._sample_task()
            columns = self._work_columns()
            number = int(rng.integers(fewest, most + 1))
            keep = [ready.tolist(), *(c.point.tolist() for c in columns)]
            try:
                obstacles = random_obstacles(rng, number, keep_free=keep, gap_m=_OBSTACLE_GAP_M)
            except InvalidInputError:  # no room around these points: draw them again
                continue
            self._set_obstacles(slots, obstacles)
            if self._workable(columns):
                return
        raise LynxsimError(
            f"no scene with {fewest}..{most} obstacles left the arm room to work in "
            f"{_MAX_SCENE_DRAWS} draws"
        )

    def _set_obstacles(self, slots: ObstacleSlots, obstacles: Sequence[Obstacle]) -> None:
        slots.place(obstacles)
        self._obstacles = tuple(obstacles)

    def _workable(self, columns: list[WorkColumn]) -> bool:
        """Whether the ready pose and every work column keep :data:`WORK_CLEARANCE_M`."""
        groups: dict[bool, list[FloatArray]] = {False: [np.array([self._q_ready])], True: []}
        for column in columns:
            q = work_column(column.point, column.top_z, self._q_ready)
            if q is None:
                return False
            groups[column.grasped].append(q)
        for grasped, parts in groups.items():
            if parts:
                clearance = self._checker.min_clearance(
                    np.concatenate(parts), grasped=grasped, cap=WORK_CLEARANCE_M
                )
                if clearance.min() < WORK_CLEARANCE_M:
                    return False
        return True

    def _draw_point(
        self, region: PolarRegion, away_from: npt.ArrayLike | None = None
    ) -> FloatArray:
        """A point of ``region`` reachable top-down and clear of the obstacle.

        Args:
            region: Where to draw.
            away_from: A point, shape (3,) [m], that the drawn one must be more
                than ``distance_threshold`` away from.

        Returns:
            The point, shape (3,) [m].

        Raises:
            InvalidInputError: No such point after many draws (the obstacle blocks the region).
        """
        rng = self.np_random
        for _ in range(_MAX_DRAWS):
            p = sample_points(rng, region, _DRAW_BATCH)
            ok = top_down_reachable(p)
            for obstacle in self.obstacles:
                ok &= clear_of_obstacle(p, obstacle)
            if away_from is not None:
                gap = p - np.asarray(away_from, dtype=float)
                ok &= np.sqrt(np.sum(gap * gap, axis=1)) > self.distance_threshold
            hits = np.flatnonzero(ok)
            if hits.size:
                point: FloatArray = p[hits[0]]
                return point
        raise InvalidInputError(
            f"found no point of {region} that the arm reaches top-down clear of {self.obstacles}"
        )

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
        a = real_array(action, "action")
        if a.shape != (self._n_act,):
            raise InvalidInputError(f"action must have shape ({self._n_act},), got {a.shape}")
        values = a.tolist()
        if not all(map(math.isfinite, values)):
            raise NonFiniteInputError(f"action must be finite, got {values}")
        values = [-1.0 if v < -1.0 else 1.0 if v > 1.0 else v for v in values]
        ctrl = self.data.ctrl
        before = self._controller.target
        status = self._controller.apply(values)
        ctrl[self._arm_act] = self._controller.q_cmd
        if self._GRIPPER_ACTION:
            ctrl[self._grip_act] = (values[-1] + 1.0) * (0.5 * GRIPPER_OPEN_M)
        collision = self._simulate()

        obs = self._observation()
        if self._pixels is not None:
            obs["pixels"] = self._pixels.render(self.data)
        info = self._info(obs, collision, status, held=self._controller.target == before)
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
        return {
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

    def _simulate(self) -> bool:
        """Run the control period's physics steps; True on arm–obstacle contact."""
        m, d = self.model, self.data
        if self.collision_check is CollisionCheck.CONTROL_STEP:
            mujoco.mj_step(m, d, nstep=self.frame_skip)
            return self._touching_obstacle()
        hit = False
        for _ in range(self.frame_skip):
            mujoco.mj_step(m, d)
            hit = self._touching_obstacle() or hit
        return hit

    def _touching_obstacle(self) -> bool:
        """Whether the arm or the cube touches an obstacle in the current contacts.

        The pairs are those :func:`lynxsim.sim.collision.classify_contacts` calls
        obstacle hits (:meth:`~lynxsim.sim.collision.CollisionGroups.obstacle_pairs`),
        looked up in a set: this runs every physics step.
        """
        if not self._has_obstacle or self.data.ncon == 0:
            return False
        contact = self.data.contact
        pairs = self._arm_obstacle_pairs
        for k, (g1, g2) in enumerate(contact.geom.tolist()):
            if (g1, g2) in pairs and contact.dist[k] <= 0.0:
                return True
        return False

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


def _obstacle_range(value: object) -> tuple[int, int] | None:
    """``random_obstacles`` as ``(fewest, most)``, or None.

    Raises:
        InvalidInputError: Not None, a count or a pair of counts in order, within
            0..:data:`~lynxsim.bounds.MAX_RANDOM_OBSTACLES`.
    """
    if value is None:
        return None
    pair = value if isinstance(value, tuple | list) else (value, value)
    if len(pair) != 2:
        raise InvalidInputError(
            f"random_obstacles must be a count or (fewest, most), got {value!r}"
        )
    fewest = count(pair[0], "random_obstacles (fewest)", 0, MAX_RANDOM_OBSTACLES)
    most = count(pair[1], "random_obstacles (most)", fewest, MAX_RANDOM_OBSTACLES)
    return fewest, most


def _pixel_settings(
    cameras: object, width: object, height: object, quality: Quality
) -> tuple[RenderSettings, ...]:
    """The frames of the image observation, one per camera (none without one).

    Raises:
        InvalidInputError: ``pixels`` not a camera name or a sequence of distinct
            names, or a size not an integer in 1.._MAX_FRAME_PX.
    """
    names = (cameras,) if isinstance(cameras, str) else cameras
    if not isinstance(names, list | tuple) or not all(isinstance(n, str) for n in names):
        raise InvalidInputError(
            f"pixels must be a camera name or a sequence of them (e.g. ('front', 'top')), "
            f"got {cameras!r}"
        )
    if len(set(names)) != len(names):
        raise InvalidInputError(f"pixels must name distinct cameras, got {cameras!r}")
    width = count(width, "pixel_width", 1, _MAX_FRAME_PX)
    height = count(height, "pixel_height", 1, _MAX_FRAME_PX)
    return tuple(
        RenderSettings(width=width, height=height, camera=n, quality=quality, sites=False)
        for n in names
    )


def _check_frame(model: mujoco.MjModel, settings: RenderSettings) -> None:
    """Refuse a frame larger than the model's off-screen buffer or an unknown camera.

    Checked at construction, so that a bad argument fails where it is given and
    not at the first ``render()``.
    """
    buf_w, buf_h = int(model.vis.global_.offwidth), int(model.vis.global_.offheight)
    if settings.width > buf_w or settings.height > buf_h:
        raise InvalidInputError(
            f"frame {settings.width}x{settings.height} exceeds the model's off-screen buffer "
            f"{buf_w}x{buf_h} px"
        )
    if mujoco.mj_name2id(model, int(mujoco.mjtObj.mjOBJ_CAMERA), settings.camera) < 0:
        names = ", ".join(model.camera(i).name for i in range(model.ncam))
        raise InvalidInputError(f"no camera named {settings.camera!r}; cameras: {names}")


def _as_index(ids: tuple[int, ...]) -> slice | list[int]:
    """A slice when the ids are consecutive (faster to index with), else the list."""
    if list(ids) == list(range(ids[0], ids[0] + len(ids))):
        return slice(ids[0], ids[0] + len(ids))
    return list(ids)
