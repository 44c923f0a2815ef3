"""Planning in a subspace of the joints: some held, some tied to others.

A robot commanded in tool space may not move every joint freely: the arm envs
hold the wrist roll, and a gripper that should keep pointing down ties the
wrist pitch to the shoulder and elbow. :class:`JointSubspace` presents such a
world to the planner as one with fewer joints, ``q = basis @ p + offset`` for
the planner's vector ``p``; :meth:`JointSubspace.full` maps a path back.

The joint box of the full vector is part of the subspace's world: a ``p``
whose full vector leaves it reads ``-inf``. The box and the subspace are
convex, so an edge between two accepted vectors never leaves the box, and the
Lipschitz certificate of an edge (:mod:`lynxsim.plan.edges`) holds with the
robot's constant times :attr:`JointSubspace.stretch`.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError
from lynxsim.inputs import finite_array
from lynxsim.plan.oracle import ClearanceOracle, FloatArray

__all__ = ["JointSubspace"]


class JointSubspace:
    """A :class:`~lynxsim.plan.oracle.ClearanceOracle` over ``p`` with ``q = basis @ p + offset``.

    Args:
        oracle: The world over all ``n`` joints.
        basis: Shape (n, k), rank k >= 1.
        offset: Shape (n,) [rad].
        lower: Lower joint bounds of the full vector, shape (n,) [rad].
        upper: Upper joint bounds of the full vector, shape (n,) [rad].

    Raises:
        InvalidInputError: Shapes that do not fit, or a basis of lower rank.
        NonFiniteInputError: A value is NaN or infinite.
    """

    def __init__(
        self,
        oracle: ClearanceOracle,
        basis: npt.ArrayLike,
        offset: npt.ArrayLike,
        lower: npt.ArrayLike,
        upper: npt.ArrayLike,
    ) -> None:
        n = oracle.n_joints
        a = np.array(finite_array(basis, "basis"), dtype=float)
        if a.ndim != 2 or a.shape[0] != n or a.shape[1] < 1:
            raise InvalidInputError(f"basis must have shape ({n}, k) with k >= 1, got {a.shape}")
        if np.linalg.matrix_rank(a) != a.shape[1]:
            raise InvalidInputError(f"basis must have full column rank {a.shape[1]}")
        vectors = {}
        for name, value in (("offset", offset), ("lower", lower), ("upper", upper)):
            v = np.array(finite_array(value, name), dtype=float).reshape(-1)
            if v.shape != (n,):
                raise InvalidInputError(f"{name} must have shape ({n},), got {v.shape}")
            vectors[name] = v
        self._oracle = oracle
        self._basis = a
        self._offset = vectors["offset"]
        self._lower = vectors["lower"]
        self._upper = vectors["upper"]
        self.n_joints = a.shape[1]
        self.stretch = float(np.linalg.norm(a, 2))
        """Largest ``|basis @ dp| / |dp|``: multiplies the robot's Lipschitz constant."""

    @classmethod
    def holding(
        cls,
        oracle: ClearanceOracle,
        fixed: Sequence[int],
        values: Sequence[float],
        lower: npt.ArrayLike,
        upper: npt.ArrayLike,
    ) -> JointSubspace:
        """The subspace with joints ``fixed`` held at ``values`` [rad], the others free.

        Raises:
            InvalidInputError: Indices out of range or repeated, or every joint held.
        """
        n = oracle.n_joints
        held = [int(i) for i in fixed]
        if len(set(held)) != len(held) or any(not 0 <= i < n for i in held):
            raise InvalidInputError(
                f"fixed joints must be distinct indices in [0, {n}), got {held}"
            )
        v = np.array(finite_array(values, "values"), dtype=float).reshape(-1)
        if v.shape != (len(held),):
            raise InvalidInputError(f"values must have one value per fixed joint, got {v.shape}")
        free = [i for i in range(n) if i not in held]
        if not free:
            raise InvalidInputError("at least one joint must stay free")
        basis = np.zeros((n, len(free)))
        basis[free, np.arange(len(free))] = 1.0
        offset = np.zeros(n)
        offset[held] = v
        return cls(oracle, basis, offset, lower, upper)

    def full(self, p: FloatArray) -> FloatArray:
        """Full joint vectors of subspace vectors, (N, k) -> (N, n) [rad]."""
        out: FloatArray = np.asarray(p, dtype=float) @ self._basis.T + self._offset
        return out

    def project(self, q: npt.ArrayLike) -> FloatArray:
        """The subspace vector nearest a full one (least squares), (N, n) -> (N, k) [rad]."""
        full = np.atleast_2d(np.asarray(q, dtype=float)) - self._offset
        p, *_ = np.linalg.lstsq(self._basis, full.T, rcond=None)
        out: FloatArray = p.T
        return out

    def clearance(self, p: FloatArray, *, grasped: bool) -> FloatArray:
        """Clearance of subspace vectors, (N, k) -> (N,) [m]; -inf outside the joint box."""
        q = self.full(p)
        outside = ((q < self._lower) | (q > self._upper)).any(axis=1)
        out = np.full(len(q), -np.inf)
        if not outside.all():
            out[~outside] = self._oracle.clearance(q[~outside], grasped=grasped)
        return out
