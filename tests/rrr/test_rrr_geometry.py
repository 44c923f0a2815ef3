"""Geometry, working-mode encoding and package hygiene of lynxsim.rrr."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest

import lynxsim.rrr
from lynxsim.errors import InvalidInputError
from lynxsim.rrr import (
    MODE_SIGNS,
    RRR_ROBOT,
    RRRGeometry,
    mode_index,
    mode_label,
    mode_signs,
    platform_joints,
    rotation,
)
from tests.helpers import assert_close

EXACT_M = 1e-12
"""Agreement of positions computed two ways [m]."""


def test_robot_matches_spec_section_2():
    g = RRR_ROBOT
    r_b, c30, s30 = 0.290, math.cos(math.radians(30)), math.sin(math.radians(30))
    assert_close(g.base, [[0, 0], [2 * r_b * c30, 0], [r_b * c30, r_b * (1 + s30)]], atol=EXACT_M)
    assert_close(g.base * 1e3, [[0, 0], [502.29, 0], [251.15, 435]], atol=0.01)
    assert_close(g.base_centre, [0.25115, 0.145], atol=1e-5)
    assert (g.proximal, g.distal) == (0.170, 0.130)
    assert g.platform_radius == pytest.approx(0.130)
    assert (g.reach_min, g.reach_max) == (pytest.approx(0.040), pytest.approx(0.300))


def test_base_joints_lie_on_the_base_circle():
    assert_close(
        np.linalg.norm(RRR_ROBOT.base - RRR_ROBOT.base_centre, axis=1), [0.29] * 3, atol=EXACT_M
    )


def test_symmetric_constructor_reproduces_the_robot():
    g = RRRGeometry.symmetric(
        base_centre=RRR_ROBOT.base_centre,
        base_radius=0.29,
        platform_radius=0.13,
        proximal=0.17,
        distal=0.13,
    )
    assert_close(g.base, RRR_ROBOT.base, atol=EXACT_M)
    assert_close(g.platform, RRR_ROBOT.platform, atol=EXACT_M)


def test_platform_joints_point_like_the_base_joints_at_alpha_zero():
    centre = np.array(RRR_ROBOT.base_centre)
    p = platform_joints([*centre, 0.0])
    from_centre = p - centre
    base_dirs = RRR_ROBOT.base - centre
    assert_close(from_centre / 0.13, base_dirs / 0.29, atol=EXACT_M)
    angles = np.degrees(np.arctan2(from_centre[:, 1], from_centre[:, 0])) % 360
    assert_close(angles, [210, 330, 90], atol=1e-9)


def test_alpha_turns_the_platform_counter_clockwise():
    p0 = platform_joints([0.2, 0.1, 0.0])
    p1 = platform_joints([0.2, 0.1, math.radians(10.0)])
    a0 = np.arctan2(p0[:, 1] - 0.1, p0[:, 0] - 0.2)
    a1 = np.arctan2(p1[:, 1] - 0.1, p1[:, 0] - 0.2)
    assert_close(np.degrees(np.angle(np.exp(1j * (a1 - a0)))), [10.0] * 3, atol=1e-9)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"proximal": 0.0}, "proximal link length must be positive"),
        ({"distal": math.nan}, "distal link length must be positive"),
        ({"base_joints": ((0.0, 0.0), (1.0, 0.0))}, "base_joints must hold 3 points"),
        ({"platform_offsets": ((0.0, 0.0), (1.0, 0.0), (0.0, math.inf))}, r"platform_offsets\[2\]"),
    ],
    ids=["zero-proximal", "nan-distal", "two-legs", "infinite-offset"],
)
def test_geometry_rejects_bad_values(kwargs, match):
    base = {
        "base_joints": RRR_ROBOT.base_joints,
        "platform_offsets": RRR_ROBOT.platform_offsets,
        "proximal": 0.17,
        "distal": 0.13,
    }
    with pytest.raises(InvalidInputError, match=match):
        RRRGeometry(**(base | kwargs))


def test_geometry_is_frozen():
    with pytest.raises(AttributeError):
        RRR_ROBOT.proximal = 1.0  # type: ignore[misc]


def test_mode_encoding_round_trips_and_matches_the_table():
    assert MODE_SIGNS.shape == (8, 3)
    assert len({tuple(r) for r in MODE_SIGNS}) == 8
    assert_close(mode_index(MODE_SIGNS), np.arange(8), atol=0)
    assert mode_signs(0).tolist() == [1, 1, 1]
    assert mode_signs(1).tolist() == [-1, 1, 1]
    assert mode_signs(6).tolist() == [1, -1, -1]
    assert mode_label(5) == "-+-"
    with pytest.raises(ValueError, match=r"read-only"):
        MODE_SIGNS[0, 0] = 0


@pytest.mark.parametrize("bad", [8, -1, 1.5], ids=["eight", "negative", "float"])
def test_mode_index_out_of_range_is_rejected(bad):
    with pytest.raises(InvalidInputError, match=r"0\.\.7"):
        mode_signs(bad)


def test_bad_elbow_signs_are_rejected():
    with pytest.raises(InvalidInputError, match="±1"):
        mode_index([1, 0, 1])


def test_every_name_in_all_resolves():
    for name in lynxsim.rrr.__all__:
        assert hasattr(lynxsim.rrr, name), name


def test_kinematics_do_not_import_mujoco_or_matplotlib():
    code = (
        "import sys, lynxsim.rrr, lynxsim.reproduce.rrr_formulas; "
        "print('mujoco' in sys.modules, 'matplotlib' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["False", "False"]


# ------------------------------------------------------------ odd inputs (fuzz campaign)


@pytest.mark.parametrize(
    "kwargs",
    [
        {"proximal": "0.17"},
        {"distal": 10**400},
        {"proximal": True},
        {"base_joints": 3.0},
        {"platform_offsets": ((0.0, 0.0), (1.0, 0.0), "xy")},
        {"base_centre": None},
    ],
    ids=[
        "str-length",
        "int-beyond-float64",
        "bool-length",
        "number-not-points",
        "str-point",
        "none",
    ],
)
def test_geometry_refuses_odd_types_with_a_typed_error(kwargs):
    base = {
        "base_joints": RRR_ROBOT.base_joints,
        "platform_offsets": RRR_ROBOT.platform_offsets,
        "proximal": 0.17,
        "distal": 0.13,
    }
    with pytest.raises(InvalidInputError):
        RRRGeometry(**(base | kwargs))


@pytest.mark.parametrize(
    "alpha",
    ["0.1", None, 1j, np.array([True]), np.array([0.1, "a"], dtype=object)],
    ids=["str", "none", "complex", "bool-array", "object-array"],
)
def test_rotation_and_platform_joints_refuse_non_numbers(alpha):
    with pytest.raises(InvalidInputError, match="alpha must be real numbers"):
        rotation(alpha)
    with pytest.raises(InvalidInputError, match="pose must be real numbers"):
        platform_joints([0.2, 0.1, alpha])


def test_non_finite_poses_give_nan_platform_joints_not_infinity():
    out = platform_joints([[0.2, math.inf, 0.0], [0.2, 0.1, 0.0]])
    assert np.isnan(out[0]).all()
    assert np.isfinite(out[1]).all()
    with pytest.raises(InvalidInputError, match=r"within ±10 m"):
        platform_joints([1e300, 0.0, 0.0])
