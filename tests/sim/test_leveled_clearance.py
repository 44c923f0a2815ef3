"""The checker asked up to levels: ``min(clearance, level)``, the same numbers at or below them."""

from __future__ import annotations

import numpy as np
import pytest

from lynxsim.errors import InvalidInputError
from lynxsim.scene import REPORT_SCENE, TABLE, Box, Cylinder, Scene, Sphere
from lynxsim.sim.arm.model import load_arm_scene
from lynxsim.sim.arm.playback import arm_checker

CROWDED = Scene(
    (
        Cylinder("pillar", (0.15, 0.15, TABLE.top_z), 0.04, 0.3),
        Box("crate", (0.22, -0.12, TABLE.top_z), (0.06, 0.05, 0.12), yaw=0.6),
        Sphere("ball", (-0.2, 0.2, 0.25), 0.05),
        Sphere("low_ball", (0.0, -0.25, 0.08), 0.04),
    )
)
"""Four obstacles around the arm, of every shape (and the report's scene with its cube)."""


@pytest.mark.parametrize(("scene", "grasped"), [(CROWDED, False), (REPORT_SCENE, True)])
def test_levels_cut_clearances_above_them_and_keep_the_rest_bit_for_bit(
    scene: Scene, grasped: bool
) -> None:
    checker = arm_checker(load_arm_scene(scene))
    rng = np.random.default_rng(5)
    q = rng.uniform(-1.2, 1.2, (400, 5))
    exact = checker.min_clearance(q, grasped=grasped)
    finite = exact[np.isfinite(exact)]
    assert (exact == -np.inf).any()  # hits and clearances both asked
    assert finite.size > 100
    for level in (
        np.full(len(q), np.median(finite)),
        exact,  # every vector exactly at its level
        np.nextafter(exact, -np.inf),
        rng.uniform(0.0, 0.2, len(q)),
        np.full(len(q), np.inf),
    ):
        below = checker.min_clearance(q, grasped=grasped, below=level)
        np.testing.assert_array_equal(below, np.minimum(exact, np.minimum(level, checker.cap_m)))


def test_levels_must_be_one_per_vector() -> None:
    checker = arm_checker(load_arm_scene(CROWDED))
    with pytest.raises(InvalidInputError):
        checker.min_clearance(np.zeros((3, 5)), below=np.zeros(2))
    with pytest.raises(InvalidInputError):
        checker.min_clearance(np.zeros((1, 5)), below=[np.nan])
