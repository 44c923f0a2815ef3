"""Jacobians against finite differences of the forward kinematics."""

from __future__ import annotations

import numpy as np
import pytest

from lynxsim.arm import LYNX_ARM, fk, geometric_jacobian, jacobian, manipulability, tool_pose
from tests.helpers import assert_close

STEP_RAD = 1e-6
FD_TOL = 1e-8
"""Central differences with a 1e-6 rad step are accurate to ~1e-11; margin for rounding."""


@pytest.fixture
def joint_samples():
    return np.random.default_rng(5).uniform(LYNX_ARM.lower, LYNX_ARM.upper, size=(300, 5))


def _central_difference(f, q):
    cols = []
    for j in range(5):
        dq = np.zeros(5)
        dq[j] = STEP_RAD
        cols.append((f(q + dq) - f(q - dq)) / (2 * STEP_RAD))
    return np.stack(cols, axis=-1)


def test_position_pitch_jacobian_matches_finite_differences(joint_samples):
    def position_pitch(q):
        pose = tool_pose(q)
        return np.concatenate([pose.position, pose.pitch[..., None]], axis=-1)

    assert_close(
        jacobian(joint_samples), _central_difference(position_pitch, joint_samples), atol=FD_TOL
    )


def test_geometric_jacobian_linear_part_matches_finite_differences(joint_samples):
    numeric = _central_difference(lambda q: fk(q)[..., :3, 3], joint_samples)
    assert_close(geometric_jacobian(joint_samples)[..., :3, :], numeric, atol=FD_TOL)


def test_geometric_jacobian_angular_part_matches_rotation_derivative(joint_samples):
    rot = fk(joint_samples)[..., :3, :3]
    d_rot = _central_difference(
        lambda q: fk(q)[..., :3, :3].reshape(*q.shape[:-1], 9), joint_samples
    )
    d_rot = d_rot.reshape(*joint_samples.shape[:-1], 3, 3, 5)
    # omega^ = dR/dq R^T for each joint.
    skew = np.einsum("...ikj,...lk->...jil", d_rot, rot)
    omega = np.stack([skew[..., 2, 1], skew[..., 0, 2], skew[..., 1, 0]], axis=-1)
    assert_close(
        geometric_jacobian(joint_samples)[..., 3:, :], np.swapaxes(omega, -1, -2), atol=FD_TOL
    )


def test_manipulability_vanishes_when_the_arm_is_stretched():
    stretched = np.array([0.3, 1.0, 0.0, 0.0, 0.0])
    bent = np.array([0.3, 1.0, -1.0, 0.2, 0.0])
    assert manipulability(stretched) < 1e-12
    assert manipulability(bent) > 1e-4
    assert manipulability(bent, kind="position_pitch") > 0.0


def test_manipulability_rejects_unknown_kind():
    with pytest.raises(ValueError, match="kind must be"):
        manipulability(np.zeros(5), kind="velocity")  # type: ignore[arg-type]
