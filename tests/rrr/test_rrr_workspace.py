"""Constant-orientation workspaces, orientation ranges and singularity loci."""

from __future__ import annotations

import math

import numpy as np
import pytest

from lynxsim.errors import InvalidInputError
from lynxsim.rrr import (
    RRR_ROBOT,
    grid_extent,
    ik,
    leg_annuli,
    mode_index,
    mode_label,
    orientation_intervals,
    orientation_range,
    orientation_range_in_mode,
    parallel_singularity_loci,
    singularity_measures,
    workspace_map,
)
from lynxsim.rrr.workspace import workspace_maps
from tests.helpers import assert_close

ALPHA_STEP = math.radians(0.005)
"""Orientation sampling of the brute-force checks [rad]."""

FIGURE21_DEG = (0.0, 20.0, -20.0, 50.0, -50.0)


@pytest.fixture(scope="module")
def grid_map():
    x = np.arange(0.0, 0.5025, 0.0025)
    y = np.arange(0.0, 0.4025, 0.0025)
    return workspace_map(x, y, math.radians(20.0), with_theta=True)


def test_map_agrees_with_point_by_point_ik(grid_map):
    gx, gy = np.meshgrid(grid_map.x, grid_map.y)
    poses = np.stack([gx, gy, np.full(gx.shape, grid_map.alpha)], axis=-1)
    result = ik(poses)
    assert (result.ok == grid_map.reachable).all()
    assert (result.leg_status == 0).tolist() == grid_map.leg_reachable.tolist()
    ok = result.ok
    assert_close(grid_map.theta[ok], result.theta[ok], atol=1e-12)
    meas = singularity_measures(poses[ok][:, None, :], result.theta[ok])
    assert_close(grid_map.parallel[ok], meas.parallel, atol=1e-12)
    assert_close(grid_map.serial[ok], meas.serial[:, 0], atol=1e-12)
    assert np.isnan(grid_map.parallel[~ok]).all()
    assert np.isnan(grid_map.serial[~ok]).all()


def test_reachable_set_is_the_intersection_of_the_leg_annuli(grid_map):
    ann = leg_annuli(grid_map.alpha)
    gx, gy = np.meshgrid(grid_map.x, grid_map.y)
    dist = np.hypot(gx[..., None] - ann.centres[:, 0], gy[..., None] - ann.centres[:, 1])
    inside = (dist >= ann.r_min) & (dist <= ann.r_max)
    assert (inside == grid_map.leg_reachable).all()


def test_grid_extent_holds_every_reachable_centre():
    alphas = [math.radians(a) for a in FIGURE21_DEG]
    x0, x1, y0, y1 = grid_extent(alphas, margin=0.0)
    x = np.arange(-0.1, 0.65, 0.004)
    y = np.arange(-0.1, 0.6, 0.004)
    for a in alphas:
        wmap = workspace_map(x, y, a)
        gx, gy = np.meshgrid(x, y)
        assert (gx[wmap.reachable] >= x0).all()
        assert (gx[wmap.reachable] <= x1).all()
        assert (gy[wmap.reachable] >= y0).all()
        assert (gy[wmap.reachable] <= y1).all()


@pytest.mark.parametrize("alpha_deg", [20.0, 50.0], ids=["20deg", "50deg"])
def test_mirror_symmetry_maps_alpha_to_minus_alpha(alpha_deg):
    # The robot is symmetric about x = C_b,x; mirroring turns alpha into -alpha.
    cx = RRR_ROBOT.base_centre[0]
    half = np.arange(-0.2, 0.2001, 0.002)
    y = np.arange(0.0, 0.4, 0.002)
    plus = workspace_map(cx + half, y, math.radians(alpha_deg))
    minus = workspace_map(cx - half, y, math.radians(-alpha_deg))
    disagree = plus.reachable != minus.reachable
    assert disagree.mean() < 1e-3  # only boundary rounding
    assert plus.area == pytest.approx(minus.area, rel=5e-3)


def test_figure21_areas_shrink_with_rotation():
    x0, x1, y0, y1 = grid_extent([0.0])
    x = np.arange(x0, x1, 0.002)
    y = np.arange(y0, y1, 0.002)
    areas = {a: workspace_map(x, y, math.radians(a)).area * 1e6 for a in FIGURE21_DEG}
    assert areas[0.0] == pytest.approx(64_770, rel=0.01)
    assert areas[0.0] > areas[20.0] > areas[50.0] > 0.0


