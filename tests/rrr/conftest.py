"""Shared strategies and samples for the 3-RRR tests."""

from __future__ import annotations

import numpy as np
import pytest

from lynxsim.rrr import RRR_ROBOT, ik


def reachable_poses(rng: np.random.Generator, n: int, alpha_max_deg: float = 60.0) -> np.ndarray:
    """``n`` random reachable poses (x, y, alpha) [m, m, rad] around the base centre."""
    cx, cy = RRR_ROBOT.base_centre
    out = np.empty((0, 3))
    while len(out) < n:
        cand = np.column_stack(
            [
                rng.uniform(cx - 0.16, cx + 0.16, 4 * n),
                rng.uniform(cy - 0.14, cy + 0.16, 4 * n),
                np.radians(rng.uniform(-alpha_max_deg, alpha_max_deg, 4 * n)),
            ]
        )
        out = np.concatenate([out, cand[ik(cand).ok]])
    return out[:n]


@pytest.fixture
def random_poses() -> np.ndarray:
    """2000 seeded reachable poses, |alpha| <= 60 deg."""
    return reachable_poses(np.random.default_rng(20240607), 2000)
