"""Bad arguments are typed errors that name the value; fuzzed calls never do anything else."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from lynxsim.datasets import MAX_SEED, check_dataset_id, check_noise, read_npz, write_dataset
from lynxsim.errors import InvalidInputError, LynxsimError, NonFiniteInputError

FUZZ_EXAMPLES = 30
"""Hypothesis examples of the fuzz test (a valid call records one episode, ~0.1 s)."""


@pytest.mark.parametrize(
    ("kwargs", "error", "message"),
    [
        ({"episodes": 0}, InvalidInputError, r"episodes must be between 1 and 1,000,000, got 0"),
        ({"episodes": True}, InvalidInputError, r"episodes must be an integer, got True"),
        ({"episodes": 1.5}, InvalidInputError, r"episodes must be an integer, got 1\.5"),
        ({"seed": -1}, InvalidInputError, r"seed must be between 0 and"),
        ({"seed": MAX_SEED, "episodes": 2}, InvalidInputError, r"last episode's seed"),
        ({"noise": -0.1}, InvalidInputError, r"noise must be between 0 and 1, got -0\.1"),
        ({"noise": 1.5}, InvalidInputError, r"noise must be between 0 and 1"),
        ({"noise": math.nan}, NonFiniteInputError, r"noise must be finite"),
        ({"noise": True}, InvalidInputError, r"noise must be a number, got True"),
        ({"noise": "0.1"}, InvalidInputError, r"noise must be a number"),
        ({"env_id": "Nope-v0"}, InvalidInputError, r"env_id must be one of \['LynxPick"),
        ({"env_id": None}, InvalidInputError, r"env_id must be one of"),
        (
            {"format": "hdf5"},
            InvalidInputError,
            r"format must be one of \['npz', 'minari', 'lerobot'\]",
        ),
        ({"format": ["npz"]}, InvalidInputError, r"format must be one of"),
        ({"dataset_id": "../escaped-v0"}, InvalidInputError, r"dataset id must look like"),
        ({"dataset_id": 3}, InvalidInputError, r"dataset_id must be a string, got 3"),
    ],
    ids=lambda v: v if isinstance(v, str) else None,
)
def test_bad_arguments_raise_typed_errors_before_any_work(tmp_path, kwargs, error, message):
    with pytest.raises(error, match=message):
        write_dataset(tmp_path, **{"episodes": 1} | kwargs)
    assert list(tmp_path.iterdir()) == []


def test_out_must_be_a_path():
    with pytest.raises(InvalidInputError, match=r"out must be a path, got None"):
        write_dataset(None, 1)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    "dataset_id",
    ["expert-v0", "lynxsim/reach-v1/expert-v12", "A_b/c-d/e_f-v3", "x" * 197 + "-v0"],
)
def test_minari_style_ids_are_accepted(dataset_id):
    assert check_dataset_id(dataset_id) == dataset_id


@pytest.mark.parametrize(
    "dataset_id",
    [
        "expert",  # no version
        "expert-v",
        "../up-v0",
        "a/../b-v0",
        "/abs/olute-v0",
        ".hidden-v0",
        "a/.hidden/b-v0",
        "-flag-v0",
        "a//b-v0",
        "a/b/-v0",
        "with space-v0",
        "dot.ted-v0",
        "é-v0",
        "a\nb-v0",
        "x" * 198 + "-v0",
        "",
    ],
)
def test_ids_that_are_not_safe_relative_paths_are_refused(dataset_id):
    with pytest.raises(InvalidInputError, match="dataset id must look like 'namespace/name-v0'"):
        check_dataset_id(dataset_id)


def test_noise_accepts_numbers_from_zero_to_one():
    assert check_noise(0) == 0.0
    assert check_noise(1) == 1.0


def test_reading_what_is_not_an_npz_dataset_is_a_typed_error(tmp_path):
    with pytest.raises(InvalidInputError, match="is not a lynxsim NPZ dataset"):
        read_npz(tmp_path)


_ODD = [None, True, -1, 0, 2, 0.5, math.nan, math.inf, "1", "npz", b"x", [1], {}, 2**64]


def _mostly(valid: st.SearchStrategy, odd: st.SearchStrategy) -> st.SearchStrategy:
    """``valid`` four times in five, else ``odd``: a quarter of the calls are all valid."""
    return st.tuples(st.integers(0, 4), valid, odd).map(lambda t: t[1] if t[0] else t[2])


@settings(
    max_examples=FUZZ_EXAMPLES,
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture],
)
@given(
    episodes=_mostly(st.just(1), st.sampled_from([*_ODD, 1.0, 10**30])),
    noise=_mostly(st.floats(0.0, 1.0), st.one_of(st.floats(), st.sampled_from(_ODD))),
    seed=_mostly(st.integers(0, 2**63 - 1), st.one_of(st.integers(), st.sampled_from(_ODD))),
    fmt=_mostly(st.sampled_from(["npz", "minari", "lerobot"]), st.sampled_from(["NPZ", "", *_ODD])),
    dataset_id=_mostly(
        st.sampled_from([None, "a-v0", "b/c_d-v12"]),
        st.one_of(st.text(max_size=12), st.sampled_from(_ODD)),
    ),
    env_id=_mostly(
        st.sampled_from(["LynxReach-v1", "LynxPickAndPlace-v1"]), st.sampled_from(["Lynx", *_ODD])
    ),
    videos=_mostly(st.booleans(), st.sampled_from(_ODD)),
)
def test_fuzzed_calls_write_a_whole_dataset_or_raise_a_typed_error(
    tmp_path_factory, episodes, noise, seed, fmt, dataset_id, env_id, videos
):
    root: Path = tmp_path_factory.mktemp("fuzz")
    try:
        summary = write_dataset(
            root,
            episodes,
            noise=noise,
            seed=seed,
            format=fmt,
            dataset_id=dataset_id,
            env_id=env_id,
            videos=videos,
        )
    except LynxsimError:
        assert not [p for p in root.rglob("*") if p.is_file()]
    else:
        assert summary.path.is_relative_to(root)
        assert summary.episodes == 1
        assert any(summary.path.rglob("metadata.json")) or any(summary.path.rglob("info.json"))
    assert not list(root.rglob(".*"))  # no temporary folder left