def test_orientation_range_at_the_base_centre_is_closed_form():
    # At C_b every leg spans |r_p e^{i alpha} - r_b|: reachable while
    # r_b^2 + r_p^2 - 2 r_b r_p cos(alpha) <= (s_a + L)^2.
    limit = math.acos((0.29**2 + 0.13**2 - 0.30**2) / (2 * 0.29 * 0.13))
    rng = orientation_range(np.array(RRR_ROBOT.base_centre))
    assert_close([rng.lower, rng.upper], [-limit, limit], atol=1e-12)
    assert math.degrees(limit) == pytest.approx(81.611, abs=1e-3)
    assert not rng.full_turn
    assert orientation_intervals(*RRR_ROBOT.base_centre) == [pytest.approx((-limit, limit))]


def test_orientation_range_matches_brute_force_sampling():
    rng = np.random.default_rng(8)
    points = rng.uniform([0.05, 0.0], [0.45, 0.4], size=(60, 2))
    alphas = np.arange(-np.pi, np.pi, ALPHA_STEP)
    result = orientation_range(points)
    for p, lo, hi in zip(points, result.lower, result.upper, strict=True):
        poses = np.column_stack([np.full(alphas.shape, p[0]), np.full(alphas.shape, p[1]), alphas])
        ok = ik(poses).ok
        arcs = orientation_intervals(*p)
        total = sum(e - s for s, e in arcs)
        assert total == pytest.approx(ok.mean() * 2 * np.pi, abs=4 * ALPHA_STEP)
        if not ik([p[0], p[1], 0.0]).ok:
            assert math.isnan(lo)
            assert math.isnan(hi)
            continue
        inside = ik(
            np.column_stack([np.full(5, p[0]), np.full(5, p[1]), np.linspace(lo, hi, 7)[1:-1]])
        ).ok
        assert inside.all()
        outside = ik([[p[0], p[1], lo - 1e-6], [p[0], p[1], hi + 1e-6]]).ok
        assert not outside.any()
        assert any(s - 1e-9 <= lo and hi <= e + 1e-9 for s, e in arcs)


def test_orientation_range_names_the_limiting_legs():
    rng = orientation_range(np.array([[0.3, 0.25], [0.2, 0.15]]))
    assert rng.limiting_leg.shape == (2, 2)
    for (x, y), lo, hi, legs in zip(
        [[0.3, 0.25], [0.2, 0.15]], rng.lower, rng.upper, rng.limiting_leg, strict=True
    ):
        for alpha, leg in ((lo - 1e-6, legs[0]), (hi + 1e-6, legs[1])):
            assert ik([x, y, alpha]).failing_legs() == (int(leg),)


def test_unreachable_point_has_no_orientations():
    assert orientation_intervals(0.6, 0.6) == []
    assert np.isnan(orientation_range(np.array([0.6, 0.6])).lower)


def test_orientation_range_in_mode_stops_at_parallel_singularities():
    cx, cy = RRR_ROBOT.base_centre
    reach = orientation_range(np.array([cx, cy]))
    for mode in range(8):
        lo, hi = orientation_range_in_mode(cx, cy, mode)
        assert reach.lower - 1e-12 <= lo < 0.0 < hi <= reach.upper + 1e-12
        for end, limit in ((lo, reach.lower), (hi, reach.upper)):
            if abs(end - limit) > 1e-9:  # stopped inside the reachable range
                pose = np.array([cx, cy, end])
                assert abs(singularity_measures(pose, ik(pose).theta[mode]).parallel) < 1e-9


def test_singularity_loci_lie_where_the_measure_vanishes(grid_map):
    lines = parallel_singularity_loci(grid_map, 0)
    assert lines
    pts = np.concatenate(lines)
    poses = np.column_stack([pts, np.full(len(pts), grid_map.alpha)])
    result = ik(poses)
    ok = result.ok
    meas = singularity_measures(poses[ok], result.theta[ok, 0]).parallel
    assert ok.mean() > 0.98
    assert np.abs(meas).max() < 0.03  # linear interpolation on a 2.5 mm grid


def test_singularity_free_mask_is_inside_the_reachable_set(grid_map):
    free = grid_map.singularity_free(0, margin=0.05)
    assert (free <= grid_map.reachable).all()
    assert 0.5 < free.sum() / grid_map.reachable.sum() < 1.0


