"""Spheres enclosing one primitive geom, and how far the cover reaches beyond it (its slack).

A capsule is covered by spheres on its axis, each enclosing a slice of the
cylinder between its end caps (radius ``hypot(r, h)`` for a slice of half
length ``h``, slack ``hypot(r, h) - r``), and one sphere per end cap (its own
radius). Any other geom's box (the geom itself for a box, the bounding box of
a cylinder) is cut into an ``n_x x n_y x n_z`` grid of equal pieces; each piece
that meets the geom gets one sphere enclosing the whole piece, its centre the
point of the geom nearest the piece's centre (so every centre lies in the
geom). The spheres enclose every piece that may meet the geom (whose centre
lies within its half diagonal of it), so their union encloses the geom: a
cover is never optimistic.

The slack is the farthest any point of the cover lies from the geom [m]. For a
box piece of half sizes ``h`` it is at most ``|h| - min(h)`` (the sphere's
point farthest from the piece lies on its shortest axis). For cylinders it is
measured: the largest distance to the geom over :data:`SLACK_SAMPLES` points
on each sphere, plus the radius times the angular spacing of those points (the
distance to a convex set changes by at most the distance moved). The grid is
the one of fewest spheres whose slack is at most the target, or of least slack
when none is.
"""

from __future__ import annotations

import functools
import itertools
import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError
from lynxsim.plan.cover.world import GEOM_BOX, GEOM_CAPSULE, GEOM_CYLINDER, GEOM_SPHERE

__all__ = ["DEFAULT_SLACK_M", "MAX_PIECES", "SLACK_SAMPLES", "GeomCover", "cover_geom"]

FloatArray = npt.NDArray[np.float64]

DEFAULT_SLACK_M = 0.006
"""Target slack of a geom's cover [m]."""

MAX_PIECES = 8
"""Most pieces along one axis of a geom [-]."""

SLACK_SAMPLES = 2000
"""Points per sphere at which a cylinder's slack is measured [-]."""

_SEARCH_SAMPLES = 96
"""Points per sphere while the grid is chosen (the slack reported uses :data:`SLACK_SAMPLES`)."""


@dataclass(frozen=True)
class GeomCover:
    """The spheres of one geom, in its frame.

    Attributes:
        centres: Shape (k, 3) [m].
        radii: Shape (k,) [m].
        slack_m: Farthest a point of the spheres lies from the geom [m].
        grid: Pieces along the geom's x, y, z.
    """

    centres: FloatArray
    radii: FloatArray
    slack_m: float
    grid: tuple[int, int, int]


def _fibonacci(count: int) -> tuple[FloatArray, float]:
    """``count`` unit vectors spread over the sphere (count, 3), and their angular spacing [rad].

    The spacing is a bound on the angle from any direction to the nearest
    vector: twice the angular radius of a cap of ``1 / count`` of the sphere.
    """
    k = np.arange(count) + 0.5
    z = 1.0 - 2.0 * k / count
    phi = math.pi * (3.0 - math.sqrt(5.0)) * k
    r = np.sqrt(1.0 - z * z)
    spacing = 2.0 * 2.0 * math.asin(math.sqrt(1.0 / count))
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1), spacing


def _distance(kind: int, size: FloatArray, p: FloatArray) -> FloatArray:
    """Distance of points ``p`` (..., 3) to the geom (0 inside) [m]."""
    if kind == GEOM_CYLINDER:
        radial = np.maximum(np.hypot(p[..., 0], p[..., 1]) - size[0], 0.0)
        axial = np.maximum(np.abs(p[..., 2]) - size[1], 0.0)
        out: FloatArray = np.hypot(radial, axial)
        return out
    z = np.clip(p[..., 2], -size[1], size[1])
    capsule: FloatArray = np.maximum(
        np.sqrt(p[..., 0] ** 2 + p[..., 1] ** 2 + (p[..., 2] - z) ** 2) - size[0], 0.0
    )
    return capsule


def _nearest(kind: int, size: FloatArray, p: FloatArray) -> FloatArray:
    """The geom's points nearest ``p`` (k, 3) [m] (cylinder or capsule)."""
    if kind == GEOM_CAPSULE:
        axis = np.zeros_like(p)
        axis[:, 2] = np.clip(p[:, 2], -size[1], size[1])
        d = p - axis
        norm = np.linalg.norm(d, axis=1)
        scale = np.where(norm > size[0], size[0] / np.maximum(norm, 1e-300), 1.0)
        capsule: FloatArray = axis + d * scale[:, None]
        return capsule
    radial = np.hypot(p[:, 0], p[:, 1])
    scale = np.where(radial > size[0], size[0] / np.maximum(radial, 1e-300), 1.0)
    out: FloatArray = p * np.stack([scale, scale, np.ones_like(scale)], axis=1)
    out[:, 2] = np.clip(out[:, 2], -size[1], size[1])
    return out


def _grid(half: FloatArray, n: tuple[int, int, int]) -> tuple[FloatArray, FloatArray]:
    """Centres (k, 3) and half sizes (3,) of the pieces of a box of half sizes ``half``."""
    h = half / np.array(n)
    axes = [-half[i] + (2 * np.arange(n[i]) + 1) * h[i] for i in range(3)]
    centres = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    return centres, h


