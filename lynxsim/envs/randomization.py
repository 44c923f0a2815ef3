"""Domain randomisation of the arm envs: what to draw at reset, and what was drawn.

:class:`Randomization` says which physical parameters an env draws anew from
``np_random`` at every ``reset`` (cube size, mass and friction, servo gains,
joint damping, camera poses; all off by default); :class:`Domain` records the
values of an episode. The env applies them to its model at reset
(:class:`lynxsim.sim.arm.randomizer.ModelRandomizer`).
"""

from __future__ import annotations

from dataclasses import dataclass

from lynxsim.errors import InvalidInputError
from lynxsim.inputs import number_in_range
from lynxsim.scene import MIN_CUBE_MASS_KG
from lynxsim.sim.arm.randomizer import Domain
from lynxsim.sim.arm.task import GRIPPER_OPEN_M

__all__ = ["Domain", "Randomization"]

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
        cube_mass_kg: Cube mass range [kg], within 1e-4..0.5
            (:data:`lynxsim.scene.MIN_CUBE_MASS_KG`: the lightest cube a scene
            holds); None: 10 g.
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
                if name == "cube_mass_kg" and pair[0] < MIN_CUBE_MASS_KG:
                    raise InvalidInputError(
                        f"cube_mass_kg must be >= {MIN_CUBE_MASS_KG:g} kg (the lightest cube "
                        f"a scene holds), got {value!r}"
                    )
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
