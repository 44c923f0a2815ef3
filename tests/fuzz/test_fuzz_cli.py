"""Fuzzed command lines, in-process: help, a result, or one line on stderr; no stray file."""

from __future__ import annotations

import random

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tools.fuzz_cli import check_run, make_sandbox, random_argv


@pytest.fixture(scope="module")
def sandbox(tmp_path_factory):
    outer = tmp_path_factory.mktemp("cli_fuzz")
    root = outer / "sandbox"
    return outer, root, make_sandbox(root)


@settings(max_examples=60, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(seed=st.integers(0, 2**32 - 1))
def test_fuzzed_command_lines_fail_cleanly(sandbox, seed):
    outer, root, paths = sandbox
    outcome = check_run(random_argv(random.Random(seed), paths), root, outer)
    assert outcome.problems == (), outcome
