"""Fixtures of the 3-RRR simulation tests: the shipped model and scene, shared samples.

``MUJOCO_GL`` defaults to ``egl`` here, before any test module imports ``mujoco``
(MuJoCo reads it once, at import), so that off-screen rendering works headless.
"""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import math

import mujoco
import numpy as np
import pytest

from lynxsim.rrr import RRR_ROBOT, ik, singularity_measures
from lynxsim.sim.rrr.model import RRRIds, load_rrr_model, load_rrr_scene

FIGURE20_A = np.array([0.200, 0.150, 0.0])
"""Figure 20 (a): reachable, links clear in every mode [m, m, rad]."""
FIGURE20_D = np.array([0.300, 0.250, 0.0])
"""Figure 20 (d): reachable [m, m, rad]."""
FIGURE20_E = np.array([0.300, 0.250, math.radians(-40.0)])
"""Figure 20 (e): out of reach, leg 1 would need 322 mm [m, m, rad]."""
FIGURE20_F = np.array([0.200, 0.210, math.radians(40.0)])
"""Figure 20 (f): reachable, but in modes 4..7 proximal link 3 crosses the platform."""


@pytest.fixture(scope="session")
def rrr_scene() -> mujoco.MjModel:
    """The scene at ``home`` (``lynxsim/models/rrr/scene.xml``)."""
    return load_rrr_scene()


@pytest.fixture(scope="session")
def rrr_model() -> mujoco.MjModel:
    """The robot alone (``lynxsim/models/rrr/rrr.xml``)."""
    return load_rrr_model()


@pytest.fixture(scope="session")
def rrr_ids(rrr_scene: mujoco.MjModel) -> RRRIds:
    """Ids of the scene's joints, sites, actuators and loops."""
    return RRRIds.from_model(rrr_scene)


@pytest.fixture
def rrr_data(rrr_scene: mujoco.MjModel, rrr_ids: RRRIds) -> mujoco.MjData:
    """Fresh data of the scene, reset to the ``home`` keyframe."""
    data = mujoco.MjData(rrr_scene)
    mujoco.mj_resetDataKeyframe(rrr_scene, data, rrr_ids.home_key)
    mujoco.mj_forward(rrr_scene, data)
    return data


def well_conditioned_poses(
    rng: np.random.Generator,
    n: int,
    *,
    min_parallel: float = 0.3,
    min_serial: float = 0.2,
    alpha_max_deg: float = 45.0,
) -> list[tuple[np.ndarray, int]]:
    """``n`` random reachable (pose, working mode) pairs away from singularities.

    Poses are drawn over the whole reachable region around the base centre
    (±200 mm), modes uniformly; a pair is kept when its parallel measure is at
    least ``min_parallel`` and its serial measure at least ``min_serial``.
    """
    cx, cy = RRR_ROBOT.base_centre
    out: list[tuple[np.ndarray, int]] = []
    while len(out) < n:
        cand = np.column_stack(
            [
                rng.uniform(cx - 0.2, cx + 0.2, 8 * n),
                rng.uniform(cy - 0.2, cy + 0.2, 8 * n),
                np.radians(rng.uniform(-alpha_max_deg, alpha_max_deg, 8 * n)),
            ]
        )
        result = ik(cand)
        for i in np.flatnonzero(result.ok):
            mode = int(rng.integers(8))
            meas = singularity_measures(cand[i], result.theta[i, mode])
            if abs(float(meas.parallel)) >= min_parallel and float(meas.serial) >= min_serial:
                out.append((cand[i], mode))
                if len(out) == n:
                    break
    return out
