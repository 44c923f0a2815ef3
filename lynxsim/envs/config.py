"""The options of an arm env, as one frozen, validated value.

:class:`EnvConfig` holds what :class:`~lynxsim.envs.base.LynxArmEnv` is built
from; the env takes the same options as keyword arguments (``gym.make``
kwargs, with their defaults) and makes its config with :meth:`EnvConfig.of`. Everything that can be
checked without the compiled model is checked here, in the order of the
arguments, with messages that name the argument and its valid values; the
control period against the physics step (:meth:`EnvConfig.frame_skip`), the
frames against the model's cameras and off-screen buffer, and the
randomisation against the env's cube are checked by the env once its model
exists.
"""

from __future__ import annotations

import enum
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Literal, TypeVar

import numpy as np

from lynxsim.bounds import MAX_CONTROL_DT_S, MAX_COORDINATE_M, MAX_RANDOM_OBSTACLES, check_range
from lynxsim.envs.control import ControlMode, TargetFallback
from lynxsim.envs.randomization import Randomization
from lynxsim.envs.reward import RewardType
from lynxsim.errors import InvalidInputError, NonFiniteInputError
from lynxsim.inputs import count
from lynxsim.scene import REPORT_CYLINDER, Box, Cylinder, Obstacle, Sphere
from lynxsim.sim.env_render import RENDER_MODES
from lynxsim.sim.render import Quality, RenderSettings

__all__ = [
    "MAX_FRAME_PX",
    "CollisionCheck",
    "EnvConfig",
    "check_control_dt",
    "check_randomization",
    "real_option",
    "reset_options",
]

E = TypeVar("E", bound=enum.Enum)

MAX_FRAME_PX = 16_384
"""Largest frame side accepted before the model's off-screen buffer is known [px]."""
_MAX_PENALTY = 1e6
"""Largest collision penalty (rewards are -1..0 or minus metres)."""


class CollisionCheck(enum.Enum):
    """When the arm–obstacle contact test runs.

    CONTROL_STEP: on the contacts of the last physics step of each control period
        (one test per env step; the default, cheap).
    PHYSICS_STEP: after every physics step (exact: a graze shorter than the
        control period is caught; costs a Python loop over the physics steps).
    """

    CONTROL_STEP = "control_step"
    PHYSICS_STEP = "physics_step"


def real_option(value: object, name: str, low: float, high: float, unit: str = "") -> float:
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
    timestep = real_option(timestep, "timestep", 1e-9, MAX_CONTROL_DT_S, "s")
    control_dt = real_option(control_dt, "control_dt", timestep, MAX_CONTROL_DT_S, "s")
    ratio = control_dt / timestep
    n = round(ratio)
    if n < 1 or abs(ratio - n) > 1e-6:
        raise InvalidInputError(
            f"control_dt = {control_dt} s is not a whole multiple of the physics timestep "
            f"{timestep} s (ratio {ratio:.6g}); use e.g. {max(n, 1) * timestep:g} s"
        )
    return n


