"""Fixtures of the simulation tests: the shipped arm model and its scene.

``MUJOCO_GL`` defaults to ``egl`` here, before any test module imports ``mujoco``
(MuJoCo reads it once, at import), so that off-screen rendering works headless.
"""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import mujoco
import pytest

from lynxsim.sim.arm.model import SceneIds, load_arm_model, load_arm_scene


@pytest.fixture(scope="session")
def arm_model() -> mujoco.MjModel:
    """The robot alone (``lynxsim/models/lynx_arm/lynx_arm.xml``)."""
    return load_arm_model()


@pytest.fixture(scope="session")
def scene_model() -> mujoco.MjModel:
    """The default scene: table, the report's obstacle, the cube at P1."""
    return load_arm_scene()


@pytest.fixture(scope="session")
def scene_ids(scene_model: mujoco.MjModel) -> SceneIds:
    """Ids of the default scene's arm, obstacle, table and cube."""
    return SceneIds.from_model(scene_model)


@pytest.fixture
def scene_data(scene_model: mujoco.MjModel) -> mujoco.MjData:
    """Fresh data of the default scene, reset to the ``home`` keyframe."""
    data = mujoco.MjData(scene_model)
    mujoco.mj_resetDataKeyframe(scene_model, data, 0)
    mujoco.mj_forward(scene_model, data)
    return data
