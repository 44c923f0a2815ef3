"""The AL5D arm's side of the real-arm tools: its joints, its default calibration, its tool point.

The rest of :mod:`lynxsim.real` names no robot; this module binds it to the
arm of :mod:`lynxsim.arm` (joint names, the trajectories' velocity limits from
:mod:`lynxsim.arm.servos`, the forward kinematics of the tool point).
"""

from __future__ import annotations

import os
from importlib import resources
from pathlib import Path

import numpy as np
import numpy.typing as npt

from lynxsim.arm import AL5D_SERVOS, LYNX_ARM, tool_pose
from lynxsim.real.calibration import Calibration, load_calibration

__all__ = ["DEFAULT_CALIBRATION", "arm_tool_points", "load_arm_calibration"]


def _default() -> Path:
    return Path(str(resources.files("lynxsim.real").joinpath("al5d_ssc32u.toml")))


DEFAULT_CALIBRATION = _default()
"""The default calibration file shipped with lynxsim (``lynxsim/real/al5d_ssc32u.toml``)."""


def load_arm_calibration(path: str | os.PathLike[str] | None = None) -> Calibration:
    """Read an arm calibration file (None: the default); joints as :data:`lynxsim.arm.LYNX_ARM`.

    A joint without ``max_speed_deg_s`` gets the velocity limit the trajectories
    are generated with (:attr:`lynxsim.arm.ServoSpec.velocity_limit`).

    Raises:
        CalibrationFileError: See :func:`lynxsim.real.calibration.load_calibration`.
    """
    return load_calibration(
        DEFAULT_CALIBRATION if path is None else path,
        LYNX_ARM.joint_names,
        [s.velocity_limit for s in AL5D_SERVOS],
    )


def arm_tool_points(q: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    """Tool points of joint vectors, (N, 5) [rad] -> (N, 3) [m] (the analytic FK)."""
    points: npt.NDArray[np.float64] = tool_pose(q).position
    return points
