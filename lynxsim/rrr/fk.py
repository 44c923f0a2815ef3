"""Forward kinematics of the 3-RRR robot: platform poses from the actuated angles.

With the actuated angles known, the elbows ``E_i`` are fixed and the platform
must put each joint ``P_i`` on the circle of radius ``L`` about ``E_i``: the
forward kinematics of a 3-RPR robot with equal leg lengths, which has at most
six real solutions (**assembly modes**). Two numerical routes:

* :func:`fk_all` finds every assembly mode, the roots of one polynomial
  (:mod:`lynxsim.rrr.assembly`);
* :func:`fk_near` and :func:`fk_path` follow one assembly mode by Newton's
  method from a nearby pose (branch continuation), as a controller would.

For the report's robot, random reachable configurations have 2, 4 or 6
assembly modes (see the tests and ``benchmarks/bench_rrr_workspace.py``).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from lynxsim.bounds import MAX_SAMPLES
from lynxsim.errors import InvalidInputError
from lynxsim.inputs import count
from lynxsim.rrr.assembly import MAX_ASSEMBLY_MODES, FKSolutions, fk_all
from lynxsim.rrr.closure import (
    CLOSURE_TOL,
    batch_size,
    elbow_points,
    elbows_of,
    loop_residual,
    newton,
    pose_modes,
)
from lynxsim.rrr.geometry import (
    RRR_ROBOT,
    RRRGeometry,
    as_pose_array,
    as_theta_array,
    check_rrr_geometry,
)

__all__ = [
    "CLOSURE_TOL",
    "MAX_ASSEMBLY_MODES",
    "FKResult",
    "FKSolutions",
    "elbow_points",
    "fk_all",
    "fk_near",
    "fk_path",
    "loop_residual",
]

FloatArray = npt.NDArray[np.float64]


class FKResult(NamedTuple):
    """One platform pose per actuated-angle triple, batch shape ``B``.

    Attributes:
        pose: Platform poses, shape B + (3,) [m, m, rad]; NaN where not converged.
        converged: Whether Newton's method closed every loop to
            :data:`CLOSURE_TOL`, shape B.
        mode: Working mode (0..7) of the pose, shape B, -1 where not converged.
    """

    pose: FloatArray
    converged: npt.NDArray[np.bool_]
    mode: npt.NDArray[np.int8]


MAX_NEWTON_ITER = 10_000
"""Largest Newton iteration limit :func:`fk_near` accepts."""
MAX_HALVINGS = 16
"""Largest ``max_halvings`` of :func:`fk_path` (2**16 sub-steps of one sample)."""


def fk_near(
    theta: npt.ArrayLike,
    guess: npt.ArrayLike,
    geometry: RRRGeometry = RRR_ROBOT,
    *,
    max_iter: int = 50,
) -> FKResult:
    """The platform pose of the assembly mode nearest a guess (Newton's method).

    Newton's method converges to the solution whose basin holds ``guess``; from
    a pose of the previous control step that is the same assembly mode unless
    the motion crossed or grazed a parallel singularity.

    Args:
        theta: Actuated angles, shape (..., 3) [rad].
        guess: Starting poses, shape (..., 3) [m, m, rad]; broadcast against ``theta``.
        geometry: The robot description.
        max_iter: Newton iteration limit (steps are limited to 20 mm).

    Returns:
        The :class:`FKResult` (not converged where an input is NaN or infinite).

    Raises:
        InvalidInputError: Bad shapes, types or geometry, shapes that do not
            broadcast, or ``max_iter`` not an integer from 1 to
            :data:`MAX_NEWTON_ITER`.
    """
    geometry = check_rrr_geometry(geometry)
    th = as_theta_array(theta)
    g = as_pose_array(guess, "guess")
    max_iter = count(max_iter, "max_iter", 1, MAX_NEWTON_ITER)
    try:
        batch = np.broadcast_shapes(th.shape[:-1], g.shape[:-1])
    except ValueError as exc:
        raise InvalidInputError(f"theta and guess do not broadcast: {exc}") from None
    n = batch_size(batch)
    elbows = elbows_of(np.broadcast_to(th, batch + (3,)).reshape(n, 3), geometry)
    pose, converged = newton(
        elbows, np.broadcast_to(g, batch + (3,)).reshape(n, 3).copy(), geometry, max_iter
    )
    mode = pose_modes(pose, elbows, geometry)
    return FKResult(
        pose=pose.reshape(batch + (3,)),
        converged=converged.reshape(batch),
        mode=mode.reshape(batch),
    )


def fk_path(
    theta_path: npt.ArrayLike,
    start: npt.ArrayLike,
    geometry: RRRGeometry = RRR_ROBOT,
    *,
    max_halvings: int = 6,
) -> FKResult:
    """Follow one assembly mode along a sequence of actuated angles.

    Each sample starts Newton's method from the previous pose; a step that does
    not converge is retried in up to ``2**max_halvings`` linear sub-steps. After
    a failure the rest of the path is NaN (not converged).

    Args:
        theta_path: Actuated angles, shape (T, 3) [rad].
        start: Platform pose near ``theta_path[0]``'s, shape (3,) [m, m, rad].
        geometry: The robot description.
        max_halvings: How often a failed step may be halved.

    Returns:
        The :class:`FKResult`, batch shape (T,); not converged from the first
        sample with a NaN or infinite angle on.

    Raises:
        InvalidInputError: ``theta_path`` is not real numbers of shape (T, 3)
            with 1 <= T <= :data:`~lynxsim.bounds.MAX_SAMPLES`, ``start`` not a
            pose (3,), ``max_halvings`` not an integer from 0 to
            :data:`MAX_HALVINGS`, or a bad ``geometry``.
    """
    geometry = check_rrr_geometry(geometry)
    th = as_theta_array(theta_path, "theta_path")
    if th.ndim != 2 or not 1 <= len(th) <= MAX_SAMPLES:
        raise InvalidInputError(
            f"theta_path must have shape (T, 3) with 1 <= T <= {MAX_SAMPLES:,}, got {th.shape}"
        )
    start_pose = as_pose_array(start, "start")
    if start_pose.shape != (3,):
        raise InvalidInputError(f"start must have shape (3,), got {start_pose.shape}")
    max_halvings = count(max_halvings, "max_halvings", 0, MAX_HALVINGS)
    pose = np.full(th.shape, np.nan)
    converged = np.zeros(len(th), dtype=bool)
    current = start_pose.reshape(1, 3)
    previous = th[0]
    finite_rows = np.isfinite(th).all(axis=-1)
    stop = len(th) if finite_rows.all() else int(np.argmin(finite_rows))
    for t in range(stop):
        for halvings in range(max_halvings + 1):
            parts = 2**halvings
            trial = current
            for k in range(1, parts + 1):
                target = previous + (th[t] - previous) * (k / parts)
                trial, ok = newton(elbows_of(target[None], geometry), trial, geometry, 50)
                if not ok[0]:
                    break
            if ok[0]:
                break
        if not ok[0]:
            break
        current, previous = trial, th[t]
        pose[t], converged[t] = current[0], True
    mode = np.full(len(th), -1, dtype=np.int8)
    mode[converged] = pose_modes(pose[converged], elbows_of(th[converged], geometry), geometry)
    return FKResult(pose=pose, converged=converged, mode=mode)
