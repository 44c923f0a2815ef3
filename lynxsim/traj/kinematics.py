"""A joint-space robot's kinematics as the commands need it: joints, limits, tool point.

:class:`Kinematics` is what a robot whose motions are joint trajectories tells
the robot-free commands (``lynxsim traj``, the plots, the generic playback):
its joints and ranges (:class:`~lynxsim.traj.JointBounds`), its default limits
(:class:`~lynxsim.traj.JointLimits`) and its forward kinematics to the tool
point, :attr:`Kinematics.tool`, which reads joint vectors out as a
:class:`ToolReadout`: the point and any named angles of the tool (the arm's
pitch), which ``lynxsim traj`` writes as columns.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from lynxsim.errors import InvalidInputError
from lynxsim.inputs import instance
from lynxsim.traj.limits import JointBounds, JointLimits

__all__ = ["Kinematics", "ToolFn", "ToolReadout"]

FloatArray = npt.NDArray[np.float64]
_ANGLE_NAME = "abcdefghijklmnopqrstuvwxyz_0123456789"


@dataclass(frozen=True, eq=False)
class ToolReadout:
    """The tool of N joint vectors.

    Attributes:
        position: Tool points, shape (N, 3) [m].
        angles: Named tool angles, each ``(name, values (N,) [rad])``: the columns
            ``lynxsim traj`` writes after the point (names: lower-case letters,
            digits and ``_``).

    Raises:
        InvalidInputError: A shape disagrees or an angle's name is malformed.
    """

    position: FloatArray
    angles: tuple[tuple[str, FloatArray], ...] = ()

    def __post_init__(self) -> None:
        position = np.asarray(self.position, dtype=float)
        if position.ndim != 2 or position.shape[1] != 3:
            raise InvalidInputError(f"tool points must have shape (N, 3), got {position.shape}")
        angles = []
        for name, values in self.angles:
            if not (isinstance(name, str) and name and set(name) <= set(_ANGLE_NAME)):
                raise InvalidInputError(f"a tool angle's name must be lower-case, got {name!r}")
            arr = np.asarray(values, dtype=float)
            if arr.shape != (position.shape[0],):
                raise InvalidInputError(
                    f"tool angle {name!r} must have shape ({position.shape[0]},), got {arr.shape}"
                )
            angles.append((name, arr))
        object.__setattr__(self, "position", position)
        object.__setattr__(self, "angles", tuple(angles))


ToolFn = Callable[[FloatArray], ToolReadout]
"""Forward kinematics of the tool: joint vectors (N, n) [rad] -> :class:`ToolReadout`."""


@dataclass(frozen=True)
class Kinematics:
    """A joint-space robot's joints, default limits and tool.

    Attributes:
        bounds: Its joints (n) and their ranges.
        limits: The default limits of its trajectories (n joints).
        tool: Forward kinematics of the tool point (:data:`ToolFn`); a module-level
            function, so that a record holding it can be sent to worker processes.

    Raises:
        InvalidInputError: A field of the wrong type, or bounds and limits of
            different joint counts.
    """

    bounds: JointBounds
    limits: JointLimits
    tool: ToolFn

    def __post_init__(self) -> None:
        instance(self.bounds, JointBounds, "bounds")
        instance(self.limits, JointLimits, "limits")
        if self.limits.n_joints != self.bounds.n_joints:
            raise InvalidInputError(
                f"{self.bounds.n_joints} joints need limits of {self.bounds.n_joints} joints, "
                f"got {self.limits.n_joints}"
            )
        if not callable(self.tool):
            raise InvalidInputError(f"tool must be callable, got {self.tool!r}")

    @property
    def n_joints(self) -> int:
        """The number of joints n."""
        return self.bounds.n_joints

    def tool_points(self, q: npt.ArrayLike) -> FloatArray:
        """Tool points of joint vectors, (N, n) [rad] -> (N, 3) [m]."""
        return self.tool(np.asarray(q, dtype=float).reshape(-1, self.n_joints)).position
