"""A quaternion's yaw, once (:func:`lynxsim.angles.quat_yaw`), judged by MuJoCo's rotation."""

from __future__ import annotations

import math

import mujoco
import numpy as np

from lynxsim.angles import quat_yaw

YAW_TOL_RAD = 1e-12
"""Agreement with the yaw read off MuJoCo's rotation matrix [rad]."""


def test_yaw_is_the_turn_about_z_of_mujocos_rotation():
    rng = np.random.default_rng(0)
    for quat in rng.standard_normal((500, 4)):
        quat /= np.linalg.norm(quat)
        mat = np.empty(9)
        mujoco.mju_quat2Mat(mat, quat)
        expected = math.atan2(mat[3], mat[0])  # R[1, 0], R[0, 0]
        yaw = quat_yaw(*quat.tolist())
        assert abs(math.remainder(yaw - expected, 2 * math.pi)) < YAW_TOL_RAD
        assert -math.pi <= yaw <= math.pi


def test_yaw_of_a_turn_about_z_is_its_angle():
    for angle in np.linspace(-3.0, 3.0, 13).tolist():
        w, z = math.cos(0.5 * angle), math.sin(0.5 * angle)
        assert abs(quat_yaw(w, 0.0, 0.0, z) - angle) < YAW_TOL_RAD
