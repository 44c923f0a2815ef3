"""Workspace sampling and its figure."""

from __future__ import annotations

import numpy as np
import pytest

from lynxsim.arm import LYNX_ARM, sample_workspace, tool_pose
from lynxsim.errors import InvalidInputError
from lynxsim.plots.arm_workspace import plot_arm_workspace
from tests.helpers import assert_close


def test_samples_lie_in_joint_ranges_and_reach():
    calls = []
    samples = sample_workspace(
        600_000, np.random.default_rng(0), progress=lambda d, n: calls.append(d)
    )
    assert (samples.q >= LYNX_ARM.lower).all()
    assert (samples.q <= LYNX_ARM.upper).all()
    shoulder = np.array([0.0, 0.0, LYNX_ARM.shoulder_height])
    assert (np.linalg.norm(samples.position - shoulder, axis=1) <= LYNX_ARM.max_reach + 1e-12).all()
    assert calls[-1] == 600_000
    assert len(calls) > 1
    assert_close(samples.position[:10], tool_pose(samples.q[:10]).position, atol=0.0)


def test_same_seed_gives_same_samples():
    a = sample_workspace(1000, np.random.default_rng(7))
    b = sample_workspace(1000, np.random.default_rng(7))
    np.testing.assert_array_equal(a.position, b.position)


def test_non_positive_sample_count_is_refused():
    with pytest.raises(InvalidInputError, match="between 1 and 10,000,000, got 0"):
        sample_workspace(0, np.random.default_rng())


def test_workspace_plot_is_a_png(tmp_path):
    dest = tmp_path / "ws.png"
    plot_arm_workspace(sample_workspace(5000, np.random.default_rng(0)), dest)
    assert dest.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert list(tmp_path.iterdir()) == [dest]


@pytest.mark.parametrize(
    ("n", "match"),
    [
        (999_999_999_999, "between 1 and 10,000,000, got 999,999,999,999"),
        (10**400, "between 1 and 10,000,000"),
        (2.5, "must be an integer"),
        (np.array([5]), "must be an integer"),
        (True, "must be an integer"),
    ],
    ids=["huge", "int-beyond-float64", "float", "array", "bool"],
)
def test_sample_counts_are_bounded_before_anything_is_allocated(n, match):
    with pytest.raises(InvalidInputError, match=match):
        sample_workspace(n, np.random.default_rng(0))


def test_rng_must_be_a_generator():
    with pytest.raises(InvalidInputError, match=r"rng must be a numpy\.random\.Generator"):
        sample_workspace(10, 0)  # type: ignore[arg-type]
