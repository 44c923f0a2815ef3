"""Fake worlds in pure numpy: clearance = Euclidean distance in joint space (Lipschitz 1)."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]

LIPSCHITZ = 1.0
"""The fake worlds' clearance changes by at most the joint-space distance [m/rad]."""

MARGIN_M = 0.01
"""Planning margin used by the tests [m]."""

DENSE_POINTS = 1000
"""Points per edge of the dense re-checks [-]."""


class Boxes:
    """Axis-aligned boxes in an n-D joint space; clearance = signed distance to the nearest."""

    def __init__(self, centres: npt.ArrayLike, halves: npt.ArrayLike) -> None:
        self.centres = np.atleast_2d(np.asarray(centres, dtype=float))
        self.halves = np.atleast_2d(np.asarray(halves, dtype=float))
        self.n_joints = self.centres.shape[1]
        self.calls = 0
        self.vectors = 0
        self.grasped_calls = 0

    def clearance(self, q: FloatArray, *, grasped: bool) -> FloatArray:
        self.calls += 1
        self.vectors += q.shape[0]
        self.grasped_calls += int(grasped)
        d = np.abs(q[:, None, :] - self.centres[None]) - self.halves[None]
        outside = np.linalg.norm(np.maximum(d, 0.0), axis=2)
        inside = np.minimum(d.max(axis=2), 0.0)
        out: FloatArray = (outside + inside).min(axis=1)
        return out


class Spheres:
    """Balls in an n-D joint space; clearance = distance to the nearest surface."""

    def __init__(self, centres: npt.ArrayLike, radii: npt.ArrayLike) -> None:
        self.centres = np.atleast_2d(np.asarray(centres, dtype=float))
        self.radii = np.asarray(radii, dtype=float).reshape(-1)
        self.n_joints = self.centres.shape[1]
        self.grasped_calls = 0

    def clearance(self, q: FloatArray, *, grasped: bool) -> FloatArray:
        self.grasped_calls += int(grasped)
        d = np.linalg.norm(q[:, None, :] - self.centres[None], axis=2) - self.radii[None]
        out: FloatArray = d.min(axis=1)
        return out


LOWER_2D = np.array([-1.0, -1.0])
UPPER_2D = np.array([1.0, 1.0])

WALL = Boxes([[0.0, 0.0]], [[0.05, 0.8]])
"""A wall across the middle of the square, passages above and below."""

U_TRAP = Boxes(
    [[0.3, 0.0], [0.0, 0.4], [0.0, -0.4]],
    [[0.05, 0.45], [0.35, 0.05], [0.35, 0.05]],
)
"""A U open to the left; a start inside it is pulled against its bottom by a goal behind it."""

ENCLOSED_GOAL = Boxes(
    [[0.5, 0.7], [0.5, 0.3], [0.3, 0.5], [0.7, 0.5]],
    [[0.25, 0.05], [0.25, 0.05], [0.05, 0.25], [0.05, 0.25]],
)
"""A closed square ring around (0.5, 0.5): its inside cannot be reached from outside."""


def dense_edge_clearance(world: Boxes | Spheres, a: FloatArray, b: FloatArray) -> float:
    """Smallest clearance at :data:`DENSE_POINTS` points of the edge a -> b [m]."""
    u = np.linspace(0.0, 1.0, DENSE_POINTS)[:, None]
    return float(world.clearance(a + u * (b - a), grasped=False).min())
