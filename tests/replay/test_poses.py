"""16-bit poses: the quantisation error bound, interpolation, and the point error bound."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from lynxsim.web.poses import (
    QUAT_SCALE,
    dequantise_positions,
    dequantise_quaternions,
    interpolate_poses,
    point_error_bound,
    quantise_positions,
    quantise_quaternions,
)

_coords = st.floats(-2.0, 2.0, allow_nan=False, width=64)


@settings(max_examples=200, deadline=None)
@given(
    hnp.arrays(
        np.float64,
        hnp.array_shapes(min_dims=2, max_dims=3, max_side=6).map(lambda s: (*s[:-1], 3)),
        elements=_coords,
    )
)
def test_positions_come_back_within_half_a_step_on_each_axis(p):
    q, origin, step = quantise_positions(p)
    assert q.dtype == np.int16
    back = dequantise_positions(q, origin, step)
    assert np.all(np.abs(back - p) <= step / 2 * (1 + 1e-9) + 1e-15)
    span = float(np.ptp(p.reshape(-1, 3), axis=0).max()) if p.size else 0.0
    assert step <= max(span / 65534 * (1 + 1e-12), 1e-9)  # the grid uses the int16 range


def _unit_quaternions(draw_array: np.ndarray) -> np.ndarray:
    q = draw_array + np.array([1e-3, 0, 0, 0])
    return q / np.linalg.norm(q, axis=-1, keepdims=True)


@settings(max_examples=200, deadline=None)
@given(hnp.arrays(np.float64, (7, 4), elements=st.floats(-1, 1, width=64)))
def test_quaternions_come_back_within_a_rounding_of_each_component(raw):
    quat = _unit_quaternions(raw)
    back = dequantise_quaternions(quantise_quaternions(quat))
    assert np.allclose(np.linalg.norm(back, axis=1), 1.0)
    # rounding moves each component by <= 1/2 of 1/32767 before renormalising
    half_angle = np.arccos(np.clip(np.abs(np.sum(back * quat, axis=1)), 0, 1))
    assert np.all(half_angle <= 2.0 / QUAT_SCALE)


def test_interpolation_holds_the_frames_and_the_ends_and_takes_the_shorter_arc():
    frames = np.array([0.0, 1.0, 2.0])
    pos = np.array([[[0.0, 0, 0]], [[1.0, 0, 0]], [[1.0, 2, 0]]])
    half = np.sqrt(0.5)
    quat = np.array([[[1.0, 0, 0, 0]], [[-half, 0, 0, -half]], [[0.0, 0, 0, 1]]])  # -q: same turn
    p, q = interpolate_poses(frames, pos, quat, [-1.0, 0.0, 0.5, 1.0, 1.5, 2.0, 9.0])
    np.testing.assert_allclose(
        p[:, 0], [[0, 0, 0], [0, 0, 0], [0.5, 0, 0], [1, 0, 0], [1, 1, 0], [1, 2, 0], [1, 2, 0]]
    )
    # half way from identity to 90 deg about z is 45 deg about z (not the long way round)
    angle = 2 * np.arctan2(q[2, 0, 3] * np.sign(q[2, 0, 0]), abs(q[2, 0, 0]))
    np.testing.assert_allclose(angle, np.pi / 4, atol=1e-12)
    np.testing.assert_allclose(np.abs(q[3, 0]), [half, 0, 0, half], atol=1e-12)
    single_p, single_q = interpolate_poses([0.5], pos[:1], quat[:1], [0.0, 3.0])
    assert single_p.shape == (2, 1, 3)
    assert single_q.shape == (2, 1, 4)


def _rotate(q: np.ndarray, v: np.ndarray) -> np.ndarray:
    w, x, y, z = q
    m = np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )
    return m @ v


@settings(max_examples=100, deadline=None)
@given(
    hnp.arrays(np.float64, (2, 4), elements=st.floats(-1, 1, width=64)),
    hnp.arrays(np.float64, (2, 3), elements=st.floats(-0.1, 0.1, width=64)),
    hnp.arrays(np.float64, (20, 3), elements=st.floats(-1, 1, width=64)),
    st.floats(0.001, 0.5),
)
def test_no_point_within_reach_moves_more_than_the_bound(raw_q, raw_p, raw_points, reach):
    q = _unit_quaternions(raw_q)
    lengths = np.linalg.norm(raw_points, axis=1, keepdims=True)
    points = raw_points / np.where(lengths > 0, lengths, 1) * reach  # on the reach sphere
    moved = np.array(
        [np.linalg.norm(_rotate(q[0], v) + raw_p[0] - _rotate(q[1], v) - raw_p[1]) for v in points]
    )
    bound = point_error_bound(raw_p[0], q[0], raw_p[1], q[1], np.array(reach))
    assert moved.max() <= bound * (1 + 1e-9) + 1e-12
