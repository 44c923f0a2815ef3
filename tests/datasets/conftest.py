"""Fixtures of the dataset tests: small datasets recorded once per module, in every format."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

from lynxsim.datasets import DatasetSummary, write_dataset

EPISODES = 3
"""Episodes of the datasets the tests share (100 take about 10 s: measured by hand)."""
SEED = 7
NOISE = 0.1

MINARI = pytest.param(
    "minari",
    marks=pytest.mark.skipif(
        importlib.util.find_spec("minari") is None, reason="needs the extra lynxsim[datasets]"
    ),
)
LEROBOT = pytest.param(
    "lerobot",
    marks=pytest.mark.skipif(
        importlib.util.find_spec("pyarrow") is None, reason="needs the extra lynxsim[datasets]"
    ),
)
FORMATS = ["npz", MINARI, LEROBOT]
"""Every format; Minari's and LeRobot's only where the optional extra is installed (CI installs
it)."""


def record(root: Path, fmt: str, **kwargs: object) -> DatasetSummary:
    """``write_dataset`` with the shared arguments, overridable."""
    args: dict[str, object] = {"episodes": EPISODES, "seed": SEED, "noise": NOISE} | kwargs
    return write_dataset(root, format=fmt, **args)


@pytest.fixture(scope="module")
def npz_dataset(tmp_path_factory: pytest.TempPathFactory) -> DatasetSummary:
    """Pick-and-place, 3 episodes, seed 7, noise 0.1, NPZ."""
    return record(tmp_path_factory.mktemp("npz"), "npz")


@pytest.fixture(scope="module")
def minari_dataset(tmp_path_factory: pytest.TempPathFactory) -> DatasetSummary:
    """The same episodes as ``npz_dataset``, in Minari's format."""
    pytest.importorskip("minari")
    return record(tmp_path_factory.mktemp("minari"), "minari")
