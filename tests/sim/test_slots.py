"""Obstacle slots: obstacles placed at run time collide exactly as compiled ones."""

from __future__ import annotations

import numpy as np
import pytest

from lynxsim.arm import LYNX_ARM
from lynxsim.errors import InvalidInputError
from lynxsim.random_scenes import random_obstacles
from lynxsim.scene import REPORT_CUBE, Box, Cylinder, Scene, Sphere
from lynxsim.sim.arm.model import load_arm_spec
from lynxsim.sim.arm.playback import arm_checker
from lynxsim.sim.arm.slots import ObstacleSlots, add_obstacle_slots
from lynxsim.sim.collision import CLEARANCE_CAP_M

PER_SHAPE = 3


def _slot_model() -> tuple[object, ObstacleSlots]:
    spec = load_arm_spec(Scene((), cube=REPORT_CUBE))
    add_obstacle_slots(spec, PER_SHAPE)
    model = spec.compile()
    return model, ObstacleSlots.from_model(model)


def _compiled(obstacles: tuple[Cylinder | Box | Sphere, ...]) -> object:
    return load_arm_spec(Scene(obstacles, cube=REPORT_CUBE)).compile()


def _configs(count: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return rng.uniform(LYNX_ARM.q_min, LYNX_ARM.q_max, (count, 5))


def test_slots_are_found() -> None:
    _, slots = _slot_model()
    assert slots.per_shape == PER_SHAPE
    assert all(len(ids) == PER_SHAPE for ids in slots.geoms.values())


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_placed_obstacles_collide_as_compiled_ones(seed: int) -> None:
    """Same verdicts and bit-identical clearances as a model compiled with the obstacles.

    The obstacles are placed twice (a first scene, then the tested one), so a
    slot that moved and changed size is tested too.
    """
    model, slots = _slot_model()
    rng = np.random.default_rng(seed)
    slots.place(random_obstacles(rng, 3))
    obstacles = random_obstacles(rng, 3)
    slots.place(obstacles)
    reference = _compiled(obstacles)
    q = _configs(1500, seed)
    got = arm_checker(model).check(q)
    want = arm_checker(reference).check(q)
    assert want.obstacle.sum() > 50  # the configurations do hit the obstacles
    np.testing.assert_array_equal(got.obstacle, want.obstacle)
    np.testing.assert_array_equal(got.self_hit, want.self_hit)
    # the reference has one column per obstacle; the slot model one per slot
    names = [model.geom(g).name for g in arm_checker(model).groups.obstacle_geoms]
    for k, obstacle in enumerate(obstacles):
        shape_slots = slots.geoms[type(obstacle)]
        index = sum(type(o) is type(obstacle) for o in obstacles[:k])
        column = names.index(model.geom(shape_slots[index]).name)
        np.testing.assert_array_equal(got.clearance_m[:, column], want.clearance_m[:, k])


def test_bounds_are_the_compilers() -> None:
    model, slots = _slot_model()
    obstacles = (
        Cylinder("c", (0.2, 0.1, -0.0125), radius=0.03, height=0.25),
        Box("b", (0.1, -0.2, -0.0125), size=(0.05, 0.07, 0.2), yaw=0.7),
        Sphere("s", (-0.1, 0.2, 0.15), radius=0.04),
    )
    slots.place(obstacles)
    reference = _compiled(obstacles)
    for obstacle in obstacles:
        g = slots.geoms[type(obstacle)][0]
        r = reference.geom(obstacle.name).id
        np.testing.assert_allclose(model.geom_aabb[g], reference.geom_aabb[r], rtol=1e-15)
        np.testing.assert_allclose(model.geom_rbound[g], reference.geom_rbound[r], rtol=1e-15)
        np.testing.assert_allclose(model.geom_pos[g], reference.geom_pos[r], rtol=1e-15)
        np.testing.assert_allclose(model.geom_quat[g], reference.geom_quat[r], rtol=1e-15)


def test_parked_slots_never_touch() -> None:
    model, slots = _slot_model()
    slots.place(random_obstacles(np.random.default_rng(5), 3))
    slots.place(())
    check = arm_checker(model).check(_configs(500, 3))
    assert not check.obstacle.any()
    assert (check.clearance_m == CLEARANCE_CAP_M).all()  # nothing within the cap
    assert (model.geom_rgba[[g for ids in slots.geoms.values() for g in ids], 3] == 0).all()


def test_too_many_obstacles_of_a_shape_are_refused() -> None:
    _, slots = _slot_model()
    spheres = tuple(Sphere(f"s{i}", (0.2, 0.0, 0.1 * i), radius=0.02) for i in range(4))
    with pytest.raises(InvalidInputError, match="sphere slot"):
        slots.place(spheres)
