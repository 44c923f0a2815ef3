"""Forward kinematics: every assembly mode, continuation along paths."""

from __future__ import annotations

import math

import numpy as np
import pytest

from lynxsim.errors import InvalidInputError
from lynxsim.rrr import (
    CLOSURE_TOL,
    MAX_ASSEMBLY_MODES,
    elbow_points,
    fk_all,
    fk_near,
    fk_path,
    ik,
    loop_residual,
    singularity_measures,
)
from lynxsim.rrr.ik import wrap_angle
from tests.helpers import assert_close

POSE_M = 1e-9
"""Agreement of recovered platform poses [m] and [rad]."""


def test_every_solution_closes_the_loops_and_counts_are_even(random_poses):
    theta = ik(random_poses[:500]).theta.reshape(-1, 3)
    sol = fk_all(theta)
    assert sol.pose.shape == (4000, MAX_ASSEMBLY_MODES, 3)
    assert (sol.num_solutions >= 1).all()
    assert (sol.num_solutions <= MAX_ASSEMBLY_MODES).all()
    filled = np.arange(MAX_ASSEMBLY_MODES) < sol.num_solutions[:, None]
    residual = loop_residual(sol.pose, theta[:, None, :])
    assert (np.abs(residual[filled]) <= CLOSURE_TOL).all()
    assert np.isnan(sol.pose[~filled]).all()
    assert (sol.mode[~filled] == -1).all()
    assert ((sol.mode[filled] >= 0) & (sol.mode[filled] < 8)).all()
    # A degree-6 polynomial has an even number of real roots away from double roots.
    assert (sol.num_solutions % 2 == 0).mean() > 0.99
    # Solutions are sorted by alpha and distinct.
    both = filled[:, 1:]
    assert (np.diff(sol.pose[..., 2], axis=-1)[both] > 0).all()


def test_the_robot_has_configurations_with_six_assembly_modes(random_poses):
    counts = fk_all(ik(random_poses[:300]).theta).num_solutions
    assert set(np.unique(counts)) <= {1, 2, 3, 4, 5, 6}
    assert (counts == 6).any()
    assert (counts == 2).any()
    assert (counts == 4).any()


def test_fk_of_angles_that_close_no_loop_is_empty():
    # Elbows of legs 1 and 2 pointing away from each other: no platform fits.
    theta = np.radians([180.0, 0.0, 90.0])
    sol = fk_all(theta)
    assert sol.num_solutions == 0
    assert np.isnan(sol.pose).all()


def test_non_finite_angles_give_no_solution():
    sol = fk_all(np.array([[0.1, np.nan, 0.2], [0.0, 1.0, -1.0]]))
    assert sol.num_solutions[0] == 0
    assert np.isnan(sol.pose[0]).all()


def test_fk_all_keeps_the_batch_shape(random_poses):
    theta = ik(random_poses[:6]).theta.reshape(2, 3, 8, 3)
    sol = fk_all(theta)
    assert sol.pose.shape == (2, 3, 8, MAX_ASSEMBLY_MODES, 3)
    assert sol.num_solutions.shape == (2, 3, 8)


def test_fk_near_returns_the_nearby_assembly_mode(random_poses):
    poses = random_poses[:400]
    theta = ik(poses).theta[:, 3]
    # Near a parallel singularity another assembly mode lies close by; stay away.
    keep = np.abs(singularity_measures(poses, theta).parallel) > 0.05
    poses, theta = poses[keep], theta[keep]
    near = fk_near(theta, poses + np.array([0.001, -0.001, math.radians(0.5)]))
    assert near.converged.all()
    assert_close(near.pose[:, :2], poses[:, :2], atol=POSE_M)
    assert_close(wrap_angle(near.pose[:, 2] - poses[:, 2]), np.zeros(len(poses)), atol=POSE_M)
    assert (near.mode == 3).all()


def test_fk_path_follows_one_assembly_mode():
    s = np.linspace(0.0, 1.0, 120)
    path = np.column_stack(
        [0.22 + 0.06 * s, 0.14 + 0.04 * np.sin(np.pi * s), np.radians(-20.0 + 40.0 * s)]
    )
    result = ik(path)
    assert result.ok.all()
    for mode in (0, 5):
        theta = result.theta[:, mode]
        follow = fk_path(theta, path[0] + [0.001, 0.001, 0.01])
        assert follow.converged.all()
        assert_close(follow.pose[:, :2], path[:, :2], atol=POSE_M)
        assert_close(wrap_angle(follow.pose[:, 2] - path[:, 2]), np.zeros(len(path)), atol=POSE_M)
        assert (follow.mode == mode).all()