def _round(kind: int, size: FloatArray, n: tuple[int, int, int], samples: int) -> GeomCover:
    """The cover of a cylinder or capsule by grid ``n``, its slack measured on ``samples``."""
    reach = size[1] if kind == GEOM_CYLINDER else size[1] + size[0]
    half = np.array([size[0], size[0], reach])
    pieces, h = _grid(half, n)
    # A piece that meets the geom has its centre within its half diagonal of it
    # (a superset of the pieces that meet it is kept).
    near = _nearest(kind, size, pieces)
    keep = np.linalg.norm(near - pieces, axis=1) <= np.linalg.norm(h) * (1.0 + 1e-12)
    pieces, centres = pieces[keep], near[keep]
    corners = np.array(list(itertools.product((-1.0, 1.0), repeat=3))) * h
    radii = np.linalg.norm(pieces[:, None, :] + corners[None] - centres[:, None, :], axis=2).max(1)
    dirs, spacing = _fibonacci(samples)
    points = centres[:, None, :] + radii[:, None, None] * dirs[None]
    slack = float((_distance(kind, size, points).max(axis=1) + radii * spacing).max())
    return GeomCover(centres, radii, slack, n)


def _capsule(size: FloatArray, k: int) -> GeomCover:
    """A capsule by ``k`` spheres along its axis, each enclosing a slice, and one per end cap."""
    radius, half = size[0], size[1]
    h = half / k
    z = -half + (2 * np.arange(k) + 1) * h
    ends = np.array([-half, half])
    centres = np.zeros((k + 2, 3))
    centres[:, 2] = np.concatenate([z, ends])
    rho = math.hypot(radius, h)
    radii = np.concatenate([np.full(k, rho), np.full(2, radius)])
    return GeomCover(centres, radii, rho - radius, (1, 1, k))


def _box(size: FloatArray, n: tuple[int, int, int]) -> GeomCover:
    centres, h = _grid(size, n)
    r = float(np.linalg.norm(h))
    return GeomCover(centres, np.full(len(centres), r), r - float(h.min()), n)


@functools.lru_cache(maxsize=256)
def _cached(kind: int, size: tuple[float, float, float], slack_m: float) -> GeomCover:
    s = np.array(size)
    if kind == GEOM_SPHERE:
        return GeomCover(np.zeros((1, 3)), np.array([s[0]]), 0.0, (1, 1, 1))
    if kind not in (GEOM_BOX, GEOM_CYLINDER, GEOM_CAPSULE):
        raise InvalidInputError(
            f"a sphere cover needs spheres, capsules, cylinders or boxes; got geom type {kind}"
        )
    ranks = range(1, MAX_PIECES + 1)
    if kind == GEOM_BOX:
        grids = np.array(list(itertools.product(ranks, repeat=3)))
        h = s / grids
        slack = np.linalg.norm(h, axis=1) - h.min(axis=1)
        count = grids.prod(axis=1)
        fits = slack <= slack_m
        order = np.lexsort((slack, count)) if fits.any() else np.lexsort((count, slack))
        pick = next(int(i) for i in order if fits[i] or not fits.any())
        a, b, c = (int(x) for x in grids[pick])
        covers = [_box(s, (a, b, c))]
    elif kind == GEOM_CAPSULE:
        covers = [_capsule(s, k) for k in range(1, 2 * MAX_PIECES + 1)]
    else:
        covers = [_round(kind, s, (a, a, c), _SEARCH_SAMPLES) for a in ranks for c in ranks]
    fit = [c for c in covers if c.slack_m <= slack_m]
    best = (
        min(fit, key=lambda c: (len(c.radii), c.slack_m))
        if fit
        else min(covers, key=lambda c: (c.slack_m, len(c.radii)))
    )
    if kind == GEOM_CYLINDER:
        best = _round(kind, s, best.grid, SLACK_SAMPLES)
    for arr in (best.centres, best.radii):
        arr.setflags(write=False)
    return best


def cover_geom(kind: int, size: npt.ArrayLike, slack_m: float = DEFAULT_SLACK_M) -> GeomCover:
    """Spheres enclosing a primitive geom, in its frame.

    Args:
        kind: MuJoCo geom type: sphere, capsule, cylinder or box.
        size: Its MuJoCo size (3,) [m].
        slack_m: Target slack [m], > 0.

    Returns:
        The :class:`GeomCover` (cached per type, size and target).

    Raises:
        InvalidInputError: Another geom type, a size that is not positive, or a bad target.
    """
    s = np.asarray(size, dtype=float).reshape(-1)
    if s.shape != (3,) or not np.isfinite(s).all():
        raise InvalidInputError(f"a geom size must be 3 finite numbers, got {s!r}")
    used = {GEOM_SPHERE: 1, GEOM_CAPSULE: 2, GEOM_CYLINDER: 2, GEOM_BOX: 3}.get(int(kind), 3)
    if (s[:used] <= 0.0).any():
        raise InvalidInputError(f"a geom size must be positive, got {s!r}")
    if not (math.isfinite(slack_m) and slack_m > 0.0):
        raise InvalidInputError(f"slack_m must be positive, got {slack_m!r}")
    return _cached(int(kind), (float(s[0]), float(s[1]), float(s[2])), float(slack_m))
