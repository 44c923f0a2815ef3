"""Every public function of the math packages, the scene and the envs, called with odd inputs.

Hypothesis draws the arguments from the targets and value pools of
``tools/fuzz_api.py`` (the campaign script) plus its own floats, integers and
arrays of any value; the oracle is the campaign's: a call returns a valid result
or raises a :class:`~lynxsim.errors.LynxsimError`, never another exception, a
RuntimeWarning or a non-finite result where none is documented.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import lynxsim.envs
from tools import fuzz_api as campaign

EXAMPLES = 40
"""Hypothesis examples per library function (45 functions: ~4 s in all)."""

_ANY_ARRAY = hnp.arrays(
    dtype=st.sampled_from([np.float64, np.float32, np.int64, np.bool_, np.complex128]),
    shape=hnp.array_shapes(min_dims=0, max_dims=3, max_side=5),
)


def _argument(spec: Any) -> st.SearchStrategy[Any]:
    """Valid values (seeded from the spec), the spec's and the common odd values, anything."""
    return st.one_of(
        st.integers(0, 2**32 - 1).map(lambda seed: spec.valid(np.random.default_rng(seed))),
        st.sampled_from(spec.odd + campaign._ODD_COMMON),
        st.integers(0, 2**32 - 1).map(
            lambda seed: (
                campaign._mutate(
                    np.random.default_rng(seed), spec.valid(np.random.default_rng(seed))
                )
                if spec.mutate
                else spec.valid(np.random.default_rng(seed))
            )
        ),
        st.floats(),
        st.integers(min_value=-(10**30), max_value=10**30),
        _ANY_ARRAY,
    )


@pytest.mark.parametrize("target", campaign.TARGETS, ids=lambda t: t.name.removeprefix("lynxsim."))
@settings(max_examples=EXAMPLES, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_public_functions_return_valid_results_or_raise_typed_errors(target, data):
    args = tuple(data.draw(_argument(spec), label=f"arg{i}") for i, spec in enumerate(target.args))
    kwargs = {}
    for name, spec in target.kwargs.items():
        if data.draw(st.booleans(), label=f"pass {name}"):
            kwargs[name] = data.draw(_argument(spec), label=name)
    outcome = campaign.run_call(target.fn, target.check, args, kwargs)
    assert outcome.kind != "untyped", (
        f"{campaign.reproducer(target.name, args, kwargs)}  # {outcome.detail}"
    )


@pytest.fixture(scope="module")
def reach_env():
    env = lynxsim.envs.ReachEnv()
    env.reset(seed=0)
    yield env
    env.close()


@settings(max_examples=60)
@given(
    action=st.one_of(
        st.sampled_from(campaign._ODD_ACTIONS),
        hnp.arrays(np.float64, 4, elements=st.floats()),
        hnp.arrays(np.float32, 4, elements=st.floats(width=32)),
        _ANY_ARRAY,
        st.lists(st.one_of(st.floats(), st.integers(-(10**400), 10**400), st.text()), max_size=5),
    )
)
def test_env_step_returns_finite_observations_or_raises_typed_errors(reach_env, action):
    def step(a: Any) -> Any:
        obs, reward, *_ = reach_env.step(a)
        return obs["observation"], reward

    outcome = campaign.run_call(step, campaign.finite, (action,), {})
    assert outcome.kind != "untyped", (
        f"ReachEnv().step({campaign._show(action)})  # {outcome.detail}"
    )


@settings(max_examples=25)
@given(
    key=st.sampled_from(sorted(campaign._ENV_ARGS)),
    data=st.data(),
)
def test_env_constructors_raise_typed_errors_for_odd_arguments(key, data):
    value = data.draw(
        st.one_of(
            st.sampled_from(campaign._ENV_ARGS[key]),
            st.floats(),
            st.integers(-(10**400), 10**400),
            st.text(max_size=3),
        )
    )
    cls = lynxsim.envs.PickAndPlaceEnv

    def make(**kwargs: Any) -> None:
        cls(**kwargs).close()

    outcome = campaign.run_call(make, campaign.finite, (), {key: value})
    assert outcome.kind != "untyped", (
        f"PickAndPlaceEnv({key}={campaign._show(value)})  # {outcome.detail}"
    )
