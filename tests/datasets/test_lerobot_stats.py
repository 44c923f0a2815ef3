"""LeRobot statistics: exact per episode (images from histograms), merged as LeRobot merges them."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from lynxsim.datasets.lerobot_stats import QUANTILES, RunningStats, feature_stats, image_stats

RTOL = 1e-12
"""Relative tolerance of float64 statistics summed in another order."""

_images = arrays(
    np.uint8,
    st.tuples(st.integers(1, 4), st.integers(1, 6), st.integers(1, 6), st.integers(1, 4)),
)


@settings(max_examples=200, deadline=None)
@given(frames=_images)
def test_image_statistics_are_numpys_per_channel_in_unit_range(frames):
    stats = image_stats(frames)
    channels = frames.shape[-1]
    values = frames.reshape(-1, channels).astype(np.float64) / 255
    expected = {
        "min": values.min(axis=0),
        "max": values.max(axis=0),
        "mean": values.mean(axis=0),
        "std": values.std(axis=0),
    } | {name: np.quantile(values, q, axis=0) for name, q in QUANTILES.items()}
    assert list(stats) == ["min", "max", "mean", "std", "count", *QUANTILES]
    np.testing.assert_array_equal(stats["count"], [frames.shape[0]])
    for name, value in expected.items():
        assert stats[name].shape == (channels, 1, 1)
        np.testing.assert_allclose(stats[name].reshape(-1), value, rtol=RTOL, atol=1e-15)


_vectors = st.integers(1, 3).flatmap(
    lambda d: st.lists(
        arrays(
            np.float64,
            st.tuples(st.integers(1, 12), st.just(d)),
            elements=st.floats(-1e3, 1e3, allow_nan=False),
        ),
        min_size=1,
        max_size=6,
    )
)


@settings(max_examples=200, deadline=None)
@given(episodes=_vectors)
def test_merged_statistics_are_those_of_all_frames_and_bound_the_quantiles(episodes):
    running = RunningStats()
    for values in episodes:
        running.add(feature_stats(values))
    assert running.stats is not None
    merged = running.stats
    everything = np.concatenate(episodes)
    np.testing.assert_array_equal(merged["min"], everything.min(axis=0))
    np.testing.assert_array_equal(merged["max"], everything.max(axis=0))
    np.testing.assert_array_equal(merged["count"], [len(everything)])
    np.testing.assert_allclose(merged["mean"], everything.mean(axis=0), rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(merged["std"], everything.std(axis=0), rtol=1e-9, atol=1e-9)
    for name, q in QUANTILES.items():
        per_episode = np.stack([np.quantile(v, q, axis=0) for v in episodes])
        bound = per_episode.min(axis=0) if q <= 0.5 else per_episode.max(axis=0)
        np.testing.assert_array_equal(merged[name], bound)


def test_booleans_count_as_zero_and_one():
    stats = feature_stats(np.array([[True], [False], [True], [True]]))
    np.testing.assert_array_equal(stats["mean"], [0.75])
    np.testing.assert_array_equal(stats["min"], [0.0])
    np.testing.assert_array_equal(stats["q50"], [1.0])
