"""Resets that always find a scene and never remember the episode before."""

from __future__ import annotations

import itertools

import mujoco
import numpy as np
import pytest

from lynxsim.envs import PickAndPlaceEnv, Randomization, ReachEnv
from lynxsim.errors import InfeasibleSceneError, InvalidInputError
from lynxsim.scene import Box

WIDEST = Randomization(
    cube_size_m=(0.005, 0.03),
    cube_mass_kg=(1e-4, 0.5),
    cube_friction=(0.01, 5.0),
    servo_gain_tolerance=0.5,
    joint_damping_tolerance=0.5,
    camera_shift_m=0.1,
    camera_tilt_rad=0.5,
)
"""Every documented randomisation range at its widest."""
ARM_ONLY = Randomization(servo_gain_tolerance=0.5, joint_damping_tolerance=0.5, camera_shift_m=0.1)
"""The widest randomisation of an env without a cube."""
MOST_OBSTACLES = (1, 4)
"""The widest documented range of random obstacles."""
WALL = Box(name="wall", position=(0.2, 0.0, -0.0125), size=(0.08, 0.6, 0.3))
"""A wall across every place the tasks draw from."""
STEPS = 15
"""Steps of each compared episode."""


@pytest.mark.parametrize("cls", [PickAndPlaceEnv, ReachEnv], ids=["pick", "reach"])
@pytest.mark.parametrize(
    "kwargs", [{"distance_threshold": 0.6}, {"obstacles": [WALL]}], ids=["radius", "wall"]
)
def test_options_that_can_never_give_an_episode_are_refused_at_construction(cls, kwargs):
    with pytest.raises(InfeasibleSceneError, match="can never draw an episode"):
        cls(**kwargs)


def test_a_cube_mass_no_scene_holds_is_refused_by_the_randomization():
    with pytest.raises(InvalidInputError, match=r"cube_mass_kg must be >= 0.0001 kg"):
        Randomization(cube_mass_kg=(1e-5, 0.01))
    assert Randomization(cube_mass_kg=(1e-4, 0.5)).cube_mass_kg == (1e-4, 0.5)


def _resets(n: int) -> None:
    env = PickAndPlaceEnv(random_obstacles=MOST_OBSTACLES, randomize=WIDEST)
    fewest, most = MOST_OBSTACLES
    for seed in range(n):
        env.reset(seed=seed)
        size = env.domain.cube_size_m
        assert fewest <= len(env.obstacles) <= most
        assert env.cube_position[2] == pytest.approx(env.table_top_z + 0.5 * size, abs=1e-12)
    reach = ReachEnv(random_obstacles=MOST_OBSTACLES, randomize=ARM_ONLY)
    for seed in range(n // 10):
        reach.reset(seed=seed)
        assert fewest <= len(reach.obstacles) <= most


def test_resets_with_the_most_obstacles_and_the_widest_randomisation_find_a_scene():
    _resets(300)


@pytest.mark.slow
def test_ten_thousand_such_resets_find_a_scene():
    _resets(10_000)


def _model_arrays(model: mujoco.MjModel) -> dict[str, np.ndarray]:
    """Every array of a model (sizes, positions, masses, bounding volumes, ...)."""
    out = {}
    for name in dir(model):
        if not name.startswith("_"):
            value = getattr(model, name)
            if isinstance(value, np.ndarray):
                out[name] = value.copy()
    return out


def _episode(env, seed: int, options: dict | None, actions: np.ndarray) -> list:
    obs, info = env.reset(seed=seed, options=options)
    out = [obs, info, _model_arrays(env.model)]
    for a in actions:
        out.append(env.step(a))
    spec = int(mujoco.mjtState.mjSTATE_INTEGRATION)
    state = np.empty(mujoco.mj_stateSize(env.model, spec))
    mujoco.mj_getState(env.model, env.data, state, spec)
    return [*out, state]


def _assert_same(a: object, b: object) -> None:
    if isinstance(a, dict):
        assert a.keys() == b.keys()
        for k in a:
            _assert_same(a[k], b[k])
    elif isinstance(a, tuple | list):
        assert len(a) == len(b)
        for x, y in zip(a, b):
            _assert_same(x, y)
    else:
        np.testing.assert_array_equal(a, b)


COMBINATIONS = [
    (cls, obstacles, randomize, override)
    for cls, obstacles, randomize, override in itertools.product(
        (PickAndPlaceEnv, ReachEnv), (None, MOST_OBSTACLES), (False, True), (False, True)
    )
]


@pytest.mark.parametrize(
    ("cls", "obstacles", "randomize", "override"),
    COMBINATIONS,
    ids=[
        f"{c.__name__[:-3]}-obst{o is not None:d}-rand{r:d}-opt{v:d}" for c, o, r, v in COMBINATIONS
    ],
)
def test_a_seeded_reset_gives_the_same_episode_whatever_came_before(
    cls, obstacles, randomize, override
):
    widest = WIDEST if cls is PickAndPlaceEnv else ARM_ONLY
    kwargs = {"random_obstacles": obstacles, "randomize": widest if randomize else None}
    options = {"randomize": None if randomize else widest} if override else None
    rng = np.random.default_rng(5)
    plain, busy = cls(**kwargs), cls(**kwargs)
    shape = plain.action_space.shape
    for seed in range(6):
        actions = rng.uniform(-1.0, 1.0, (STEPS, *shape)).astype(np.float32)
        # busy: other episodes in between, with and without the options, stepped
        for other in (1000 + seed, 2000 + seed):
            flip = None if options else {"randomize": widest}
            busy.reset(seed=other, options=flip if other % 2 else options)
            for a in rng.uniform(-1.0, 1.0, (STEPS, *shape)).astype(np.float32):
                busy.step(a)
        first = _episode(plain, seed, options, actions)
        _assert_same(first, _episode(busy, seed, options, actions))
        if seed == 0:
            _assert_same(first, _episode(cls(**kwargs), seed, options, actions))
