"""The sphere cover made from the MJCF: it encloses every geom, and is never optimistic.

The cover's clearance of a joint vector must never exceed the exact
clearance of :class:`~lynxsim.sim.collision.CollisionChecker` (MuJoCo's
``mj_geomDistance`` to the obstacles; ``-inf`` on an obstacle, self or table
contact), checked on 10^5 random configurations per obstacle shape, half of
them holding the cube.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from lynxsim.arm import LYNX_ARM
from lynxsim.arm.motion import arm_lipschitz
from lynxsim.errors import InvalidInputError
from lynxsim.plan import check_path
from lynxsim.plan.cover import CoverOracle
from lynxsim.plan.cover.search import FOUND
from lynxsim.plan.cover.world import GEOM_BOX, GEOM_CAPSULE, GEOM_CYLINDER, GEOM_SPHERE
from lynxsim.scene import TABLE, Box, Cylinder, Scene, Sphere
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import arm_checker
from lynxsim.sim.cover import DEFAULT_SLACK_M, cover_geom, cover_world
from lynxsim.sim.planning import PLANNING_CAP_M, CheckerOracle, cover_oracle

CONFIGS_PER_SHAPE = 100_000
PLACEMENTS = 4


def _obstacle(shape: str, k: int) -> Cylinder | Box | Sphere:
    angle = k * math.pi / 2 + 0.3
    x, y = 0.2 * math.cos(angle), 0.2 * math.sin(angle)
    if shape == "cylinder":
        return Cylinder(f"c{k}", (x, y, 0.0), radius=0.03, height=0.22)
    if shape == "box":
        return Box(f"b{k}", (x, y, 0.06), size=(0.06, 0.05, 0.12))
    if shape == "rotated box":
        return Box(f"r{k}", (x, y, 0.08), size=(0.05, 0.12, 0.04), yaw=0.6 + k)
    return Sphere(f"s{k}", (x, y, 0.12), radius=0.045)


def _distance(kind: int, size: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Distance of points (N, 3) to a geom in its frame (0 inside) [m]."""
    if kind == GEOM_BOX:
        return np.linalg.norm(np.maximum(np.abs(p) - size, 0.0), axis=1)
    if kind == GEOM_CYLINDER:
        radial = np.maximum(np.hypot(p[:, 0], p[:, 1]) - size[0], 0.0)
        return np.hypot(radial, np.maximum(np.abs(p[:, 2]) - size[1], 0.0))
    if kind == GEOM_SPHERE:
        return np.maximum(np.linalg.norm(p, axis=1) - size[0], 0.0)
    z = np.clip(p[:, 2], -size[1], size[1])
    return np.maximum(np.sqrt(p[:, 0] ** 2 + p[:, 1] ** 2 + (p[:, 2] - z) ** 2) - size[0], 0.0)


def _inside(kind: int, size: np.ndarray, p: np.ndarray) -> np.ndarray:
    return _distance(kind, size, p) <= 0.0


@pytest.mark.parametrize(
    ("kind", "size"),
    [
        (GEOM_BOX, (0.034, 0.0303, 0.0135)),
        (GEOM_BOX, (0.024, 0.01, 0.002)),
        (GEOM_CAPSULE, (0.008, 0.0467, 0.0)),
        (GEOM_CYLINDER, (0.06, 0.00625, 0.0)),
        (GEOM_CYLINDER, (0.01, 0.05, 0.0)),
        (GEOM_SPHERE, (0.02, 0.0, 0.0)),
    ],
)
def test_every_point_of_a_geom_lies_in_a_sphere_and_the_slack_is_bounded(kind, size):
    cover = cover_geom(kind, size)
    s = np.array(size)
    reach = np.array([s[0], s[0], s[1] + (s[0] if kind == GEOM_CAPSULE else 0.0)])
    if kind == GEOM_BOX:
        reach = s
    if kind == GEOM_SPHERE:
        reach = np.full(3, s[0])
    rng = np.random.default_rng(0)
    points = rng.uniform(-reach, reach, size=(200_000, 3))
    points = points[_inside(kind, s, points)]
    corners = np.array(np.meshgrid(*[[-1, 1]] * 3)).reshape(3, -1).T * reach
    points = np.vstack([points, corners[_inside(kind, s, corners)]])
    d = np.linalg.norm(points[:, None, :] - cover.centres[None], axis=2) - cover.radii
    assert (d.min(axis=1) <= 1e-12).all()
    # No point of a sphere lies farther from the geom than the slack.
    dirs = rng.normal(size=(400, 3))
    dirs /= np.linalg.norm(dirs, axis=1, keepdims=True)
    surface = (cover.centres[:, None, :] + cover.radii[:, None, None] * dirs[None]).reshape(-1, 3)
    assert _distance(kind, s, surface).max() <= cover.slack_m + 1e-12
    if kind != GEOM_CYLINDER:  # the default target holds for boxes and capsules
        assert cover.slack_m <= DEFAULT_SLACK_M


def test_the_arm_cover_reports_its_size_and_slack():
    checker = arm_checker(load_arm_scene(Scene((), TABLE)))
    world, report = cover_world(checker, cap_m=PLANNING_CAP_M)
    assert 0 < report.geoms <= int((checker.groups.robot | checker.groups.payload).sum())
    assert report.spheres == world.n_spheres
    assert 0.0 < report.slack_m <= DEFAULT_SLACK_M
    assert report.self_pairs > 0
    assert report.fixed_pairs > 0


