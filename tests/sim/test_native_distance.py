"""The compiled minima call MuJoCo's own ``mj_geomDistance`` and find the argmin's values.

:mod:`lynxsim.sim.collision.native_distance` calls the C function from numba
code on geom poses written into a data; it must give what
``mujoco.mj_geomDistance`` gives from Python, bit for bit, and
:class:`~lynxsim.sim.collision.minima.ClearanceMinima` (its search compiled)
what :func:`~lynxsim.sim.collision.clearances_of_states` and ``argmin`` give,
on random arm states that reach into the obstacles (penetration included).
"""

from __future__ import annotations

import itertools

import mujoco
import numpy as np
from numba import njit

from lynxsim.arm import LYNX_ARM
from lynxsim.random_scenes import random_obstacles
from lynxsim.scene import REPORT_CUBE, Scene
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import arm_binding
from lynxsim.sim.collision import ClearanceGeometry, clearances_of_states
from lynxsim.sim.collision.minima import ClearanceMinima
from lynxsim.sim.collision.native_distance import geom_distance, geom_distance_address
from lynxsim.sim.collision.nearest_bounds import NearestBounds


@njit(cache=True)
def _distances(function, model, data, pairs, cut, out):  # type: ignore[no-untyped-def]  # numba
    for i in range(pairs.shape[0]):
        out[i] = geom_distance(function, model, data, pairs[i, 0], pairs[i, 1], cut)


def _states(n: int, seed: int) -> tuple[mujoco.MjModel, np.ndarray, np.ndarray, np.ndarray]:
    """A scene of n obstacles near the arm and random states of it: qpos, carried poses."""
    rng = np.random.default_rng(seed)
    scene = Scene(obstacles=random_obstacles(rng, n, keep_free=(REPORT_CUBE.position,)))
    model = load_arm_scene(scene)
    binding = arm_binding(model)
    data = mujoco.MjData(model)
    carried = np.flatnonzero(binding.groups.carried)
    qpos = np.repeat(np.array(model.qpos0)[None], 300, axis=0)
    qpos[:, binding.qpos_adr] = rng.uniform(LYNX_ARM.q_min, LYNX_ARM.q_max, size=(300, 5))
    xpos, xmat = np.empty((300, len(carried), 3)), np.empty((300, len(carried), 9))
    for k, q in enumerate(qpos):
        data.qpos[:] = q
        mujoco.mj_kinematics(model, data)
        xpos[k], xmat[k] = data.geom_xpos[carried], data.geom_xmat[carried]
    return model, qpos, xpos, xmat


def test_the_compiled_call_is_mujocos_distance() -> None:
    model, qpos, _, _ = _states(3, 5)
    groups = arm_binding(model).groups
    data = mujoco.MjData(model)
    pairs = np.array(
        [(g, o) for g in np.flatnonzero(groups.carried) for o in groups.obstacle_geoms],
        dtype=np.int64,
    )
    out = np.empty(len(pairs))
    for q in qpos[:40]:
        data.qpos[:] = q
        mujoco.mj_kinematics(model, data)
        for cut in (0.0, 0.05, 1.0):
            _distances(geom_distance_address(), model._address, data._address, pairs, cut, out)
            want = [mujoco.mj_geomDistance(model, data, a, b, cut, None) for a, b in pairs]
            np.testing.assert_array_equal(out, want)


def test_compiled_minima_are_the_argmins_of_every_clearance() -> None:
    for n, seed in ((1, 3), (3, 5), (8, 7)):
        model, qpos, xpos, xmat = _states(n, seed)
        groups = arm_binding(model).groups
        data = mujoco.MjData(model)
        want = clearances_of_states(model, data, groups, qpos, xpos, xmat)
        mujoco.mj_kinematics(model, data)
        minima = ClearanceMinima(model, data, ClearanceGeometry.of(model, data, groups))
        for first in range(0, len(qpos), 64):  # in chunks, as a run gives them
            minima.add(first, xpos[first : first + 64], xmat[first : first + 64])
        assert (want < 0.0).any()  # states in penetration were searched
        np.testing.assert_array_equal(minima.value, want.min(axis=0))
        np.testing.assert_array_equal(minima.step, want.argmin(axis=0))
        assert 0 < minima.exact_calls < want.size  # the bounds ruled states out


def test_bounds_kept_along_a_motion_never_exceed_the_clearance() -> None:
    """A geom's bound carried to later states (less how far the geom moved) stays below."""
    rng = np.random.default_rng(11)
    scene = Scene(obstacles=random_obstacles(rng, 8, keep_free=(REPORT_CUBE.position,)))
    model = load_arm_scene(scene)
    binding = arm_binding(model)
    groups = binding.groups
    data = mujoco.MjData(model)
    carried = np.flatnonzero(groups.carried)
    ends = rng.uniform(LYNX_ARM.q_min, LYNX_ARM.q_max, size=(4, 5))
    s = np.linspace(0.0, 1.0, 150)[:, None]
    path = np.concatenate([a + s * (b - a) for a, b in itertools.pairwise(ends)])
    qpos = np.repeat(np.array(model.qpos0)[None], len(path), axis=0)
    qpos[:, binding.qpos_adr] = path
    xpos, xmat = np.empty((len(path), len(carried), 3)), np.empty((len(path), len(carried), 9))
    for k, q in enumerate(qpos):
        data.qpos[:] = q
        mujoco.mj_kinematics(model, data)
        xpos[k], xmat[k] = data.geom_xpos[carried], data.geom_xmat[carried]
    exact = clearances_of_states(model, data, groups, qpos, xpos, xmat)
    bounds = NearestBounds(model, data, ClearanceGeometry.of(model, data, groups), 1.0)
    for below in (np.full(8, 1.0), exact.min(axis=0), exact.min(axis=0) + 0.05):
        low = bounds.nearest(xpos, xmat, below)
        assert (low <= exact).all()
        assert (low > exact - 0.2).mean() > 0.5  # and they are not all vacuous
        alone = np.concatenate(
            [bounds.nearest(xpos[k : k + 1], xmat[k : k + 1], below) for k in range(len(xpos))]
        )
        assert (low != alone).any()  # bounds were carried from state to state
