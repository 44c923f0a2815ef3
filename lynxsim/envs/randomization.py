"""Domain randomisation of the arm envs: what to draw at reset, and what was drawn.

:class:`Randomization` says which physical parameters an env draws anew from
``np_random`` at every ``reset`` (cube size, mass and friction, servo gains,
joint damping, camera poses; all off by default); :class:`Domain` records the
values of an episode. The env applies them to its model
(:meth:`lynxsim.envs.base.LynxArmEnv.reset`).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import mujoco
import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError
from lynxsim.inputs import number_in_range
from lynxsim.scene import Cube
from lynxsim.sim.arm.slots import primitive_bounds
from lynxsim.sim.arm.task import GRIPPER_OPEN_M

__all__ = ["Domain", "ModelRandomizer", "Randomization"]

FloatArray = npt.NDArray[np.float64]

_MIN_CUBE_SIZE_M = 0.005
"""Smallest randomised cube edge [m]; the largest is the open gripper, :data:`GRIPPER_OPEN_M`."""
_MAX_CUBE_MASS_KG = 0.5
"""Heaviest randomised cube [kg] (the gripper servo pushes at most 21 N)."""
_MAX_FRICTION = 5.0
"""Largest randomised sliding friction coefficient [-]."""
_MAX_TOLERANCE = 0.5
"""Largest relative tolerance of servo gains and joint damping [-] (keeps them positive)."""
_MAX_CAMERA_SHIFT_M = 0.1
_MAX_CAMERA_TILT_RAD = 0.5


def _interval(value: object, name: str, low: float, high: float, unit: str) -> tuple[float, float]:
    """``(lo, hi)`` with ``low <= lo <= hi <= high``, as floats.

    Raises:
        InvalidInputError: Not a pair of numbers in order within the range (states it).
        NonFiniteInputError: NaN or infinity.
    """
    if not isinstance(value, tuple | list) or len(value) != 2:
        raise InvalidInputError(f"{name} must be None or a pair (lo, hi) [{unit}], got {value!r}")
    lo = number_in_range(value[0], f"{name} (lo)", low, high, unit)
    hi = number_in_range(value[1], f"{name} (hi)", lo, high, unit)
    return lo, hi


@dataclass(frozen=True)
class Randomization:
    """What :class:`LynxArmEnv` draws anew from ``np_random`` at every ``reset``.

    Every field off by default; a range is ``(lo, hi)`` drawn uniformly, a
    tolerance ``t`` scales a nominal value by a factor drawn uniformly from
    ``[1 - t, 1 + t]``, independently per servo, joint or camera. Nominal values
    are those of the compiled model; each reset starts from them (nothing compounds).

    Attributes:
        cube_size_m: Cube edge range [m], within 0.005..0.03 (the open gripper);
            None: 25 mm. The cube rests on the table whatever its size.
        cube_mass_kg: Cube mass range [kg], within 0..0.5 (lo > 0); None: 10 g.
        cube_friction: Range of the cube's sliding friction coefficient [-],
            within 0..5 (lo > 0); None: 1. MuJoCo takes the larger coefficient
            of the two geoms in contact (fingers and table: 1).
        servo_gain_tolerance: Relative tolerance of the five arm servos'
            proportional gains ``kp`` [-], 0..0.5 (0.1 is a usual tolerance of a DC
            motor's torque constant, which sets the stall torque and with it
            kp = stall torque / 0.25 deg); the actuator's ``gainprm[0] = kp`` and
            ``biasprm[1] = -kp`` change together, its damping ``biasprm[2]`` stays.
        joint_damping_tolerance: Relative tolerance of the five arm joints'
            damping (the servos' back-EMF damping) [-], 0..0.5.
        camera_shift_m: Largest shift of each camera's position along each world
            axis [m], 0..0.1 (drawn uniformly per axis).
        camera_tilt_rad: Largest rotation of each camera about a random axis of
            its own frame [rad], 0..0.5 (angle drawn uniformly).

    Raises:
        InvalidInputError: A range not a pair in order within its limits, or a
            tolerance, shift or tilt out of its range (the message names it).
    """

    cube_size_m: tuple[float, float] | None = None
    cube_mass_kg: tuple[float, float] | None = None
    cube_friction: tuple[float, float] | None = None
    servo_gain_tolerance: float = 0.0
    joint_damping_tolerance: float = 0.0
    camera_shift_m: float = 0.0
    camera_tilt_rad: float = 0.0

    def __post_init__(self) -> None:
        ranges = (
            ("cube_size_m", _MIN_CUBE_SIZE_M, GRIPPER_OPEN_M, "m"),
            ("cube_mass_kg", 0.0, _MAX_CUBE_MASS_KG, "kg"),
            ("cube_friction", 0.0, _MAX_FRICTION, ""),
        )
        for name, low, high, unit in ranges:
            value = getattr(self, name)
            if value is not None:
                pair = _interval(value, name, low, high, unit)
                if pair[0] <= 0.0:
                    raise InvalidInputError(f"{name} must be > 0 {unit}, got {value!r}")
                object.__setattr__(self, name, pair)
        limits = (
            ("servo_gain_tolerance", _MAX_TOLERANCE, ""),
            ("joint_damping_tolerance", _MAX_TOLERANCE, ""),
            ("camera_shift_m", _MAX_CAMERA_SHIFT_M, "m"),
            ("camera_tilt_rad", _MAX_CAMERA_TILT_RAD, "rad"),
        )
        for name, high, unit in limits:
            object.__setattr__(
                self, name, number_in_range(getattr(self, name), name, 0.0, high, unit)
            )

    @property
    def touches_cube(self) -> bool:
        """Whether the cube is randomised."""
        return (self.cube_size_m, self.cube_mass_kg, self.cube_friction) != (None, None, None)


@dataclass(frozen=True)
class Domain:
    """The physical parameters of an episode (drawn, or nominal where not randomised).

    Attributes:
        cube_size_m: Cube edge [m], None without a cube.
        cube_mass_kg: Cube mass [kg], None without a cube.
        cube_friction: Cube sliding friction coefficient [-], None without a cube.
        servo_kp: Proportional gains of the five arm servos, q1..q5 [N·m/rad].
        joint_damping: Damping of the five arm joints [N·m·s/rad].
        camera_pos: Each camera's position, shape (ncam, 3) [m], world frame.
        camera_quat: Each camera's orientation (w, x, y, z), shape (ncam, 4).
    """

    cube_size_m: float | None
    cube_mass_kg: float | None
    cube_friction: float | None
    servo_kp: tuple[float, ...]
    joint_damping: tuple[float, ...]
    camera_pos: tuple[tuple[float, ...], ...]
    camera_quat: tuple[tuple[float, ...], ...]


class ModelRandomizer:
    """Writes an episode's draws into a model and puts its nominal values back.

    Args:
        model: The env's model (edited in place).
        data: Its data (``mj_setConst`` uses it as scratch: apply before ``mj_resetData``).
        actuators: The arm's position actuators (index into ``actuator_*``).
        dofs: The arm's dofs (index into ``dof_*``).
        cube_geom: The cube's geom, or None.
        cube: The nominal cube (its size, mass and friction are the model's).
    """

    def __init__(
        self,
        model: mujoco.MjModel,
        data: mujoco.MjData,
        actuators: slice | list[int],
        dofs: list[int],
        cube_geom: int | None,
        cube: Cube,
    ) -> None:
        self._model, self._data = model, data
        self._act, self._dofs, self._geom = actuators, dofs, cube_geom
        self._cube = cube
        self._nominal = self._read()
        self._randomized = False
        self.domain = self._current()
        """The model's physical parameters now (a :class:`Domain`)."""

    def _read(self) -> list[FloatArray]:
        """Copies of the fields randomisation writes (the cube's: none without one)."""
        m, g = self._model, self._geom
        fields = [
            m.actuator_gainprm[self._act, 0].copy(),
            m.actuator_biasprm[self._act, 1].copy(),
            m.dof_damping[self._dofs].copy(),
            m.cam_pos.copy(),
            m.cam_quat.copy(),
        ]
        if g is not None:
            b = int(m.geom_bodyid[g])
            fields += [
                m.geom_size[g].copy(),
                m.geom_aabb[g].copy(),
                m.geom_rbound[g : g + 1].copy(),
                m.geom_friction[g].copy(),
                m.body_mass[b : b + 1].copy(),
                m.body_inertia[b].copy(),
            ]
        return fields

    def _write(self, fields: list[FloatArray]) -> None:
        """Write what :meth:`_read` read."""
        m, g = self._model, self._geom
        m.actuator_gainprm[self._act, 0] = fields[0]
        m.actuator_biasprm[self._act, 1] = fields[1]
        m.dof_damping[self._dofs] = fields[2]
        m.cam_pos[:] = fields[3]
        m.cam_quat[:] = fields[4]
        if g is not None:
            b = int(m.geom_bodyid[g])
            m.geom_size[g] = fields[5]
            m.geom_aabb[g] = fields[6]
            m.geom_rbound[g] = fields[7][0]
            m.geom_friction[g] = fields[8]
            m.body_mass[b] = fields[9][0]
            m.body_inertia[b] = fields[10]

    def apply(self, r: Randomization | None, rng: np.random.Generator) -> Cube:
        """Draw from ``rng`` what ``r`` asks, starting from the nominal model; return the cube.

        ``r`` None restores the nominal model (touching nothing when nothing was
        randomised, so the random stream is untouched). Runs ``mj_setConst``, so
        the constants that depend on masses (``body_subtreemass``,
        ``*_invweight0``, ``dof_M0``, ``actuator_acc0``) follow the cube.
        """
        if r is None and not self._randomized:
            return self._cube
        m, g = self._model, self._geom
        self._write(self._nominal)
        cube = self._cube
        if r is not None:
            if r.touches_cube and g is not None:
                size, mass, friction = (
                    default if span is None else float(rng.uniform(*span))
                    for span, default in (
                        (r.cube_size_m, cube.size),
                        (r.cube_mass_kg, cube.mass),
                        (r.cube_friction, cube.friction),
                    )
                )
                cube = replace(cube, size=size, mass=mass, friction=friction)
                b = int(m.geom_bodyid[g])
                half = 0.5 * size
                extents, radius = primitive_bounds(int(m.geom_type[g]), (half, half, half))
                m.geom_size[g] = half
                m.geom_aabb[g, 3:] = extents
                m.geom_rbound[g] = radius
                m.geom_friction[g, 0] = friction
                m.body_mass[b] = mass
                m.body_inertia[b] = mass * size * size / 6.0  # a solid cube
            self._draw_servos_and_cameras(r, rng)
        mujoco.mj_setConst(m, self._data)
        self._randomized = r is not None
        self.domain = self._current()
        return cube

    def _draw_servos_and_cameras(self, r: Randomization, rng: np.random.Generator) -> None:
        m, n = self._model, len(self._dofs)
        if r.servo_gain_tolerance:
            t = r.servo_gain_tolerance
            kp = self._nominal[0] * rng.uniform(1.0 - t, 1.0 + t, n)
            m.actuator_gainprm[self._act, 0] = kp
            m.actuator_biasprm[self._act, 1] = -kp
        if r.joint_damping_tolerance:
            t = r.joint_damping_tolerance
            m.dof_damping[self._dofs] = self._nominal[2] * rng.uniform(1.0 - t, 1.0 + t, n)
        if r.camera_shift_m:
            shift = r.camera_shift_m
            m.cam_pos[:] = self._nominal[3] + rng.uniform(-shift, shift, (m.ncam, 3))
        if r.camera_tilt_rad:
            axes = rng.standard_normal((m.ncam, 3))
            angles = rng.uniform(0.0, r.camera_tilt_rad, m.ncam)
            turn, quat = np.zeros(4), np.zeros(4)
            for i in range(m.ncam):
                mujoco.mju_axisAngle2Quat(turn, axes[i] / np.linalg.norm(axes[i]), angles[i])
                mujoco.mju_mulQuat(quat, self._nominal[4][i], turn)
                m.cam_quat[i] = quat / np.linalg.norm(quat)

    def _current(self) -> Domain:
        """The model's physical parameters now."""
        m, g = self._model, self._geom
        return Domain(
            cube_size_m=None if g is None else 2.0 * float(m.geom_size[g, 0]),
            cube_mass_kg=None if g is None else float(m.body_mass[m.geom_bodyid[g]]),
            cube_friction=None if g is None else float(m.geom_friction[g, 0]),
            servo_kp=tuple(m.actuator_gainprm[self._act, 0].tolist()),
            joint_damping=tuple(m.dof_damping[self._dofs].tolist()),
            camera_pos=tuple(map(tuple, m.cam_pos.tolist())),
            camera_quat=tuple(map(tuple, m.cam_quat.tolist())),
        )
