"""The servo table: the AL5D's datasheets, and the MJCF numbers derived from them."""

from __future__ import annotations

import math

import numpy as np
import pytest

from lynxsim.arm import LYNX_ARM
from lynxsim.arm.servos import AL5D_SERVOS, GRIPPER_SERVO, GRIPPER_SERVO_TRAVEL_RAD, ServoSpec
from lynxsim.errors import InvalidInputError
from lynxsim.resources import model_path

MJCF_DIGITS = 3
"""Significant digits the MJCF writes derived servo values to [-]."""
GRIPPER_TENDON = "gripper_opening"


def _as_written(value: float) -> float:
    """``value`` rounded as the MJCF writes it."""
    return float(f"{value:.{MJCF_DIGITS}g}")


@pytest.fixture(scope="module")
def arm_model():
    import lynxsim.sim  # noqa: F401  # chooses MUJOCO_GL before mujoco is imported

    mujoco = pytest.importorskip("mujoco")
    return mujoco.MjModel.from_xml_path(str(model_path("lynx_arm/lynx_arm.xml")))


def _id(model, kind: str, name: str) -> int:
    import mujoco

    index = mujoco.mj_name2id(model, getattr(mujoco.mjtObj, f"mjOBJ_{kind}"), name)
    assert index >= 0, f"no {kind.lower()} named {name!r}"
    return int(index)


def test_servos_are_the_al5d_ones_in_joint_order():
    assert [s.model for s in AL5D_SERVOS] == [
        "HS-485HB",
        "HS-805BB",
        "HS-755HB",
        "HS-645MG",
        "HS-225MG",
    ]
    assert tuple(s.joint for s in AL5D_SERVOS) == LYNX_ARM.joint_names


def test_base_servo_no_load_speed_matches_its_datasheet():
    # 0.18 s per 60 deg at 6.0 V.
    assert AL5D_SERVOS[0].no_load_speed == pytest.approx(math.radians(60) / 0.18)
    assert AL5D_SERVOS[0].no_load_speed == pytest.approx(5.82, abs=0.005)


def test_shoulder_servo_derivations():
    # HS-805BB: 24.7 kgf·cm, 0.14 s / 60 deg (the README's table row).
    servo = AL5D_SERVOS[1]
    assert servo.stall_torque == pytest.approx(2.42224, abs=1e-5)
    assert servo.forcerange == (-servo.stall_torque, servo.stall_torque)
    assert servo.kp == pytest.approx(servo.stall_torque / math.radians(0.25))
    assert servo.damping == pytest.approx(servo.stall_torque / servo.no_load_speed)
    assert servo.velocity_limit == pytest.approx(0.6 * servo.no_load_speed)


@pytest.mark.parametrize("servo", AL5D_SERVOS, ids=[s.joint for s in AL5D_SERVOS])
def test_mjcf_joint_servo_equals_the_table(arm_model, servo):
    act = _id(arm_model, "ACTUATOR", servo.joint)
    joint = _id(arm_model, "JOINT", servo.joint)
    dof = arm_model.jnt_dofadr[joint]
    lo, hi = servo.forcerange
    assert arm_model.actuator_forcerange[act].tolist() == [_as_written(lo), _as_written(hi)]
    assert arm_model.actuator_gainprm[act, 0] == _as_written(servo.kp)
    assert arm_model.actuator_biasprm[act, 1] == -_as_written(servo.kp)
    assert arm_model.dof_damping[dof] == _as_written(servo.damping)
    assert arm_model.dof_armature[dof] == servo.armature


def test_mjcf_gripper_servo_equals_the_table_through_its_transmission(arm_model):
    act = _id(arm_model, "ACTUATOR", "gripper")
    tendon = _id(arm_model, "TENDON", GRIPPER_TENDON)
    opening_m = float(arm_model.actuator_ctrlrange[act, 1])
    r = opening_m / GRIPPER_SERVO_TRAVEL_RAD  # [m/rad]
    force = GRIPPER_SERVO.stall_torque / r
    assert arm_model.actuator_forcerange[act].tolist() == [-_as_written(force), _as_written(force)]
    assert arm_model.actuator_gainprm[act, 0] == _as_written(GRIPPER_SERVO.kp / r**2)
    assert arm_model.tendon_damping[tendon] == _as_written(GRIPPER_SERVO.damping / r**2)
    assert arm_model.tendon_armature[tendon] == _as_written(GRIPPER_SERVO.armature / r**2)


@pytest.mark.parametrize(
    "field", ["stall_torque_kgf_cm", "seconds_per_60deg", "armature", "proportional_band"]
)
@pytest.mark.parametrize("bad", [0.0, -1.0, np.nan, np.inf])
def test_servo_spec_refuses_non_positive_values(field, bad):
    values = {"stall_torque_kgf_cm": 1.0, "seconds_per_60deg": 0.1, "armature": 0.001} | {
        field: bad
    }
    with pytest.raises(InvalidInputError, match=f"{field} must be a positive number"):
        ServoSpec("base", "HS-000", **values)
