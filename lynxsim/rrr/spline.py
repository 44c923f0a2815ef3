"""Cubic splines through poses: the second derivatives at the knots, natural or periodic."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

__all__ = ["spline_second_derivatives"]

FloatArray = npt.NDArray[np.float64]


def spline_second_derivatives(u: FloatArray, y: FloatArray, closed: bool) -> FloatArray:
    """Second derivatives at the knots of a cubic spline through ``y`` (natural or periodic).

    Args:
        u: Knots, strictly increasing, shape (N,).
        y: Values, shape (N, 3).
        closed: Periodic conditions (``y[0] == y[-1]``) instead of natural ends.

    Returns:
        Shape (N, 3).
    """
    n = len(u)
    h = np.diff(u)
    slope = np.diff(y, axis=0) / h[:, None]
    m = np.zeros_like(y)
    if closed:
        k = n - 1  # unknowns M_0 .. M_{n-2}; M_{n-1} = M_0
        a = np.zeros((k, k))
        rhs = np.empty((k, 3))
        for i in range(k):
            hp, hn = h[i - 1], h[i]  # h[-1] is the last interval: periodic wrap
            a[i, (i - 1) % k] += hp
            a[i, i] += 2.0 * (hp + hn)
            a[i, (i + 1) % k] += hn
            rhs[i] = 6.0 * (slope[i] - slope[i - 1])
        m[:k] = np.linalg.solve(a, rhs)
        m[k] = m[0]
    elif n > 2:
        k = n - 2  # interior unknowns; natural ends M_0 = M_{n-1} = 0
        a = np.zeros((k, k))
        for i in range(k):
            a[i, i] = 2.0 * (h[i] + h[i + 1])
            if i > 0:
                a[i, i - 1] = h[i]
            if i < k - 1:
                a[i, i + 1] = h[i + 1]
        m[1:-1] = np.linalg.solve(a, 6.0 * (slope[1:] - slope[:-1]))
    return m
