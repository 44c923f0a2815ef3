"""Contact bookkeeping over a run: every physics step, every pair, the worst moment."""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from lynxsim.sim.binding import RobotBinding
from lynxsim.sim.report import CollisionVerdict, ContactPair

__all__ = ["ContactTracker"]


@dataclass
class _PairStats:
    first_time_s: float
    max_penetration_m: float


class ContactTracker:
    """Classifies the active contacts of each step into obstacle, self and support.

    Args:
        model: The model (for geom names).
        binding: Which geoms are the robot's, the obstacle's, the support's.
    """

    def __init__(self, model: mujoco.MjModel, binding: RobotBinding) -> None:
        self._model = model
        self._b = binding
        self._obstacle: dict[tuple[int, int], _PairStats] = {}
        self._self: dict[tuple[int, int], _PairStats] = {}
        self._support: dict[tuple[int, int], _PairStats] = {}
        self._first: tuple[float, tuple[int, int]] | None = None
        self.obstacle_steps = 0

    def update(self, data: mujoco.MjData) -> frozenset[int]:
        """Record this step's contacts; returns the bodies touching the obstacle.

        Robot and payload geoms count for the obstacle verdict; self-collisions
        and table contacts are the robot's own.
        """
        n = int(data.ncon)
        if n == 0:
            return frozenset()
        geoms = np.asarray(data.contact.geom[:n])
        dist = np.asarray(data.contact.dist[:n])
        robot = self._b.robot_geoms[geoms]  # (n, 2)
        carried = self._b.carried_geoms[geoms]  # robot or payload, (n, 2)
        obstacle = self._b.obstacle_geoms[geoms].any(axis=1)
        both_robot = robot.all(axis=1)
        support = self._b.support_geoms[geoms].any(axis=1)
        # Contacts inside the margin but apart (dist > 0) do not count as touching.
        hits_obstacle = carried.any(axis=1) & obstacle
        wanted = (dist <= 0.0) & (hits_obstacle | (robot.any(axis=1) & (both_robot | support)))
        t = float(data.time)
        hit: set[int] = set()
        for k in np.flatnonzero(wanted):
            g1, g2 = int(geoms[k, 0]), int(geoms[k, 1])
            if not carried[k, 0]:  # robot (or payload) geom first
                g1, g2 = g2, g1
            pen = float(-dist[k])
            if hits_obstacle[k]:
                table = self._obstacle
                hit.add(g1)
                if self._first is None:
                    self._first = (t, (g1, g2))
            elif both_robot[k]:
                table = self._self
                g1, g2 = min(g1, g2), max(g1, g2)
            else:
                table = self._support
            stats = table.get((g1, g2))
            if stats is None:
                table[(g1, g2)] = _PairStats(t, pen)
            else:
                stats.max_penetration_m = max(stats.max_penetration_m, pen)
        if hit:
            self.obstacle_steps += 1
        return frozenset(int(self._model.geom_bodyid[g]) for g in hit)

    def _pairs(self, table: dict[tuple[int, int], _PairStats]) -> tuple[ContactPair, ...]:
        name = self._model.geom
        return tuple(
            ContactPair(name(g1).name, name(g2).name, s.first_time_s, s.max_penetration_m)
            for (g1, g2), s in sorted(table.items(), key=lambda kv: kv[1].first_time_s)
        )

    def verdict(self) -> CollisionVerdict:
        """The obstacle-collision verdict so far."""
        pairs = self._pairs(self._obstacle)
        first_pair = None
        first_time = None
        if self._first is not None:
            first_time = self._first[0]
            g1, g2 = self._first[1]
            first_pair = (self._model.geom(g1).name, self._model.geom(g2).name)
        return CollisionVerdict(
            collided=self._first is not None,
            first_time_s=first_time,
            first_pair=first_pair,
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
