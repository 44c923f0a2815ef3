"""Which geoms are the robot, its payload, the obstacles and the support; what a contact is.

:class:`CollisionGroups` names the geoms of each kind in a model;
:func:`classify_contacts` applies the collision definition of
:mod:`lynxsim.sim.collision` to a list of contacts.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError

__all__ = ["CollisionGroups", "ContactClasses", "classify_contacts"]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]
BoolArray = npt.NDArray[np.bool_]


@dataclass(frozen=True)
class CollisionGroups:
    """Which geoms of a model are the robot, its payload, the obstacles and the support.

    Attributes:
        robot: Mask over geoms: the robot's colliding geoms, (ngeom,).
        payload: Mask over geoms: what the robot carries (the cube), (ngeom,).
        support: Mask over geoms: the table and floor, (ngeom,).
        obstacle_geoms: Geom id of each obstacle, in the scene's order, (m,).
        obstacle_names: Name of each obstacle, (m,).
    """

    robot: BoolArray
    payload: BoolArray
    support: BoolArray
    obstacle_geoms: IntArray
    obstacle_names: tuple[str, ...]

    def __post_init__(self) -> None:
        if len(self.obstacle_geoms) != len(self.obstacle_names):
            raise InvalidInputError("one name per obstacle geom is needed")

    @property
    def carried(self) -> BoolArray:
        """Robot and payload geoms: what must not touch an obstacle, (ngeom,)."""
        out: BoolArray = self.robot | self.payload
        return out

    def obstacle_pairs(self) -> frozenset[tuple[int, int]]:
        """Every ordered geom pair whose contact is an obstacle hit (for fast per-step lookups)."""
        carried = np.flatnonzero(self.carried).tolist()
        return frozenset(
            pair for c in carried for o in self.obstacle_geoms.tolist() for pair in ((c, o), (o, c))
        )

    @property
    def obstacle_index(self) -> IntArray:
        """Per geom, the index of the obstacle it is, or -1, (ngeom,)."""
        index = np.full(len(self.robot), -1, dtype=np.intp)
        index[self.obstacle_geoms] = np.arange(len(self.obstacle_geoms))
        return index


@dataclass(frozen=True)
class ContactClasses:
    """What each of n contacts is (all False for a contact apart, dist > 0).

    Attributes:
        obstacle: Robot or payload against an obstacle, (n,).
        obstacle_index: Which obstacle (-1 where ``obstacle`` is False), (n,).
        self_hit: Robot against robot, (n,).
        support: Robot against table or floor, (n,).
        carried_first: Whether the first geom of the pair is the robot's (or the
            payload's), (n,): pairs are reported robot geom first.
    """

    obstacle: BoolArray
    obstacle_index: IntArray
    self_hit: BoolArray
    support: BoolArray
    carried_first: BoolArray


def classify_contacts(
    groups: CollisionGroups, geoms: npt.ArrayLike, dist: npt.ArrayLike
) -> ContactClasses:
    """Classify contacts by the collision definition of :mod:`lynxsim.sim.collision`.

    Args:
        groups: The geom groups of the model.
        geoms: Geom pairs of the contacts, (n, 2).
        dist: Their signed distances, (n,) [m]; only ``dist <= 0`` touches.

    Returns:
        The :class:`ContactClasses`.
    """
    g = np.asarray(geoms, dtype=np.intp).reshape(-1, 2)
    a, b = g[:, 0], g[:, 1]  # the two columns apart: a reduction over an axis of 2 is slow
    touching = np.asarray(dist, dtype=float).reshape(-1) <= 0.0
    robot, carried, support = groups.robot, groups.carried, groups.support
    index = groups.obstacle_index
    carried_a, carried_b, index_a, index_b = carried[a], carried[b], index[a], index[b]
    obstacle = touching & (carried_a | carried_b) & ((index_a >= 0) | (index_b >= 0))
    robot_a, robot_b = robot[a], robot[b]
    self_hit = touching & robot_a & robot_b
    on_support = (robot_a | robot_b) & (support[a] | support[b])
    return ContactClasses(
        obstacle=obstacle,
        obstacle_index=np.where(obstacle, np.maximum(index_a, index_b), -1),
        self_hit=self_hit,
        support=touching & on_support & ~obstacle,
        carried_first=carried_a,
    )
