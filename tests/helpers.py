"""Assertions shared by the tests."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt


def assert_close(
    actual: npt.ArrayLike,
    desired: npt.ArrayLike,
    *,
    atol: float,
    rtol: float = 0.0,
    err_msg: str = "",
) -> None:
    """``np.testing.assert_allclose`` that also fails on NaN or infinity in ``actual``."""
    a = np.asarray(actual, dtype=float)
    assert np.isfinite(a).all(), f"non-finite values in result: {a} {err_msg}"
    np.testing.assert_allclose(a, desired, atol=atol, rtol=rtol, err_msg=err_msg)
