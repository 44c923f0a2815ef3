"""The arm's Hitec servos: the datasheet table, once, and what derives from it.

The MJCF model (``lynxsim/models/lynx_arm/lynx_arm.xml``, one default class per
servo) writes the derived actuator and joint values to three significant
digits; ``tests/arm/test_servos.py`` loads it and checks every one against this
table. The trajectory generators' default limits
(:data:`lynxsim.arm.motion.ARM_LIMITS`) derive from the same table.

Datasheets (Hitec, at 6.0 V; 1 kgf·cm = 0.0980665 N·m):

===========  =========  ============  ============  ====================
joint        servo      stall torque  s per 60 deg  armature (estimate)
===========  =========  ============  ============  ====================
base         HS-485HB   6.0 kgf·cm    0.18          0.002 kg·m²
shoulder     HS-805BB   24.7 kgf·cm   0.14          0.006 kg·m²
elbow        HS-755HB   13.2 kgf·cm   0.23          0.004 kg·m²
wrist_pitch  HS-645MG   9.6 kgf·cm    0.20          0.002 kg·m²
wrist_roll   HS-225MG   4.8 kgf·cm    0.11          0.001 kg·m²
gripper      HS-422     4.1 kgf·cm    0.16          0.001 kg·m²
===========  =========  ============  ============  ====================

Simulation (the model's README explains each choice):

* ``forcerange`` = ± the stall torque;
* ``kp`` = stall torque / proportional band (0.25 deg, a digital-class servo
  loop; 5 deg for the gripper);
* joint ``damping`` = stall torque / no-load speed (the motor's back-EMF line:
  saturated and unloaded, the joint runs at the datasheet speed);
* ``armature``: reflected rotor inertia (rotor inertia × gear ratio²), an
  estimate, as Hitec publishes neither.

Trajectory limits: the velocity limit is :data:`SPEED_DERATING` = 0.6 of the
no-load speed. The datasheet speed holds at 6.0 V with no load; at 4.8 V the same
datasheets give 74–83 % of it (supply sag under five moving servos), and a DC
servo's speed falls linearly with torque: holding the arm against gravity takes
the shoulder and elbow a fifth to a third of their stall torque. 0.6 keeps the
commanded speed inside what a loaded servo reaches on a sagging supply. Hobby
servos publish no acceleration or jerk limits; a joint is assumed to reach its
speed limit in :data:`ACCELERATION_RAMP_S` = 0.25 s and its acceleration limit
in :data:`JERK_RAMP_S` = 0.1 s: at 0.25 s the torque that accelerates the arm's
links (inertia about the shoulder ~0.014 kg·m²) stays near a tenth of the
HS-805BB's stall torque, gentle on the plastic brackets.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from lynxsim.errors import InvalidInputError

__all__ = [
    "ACCELERATION_RAMP_S",
    "AL5D_SERVOS",
    "GRIPPER_SERVO",
    "GRIPPER_SERVO_TRAVEL_RAD",
    "JERK_RAMP_S",
    "NM_PER_KGF_CM",
    "SERVO_BAND_RAD",
    "SPEED_DERATING",
    "ServoSpec",
]

NM_PER_KGF_CM = 0.0980665
"""One kgf·cm in N·m (Hitec datasheets give torques in kg·cm)."""

SERVO_BAND_RAD = math.radians(0.25)
"""Proportional band of the joint servos' position loop: the error that commands
the stall torque [rad]."""

SPEED_DERATING = 0.6
"""Fraction of the datasheet no-load speed at 6.0 V used as velocity limit [-]."""

ACCELERATION_RAMP_S = 0.25
"""Assumed time from rest to the velocity limit at the acceleration limit [s]."""

JERK_RAMP_S = 0.1
"""Assumed time from zero to the acceleration limit at the jerk limit [s]."""


_MIN_VALUE = 1e-9
"""Smallest datasheet value accepted (keeps the derived gains away from overflow)."""
_MAX_VALUE = 1e9
"""Largest datasheet value accepted."""


@dataclass(frozen=True)
class ServoSpec:
    """A Hitec servo's datasheet values (6.0 V) and the quantities derived from them.

    Attributes:
        joint: The joint it drives, as in :attr:`lynxsim.arm.ArmGeometry.joint_names`
            (``"gripper"`` for the hand's servo).
        model: Hitec model number.
        stall_torque_kgf_cm: Stall torque [kgf·cm] (the datasheet's unit).
        seconds_per_60deg: No-load transit time of 60 deg [s].
        armature: Reflected rotor inertia at the output shaft [kg·m²] (an estimate).
        proportional_band: Position error at which the servo commands its stall
            torque [rad].

    Raises:
        InvalidInputError: A value is not a positive finite number.
    """

    joint: str
    model: str
    stall_torque_kgf_cm: float
    seconds_per_60deg: float
    armature: float
    proportional_band: float = SERVO_BAND_RAD

    def __post_init__(self) -> None:
        for name in ("joint", "model"):
            value = getattr(self, name)
            if not (isinstance(value, str) and value and value.isprintable()):
                raise InvalidInputError(f"servo {name} must be a non-empty string, got {value!r}")
        for name in ("stall_torque_kgf_cm", "seconds_per_60deg", "armature", "proportional_band"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, float | int):
                raise InvalidInputError(
                    f"servo {self.model}: {name} must be a positive number, got {value!r}"
                )
            try:
                v = float(value)
            except OverflowError:  # an int beyond float64
                v = math.inf
            if not (math.isfinite(v) and _MIN_VALUE <= v <= _MAX_VALUE):
                raise InvalidInputError(
                    f"servo {self.model}: {name} must be a positive number from "
                    f"{_MIN_VALUE:g} to {_MAX_VALUE:g}, got {value!r}"
                )
            object.__setattr__(self, name, v)

    @property
    def stall_torque(self) -> float:
        """Stall torque [N·m]."""
        return self.stall_torque_kgf_cm * NM_PER_KGF_CM

    @property
    def no_load_speed(self) -> float:
        """No-load speed [rad/s]."""
        return math.radians(60.0) / self.seconds_per_60deg

    @property
    def forcerange(self) -> tuple[float, float]:
        """Actuator force range: ± the stall torque [N·m]."""
        return -self.stall_torque, self.stall_torque

    @property
    def kp(self) -> float:
        """Position gain: stall torque over the proportional band [N·m/rad]."""
        return self.stall_torque / self.proportional_band

    @property
    def damping(self) -> float:
        """Back-EMF damping: stall torque over no-load speed [N·m·s/rad]."""
        return self.stall_torque / self.no_load_speed

    @property
    def velocity_limit(self) -> float:
        """Trajectory velocity limit, derated no-load speed [rad/s]."""
        return SPEED_DERATING * self.no_load_speed

    @property
    def acceleration_limit(self) -> float:
        """Trajectory acceleration limit [rad/s²]."""
        return self.velocity_limit / ACCELERATION_RAMP_S

    @property
    def jerk_limit(self) -> float:
        """Trajectory jerk limit [rad/s³]."""
        return self.acceleration_limit / JERK_RAMP_S


AL5D_SERVOS = (
    ServoSpec("base", "HS-485HB", 6.0, 0.18, 0.002),
    ServoSpec("shoulder", "HS-805BB", 24.7, 0.14, 0.006),
    ServoSpec("elbow", "HS-755HB", 13.2, 0.23, 0.004),
    ServoSpec("wrist_pitch", "HS-645MG", 9.6, 0.20, 0.002),
    ServoSpec("wrist_roll", "HS-225MG", 4.8, 0.11, 0.001),
)
"""The servos of joints q1..q5, in joint order."""

GRIPPER_SERVO = ServoSpec("gripper", "HS-422", 4.1, 0.16, 0.001, math.radians(5.0))
"""The gripper's servo; the model's actuator drives the opening through a tendon,
so its values there are these divided by the transmission (and by its square)."""

GRIPPER_SERVO_TRAVEL_RAD = math.pi / 2
"""Servo turn that opens the gripper fully (an assumption; the transmission is the
full opening over it) [rad]."""
