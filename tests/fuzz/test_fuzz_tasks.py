"""Fuzzing the task loader and the motion builders with mutants of the shipped task files.

The mutators and the oracle are those of the campaign script ``tools/fuzz_tasks.py``
(run it for 10,000 and more mutants); here hypothesis drives them, derandomized
(``tests/conftest.py``), so every run checks the same few hundred mutants. The
contract: :func:`~lynxsim.tasks.load_task` returns a task or raises a
:class:`~lynxsim.errors.TaskFileError` naming the file in one line, and the
task's motion of its own type has finite samples or the builder raises a
:class:`~lynxsim.errors.LynxsimError`.
"""

from __future__ import annotations

import copy
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from lynxsim.tasks import Task
from tools import fuzz_tasks as fuzz

ROOT = Path(__file__).resolve().parents[2]

EXAMPLES = 500
"""Mutants per test (each takes a few milliseconds)."""


CORPUS: list[tuple[str, str, dict[str, Any]]] = fuzz.seeds()
STEMS = [stem for stem, _, _ in CORPUS]


@pytest.fixture(scope="module")
def mutant_path(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Where each mutant is written (one file, rewritten per example)."""
    return tmp_path_factory.mktemp("mutants") / "mutant.toml"


def _assert_contract(text: bytes, path: Path) -> Task | None:
    """Load ``text`` and build its motion; fail on anything but the contract's outcomes."""
    result = fuzz.check(text, path)
    assert result.outcome not in fuzz.FINDINGS, (
        f"{result.outcome}: {result.detail}\nmutant:\n{text.decode('utf-8', 'replace')}"
    )
    task: Task | None = result.task
    return task


_SETTINGS = settings(
    max_examples=EXAMPLES,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
)


def test_the_seeds_load_and_build():
    assert sorted(STEMS) == STEMS
    assert len(CORPUS) >= 5
    for stem, text, _ in CORPUS:
        task = _assert_contract(text.encode(), ROOT / "tasks" / f"{stem}.toml")
        assert task is not None, stem


def test_the_serialiser_writes_what_tomllib_reads():
    import tomllib

    for _, _, data in CORPUS:
        assert tomllib.loads(fuzz.to_toml(data)) == data
    tricky = {"k": ['a\x00b\n\x1b\x7f"\\', 5e-324, -0.0, 10**400, [[]], {"": {}}]}
    assert tomllib.loads(fuzz.to_toml(tricky)) == tricky


@_SETTINGS
@given(seed=st.sampled_from(range(len(CORPUS))), rng=st.randoms(use_true_random=False))
def test_structural_mutant_loads_or_raises_a_task_file_error(mutant_path, seed, rng):
    stem, _, data = CORPUS[seed]
    others = [d for s, _, d in CORPUS if s != stem]
    _assert_contract(fuzz.mutate_structure(rng, data, others).encode("utf-8"), mutant_path)


@_SETTINGS
@given(seed=st.sampled_from(range(len(CORPUS))), rng=st.randoms(use_true_random=False))
def test_byte_mutant_loads_or_raises_a_task_file_error(mutant_path, seed, rng):
    _, text, _ = CORPUS[seed]
    _assert_contract(fuzz.mutate_bytes(rng, text.encode("utf-8")), mutant_path)


_numbers = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True, allow_subnormal=True),
    st.floats(-400.0, 400.0),
    st.integers(-(10**400), 10**400),
    st.integers(-2000, 2000),
    st.sampled_from([5e-324, 1e-300, 1e300, 6.5e306, 1e-3, 3600.0, 10_000.0, 360.0]),
)
_text = st.text(st.characters(exclude_categories=("Cs",)), max_size=120)
_leaves = st.one_of(_numbers, _text, st.booleans())
_values = st.recursive(
    _leaves,
    lambda inner: st.one_of(
        st.lists(inner, max_size=6), st.dictionaries(st.sampled_from(fuzz.KEYS), inner, max_size=3)
    ),
    max_leaves=8,
)


@_SETTINGS
@given(data=st.data(), seed=st.sampled_from(range(len(CORPUS))))
def test_any_value_at_any_field_loads_or_raises_a_task_file_error(mutant_path, data, seed):
    task = copy.deepcopy(CORPUS[seed][2])
    for _ in range(data.draw(st.integers(1, 3), label="mutations")):
        paths = fuzz._paths(task)
        path = data.draw(st.sampled_from(paths), label="field")
        parent = fuzz._get(task, path[:-1])
        parent[path[-1]] = data.draw(_values, label="value")
    _assert_contract(fuzz.to_toml(task).encode("utf-8"), mutant_path)