@pytest.mark.slow
@pytest.mark.parametrize("shape", ["cylinder", "box", "sphere", "rotated box"])
def test_the_cover_is_never_optimistic(shape):
    rng = np.random.default_rng(["cylinder", "box", "sphere", "rotated box"].index(shape))
    per = CONFIGS_PER_SHAPE // PLACEMENTS
    exact_hits = self_hits = table_hits = near = 0
    for k in range(PLACEMENTS):
        model = load_arm_scene(Scene((_obstacle(shape, k),), TABLE))
        checker = arm_checker(model)
        world, _ = cover_world(checker, cap_m=PLANNING_CAP_M)
        cover = CoverOracle(world)
        q = rng.uniform(LYNX_ARM.q_min, LYNX_ARM.q_max, size=(per, 5))
        for grasped, part in ((False, q[: per // 2]), (True, q[per // 2 :])):
            c = cover.clearance(part, grasped=grasped)
            e = checker.min_clearance(part, grasped=grasped, cap=PLANNING_CAP_M)
            bad = np.flatnonzero(c > e + 1e-9)
            assert bad.size == 0, (shape, k, grasped, part[bad[:3]], c[bad[:3]], e[bad[:3]])
            near += int(((e > 0.0) & (e < 0.05)).sum())
            hit = np.flatnonzero(np.isneginf(e))
            exact_hits += hit.size
            verdict = checker.check(part[hit[:2000]], grasped=grasped)
            self_hits += int((verdict.self_hit & ~verdict.obstacle).sum())
            table_hits += int((verdict.support & ~verdict.obstacle & ~verdict.self_hit).sum())
    # The sample holds every kind of case: near misses, obstacle, self and table hits.
    assert near > 1000
    assert exact_hits > 1000
    assert self_hits > 50
    assert table_hits > 50


def test_the_cover_follows_mujoco_kinematics_of_the_cube_held():
    model = load_arm_scene(Scene((Sphere("s", (0.2, 0.0, 0.1), radius=0.04),), TABLE))
    checker = arm_checker(model)
    world, _ = cover_world(checker, cap_m=1.0)
    cover = CoverOracle(world)
    rng = np.random.default_rng(5)
    q = rng.uniform(LYNX_ARM.q_min, LYNX_ARM.q_max, size=(500, 5))
    c = cover.clearance(q, grasped=True)
    e = checker.min_clearance(q, grasped=True, cap=1.0)
    free = np.isfinite(c) & np.isfinite(e)
    assert free.sum() > 100
    assert (c[free] <= e[free] + 1e-9).all()
    # A tight cover: far from everything its clearance is the exact one less its slack.
    assert np.median(e[free] - c[free]) < 2 * DEFAULT_SLACK_M


@settings(max_examples=60, deadline=None)
@given(
    kind=st.sampled_from([GEOM_BOX, GEOM_CAPSULE, GEOM_SPHERE]),
    size=st.tuples(*[st.floats(0.001, 0.08)] * 3),
)
def test_any_primitive_is_enclosed_by_its_cover(kind, size):
    cover = cover_geom(kind, size)
    s = np.array(size)
    rng = np.random.default_rng(1)
    reach = s if kind == GEOM_BOX else np.array([s[0], s[0], s[1] + s[0]])
    if kind == GEOM_SPHERE:
        reach = np.full(3, s[0])
    points = rng.uniform(-reach, reach, size=(4000, 3))
    points = points[_inside(kind, s, points)]
    d = np.linalg.norm(points[:, None, :] - cover.centres[None], axis=2) - cover.radii
    assert (d.min(axis=1) <= 1e-12).all()


def test_bad_geoms_get_typed_errors():
    with pytest.raises(InvalidInputError, match="geom type 4"):
        cover_geom(4, (0.1, 0.1, 0.1))
    with pytest.raises(InvalidInputError, match="positive"):
        cover_geom(GEOM_BOX, (0.1, -0.1, 0.1))
    with pytest.raises(InvalidInputError, match="3 finite"):
        cover_geom(GEOM_BOX, (0.1, np.nan, 0.1))


def test_a_compiled_path_is_certified_on_the_exact_checker_and_repeats_bit_for_bit():
    obstacles = (Box("wall", (0.2, 0.0, 0.1), size=(0.03, 0.25, 0.2)),)
    checker = arm_checker(load_arm_scene(Scene(obstacles, TABLE, cube=None)))
    exact = CheckerOracle(checker)
    start = np.array([-0.8, 1.2, -1.2, -0.5, 0.0])
    goal = np.array([0.8, 1.2, -1.2, -0.5, 0.0])
    paths = []
    for _ in range(2):
        cover = cover_oracle(checker)
        assert cover is not None
        found = cover.search(start, goal[None], LYNX_ARM.q_min, LYNX_ARM.q_max,
                             lipschitz=arm_lipschitz(), margin_m=0.01, grasped=False, seed=4,
                             shortcuts=30)  # fmt: skip
        assert found.status == FOUND
        paths.append(found.path)
    assert np.array_equal(paths[0], paths[1])
    assert np.array_equal(paths[0][0], start)
    assert np.array_equal(paths[0][-1], goal)
    verdict = check_path(paths[0], exact, lipschitz=arm_lipschitz(), margin_m=0.01, grasped=False)
    assert verdict.clear.all()
