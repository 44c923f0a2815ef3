"""Fuzzing the sweep-file reader: mutants of the shipped sweeps load or raise a SweepFileError.

Structure-aware mutants (the task-file campaign's mutators, ``tools/fuzz_tasks.py``:
deleted keys, swapped types, huge, denormal and non-finite numbers, long
integers, deep nesting, control characters, empty arrays, wrong shapes, unknown
keys) and byte mutants of the shipped sweep files, their task paths made
absolute; hypothesis drives them, derandomized (``tests/conftest.py``). The
contract: :func:`~lynxsim.sweep.spec.load_sweep` returns a sweep or raises
:class:`~lynxsim.sweep.spec.SweepFileError` whose one-line message names the file.
"""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from lynxsim.sweep.spec import SweepFileError, SweepSpec, load_sweep
from tests.sweep.conftest import ROOT
from tools import fuzz_tasks as fuzz

EXAMPLES = 300


def _seed(path: Path) -> dict[str, Any]:
    data = tomllib.loads(path.read_text())
    data["tasks"] = [str((path.parent / t).resolve()) for t in data["tasks"]]
    data["obstacle"]["grid"]["step_mm"] = 50.0  # keep each load quick
    return data


CORPUS = [_seed(p) for p in sorted((ROOT / "sweeps").glob("*.toml"))]

_SETTINGS = settings(
    max_examples=EXAMPLES,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
)


@pytest.fixture(scope="module")
def mutant_path(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return tmp_path_factory.mktemp("sweep_mutants") / "mutant.toml"


def _contract(text: bytes, path: Path) -> SweepSpec | None:
    path.write_bytes(text)
    try:
        return load_sweep(path)
    except SweepFileError as exc:
        message = str(exc)
        assert message.startswith(str(path)), message
        assert "\n" not in message, message
        return None


def test_the_seeds_load(mutant_path):
    for data in CORPUS:
        assert _contract(fuzz.to_toml(data).encode(), mutant_path) is not None


@_SETTINGS
@given(seed=st.sampled_from(range(len(CORPUS))), rng=st.randoms(use_true_random=False))
def test_structural_mutant_loads_or_raises_a_sweep_file_error(mutant_path, seed, rng):
    data = CORPUS[seed]
    others = [d for i, d in enumerate(CORPUS) if i != seed]
    _contract(fuzz.mutate_structure(rng, data, others).encode("utf-8"), mutant_path)


@_SETTINGS
@given(seed=st.sampled_from(range(len(CORPUS))), rng=st.randoms(use_true_random=False))
def test_byte_mutant_loads_or_raises_a_sweep_file_error(mutant_path, seed, rng):
    _contract(fuzz.mutate_bytes(rng, fuzz.to_toml(CORPUS[seed]).encode("utf-8")), mutant_path)


@_SETTINGS
@given(
    key=st.sampled_from(["types", "planner_seeds", "rows_per_shard", "tasks", "obstacle", "cube"]),
    value=st.recursive(
        st.none().filter(lambda _: False)
        | st.booleans()
        | st.integers()
        | st.floats()
        | st.text(max_size=20),
        lambda inner: (
            st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=8), inner, max_size=3)
        ),
        max_leaves=8,
    ),
)
def test_any_value_of_a_top_key_loads_or_raises(mutant_path, key, value):
    data = dict(CORPUS[0])
    data[key] = value
    _contract(fuzz.to_toml(data).encode("utf-8", "surrogatepass"), mutant_path)
