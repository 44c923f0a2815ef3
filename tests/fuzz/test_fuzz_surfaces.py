"""Fuzzing sweep files, saved shards, dataset arguments, planning requests and env options.

The targets and the oracle are those of the campaign script ``tools/fuzz_surfaces.py``
(run it for thousands of inputs); here hypothesis draws the seeds of its inputs,
derandomized (``tests/conftest.py``). The contract: a valid result or a
:class:`~lynxsim.errors.LynxsimError` in one line; never an untyped exception,
a damaged shard read as if whole, or a partial dataset after an error.
"""

from __future__ import annotations

import random
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tools import fuzz_surfaces as fuzz

EXAMPLES = {"sweep": 200, "shard": 300, "planner": 300, "dataset": 25, "env": 25}
"""Inputs per target (a dataset or an env costs about 0.1 s, the others milliseconds)."""


@pytest.fixture(scope="module")
def work(tmp_path_factory: pytest.TempPathFactory) -> Path:
    folder = tmp_path_factory.mktemp("surfaces")
    fuzz.prepare(folder)
    return folder


def _campaign(target: str):
    @settings(
        max_examples=EXAMPLES[target],
        deadline=None,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
    )
    @given(seed=st.integers(0, 2**64 - 1))
    def test(work, seed):
        outcome, detail = fuzz.run_one(target, random.Random(seed), work)
        assert outcome in ("ok", "typed"), detail

    test.__name__ = f"test_{target}_inputs_give_a_result_or_a_typed_error"
    return test


test_sweep_inputs_give_a_result_or_a_typed_error = _campaign("sweep")
test_shard_inputs_give_a_result_or_a_typed_error = _campaign("shard")
test_planner_inputs_give_a_result_or_a_typed_error = _campaign("planner")
test_dataset_inputs_give_a_result_or_a_typed_error = _campaign("dataset")
test_env_inputs_give_a_result_or_a_typed_error = _campaign("env")


def test_the_campaign_targets_are_the_ones_tested():
    assert set(EXAMPLES) == set(fuzz.TARGETS) == set(fuzz.WEIGHTS)
