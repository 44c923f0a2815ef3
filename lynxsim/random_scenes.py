"""Random obstacles around the arm, drawn from a NumPy generator (pure, SI).

Used by the planning benchmark (and the sweeps and environments that randomise
scenes): cylinders, boxes and spheres stand in the arm's reach, around the base
axis at any heading, never enclosing the base or a point the caller must keep
free (a start, a goal, the cube), their centres at least 50 mm apart.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from lynxsim.errors import InvalidInputError
from lynxsim.inputs import count
from lynxsim.scene import TABLE, Box, Cylinder, Obstacle, Sphere

__all__ = ["REACH_ANNULUS_M", "random_obstacles"]

REACH_ANNULUS_M = (0.12, 0.30)
"""Radial range of obstacle centres from the base axis [m]: where the arm works."""

_MAX_TRIES = 1000


def _one(rng: np.random.Generator, name: str) -> Obstacle:
    """One obstacle of a random shape, size and place."""
    radius = rng.uniform(*REACH_ANNULUS_M)
    heading = rng.uniform(-math.pi, math.pi)
    x, y = radius * math.cos(heading), radius * math.sin(heading)
    shape = rng.integers(3)
    bottom = TABLE.top_z
    if shape == 0:
        return Cylinder(
            name, (x, y, bottom), radius=rng.uniform(0.015, 0.04), height=rng.uniform(0.1, 0.4)
        )
    if shape == 1:
        size = (rng.uniform(0.03, 0.1), rng.uniform(0.03, 0.1), rng.uniform(0.1, 0.4))
        return Box(name, (x, y, bottom), size=size, yaw=rng.uniform(-math.pi, math.pi))
    r = rng.uniform(0.02, 0.045)
    return Sphere(name, (x, y, rng.uniform(0.05, 0.35)), radius=r)


def random_obstacles(
    rng: np.random.Generator,
    number: int,
    *,
    keep_free: Sequence[Sequence[float]] = (),
    gap_m: float = 0.06,
) -> tuple[Obstacle, ...]:
    """``number`` random obstacles, named ``obstacle1``, ``obstacle2``, ...

    Args:
        rng: The generator (the only source of randomness).
        number: How many, 0 to 8.
        keep_free: Points no obstacle may come within ``gap_m`` of, each (3,) [m]
            (tool targets, the cube); the base axis is always kept free.
        gap_m: Least distance from those points to any obstacle [m].

    Returns:
        The obstacles (pure :mod:`lynxsim.scene` objects).

    Raises:
        InvalidInputError: ``number`` out of range, or no placement found (the
            points to keep free leave no room).
    """
    n = count(number, "number", 0, 8)
    free: list[tuple[float, float, float]] = [
        (float(p[0]), float(p[1]), float(p[2])) for p in keep_free
    ] + [(0.0, 0.0, z) for z in (0.0, 0.1, 0.2)]
    out: list[Obstacle] = []
    for i in range(n):
        for _ in range(_MAX_TRIES):
            candidate = _one(rng, f"obstacle{i + 1}")
            if any(candidate.distance(p) < gap_m for p in free):
                continue
            centre = np.asarray(candidate.position[:2])
            if any(np.hypot(*(centre - np.asarray(o.position[:2]))) < 0.05 for o in out):
                continue
            out.append(candidate)
            break
        else:
            raise InvalidInputError(f"no room for obstacle {i + 1} after {_MAX_TRIES} tries")
    return tuple(out)