@pytest.mark.parametrize(
    ("x", "y", "alpha"),
    [
        (np.zeros((2, 2)), np.zeros(3), 0.0),
        (np.zeros(3), np.array([np.nan]), 0.0),
        (np.zeros(3), np.zeros(3), math.inf),
    ],
    ids=["2d-x", "nan-y", "inf-alpha"],
)
def test_workspace_map_rejects_bad_grids(x, y, alpha):
    with pytest.raises(InvalidInputError):
        workspace_map(x, y, alpha)


# ------------------------------------------------------------ odd inputs (fuzz campaign)


@pytest.mark.parametrize(
    "resolution", [1e-300, 5e-324, 1e-7], ids=["1e-300", "denormal", "0.1-micrometre"]
)
def test_workspace_maps_bound_the_grid_before_allocating(resolution):
    with pytest.raises(InvalidInputError, match=r"at most 10,000,000.*resolution of at least"):
        workspace_maps([0.0], (0.0, 0.5, 0.0, 0.45), resolution)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"resolution": math.nan}, "resolution must be finite"),
        ({"resolution": "0.01"}, "resolution must be a number"),
        ({"extent": (0.0, 1e9, 0.0, 1.0)}, r"extent\[1\] must be between -10 and 10 m"),
        ({"extent": (0.5, 0.0, 0.0, 0.4)}, "min <= max"),
        ({"alphas": []}, "alphas must be 1 to 10,000 orientations"),
        ({"alphas": [0.0, math.inf]}, "alphas must be finite"),
    ],
    ids=["nan-step", "str-step", "huge-extent", "inverted-extent", "no-alphas", "inf-alpha"],
)
def test_workspace_maps_refuse_odd_arguments(kwargs, match):
    args = {"alphas": [0.0], "extent": (0.0, 0.5, 0.0, 0.45), "resolution": 0.05} | kwargs
    with pytest.raises(InvalidInputError, match=match):
        workspace_maps(**args)


def test_workspace_map_bounds_its_grid_and_checks_with_theta():
    big = np.linspace(0.0, 0.5, 4000)
    with pytest.raises(InvalidInputError, match="has 16,000,000 points"):
        workspace_map(big, big, 0.0)
    with pytest.raises(InvalidInputError, match="with_theta must be True or False"):
        workspace_map(np.zeros(3), np.zeros(3), 0.0, with_theta=np.array([1, 2]))  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: orientation_range_in_mode(0.25, 0.15, 0, step=0.0), "step must be between"),
        (lambda: orientation_range_in_mode(0.25, 0.15, [0, 1]), "mode must be one integer"),
        (lambda: orientation_range_in_mode(math.inf, 0.15, 0), "x must be finite"),
        (lambda: orientation_intervals(-math.inf, 0.15), "x must be finite"),
        (lambda: orientation_intervals("0.25", 0.15), "x must be a number"),
        (lambda: orientation_range([0.25, 0.15], alpha_ref="0"), "alpha_ref must be a number"),
        (lambda: grid_extent([]), "alphas must be 1 to"),
        (lambda: leg_annuli(None), "alpha must be a number"),
        (lambda: mode_label(np.arange(3)), "mode_label takes one working mode"),
        (lambda: mode_index([True, False, True]), "elbow signs must be ±1"),
    ],
    ids=[
        "zero-step",
        "two-modes",
        "inf-x",
        "intervals-inf",
        "intervals-str",
        "str-alpha",
        "no-alphas",
        "none-alpha",
        "label-array",
        "bool-signs",
    ],
)
def test_orientation_and_mode_functions_refuse_odd_inputs(call, match):
    with pytest.raises(InvalidInputError, match=match):
        call()


@pytest.mark.parametrize("alpha", [4.0 * math.pi + 1e-9, -1e6], ids=["just-past-two-turns", "far"])
def test_orientations_beyond_two_turns_are_refused(alpha):
    xs = np.linspace(-0.1, 0.1, 3)
    with pytest.raises(InvalidInputError, match=r"alpha must be between -12\.566\d* and 12\.566"):
        workspace_map(xs, xs, alpha)
    with pytest.raises(InvalidInputError, match=r"alphas\[1\] must be between"):
        workspace_maps([0.0, alpha], xs, xs)
