"""Domain randomisation: what is drawn, that it is consistent, and that its default is off."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from lynxsim.envs import Randomization
from lynxsim.envs.pick_and_place import PickAndPlaceEnv
from lynxsim.envs.reach import ReachEnv
from lynxsim.errors import InvalidInputError
from lynxsim.scene import Cube, Scene
from lynxsim.sim.arm.model import load_arm_spec
from tests.helpers import assert_close

EVERYTHING = Randomization(
    cube_size_m=(0.02, 0.028),
    cube_mass_kg=(0.005, 0.05),
    cube_friction=(0.5, 1.5),
    servo_gain_tolerance=0.1,
    joint_damping_tolerance=0.1,
    camera_shift_m=0.02,
    camera_tilt_rad=0.05,
)
"""Every field on (±10 % servo tolerances)."""
MODEL_RTOL = 1e-9
"""Relative tolerance between a randomised model and a compiled one (rounding of the inertia)."""
CONTACT_ATOL_M = 1e-12
"""Tolerance on contact distances and positions [m]."""
ROLLOUT_ATOL = 1e-9
"""Tolerance on coordinates after a rollout on a randomised and a compiled model [m, rad]."""


def _model_arrays(model: mujoco.MjModel) -> dict[str, np.ndarray]:
    """Every numeric array of a model, by field name."""
    out = {}
    for name in dir(model):
        if name.startswith("_"):
            continue
        value = getattr(model, name, None)
        if isinstance(value, np.ndarray) and value.dtype.kind in "fiu":
            out[name] = value.copy()
    return out


def _observations(env: PickAndPlaceEnv | ReachEnv, seed: int, steps: int) -> list[np.ndarray]:
    obs, _ = env.reset(seed=seed)
    out = [obs["observation"]]
    rng = np.random.default_rng(seed)
    for _ in range(steps):
        obs, *_ = env.step(rng.uniform(-1, 1, env.action_space.shape))
        out.append(obs["observation"])
    return out


def test_default_is_off_and_unchanged_bit_for_bit():
    plain, none, off = (PickAndPlaceEnv(), PickAndPlaceEnv(randomize=None), PickAndPlaceEnv())
    for seed in (0, 7):
        expected = _observations(plain, seed, 20)
        assert all(np.array_equal(a, b) for a, b in zip(expected, _observations(none, seed, 20)))
        off.reset(seed=seed, options={"randomize": None})
        assert np.array_equal(off.reset(seed=seed)[0]["observation"], expected[0])
    assert plain.domain == none.domain


def test_a_randomised_episode_leaves_no_trace_on_the_next():
    fresh, env = PickAndPlaceEnv(), PickAndPlaceEnv()
    env.reset(seed=3, options={"randomize": EVERYTHING})
    assert env.domain != fresh.domain
    expected = _observations(fresh, 5, 20)
    got = _observations(env, 5, 20)
    assert all(np.array_equal(a, b) for a, b in zip(expected, got))
    assert env.domain == fresh.domain
    a, b = _model_arrays(env.model), _model_arrays(fresh.model)
    assert [k for k in a if not np.array_equal(a[k], b[k])] == []


def test_options_override_the_constructor_for_one_episode():
    env, nominal = PickAndPlaceEnv(randomize=EVERYTHING), PickAndPlaceEnv().domain
    env.reset(seed=1)
    assert env.domain != nominal
    env.reset(seed=1, options={"randomize": None})
    assert env.domain == nominal
    env.reset(seed=1)
    assert env.domain != nominal


def test_draws_come_from_the_seed():
    a, b = PickAndPlaceEnv(randomize=EVERYTHING), PickAndPlaceEnv(randomize=EVERYTHING)
    first = [a.reset(seed=s) and a.domain for s in range(5)]
    assert first == [b.reset(seed=s) and b.domain for s in range(5)]
    assert len({d.cube_size_m for d in first}) == 5
    assert all(
        np.array_equal(x, y) for x, y in zip(_observations(a, 9, 30), _observations(b, 9, 30))
    )


def test_draws_stay_in_their_ranges_and_servos_stay_consistent():
    env, nominal = PickAndPlaceEnv(randomize=EVERYTHING), PickAndPlaceEnv().domain
    kp0, damping0 = np.array(nominal.servo_kp), np.array(nominal.joint_damping)
    m = env.model
    for seed in range(30):
        env.reset(seed=seed)
        d = env.domain
        assert 0.02 <= d.cube_size_m <= 0.028
        assert 0.005 <= d.cube_mass_kg <= 0.05
        assert 0.5 <= d.cube_friction <= 1.5
        assert np.all(np.abs(np.array(d.servo_kp) / kp0 - 1.0) <= 0.1)
        assert np.all(np.abs(np.array(d.joint_damping) / damping0 - 1.0) <= 0.1)
        arm = list(env.ids.arm_actuators)
        assert np.array_equal(m.actuator_biasprm[arm, 1], -m.actuator_gainprm[arm, 0])
        assert np.all(np.abs(np.array(d.camera_pos) - nominal.camera_pos) <= 0.02)
        for q, q0 in zip(d.camera_quat, nominal.camera_quat):
            angle = 2.0 * math.acos(min(1.0, abs(float(np.dot(q, q0)))))
            assert angle <= 0.05 + 1e-12
        assert_close(env.data.cam_xpos, np.array(d.camera_pos), atol=1e-15)
        # the cube rests on the table whatever its size
        cube_z = env.cube_position[2]
        assert_close(cube_z, env.table_top_z + 0.5 * d.cube_size_m, atol=1e-15)
        assert env.scene.cube.size == d.cube_size_m


@pytest.mark.parametrize("seed", [0, 1, 2], ids=lambda s: f"seed{s}")
def test_a_randomised_cube_is_the_compiled_cube_of_its_size(seed):
    env = PickAndPlaceEnv(
        randomize=Randomization(
            cube_size_m=(0.01, 0.03), cube_mass_kg=(0.005, 0.2), cube_friction=(0.3, 2.0)
        )
    )
    env.reset(seed=seed)
    d = env.domain
    cube = Cube(size=d.cube_size_m, mass=d.cube_mass_kg, friction=d.cube_friction)
    compiled = load_arm_spec(Scene(env.obstacles, cube=cube)).compile()
    compiled.site_pos[:] = env.model.site_pos  # the goal mark moves at reset
    got, expected = _model_arrays(env.model), _model_arrays(compiled)
    for name, value in expected.items():
        assert_close(got[name], value, atol=0.0, rtol=MODEL_RTOL, err_msg=name)

    # Same state in both: the cube sunk 0.5 mm into the table and tilted by 0.05 rad.
    data = mujoco.MjData(compiled)
    qpos = env.data.qpos.copy()
    a = env.ids.cube_qpos
    qpos[a + 2] -= 0.0005
    turn = np.zeros(4)
    mujoco.mju_axisAngle2Quat(turn, np.array([1.0, 0.0, 0.0]), 0.05)
    mujoco.mju_mulQuat(qpos[a + 3 : a + 7], env.data.qpos[a + 3 : a + 7].copy(), turn)
    env.data.qpos[:] = qpos
    data.qpos[:] = qpos
    data.ctrl[:] = env.data.ctrl
    mujoco.mj_forward(env.model, env.data)
    mujoco.mj_forward(compiled, data)
    assert env.data.ncon == data.ncon > 0
    assert_close(env.data.contact.dist, data.contact.dist, atol=CONTACT_ATOL_M)
    assert_close(env.data.contact.pos, data.contact.pos, atol=CONTACT_ATOL_M)
    assert min(env.data.contact.dist) < 0.0
    mujoco.mj_step(env.model, env.data, nstep=250)
    mujoco.mj_step(compiled, data, nstep=250)
    assert_close(env.data.qpos, data.qpos, atol=ROLLOUT_ATOL)


def test_reach_randomises_its_servos_and_has_no_cube():
    servos = Randomization(servo_gain_tolerance=0.1, joint_damping_tolerance=0.1)
    env, nominal = ReachEnv(randomize=servos), ReachEnv().domain
    env.reset(seed=0)
    assert env.domain.cube_size_m is None
    assert env.domain.servo_kp != nominal.servo_kp
    assert env.domain.camera_pos == nominal.camera_pos
    with pytest.raises(InvalidInputError, match="ReachEnv has no cube"):
        ReachEnv(randomize=Randomization(cube_mass_kg=(0.01, 0.02)))
    with pytest.raises(InvalidInputError, match="ReachEnv has no cube"):
        env.reset(options={"randomize": Randomization(cube_friction=(0.5, 1.0))})


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"cube_size_m": (0.03, 0.02)}, r"cube_size_m \(hi\) must be between 0.03 and 0.03 m"),
        ({"cube_size_m": (0.02, 0.04)}, r"cube_size_m \(hi\) must be between 0.02 and 0.03 m"),
        ({"cube_size_m": 0.02}, r"cube_size_m must be None or a pair \(lo, hi\)"),
        ({"cube_mass_kg": (0.0, 0.1)}, "cube_mass_kg must be > 0 kg"),
        ({"cube_friction": (-1.0, 1.0)}, r"cube_friction \(lo\) must be between 0 and 5"),
        ({"servo_gain_tolerance": 0.6}, "servo_gain_tolerance must be between 0 and 0.5"),
        ({"joint_damping_tolerance": -0.1}, "joint_damping_tolerance must be between 0 and 0.5"),
        ({"camera_shift_m": "1 cm"}, "camera_shift_m must be a number"),
        ({"camera_tilt_rad": 1.0}, "camera_tilt_rad must be between 0 and 0.5 rad"),
    ],
    ids=["reversed", "too-big", "not-a-pair", "massless", "negative", "tol", "damp", "str", "tilt"],
)
def test_bad_randomizations_are_refused_by_name(kwargs, message):
    with pytest.raises(InvalidInputError, match=message):
        Randomization(**kwargs)


def test_bad_randomize_arguments_are_refused():
    with pytest.raises(InvalidInputError, match="randomize must be None or a lynxsim"):
        PickAndPlaceEnv(randomize={"cube_size_m": (0.02, 0.03)})  # type: ignore[arg-type]
    env = PickAndPlaceEnv()
    with pytest.raises(InvalidInputError, match=r"unknown reset options \['cube'\]"):
        env.reset(options={"cube": 1})
    with pytest.raises(InvalidInputError, match=r"options\['randomize'\] must be None"):
        env.reset(options={"randomize": 0.1})
