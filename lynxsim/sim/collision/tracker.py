"""The classified contacts of a run accumulated: every pair, its first time, its worst depth.

:class:`ContactTracker` gives a run's obstacle verdict, self-collisions and
table contacts (:mod:`lynxsim.sim.summary` and the 3-RRR checks use it).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from lynxsim.sim.collision.groups import CollisionGroups, classify_contacts
from lynxsim.sim.report import CollisionVerdict, ContactPair

__all__ = ["ContactTracker"]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.intp]
BoolArray = npt.NDArray[np.bool_]


@dataclass
class _PairStats:
    first_time_s: float
    max_penetration_m: float


class ContactTracker:
    """Accumulates the classified contacts of a run: every pair, its first time, its worst.

    Args:
        geom_names: Name of every geom of the model, (ngeom,).
        groups: The collision groups.
    """

    def __init__(self, geom_names: tuple[str, ...], groups: CollisionGroups) -> None:
        self._names = geom_names
        self._groups = groups
        self._obstacle: dict[tuple[int, int], _PairStats] = {}
        self._self: dict[tuple[int, int], _PairStats] = {}
        self._support: dict[tuple[int, int], _PairStats] = {}
        self._first: tuple[float, tuple[int, int], int] | None = None
        self._first_by_obstacle: dict[int, float] = {}
        self.obstacle_steps = 0

    def update(self, time_s: float, geoms: IntArray, dist: FloatArray) -> frozenset[int]:
        """Record one instant's contacts; returns the robot geoms touching an obstacle.

        Args:
            time_s: Simulated time [s].
            geoms: Geom pairs of the contacts, (n, 2).
            dist: Their signed distances, (n,) [m].
        """
        if len(geoms) == 0:
            return frozenset()
        c = classify_contacts(self._groups, geoms, dist)
        hit: set[int] = set()
        for k in np.flatnonzero(c.obstacle | c.self_hit | c.support).tolist():
            g1, g2 = int(geoms[k, 0]), int(geoms[k, 1])
            if not c.carried_first[k]:
                g1, g2 = g2, g1
            pen = float(-dist[k])
            if c.obstacle[k]:
                table = self._obstacle
                hit.add(g1)
                index = int(c.obstacle_index[k])
                self._first_by_obstacle.setdefault(index, time_s)
                if self._first is None:
                    self._first = (time_s, (g1, g2), index)
            elif c.self_hit[k]:
                table = self._self
                g1, g2 = min(g1, g2), max(g1, g2)
            else:
                table = self._support
            stats = table.get((g1, g2))
            if stats is None:
                table[(g1, g2)] = _PairStats(time_s, pen)
            else:
                stats.max_penetration_m = max(stats.max_penetration_m, pen)
        if hit:
            self.obstacle_steps += 1
        return frozenset(hit)

    def update_many(
        self, time_s: npt.ArrayLike, step: npt.ArrayLike, geoms: IntArray, dist: FloatArray
    ) -> None:
        """Record the contacts of many instants at once, in time order.

        The same records as :meth:`update` called instant by instant (first
        times, worst penetrations, the first hit, steps in contact), classified
        in one vectorised pass.

        Args:
            time_s: Simulated time of each contact, (K,) [s], non-decreasing.
            step: The instant (step) each contact belongs to, (K,).
            geoms: Geom pairs of the contacts, (K, 2).
            dist: Their signed distances, (K,) [m].
        """
        g = np.asarray(geoms, dtype=np.intp).reshape(-1, 2)
        if len(g) == 0:
            return
        times = np.asarray(time_s, dtype=float).reshape(-1)
        steps = np.asarray(step).reshape(-1)
        pen = -np.asarray(dist, dtype=float).reshape(-1)
        c = classify_contacts(self._groups, g, -pen)
        pairs = np.where(c.carried_first[:, None], g, g[:, ::-1])
        ordered = np.sort(g, axis=1)
        pairs = np.where(c.self_hit[:, None], ordered, pairs)
        for mask, table in (
            (c.obstacle, self._obstacle),
            (c.self_hit, self._self),
            (c.support & ~c.self_hit, self._support),
        ):
            rows = np.flatnonzero(mask)
            if len(rows) == 0:
                continue
            ngeom = len(self._groups.robot)  # a pair as one integer: unique over 1-D is fast
            codes, first, inverse = np.unique(
                pairs[rows, 0] * ngeom + pairs[rows, 1], return_index=True, return_inverse=True
            )
            keys = np.column_stack(np.divmod(codes, ngeom))
            worst = np.full(len(keys), -np.inf)
            np.maximum.at(worst, inverse.reshape(-1), pen[rows])
            for i in np.argsort(first, kind="stable").tolist():
                key = (int(keys[i, 0]), int(keys[i, 1]))
                stats = table.get(key)
                if stats is None:
                    table[key] = _PairStats(float(times[rows[first[i]]]), float(worst[i]))
                else:
                    stats.max_penetration_m = max(stats.max_penetration_m, float(worst[i]))
        hits = np.flatnonzero(c.obstacle)
        if len(hits) == 0:
            return
        self.obstacle_steps += len(np.unique(steps[hits]))
        index = c.obstacle_index[hits]
        for j, k in zip(*np.unique(index, return_index=True), strict=True):
            self._first_by_obstacle.setdefault(int(j), float(times[hits[k]]))
        if self._first is None:
            k = int(hits[0])
            self._first = (float(times[k]), (int(pairs[k, 0]), int(pairs[k, 1])), int(index[0]))

    def _pairs(self, table: dict[tuple[int, int], _PairStats]) -> tuple[ContactPair, ...]:
        name = self._names
        return tuple(
            ContactPair(name[g1], name[g2], s.first_time_s, s.max_penetration_m)
            for (g1, g2), s in sorted(table.items(), key=lambda kv: kv[1].first_time_s)
        )

    def first_contact_s(self, obstacle: int) -> float | None:
        """Time of the first contact with obstacle ``obstacle`` (its index) [s], or None."""
        return self._first_by_obstacle.get(obstacle)

    def verdict(self) -> CollisionVerdict:
        """The obstacle-collision verdict so far."""
        pairs = self._pairs(self._obstacle)
        first = self._first
        return CollisionVerdict(
            collided=first is not None,
            first_time_s=None if first is None else first[0],
            first_pair=None
            if first is None
            else (self._names[first[1][0]], self._names[first[1][1]]),
            first_obstacle=None if first is None else self._groups.obstacle_names[first[2]],
            max_penetration_m=max((p.max_penetration_m for p in pairs), default=0.0),
            steps_in_contact=self.obstacle_steps,
            pairs=pairs,
        )

    def self_collisions(self) -> tuple[ContactPair, ...]:
        """Robot–robot pairs that touched."""
        return self._pairs(self._self)

    def support_contacts(self) -> tuple[ContactPair, ...]:
        """Robot geoms that touched the table or floor."""
        return self._pairs(self._support)
