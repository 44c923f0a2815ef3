"""What the planner asks of the world: clearances of batches of joint vectors.

The planner never sees obstacles. It asks a :class:`ClearanceOracle` how far
the robot (and, when it holds one, its payload) is from everything it must not
touch. The MuJoCo side adapts :class:`lynxsim.sim.collision.CollisionChecker`
to it; tests use pure-numpy fake worlds.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError

__all__ = ["ClearanceOracle", "FloatArray", "query"]

FloatArray = npt.NDArray[np.float64]


class ClearanceOracle(Protocol):
    """Clearances of joint vectors, answered in batches.

    Attributes:
        n_joints: Length ``n`` of a joint vector.
    """

    n_joints: int

    def clearance(self, q: FloatArray, *, grasped: bool) -> FloatArray:
        """Smallest distance from the robot to anything it must not touch.

        Args:
            q: Joint vectors, shape (N, n) [rad].
            grasped: Whether the robot holds its payload (the payload then counts
                as part of the robot against obstacles).

        Returns:
            Clearance of each vector, shape (N,) [m]: the smallest distance from
            the robot (and payload) to any obstacle; ``<= 0`` (or ``-inf``) when
            it touches an obstacle, itself or the table.
        """
        ...


def query(oracle: ClearanceOracle, q: FloatArray, grasped: bool) -> FloatArray:
    """Ask ``oracle`` for the clearances of ``q`` (N, n); NaN reads as ``-inf`` [m].

    Raises:
        InvalidInputError: The oracle's answer does not have shape (N,).
    """
    if q.shape[0] == 0:
        return np.empty(0)
    c = np.asarray(oracle.clearance(q, grasped=grasped), dtype=float)
    if c.shape != (q.shape[0],):
        raise InvalidInputError(
            f"the clearance oracle answered shape {c.shape} for {q.shape[0]} joint vectors; "
            f"expected ({q.shape[0]},)"
        )
    return np.where(np.isnan(c), -np.inf, c)
