"""The env's options as one frozen, checked value (:class:`lynxsim.envs.config.EnvConfig`)."""

from __future__ import annotations

import dataclasses

import pytest

from lynxsim.envs import ReachEnv
from lynxsim.envs.config import CollisionCheck, EnvConfig
from lynxsim.envs.control import ControlMode
from lynxsim.errors import InvalidInputError
from lynxsim.scene import REPORT_CYLINDER


def test_an_env_keeps_its_options_as_a_frozen_config():
    env = ReachEnv(control="joint", collision_check="physics_step", pixels="top")
    config = env.config
    assert config.control is ControlMode.JOINT
    assert config.collision_check is CollisionCheck.PHYSICS_STEP
    assert config.obstacles == (REPORT_CYLINDER,)  # the default scene's
    assert [p.camera for p in config.pixels] == ["top"]
    assert (config.frames.width, config.frames.height) == (640, 480)
    with pytest.raises(dataclasses.FrozenInstanceError):
        config.control = ControlMode.TOOL  # type: ignore[misc]
    env.close()


def test_a_config_made_directly_is_checked_too():
    config = ReachEnv().config
    again = dataclasses.replace(config, control="tool", random_obstacles=2, obstacles=None)
    assert again.control is ControlMode.TOOL
    assert again.random_obstacles == (2, 2)
    assert again.obstacles == ()
    with pytest.raises(InvalidInputError, match="control must be one of 'tool', 'joint'"):
        dataclasses.replace(config, control="elbow")
    with pytest.raises(InvalidInputError, match="frames and pixels must be RenderSettings"):
        dataclasses.replace(config, frames=(640, 480))
    with pytest.raises(InvalidInputError, match="give obstacles or random_obstacles, not both"):
        dataclasses.replace(config, random_obstacles=1)  # with the report's cylinder
    assert EnvConfig(**{f.name: getattr(config, f.name) for f in dataclasses.fields(config)}) == (
        config
    )
