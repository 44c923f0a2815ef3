"""Assertions and small task files shared by the tests."""

from __future__ import annotations

import resource
import signal
from collections.abc import Callable

import numpy as np
import numpy.typing as npt


def full_disk(limit_bytes: int) -> Callable[[], None]:
    """A ``preexec_fn`` after which no file of the process grows past ``limit_bytes``.

    Writes beyond fail with EFBIG, as they would with ENOSPC on a full disk
    (SIGXFSZ ignored, so that the process sees the error instead of dying).
    """

    def limit() -> None:
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit_bytes, limit_bytes))

    return limit


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


_SHORT_ARM_TASK = """
name = "{name}"
robot = "arm"
[trajectory]
type = "quintic"
segment_duration_s = 1.0
[[poses]]
position_mm = [0.0, 300.0, 0.0]
pitch_deg = -90.0
[[poses]]
position_mm = [100.0, 250.0, 50.0]
pitch_deg = -90.0
"""

_SHORT_RRR_TASK = """
name = "{name}"
robot = "rrr"
[trajectory]
type = "quintic"
segment_duration_s = 0.6
stretch = true
[[poses]]
name = "home"
x_mm = 251.147
y_mm = 145.0
alpha_deg = 0.0
[[poses]]
name = "a"
x_mm = 220.0
y_mm = 150.0
alpha_deg = 10.0
"""


def short_arm_task(name: str = "short") -> str:
    """A two-pose arm task (TOML text): 1 s of quintic motion, reachable, within the limits."""
    return _SHORT_ARM_TASK.format(name=name)


def short_rrr_task(name: str = "short_rrr") -> str:
    """A two-pose 3-RRR task (TOML text): 0.6 s of quintic platform motion from home."""
    return _SHORT_RRR_TASK.format(name=name)
