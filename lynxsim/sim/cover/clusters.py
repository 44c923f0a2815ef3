"""Spheres of one geom grouped into clusters, each enclosed by a bounding sphere.

The compiled checks go coarse to fine: a geom's bounding sphere, then its
clusters' bounding spheres, then the spheres of a cluster that may come within
reach. A cluster's bounding sphere encloses every sphere of it, so a distance
to it is a lower bound of the distances to its spheres: the coarse levels never
change the clearance, they only skip work.

The clusters are made by splitting the spheres at the median of their centres
along the axis of widest spread, until a cluster holds at most
:data:`CLUSTER_SIZE` spheres.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

__all__ = ["CLUSTER_SIZE", "Clusters", "cluster_spheres"]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]

CLUSTER_SIZE = 6
"""Most spheres in one cluster [-]."""


@dataclass(frozen=True)
class Clusters:
    """A geom's k spheres in cluster order, and its C clusters.

    Attributes:
        order: The spheres' order (k,): cluster ``c`` holds spheres
            ``order[start[c]:start[c + 1]]``.
        start: Shape (C + 1,).
        centres: Centre of each cluster's bounding sphere, (C, 3) [m].
        radii: Its radius, (C,) [m]: every sphere of the cluster lies inside it.
    """

    order: IntArray
    start: IntArray
    centres: FloatArray
    radii: FloatArray


def _split(centres: FloatArray, index: IntArray) -> list[IntArray]:
    if len(index) <= CLUSTER_SIZE:
        return [index]
    points = centres[index]
    axis = int(np.argmax(points.max(axis=0) - points.min(axis=0)))
    ranked = index[np.argsort(points[:, axis], kind="stable")]
    half = len(ranked) // 2
    return _split(centres, ranked[:half]) + _split(centres, ranked[half:])


def cluster_spheres(centres: FloatArray, radii: FloatArray) -> Clusters:
    """Group spheres (k, 3), (k,) [m] into clusters of at most :data:`CLUSTER_SIZE`.

    Each bounding sphere is centred at the middle of its spheres' bounding box,
    with the radius that reaches the farthest point of its spheres.
    """
    groups = _split(centres, np.arange(len(radii), dtype=np.int64))
    mids, reach = [], []
    for group in groups:
        c, r = centres[group], radii[group]
        mid = 0.5 * (c.min(axis=0) + c.max(axis=0))
        mids.append(mid)
        reach.append(float((np.linalg.norm(c - mid, axis=1) + r).max()))
    sizes = [len(group) for group in groups]
    return Clusters(
        order=np.concatenate(groups),
        start=np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64),
        centres=np.array(mids, dtype=float).reshape(-1, 3),
        radii=np.array(reach, dtype=float),
    )