def _enum(kind: type[E], value: object, name: str) -> E:
    try:
        return kind(value.value if isinstance(value, kind) else value)
    except (ValueError, TypeError):
        choices = ", ".join(repr(m.value) for m in kind)
        raise InvalidInputError(f"{name} must be one of {choices}, got {value!r}") from None


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
            names, or a size not an integer in 1..:data:`MAX_FRAME_PX`.
    """
    names = (cameras,) if isinstance(cameras, str) else cameras
    if not isinstance(names, list | tuple) or not all(isinstance(n, str) for n in names):
        raise InvalidInputError(
            f"pixels must be a camera name or a sequence of them (e.g. ('front', 'top')), "
            f"got {cameras!r}"
        )
    if len(set(names)) != len(names):
        raise InvalidInputError(f"pixels must name distinct cameras, got {cameras!r}")
    width = count(width, "pixel_width", 1, MAX_FRAME_PX)
    height = count(height, "pixel_height", 1, MAX_FRAME_PX)
    return tuple(
        RenderSettings(width=width, height=height, camera=n, quality=quality, sites=False)
        for n in names
    )


@dataclass(frozen=True)
class EnvConfig:
    """The options of an arm env, checked (see :class:`~lynxsim.envs.base.LynxArmEnv`).

    Made by :meth:`of` from the env's keyword arguments; every field is then of
    its final type.

    Attributes:
        render_mode: None, ``"rgb_array"`` or ``"human"``.
        control: Tool-space or joint-space actions.
        target_fallback: What an unreachable tool request does.
        reward_type: Sparse or dense reward.
        distance_threshold: Success radius around the goal [m], > 0.
        obstacles: The fixed obstacles (given None: the report's cylinder, or
            none with ``random_obstacles``).
        random_obstacles: ``(fewest, most)`` obstacles drawn at every reset, or None.
        collision_penalty: Subtracted from the reward on a step with contact, >= 0.
        terminate_on_collision: End the episode on arm–obstacle contact.
        collision_check: When the contact test runs.
        control_dt: Control period [s] (checked against the physics step by
            :meth:`frame_skip`).
        position_step: Tool-point move for a tool action of 1 [m], > 0.
        pitch_step: Pitch change for a tool action of 1 [rad], > 0.
        roll_step: Wrist-roll change for a ``"tool_roll"`` action of 1 [rad], > 0.
        joint_step: Joint change for a joint action of 1 [rad], > 0.
        frames: Size, camera and quality of ``render()`` frames.
        pixels: One per camera of the image observation, in channel order (empty: none).
        randomize: Domain randomisation drawn at every reset, or None.
    """

    render_mode: str | None
    control: ControlMode
    target_fallback: TargetFallback
    reward_type: RewardType
    distance_threshold: float
    obstacles: tuple[Obstacle, ...]
    random_obstacles: tuple[int, int] | None
    collision_penalty: float
    terminate_on_collision: bool
    collision_check: CollisionCheck
    control_dt: float
    position_step: float
    pitch_step: float
    roll_step: float
    joint_step: float
    frames: RenderSettings
    pixels: tuple[RenderSettings, ...]
    randomize: Randomization | None

    @classmethod
    def of(
        cls,
        *,
        render_mode: str | None,
        control: Literal["tool", "tool_roll", "joint"] | ControlMode,
        target_fallback: Literal["nearest", "hold"] | TargetFallback,
        reward_type: Literal["sparse", "dense"] | RewardType,
        distance_threshold: float,
        obstacles: Sequence[Obstacle] | None,
        random_obstacles: int | tuple[int, int] | None,
        collision_penalty: float,
        terminate_on_collision: bool,
        collision_check: Literal["control_step", "physics_step"] | CollisionCheck,
        control_dt: float,
        position_step: float,
        pitch_step: float,
        roll_step: float,
        joint_step: float,
        width: int,
        height: int,
        camera: str,
        render_quality: Literal["lean", "fast", "medium", "default"],
        pixels: str | Sequence[str],
        pixel_width: int,
        pixel_height: int,
        randomize: Randomization | None,
    ) -> EnvConfig:
        """The config of an env's keyword arguments (their defaults: the env's signature).

        Args:
            render_mode: None, ``"rgb_array"`` (off-screen) or ``"human"`` (a passive
                :mod:`mujoco.viewer` window; needs a display).
            control: ``"tool"`` (tool-space deltas through the IK; ``-v0``, ``-v1``),
                ``"tool_roll"`` (the same with the wrist roll, and an unreachable request
                taken to the nearest feasible target: ``-v2``,
                :mod:`lynxsim.envs.tool_action`) or ``"joint"``.
            target_fallback: What a ``"tool"`` request the IK cannot reach does:
                ``"nearest"`` (the feasible target nearest it along the request; ``-v1``)
                or ``"hold"`` (the previous target; ``-v0``); see
                :class:`~lynxsim.envs.control.TargetFallback`. ``"tool_roll"`` takes
                ``"nearest"`` only.
            reward_type: ``"sparse"`` or ``"dense"``.
            distance_threshold: Success radius around the goal [m].
            obstacles: The obstacles (:mod:`lynxsim.scene`; default: the report's cylinder,
                or none with ``random_obstacles``; ``()`` for none).
            random_obstacles: ``(fewest, most)`` obstacles (or one number) drawn anew at
                every reset, at most :data:`~lynxsim.bounds.MAX_RANDOM_OBSTACLES`; None
                (default) keeps ``obstacles`` fixed. Exclusive with ``obstacles``.
            collision_penalty: Subtracted from the reward on a step with arm–obstacle
                contact, >= 0.
            terminate_on_collision: End the episode on arm–obstacle contact.
            collision_check: ``"control_step"`` or ``"physics_step"`` (see :class:`CollisionCheck`).
            control_dt: Control period [s], a whole multiple of the 2 ms physics step.
            position_step: Tool-point move for a tool action of 1 [m].
            pitch_step: Pitch change for a tool action of 1 [rad].
            roll_step: Wrist-roll change for a ``"tool_roll"`` action of 1 [rad].
            joint_step: Joint change for a joint action of 1 [rad].
            width: Frame width [px].
            height: Frame height [px].
            camera: Camera of the scene (``"front"`` or ``"top"``).
            render_quality: ``"lean"`` (for small image observations: no shadows, skybox,
                fog or haze, coarse shapes), ``"fast"`` (no shadows), ``"medium"``
                (shadows) or ``"default"`` (shadows and multisampling); of ``render()``
                frames and image observations.
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
            NonFiniteInputError: A number is NaN or infinite.
        """
        quality = _enum(Quality, render_quality, "render_quality")
        pixel_frames = _pixel_settings(pixels, pixel_width, pixel_height, quality)
        if not isinstance(camera, str):
            raise InvalidInputError(f"camera must be a camera name (a string), got {camera!r}")
        width = count(width, "width", 1, MAX_FRAME_PX)
        height = count(height, "height", 1, MAX_FRAME_PX)
        frames = RenderSettings(width=width, height=height, camera=camera, quality=quality)
        options: dict[str, Any] = {
            "render_mode": render_mode,
            "control": control,
            "target_fallback": target_fallback,
            "reward_type": reward_type,
            "distance_threshold": distance_threshold,
            "obstacles": obstacles,
            "random_obstacles": random_obstacles,
            "collision_penalty": collision_penalty,
            "terminate_on_collision": terminate_on_collision,
            "collision_check": collision_check,
            "control_dt": control_dt,
            "position_step": position_step,
            "pitch_step": pitch_step,
            "roll_step": roll_step,
            "joint_step": joint_step,
            "frames": frames,
            "pixels": pixel_frames,
            "randomize": randomize,
        }
        return cls(**options)

    def __post_init__(self) -> None:
        """Check every field, in the order of the env's arguments; enums from their values."""
        put = object.__setattr__
        for name, kind in (
            ("control", ControlMode),
            ("target_fallback", TargetFallback),
            ("reward_type", RewardType),
            ("collision_check", CollisionCheck),
        ):
            put(self, name, _enum(kind, getattr(self, name), name))
        if self.control is ControlMode.TOOL_ROLL and self.target_fallback is TargetFallback.HOLD:
            raise InvalidInputError(
                "control='tool_roll' takes the nearest feasible target: "
                "target_fallback must be 'nearest', got 'hold'"
            )
        threshold = real_option(
            self.distance_threshold, "distance_threshold", 0.0, MAX_COORDINATE_M, "m"
        )
        if threshold == 0.0:
            raise InvalidInputError("distance_threshold must be > 0 m, got 0")
        put(self, "distance_threshold", threshold)
        put(
            self,
            "collision_penalty",
            real_option(self.collision_penalty, "collision_penalty", 0.0, _MAX_PENALTY),
        )
        if not isinstance(self.terminate_on_collision, bool | np.bool_):
            raise InvalidInputError(
                f"terminate_on_collision must be True or False, got {self.terminate_on_collision!r}"
            )
        put(self, "terminate_on_collision", bool(self.terminate_on_collision))
        steps = (
            ("position_step", MAX_COORDINATE_M, "m"),
            ("pitch_step", 2.0 * math.pi, "rad"),
            ("roll_step", 2.0 * math.pi, "rad"),
            ("joint_step", 2.0 * math.pi, "rad"),
        )
        for name, high, unit in steps:
            put(self, name, real_option(getattr(self, name), name, 0.0, high, unit))
        for name, _, _ in steps:
            if getattr(self, name) == 0.0:
                raise InvalidInputError(f"{name} must be a positive number, got 0")
        mode = self.render_mode
        if mode is not None and not (isinstance(mode, str) and mode in RENDER_MODES):
            raise InvalidInputError(
                f"render_mode must be None or one of {list(RENDER_MODES)}, got {mode!r}"
            )
        drawn = _obstacle_range(self.random_obstacles)
        put(self, "random_obstacles", drawn)
        obstacles: object = self.obstacles
        if obstacles is None:
            obstacles = (REPORT_CYLINDER,) if drawn is None else ()
        elif drawn is not None:
            raise InvalidInputError("give obstacles or random_obstacles, not both")
        if not isinstance(obstacles, list | tuple) or not all(
            isinstance(o, Cylinder | Box | Sphere) for o in obstacles
        ):
            raise InvalidInputError(
                f"obstacles must be a sequence of Cylinder, Box or Sphere, got {obstacles!r}"
            )
        put(self, "obstacles", tuple(obstacles))
        frames = (self.frames, *self.pixels) if isinstance(self.pixels, tuple) else ()
        if not frames or not all(isinstance(f, RenderSettings) for f in frames):
            raise InvalidInputError("frames and pixels must be RenderSettings (see EnvConfig.of)")
        check_randomization(self.randomize, "randomize", has_cube=True, env="")  # the type only

    def frame_skip(self, timestep: float) -> int:
        """Physics steps per control period (:func:`check_control_dt`).

        Raises:
            InvalidInputError: ``control_dt`` is no whole multiple of ``timestep``
                within the range, or not a number.
            NonFiniteInputError: It is NaN or infinite.
        """
        return check_control_dt(self.control_dt, timestep)


