"""Forward kinematics against the report's numbers and between its two routes."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest

from lynxsim.arm import (
    LYNX_ARM,
    fk,
    frame_origins,
    frame_transforms,
    geometric_jacobian,
    ik,
    jacobian,
    manipulability,
    tool_pose,
)
from lynxsim.errors import InvalidInputError, NonFiniteInputError
from lynxsim.reproduce.arm_tables import FK_CASES, TABLE4, TABLE4_P1_ELBOW_MM, TABLE4_P1_WRIST_MM
from tests.helpers import assert_close

REPORT_MM = 0.05
"""Agreement with the report's printed positions [mm] (its inputs are rounded to 0.01 deg)."""
REPORT_DEG = 0.01
"""Agreement with the report's printed angles [deg]."""
EXACT_M = 1e-12
"""Agreement between two exact routes to the same number [m] / [rad]."""


@pytest.mark.parametrize("case", FK_CASES, ids=["figure4", "figure7"])
def test_fk_reproduces_report_cases(case):
    pose = tool_pose(np.radians(case.q_deg))
    assert_close(pose.position * 1e3, case.position_mm, atol=REPORT_MM)
    # The report's second case rounds its inputs to 0.01 deg; the pitch is their sum.
    assert_close(math.degrees(pose.pitch), case.pitch_deg, atol=2 * REPORT_DEG)


@pytest.mark.parametrize("row", TABLE4, ids=[r.name for r in TABLE4])
def test_table4_joints_reach_table4_poses(row):
    q = np.radians([*row.q_deg, 0.0])
    pose = tool_pose(q)
    assert_close(pose.position * 1e3, row.position_mm, atol=REPORT_MM)
    assert_close(math.degrees(pose.pitch), row.pitch_deg, atol=REPORT_DEG)


def test_table4_joint_origins_at_p1():
    q = ik(np.array(TABLE4[0].position_mm) * 1e-3, math.radians(TABLE4[0].pitch_deg)).q
    origins = frame_origins(q) * 1e3
    assert_close(origins[3], TABLE4_P1_ELBOW_MM, atol=REPORT_MM)
    assert_close(origins[4], TABLE4_P1_WRIST_MM, atol=REPORT_MM)


def test_closed_form_equals_dh_chain():
    rng = np.random.default_rng(1)
    q = rng.uniform(LYNX_ARM.lower, LYNX_ARM.upper, size=(1000, 5))
    frames = frame_transforms(q)
    pose = tool_pose(q)
    assert_close(frames[:, 6, :3, 3], pose.position, atol=EXACT_M)
    # The tool axis (z of the tool frame) points at the pitch angle in the arm's plane.
    direction = np.stack(
        [
            np.cos(pose.pitch) * np.cos(q[:, 0]),
            np.cos(pose.pitch) * np.sin(q[:, 0]),
            np.sin(pose.pitch),
        ],
        axis=-1,
    )
    assert_close(frames[:, 6, :3, 2], direction, atol=EXACT_M)
    assert_close(fk(q), frames[:, 6], atol=EXACT_M)


def test_frames_are_rigid_transforms():
    q = np.random.default_rng(2).uniform(LYNX_ARM.lower, LYNX_ARM.upper, size=(200, 5))
    rot = frame_transforms(q)[..., :3, :3]
    assert_close(rot @ np.swapaxes(rot, -1, -2), np.broadcast_to(np.eye(3), rot.shape), atol=1e-12)
    assert_close(np.linalg.det(rot), np.ones(rot.shape[:-2]), atol=1e-12)


def test_roll_does_not_move_the_tool_point():
    q = np.radians([10.0, 60.0, -70.0, 20.0, 0.0])
    q_rolled = q.copy()
    q_rolled[4] = 2.0
    assert_close(tool_pose(q_rolled).position, tool_pose(q).position, atol=EXACT_M)


@pytest.mark.parametrize("shape", [(), (3,), (2, 4)], ids=["single", "batch", "grid"])
def test_fk_keeps_batch_shape(shape):
    q = np.zeros((*shape, 5))
    assert fk(q).shape == (*shape, 4, 4)
    assert frame_origins(q).shape == (*shape, 7, 3)
    assert tool_pose(q).position.shape == (*shape, 3)


def test_fk_rejects_wrong_joint_count():
    with pytest.raises(InvalidInputError, match=r"shape \(\.\.\., 5\), got \(4,\)"):
        fk(np.zeros(4))


def test_kinematics_does_not_import_mujoco():
    code = "import sys, lynxsim.arm; sys.exit('mujoco' in sys.modules)"
    assert subprocess.run([sys.executable, "-c", code], check=False).returncode == 0


# ------------------------------------------------------------ odd inputs (fuzz campaign)

_ODD_Q = [
    pytest.param("0 0 0 0 0", InvalidInputError, id="str"),
    pytest.param(None, InvalidInputError, id="none"),
    pytest.param({"q": 0.0}, InvalidInputError, id="dict"),
    pytest.param([0.0, [0.0, 0.0], 0.0, 0.0], InvalidInputError, id="ragged"),
    pytest.param(np.zeros(5, dtype=complex), InvalidInputError, id="complex"),
    pytest.param(np.ones(5, dtype=bool), InvalidInputError, id="bool-array"),
    pytest.param([0.0, 0.0, 0.0, 0.0, 10**400], InvalidInputError, id="int-beyond-float64"),
    pytest.param(np.array([0.0] * 5, dtype=object), InvalidInputError, id="object-array"),
    pytest.param([0.0, math.inf, 0.0, 0.0, 0.0], NonFiniteInputError, id="inf"),
    pytest.param([0.0, 0.0, math.nan, 0.0, 0.0], NonFiniteInputError, id="nan"),
    pytest.param(np.zeros(4), InvalidInputError, id="shape-4"),
]


@pytest.mark.parametrize(
    "fn",
    [fk, frame_transforms, frame_origins, tool_pose, jacobian, geometric_jacobian, manipulability],
    ids=lambda f: f.__name__,
)
@pytest.mark.parametrize(("q", "error"), _ODD_Q)
def test_joint_functions_refuse_odd_inputs_with_typed_errors(fn, q, error):
    with pytest.raises(error):
        fn(q)


def test_joint_functions_accept_integer_and_float32_joints():
    q = np.array([0, 1, -1, 0, 2])
    assert_close(tool_pose(q).position, tool_pose(q.astype(float)).position, atol=0.0)
    assert_close(fk(q.astype(np.float32)), fk(q.astype(np.float32).astype(float)), atol=0.0)


def test_a_geometry_that_is_not_one_is_refused():
    with pytest.raises(InvalidInputError, match="geometry must be an ArmGeometry"):
        tool_pose(np.zeros(5), "lynx")  # type: ignore[arg-type]


def test_manipulability_kind_must_be_a_listed_string():
    with pytest.raises(InvalidInputError, match="kind must be 'position' or 'position_pitch'"):
        manipulability(np.zeros(5), kind=np.array(["position"]))  # type: ignore[arg-type]