def test_fk_path_stops_where_no_pose_fits():
    theta = np.radians([[-5.41, 117.24, -154.13], [180.0, 0.0, 90.0], [-5.41, 117.24, -154.13]])
    follow = fk_path(theta, [0.2, 0.15, 0.0])
    assert follow.converged.tolist() == [True, False, False]
    assert np.isnan(follow.pose[1:]).all()
    assert (follow.mode[1:] == -1).all()


def test_elbow_points_lie_on_the_proximal_circles():
    theta = np.random.default_rng(2).uniform(-np.pi, np.pi, (50, 3))
    e = elbow_points(theta)
    from lynxsim.rrr import RRR_ROBOT

    assert_close(np.linalg.norm(e - RRR_ROBOT.base, axis=-1), np.full((50, 3), 0.17), atol=1e-15)


@pytest.mark.parametrize("bad", [np.zeros(2), np.zeros((3, 4))], ids=["short", "wide"])
def test_fk_rejects_bad_shapes(bad):
    with pytest.raises(InvalidInputError, match=r"theta must have shape"):
        fk_all(bad)


def test_fk_path_needs_a_sequence():
    with pytest.raises(InvalidInputError, match=r"\(T, 3\)"):
        fk_path(np.zeros(3), [0.2, 0.15, 0.0])


# ------------------------------------------------------------ odd inputs (fuzz campaign)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"theta_path": np.zeros((0, 3))}, r"1 <= T <= 10,000,000, got \(0, 3\)"),
        ({"max_halvings": 10**9}, "max_halvings must be between 0 and 16"),
        ({"max_halvings": np.array([1, 2])}, "max_halvings must be an integer"),
        ({"start": [0.25, 0.15]}, r"start must have shape \(..., 3\)"),
        ({"theta_path": "abc"}, "theta_path must be real numbers"),
    ],
    ids=["empty-path", "huge-halvings", "array-halvings", "short-start", "str-path"],
)
def test_fk_path_refuses_odd_arguments_with_typed_errors(kwargs, match):
    args = {"theta_path": np.zeros((2, 3)), "start": [0.25, 0.15, 0.0]} | kwargs
    with pytest.raises(InvalidInputError, match=match):
        fk_path(**args)


def test_fk_path_stops_at_a_non_finite_sample_without_warnings():
    theta = ik([0.25, 0.15, 0.0]).theta[0]
    path = np.array([theta, [np.inf, 0.0, 0.0], theta])
    follow = fk_path(path, [0.25, 0.15, 0.0])
    assert follow.converged.tolist() == [True, False, False]


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: fk_near(np.zeros(3), np.zeros(3), max_iter=0), "max_iter must be between 1"),
        (lambda: fk_near(np.zeros((2, 3)), np.zeros((3, 3))), "do not broadcast"),
        (lambda: fk_all([[0.0, 0.0, 0.0], [0.0, 0.0]]), "theta must be real numbers"),
        (lambda: elbow_points(np.array([1j, 0, 0])), "theta must be real numbers"),
        (lambda: loop_residual(np.zeros((2, 3)), np.zeros((3, 3))), "do not broadcast"),
    ],
    ids=["zero-iterations", "near-broadcast", "ragged", "complex", "residual-broadcast"],
)
def test_fk_functions_refuse_odd_inputs_with_typed_errors(call, match):
    with pytest.raises(InvalidInputError, match=match):
        call()


def test_loop_residual_of_an_infinite_pose_is_nan_not_infinity():
    assert np.isnan(loop_residual([0.2, -math.inf, 0.0], [0.0, 0.0, 0.0])).all()


def test_singularity_measures_of_an_infinite_pose_are_nan_not_infinity():
    m = singularity_measures([0.25, math.inf, 0.35], [2.0, -2.5, 0.6])
    assert np.isnan(m.parallel)
    assert np.isnan(m.leg).all()