def check_randomization(
    value: object, name: str, *, has_cube: bool, env: str
) -> Randomization | None:
    """``value`` if None or a :class:`Randomization` an env (with a cube or not) can apply.

    Raises:
        InvalidInputError: ``value`` is no :class:`Randomization`, or it randomises
            the cube of an env ``env`` that has none.
    """
    if value is None:
        return None
    if not isinstance(value, Randomization):
        raise InvalidInputError(
            f"{name} must be None or a lynxsim.envs.Randomization, got {value!r}"
        )
    if value.touches_cube and not has_cube:
        raise InvalidInputError(
            f"{name} randomises the cube, but {env} has no cube: "
            f"leave cube_size_m, cube_mass_kg and cube_friction None"
        )
    return value


def reset_options(seed: object, options: object, randomize: object) -> tuple[int | None, object]:
    """A reset's seed as an int (or None), and the randomisation it asks (``randomize`` if none).

    Raises:
        InvalidInputError: ``seed`` is not None or a non-negative integer, or
            ``options`` not None or a dict whose only key may be ``"randomize"``.
    """
    if seed is not None:
        if isinstance(seed, bool | np.bool_) or not isinstance(seed, int | np.integer):
            raise InvalidInputError(f"seed must be None or an integer >= 0, got {seed!r}")
        seed = int(seed)
        if seed < 0:
            raise InvalidInputError(f"seed must be None or an integer >= 0, got {seed}")
    if options is not None and not isinstance(options, dict):
        raise InvalidInputError(f"options must be None or a dict, got {options!r}")
    if options:
        unknown = set(options) - {"randomize"}
        if unknown:
            raise InvalidInputError(
                f"unknown reset options {sorted(map(str, unknown))}; valid: ['randomize']"
            )
        randomize = options.get("randomize", randomize)
    return seed, randomize
